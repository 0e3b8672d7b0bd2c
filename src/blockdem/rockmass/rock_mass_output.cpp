// Rock mass outputs. Face tags in the VTK cell data: face_source 0 region boundary, 1 joint,
// 2 excavation outline; joint_set (-1 for none); bonded 0/1; excavation (-1 for none).
#include "blockdem/rockmass/rock_mass_output.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <omp.h>

#include "blockdem/io/csv.hpp"
#include "blockdem/io/output_error.hpp"
#include "blockdem/numerics/shares.hpp"

namespace blockdem {
namespace {

// Excavation index of each block (-1: none; the first excavation that holds it).
std::vector<int> excavation_of_blocks(const RockMassModel& m) {
  std::vector<int> out(m.rock_mass.blocks.size(), -1);
  for (int e = static_cast<int>(m.spec.excavations.size()) - 1; e >= 0; --e) {
    for (int i : m.rock_mass.blocks_inside(m.spec, e)) out[i] = e;
  }
  return out;
}

// Writes the text of items [0, n) in their order through `sink`, formatted on `threads` threads
// in pieces of kPer items (`piece(begin, end, text)` appends the text of items [begin, end)). A
// round of pieces is formatted at once and written before the next: the file is never held whole.
template <class Piece, class Sink>
void write_in_pieces(std::size_t n, int threads, Piece piece, Sink sink) {
  constexpr std::size_t kPer = 256;
  const std::size_t pieces = (n + kPer - 1) / kPer;
  const std::size_t round = 4 * static_cast<std::size_t>(std::max(threads, 1));
  std::vector<std::string> text(round);
  for (std::size_t first = 0; first < pieces; first += round) {
    const auto count = static_cast<std::int64_t>(std::min(round, pieces - first));
    for_each_share(count, count, threads, [&](std::int64_t k, std::int64_t, std::int64_t) {
      std::string& t = text[static_cast<std::size_t>(k)];
      t.clear();
      const std::size_t begin = (first + static_cast<std::size_t>(k)) * kPer;
      piece(begin, std::min(n, begin + kPer), t);
    });
    for (std::int64_t k = 0; k < count; ++k) sink(text[static_cast<std::size_t>(k)]);
  }
}

// A CSV file of the rows of items [0, n) (`rows_of(i, writer)` writes item i's), formatted in
// pieces by writers into memory and added to the file in order.
template <class Rows>
void write_csv(const std::filesystem::path& path, const std::vector<std::string>& columns,
               std::size_t n, int threads, Rows rows_of) {
  CsvWriter csv(path, columns);
  write_in_pieces(
      n, threads,
      [&](std::size_t begin, std::size_t end, std::string& t) {
        CsvWriter rows(columns.size());
        for (std::size_t i = begin; i < end; ++i) rows_of(i, rows);
        t = rows.take();
      },
      [&](const std::string& t) { csv.raw(t); });
  csv.flush();
}

// A number as a stream at precision 12 writes it (printf's "%.12g"), and an integer.
void append_number(std::string& t, double v) {
  char buf[40];
  t.append(buf, write_general12(buf, v));
}
void append_number(std::string& t, long long v) {
  char buf[24];
  t.append(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

void write_vtk(const RockMassModel& m, const std::filesystem::path& path, int threads) {
  std::ofstream f(path, std::ios::binary);
  if (!f) throw OutputError("cannot write " + path.string());
  const auto& blocks = m.rock_mass.blocks;
  std::size_t points = 0, faces = 0, refs = 0;
  std::vector<std::size_t> base(blocks.size());  // each block's first point
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const auto& b = blocks[i];
    base[i] = points;
    points += b.vertices().size();
    faces += b.faces().size();
    for (const auto& fc : b.faces()) refs += fc.vertices.size() + 1;
  }
  auto sink = [&](const std::string& t) {
    f.write(t.data(), static_cast<std::streamsize>(t.size()));
  };
  auto each_block = [&](auto text_of) {
    write_in_pieces(
        blocks.size(), threads,
        [&](std::size_t begin, std::size_t end, std::string& t) {
          for (std::size_t i = begin; i < end; ++i) text_of(i, t);
        },
        sink);
  };
  f << "# vtk DataFile Version 3.0\nblockdem rock mass\nASCII\nDATASET POLYDATA\n";
  f << "POINTS " << points << " double\n";
  each_block([&](std::size_t i, std::string& t) {
    for (const auto& v : blocks[i].vertices()) {
      append_number(t, v.x());
      t += ' ';
      append_number(t, v.y());
      t += ' ';
      append_number(t, v.z());
      t += '\n';
    }
  });
  f << "POLYGONS " << faces << " " << refs << "\n";
  each_block([&](std::size_t i, std::string& t) {
    for (const auto& fc : blocks[i].faces()) {
      append_number(t, static_cast<long long>(fc.vertices.size()));
      for (int v : fc.vertices) {
        t += ' ';
        append_number(t, static_cast<long long>(base[i] + static_cast<std::size_t>(v)));
      }
      t += '\n';
    }
  });
  const std::vector<int> exc = excavation_of_blocks(m);
  auto cell_ints = [&](const char* name, auto value) {
    f << "SCALARS " << name << " int 1\nLOOKUP_TABLE default\n";
    each_block([&](std::size_t i, std::string& t) {
      for (const auto& fc : blocks[i].faces()) {
        append_number(t, static_cast<long long>(value(i, fc)));
        t += '\n';
      }
    });
  };
  f << "CELL_DATA " << faces << "\n";
  cell_ints("block_index", [](std::size_t i, const CellFace&) { return static_cast<long>(i); });
  cell_ints("face_source",
            [](std::size_t, const CellFace& fc) { return static_cast<long>(fc.tag.source); });
  cell_ints("joint_set", [](std::size_t, const CellFace& fc) {
    return fc.tag.source == FaceSource::joint ? static_cast<long>(fc.tag.index) : -1L;
  });
  cell_ints("bonded", [](std::size_t, const CellFace& fc) { return fc.tag.bonded ? 1L : 0L; });
  cell_ints("excavation",
            [&](std::size_t i, const CellFace&) { return static_cast<long>(exc[i]); });
  if (!f) throw OutputError("cannot write " + path.string());
}

}  // namespace

nlohmann::json rock_mass_summary(const RockMassModel& m) {
  const RockMass& rm = m.rock_mass;
  nlohmann::json j;
  j["blocks"] = rm.blocks.size();
  j["total_volume_m3"] = rm.total_volume();
  j["region_volume_m3"] = rm.region_volume;
  j["removed_blocks"] = rm.removed_blocks;
  j["removed_volume_m3"] = rm.removed_volume;
  j["merged_cuts"] = rm.merged_cuts;
  j["merged_volume_m3"] = rm.merged_volume;
  j["cut_tolerance_m"] = rm.cut_tolerance;
  j["min_block_volume_m3"] = m.spec.settings.min_block_volume;

  // Block size distribution: volume quantiles, and the cumulative share of the blocks (by
  // count and by volume) at or below each of 20 sizes spaced evenly in log volume.
  std::vector<double> v;
  for (const auto& b : rm.blocks) v.push_back(b.volume());
  std::sort(v.begin(), v.end());
  nlohmann::json dist;
  if (!v.empty()) {
    auto quantile = [&](double q) {
      const double pos = q * static_cast<double>(v.size() - 1);
      const auto k = static_cast<std::size_t>(pos);
      const double t = pos - static_cast<double>(k);
      return k + 1 < v.size() ? (1 - t) * v[k] + t * v[k + 1] : v[k];
    };
    dist["min_m3"] = v.front();
    dist["max_m3"] = v.back();
    dist["mean_m3"] = rm.total_volume() / static_cast<double>(v.size());
    for (const auto& [name, q] :
         {std::pair{"v10_m3", 0.1}, std::pair{"v25_m3", 0.25}, std::pair{"v50_m3", 0.5},
          std::pair{"v75_m3", 0.75}, std::pair{"v90_m3", 0.9}})
      dist[name] = quantile(q);
    nlohmann::json sizes = nlohmann::json::array(), by_count = sizes, by_volume = sizes;
    const double lo = std::log10(v.front()), hi = std::log10(v.back());
    const int bins = 20;
    std::size_t k = 0;
    double cum = 0.0;
    for (int i = 1; i <= bins; ++i) {
      const double edge = std::pow(10.0, lo + (hi - lo) * i / bins);
      while (k < v.size() && (v[k] <= edge * (1 + 1e-12) || i == bins)) cum += v[k++];
      sizes.push_back(edge);
      by_count.push_back(static_cast<double>(k) / static_cast<double>(v.size()));
      by_volume.push_back(cum / rm.total_volume());
    }
    dist["cumulative"] = {
        {"volume_m3", sizes}, {"fraction_of_blocks", by_count}, {"fraction_of_volume", by_volume}};
  }
  j["block_size_distribution"] = dist;

  nlohmann::json sets = nlohmann::json::array();
  for (std::size_t s = 0; s < m.spec.joint_sets.size(); ++s) {
    const JointSet& js = m.spec.joint_sets[s];
    const Eigen::Vector3d n = js.normal();
    sets.push_back({{"name", js.name},
                    {"dip_deg", js.dip_deg},
                    {"dip_direction_deg", js.dip_direction_deg},
                    {"normal", {n.x(), n.y(), n.z()}},
                    {"persistent", !js.extent.has_value()},
                    {"joints", rm.joints[s].size()},
                    {"law", m.set_laws[s]}});
  }
  j["joint_sets"] = sets;
  nlohmann::json exs = nlohmann::json::array();
  for (std::size_t e = 0; e < m.spec.excavations.size(); ++e) {
    double vol = 0.0;
    const auto inside = rm.blocks_inside(m.spec, static_cast<int>(e));
    for (int i : inside) vol += rm.blocks[i].volume();
    exs.push_back({{"name", m.spec.excavations[e].name},
                   {"blocks_inside", inside.size()},
                   {"volume_inside_m3", vol}});
  }
  j["excavations"] = exs;
  return j;
}

void write_rock_mass(const RockMassModel& m, const std::filesystem::path& out, int threads) {
  if (threads <= 0) threads = omp_get_max_threads();
  std::filesystem::create_directories(out);
  write_vtk(m, out / "blocks.vtk", threads);
  const std::vector<int> exc = excavation_of_blocks(m);
  const auto& blocks = m.rock_mass.blocks;
  write_csv(out / "blocks.csv",
            {"block", "volume_m3", "centroid_x_m", "centroid_y_m", "centroid_z_m", "faces",
             "aspect_ratio", "excavation"},
            blocks.size(), threads, [&](std::size_t i, CsvWriter& rows) {
              const auto& b = blocks[i];
              rows.cell(RockMassModel::block_name(i)).cell(b.volume());
              rows.cell(b.centroid().x()).cell(b.centroid().y()).cell(b.centroid().z());
              rows.cell(static_cast<long long>(b.faces().size())).cell(b.aspect_ratio());
              rows.cell(exc[i] >= 0 ? m.spec.excavations[exc[i]].name : std::string());
              rows.end_row();
            });
  write_csv(out / "faces.csv", {"block", "face", "tag", "bonded", "area_m2"}, blocks.size(),
            threads, [&](std::size_t i, CsvWriter& rows) {
              const auto& b = blocks[i];
              for (int f = 0; f < static_cast<int>(b.faces().size()); ++f) {
                const auto poly = b.face_polygon(f);
                const double area = polygon_area(poly, b.faces()[f].plane.normal);
                rows.cell(RockMassModel::block_name(i)).cell(f).cell(m.label(b.faces()[f].tag));
                rows.cell(b.faces()[f].tag.bonded ? 1 : 0).cell(area);
                rows.end_row();
              }
            });
  std::ofstream j(out / "rock_mass.json");
  j << rock_mass_summary(m).dump(2) << "\n";
  if (!j) throw OutputError("cannot write " + (out / "rock_mass.json").string());
}

}  // namespace blockdem

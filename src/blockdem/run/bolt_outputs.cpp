// bolts.csv rows and the bolts' counts.
#include "blockdem/run/bolt_outputs.hpp"

#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/csv.hpp"

namespace blockdem {

std::string bolt_rows(const World& world, const std::string& stage) {
  CsvWriter csv(std::size(kBoltColumns));
  for (const Bolt& bolt : world.bolts()) {
    for (std::size_t k = 0; k < bolt.spans.size(); ++k) {
      const BoltSpan& s = bolt.spans[k];
      const bool active = bolt.active();
      const double shear =
          active && k < bolt.crossings.size() ? bolt.crossings[k].force.norm() : 0.0;
      csv.cell(stage).cell(bolt.spec.name).cell(static_cast<int>(k) + 1);
      csv.cell(s.block >= 0 ? world.blocks()[static_cast<std::size_t>(s.block)].name
                            : std::string());
      csv.cell(s.from).cell(s.to);
      csv.cell(active ? bolt.largest_axial_force(s.from, s.to) : 0.0).cell(shear);
      csv.cell(std::string(to_string(bolt.state)));
      csv.end_row();
    }
  }
  return csv.take();
}

void write_bolts_csv(const std::filesystem::path& path, const std::string& rows) {
  std::string text;
  for (const char* column : kBoltColumns) {
    if (!text.empty()) text.push_back(',');
    text.append(column);
  }
  text.push_back('\n');
  text.append(rows);
  write_file_atomically(path, text);
}

nlohmann::json bolt_counts(const World& world) {
  return {{"installed", world.bolts().size()},
          {"intact", world.bolt_count(Bolt::State::intact)},
          {"yielded", world.bolt_count(Bolt::State::yielded)},
          {"ruptured", world.bolt_count(Bolt::State::ruptured)},
          {"removed", world.bolt_count(Bolt::State::removed)}};
}

}  // namespace blockdem

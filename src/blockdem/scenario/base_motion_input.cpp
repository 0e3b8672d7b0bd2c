// Reading a dynamic stage's base motion: the CSV record or the pulse, checked.
#include "blockdem/scenario/base_motion_input.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "blockdem/numerics/number_text.hpp"

namespace blockdem {

namespace {

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string f;
  while (std::getline(in, f, ',')) out.push_back(trimmed(f));
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

}  // namespace

BaseMotion read_acceleration_record(const std::filesystem::path& path) {
  const std::string src = path.string();
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(src + ": cannot open the file");
  const std::vector<std::string> columns = {"time_s", "ax_m_s2", "ay_m_s2", "az_m_s2"};
  std::vector<int> column_of;  // field -> column
  BaseMotion m;
  m.shape = BaseMotion::Shape::record;
  std::string raw;
  int line_no = 0;
  while (std::getline(in, raw)) {
    ++line_no;
    const std::string line = trimmed(raw);
    const std::string at = src + ":" + std::to_string(line_no) + ": ";
    if (line.empty() || line.front() == '#') continue;
    const std::vector<std::string> fields = fields_of(line);
    if (column_of.empty()) {
      // The header: the four columns, each once.
      std::map<std::string, int> seen;
      for (const auto& name : fields) {
        int c = -1;
        for (std::size_t k = 0; k < columns.size(); ++k) {
          if (columns[k] == name) c = static_cast<int>(k);
        }
        if (c < 0 || seen.count(name))
          throw std::invalid_argument(at +
                                      "the header must name time_s, ax_m_s2, ay_m_s2, "
                                      "az_m_s2 once each, got '" +
                                      name + "'");
        seen[name] = c;
        column_of.push_back(c);
      }
      if (seen.size() != columns.size())
        throw std::invalid_argument(at + "the header must name time_s, ax_m_s2, ay_m_s2, az_m_s2");
      continue;
    }
    if (fields.size() != columns.size())
      throw std::invalid_argument(at + "expected 4 values, found " + std::to_string(fields.size()));
    double row[4] = {0, 0, 0, 0};
    for (std::size_t f = 0; f < fields.size(); ++f) {
      const std::string& name = columns[static_cast<std::size_t>(column_of[f])];
      char* end = nullptr;
      const double v = std::strtod(fields[f].c_str(), &end);
      if (fields[f].empty() || end == nullptr || *end != '\0')
        throw std::invalid_argument(at + "column '" + name + "': '" + fields[f] +
                                    "' is not a number");
      if (!std::isfinite(v))
        throw std::invalid_argument(at + "column '" + name + "' is " + fields[f] +
                                    ": every value must be finite");
      row[column_of[f]] = v;
    }
    if (!m.times.empty() && !(row[0] > m.times.back()))
      throw std::invalid_argument(at + "time_s = " + number_text(row[0]) +
                                  " does not increase (the line before has " +
                                  number_text(m.times.back()) + "): times must increase strictly");
    if (m.times.empty() && row[0] < 0.0)
      throw std::invalid_argument(at + "time_s must start at 0 or later (stage time)");
    m.times.push_back(row[0]);
    m.accelerations.emplace_back(row[1], row[2], row[3]);
  }
  if (column_of.empty())
    throw std::invalid_argument(src + ": no header line (time_s, ax_m_s2, ay_m_s2, az_m_s2)");
  if (m.times.size() < 2) throw std::invalid_argument(src + ": needs at least two samples");
  m.prepare();
  return m;
}

namespace {

BaseMotion read_pulse(const CheckedTable& b) {
  BaseMotion m;
  const std::string pulse = b.choice("pulse", "rectangular", {"rectangular", "sine", "ricker"});
  m.shape = pulse == "rectangular" ? BaseMotion::Shape::rectangular
            : pulse == "sine"      ? BaseMotion::Shape::sine
                                   : BaseMotion::Shape::ricker;
  m.amplitude = b.number("amplitude_m_s2");
  if (!std::isfinite(m.amplitude)) b.fail("amplitude_m_s2", "must be finite");
  const Eigen::Vector3d d = b.vec3("direction", Eigen::Vector3d::UnitX());
  if (!(d.norm() > 0.0) || !std::isfinite(d.norm()))
    b.fail("direction", "must be a non-zero vector of finite length");
  m.direction = d.normalized();
  const auto positive = [&b](const char* key, const char* unit) {
    const double v = b.number(key);
    if (!(v > 0.0 && std::isfinite(v)))
      b.fail(key, std::string("must be > 0 ") + unit + " and finite, got " + number_text(v));
    return v;
  };
  const auto refuse = [&b, &pulse](const char* key) {
    if (b.has(key)) b.fail(key, "a " + pulse + " pulse does not take this");
  };
  if (m.shape == BaseMotion::Shape::rectangular) {
    m.duration = positive("duration", "s");
    for (const char* k : {"period", "cycles", "frequency", "peak_time"}) refuse(k);
  } else if (m.shape == BaseMotion::Shape::sine) {
    m.period = positive("period", "s");
    const std::int64_t n = b.integer("cycles", 1);
    if (n < 1 || n > 1000000) b.fail("cycles", "must be a whole number from 1 to 1e6");
    m.cycles = static_cast<int>(n);
    for (const char* k : {"duration", "frequency", "peak_time"}) refuse(k);
  } else {
    m.frequency = positive("frequency", "Hz");
    m.peak_time = b.has("peak_time") ? positive("peak_time", "s") : 1.5 / m.frequency;
    for (const char* k : {"duration", "period", "cycles"}) refuse(k);
  }
  return m;
}

}  // namespace

void read_dynamic_stage(const CheckedTable& t, const std::set<std::string>& groups, Stage& s) {
  if (s.kind != Stage::Kind::dynamic) {
    if (t.has("base_motion")) t.fail("base_motion", "only a stage of kind \"dynamic\" takes it");
    return;
  }
  if (!t.has("base_motion"))
    t.fail("base_motion", "a stage of kind \"dynamic\" needs base_motion = { group = ..., ... }");
  const CheckedTable b = t.table("base_motion");
  if (b.has("file") == b.has("pulse"))
    b.fail("file",
           "give either file = \"accel.csv\" (a record) or pulse = \"rectangular\", "
           "\"sine\" or \"ricker\"");
  BaseMotion m;
  if (b.has("file")) {
    std::filesystem::path path = b.string("file");
    if (path.is_relative()) path = std::filesystem::path(t.file()).parent_path() / path;
    try {
      m = read_acceleration_record(path);
    } catch (const std::invalid_argument& e) {
      b.fail("file", e.what());
    }
  } else {
    m = read_pulse(b);
  }
  m.group = b.string("group", "base");
  if (!groups.count(m.group)) b.fail("group", "no block is in group \"" + m.group + "\"");
  b.finish();
  s.base_motion = std::move(m);
  s.duration = t.has("duration") ? t.positive("duration", 0.0) : s.base_motion->end_time();
  if (!(s.duration > 0.0)) t.fail("duration", "must be > 0 s");
  if (s.density_scaling.value_or(false))
    t.fail("density_scaling",
           "a dynamic stage runs in time, which density scaling distorts (it is exact only at "
           "static equilibrium): leave it off");
}

void finish_dynamic_stages(Scenario& sc) {
  double damping = sc.settings.damping;
  for (std::size_t k = 0; k < sc.stages.size(); ++k) {
    Stage& st = sc.stages[k];
    if (st.kind != Stage::Kind::dynamic) {
      if (st.damping && st.kind != Stage::Kind::strength_reduction) damping = *st.damping;
      continue;
    }
    st.damping_after = damping;
    // A record should end at rest: the base keeps its final velocity after it.
    const BaseMotion& m = *st.base_motion;
    const double t_end = m.end_time();
    const double v_end = m.at(t_end).velocity.norm();
    double a_max = 0.0;
    for (double t : m.times) a_max = std::max(a_max, m.at(t).acceleration.norm());
    a_max = std::max(a_max, std::abs(m.amplitude));
    if (v_end > 1e-6 * std::max(1.0, a_max * t_end))
      sc.warnings.push_back("stage '" + st.name +
                            "': the base motion ends with the base moving at " +
                            number_text(v_end) +
                            " m/s; the base keeps that velocity after the history ends (a record "
                            "should end at rest)");
  }
}

void check_dynamic_stages(const Scenario& sc, const World& world, int ranks) {
  for (std::size_t k = 0; k < sc.stages.size(); ++k) {
    const Stage& st = sc.stages[k];
    if (st.kind != Stage::Kind::dynamic) continue;
    const std::string key = "stages[" + std::to_string(k + 1) + "]";
    if (ranks > 1)
      throw ScenarioError(sc.file, key + ".kind",
                          "a dynamic stage runs on one process (its base is set serially): run "
                          "without mpirun");
    for (const Block& b : world.blocks()) {
      if (b.group() == st.base_motion->group && b.motion != Motion::fixed)
        throw ScenarioError(sc.file, key + ".base_motion.group",
                            "block \"" + b.name + "\" of group \"" + b.group() +
                                "\" is not fixed: the base moves fixed blocks only");
    }
  }
}

}  // namespace blockdem

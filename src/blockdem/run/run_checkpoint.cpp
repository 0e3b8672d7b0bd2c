// RunPoint as bytes: fields in a fixed order through the world's state streams.
#include "blockdem/run/run_checkpoint.hpp"

#include "blockdem/world/state_stream.hpp"

namespace blockdem {

std::pair<std::string, std::string> encode_run_point_around_world(const RunPoint& p) {
  StateWriter w;
  w.pod(static_cast<std::int32_t>(p.level));
  w.pod(static_cast<std::uint8_t>(p.in_stage));
  w.pod(p.stage.steps_done);
  w.vec(p.stage.gravity_before);
  w.pod(p.stage.start_time);
  w.str(p.monitor);
  std::string head(w.bytes().begin(), w.bytes().end());
  w.bytes().clear();
  w.str(p.before);
  w.str(p.summary);
  w.str(p.stages);
  w.size(p.steps_per_stage.size());
  for (std::int64_t s : p.steps_per_stage) w.pod(s);
  w.pod(static_cast<std::uint8_t>(p.factor_of_safety.has_value()));
  w.pod(p.factor_of_safety.value_or(0.0));
  w.size(p.files.size());
  for (const auto& [path, content] : p.files) {
    w.str(path);
    w.str(content);
  }
  w.str(p.outputs);
  return {std::move(head), std::string(w.bytes().begin(), w.bytes().end())};
}

std::string encode_run_point(const RunPoint& p) {
  auto [head, tail] = encode_run_point_around_world(p);
  StateWriter w;
  w.str(p.world);
  head.append(w.bytes().begin(), w.bytes().end());
  head.append(tail);
  return head;
}

RunPoint decode_run_point(std::string_view bytes, std::string_view& world,
                          std::string_view& before) {
  StateReader r(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  RunPoint p;
  p.level = r.pod<std::int32_t>();
  p.in_stage = r.pod<std::uint8_t>() != 0;
  r.pod(p.stage.steps_done);
  p.stage.gravity_before = r.vec();
  r.pod(p.stage.start_time);
  p.monitor = r.str();
  // The world's states (nearly all of the bytes) are passed over, not copied.
  const auto view = [&r, bytes] {
    const std::size_t n = r.size();
    const std::size_t at = r.position();
    r.skip(n);
    return bytes.substr(at, n);
  };
  world = view();
  before = view();
  p.summary = r.str();
  p.stages = r.str();
  p.steps_per_stage.resize(r.size());
  for (std::int64_t& s : p.steps_per_stage) r.pod(s);
  const bool has_fos = r.pod<std::uint8_t>() != 0;
  const double fos = r.pod<double>();
  if (has_fos) p.factor_of_safety = fos;
  p.files.resize(r.size());
  for (auto& [path, content] : p.files) {
    path = r.str();
    content = r.str();
    if (path.empty() || path.find("..") != std::string::npos || path.front() == '/')
      throw StateError("saved state is corrupt (a file path leaves the output folder)");
  }
  p.outputs = r.str();
  if (!r.done()) throw StateError("saved state is corrupt (bytes left over)");
  if (p.level < 0 || p.stage.steps_done < 0) throw StateError("saved state is corrupt");
  return p;
}

RunPoint decode_run_point(std::string bytes) {
  std::string_view world, before;
  RunPoint p = decode_run_point(bytes, world, before);
  p.before = std::string(before);
  // The world's state is cut out of `bytes` in place, not copied: a restart of a large world
  // holds its state once.
  const auto world_at = static_cast<std::size_t>(world.data() - bytes.data());
  const std::size_t world_size = world.size();
  bytes.resize(world_at + world_size);
  bytes.erase(0, world_at);
  p.world = std::move(bytes);
  return p;
}

}  // namespace blockdem

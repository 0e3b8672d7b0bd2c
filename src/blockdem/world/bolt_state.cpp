// A bolt's state as bytes, for restart files: every field of the installed bolt (its spec, the
// blocks and points it is tied to, the tendon's nodes, elements and grout springs with their
// plastic parts, the dowels), so that a world loaded with it continues bit-identically.
#include "blockdem/world/bolt_state.hpp"

#include <cstdint>
#include <string>
#include <type_traits>

#include "blockdem/world/state_fields.hpp"

namespace blockdem {
namespace {

using namespace state_fields;

// A flag of a bolt's state (state_fields::flag, its error naming the bolt).
template <class Stream>
void bolt_flag(Stream& s, bool& value) {
  state_fields::flag(s, value, "saved bolt");
}

template <class Stream>
void spec_fields(Stream& s, BoltSpec& b) {
  text(s, b.name);
  vector3(s, b.start);
  vector3(s, b.direction);
  for (double* v : {&b.length, &b.axial_stiffness, &b.yield_force, &b.rupture_strain,
                    &b.bond_stiffness, &b.bond_strength, &b.shear_stiffness, &b.shear_capacity,
                    &b.shear_rupture_displacement, &b.pretension})
    field(s, *v);
}

template <class Stream>
void bolt_fields(Stream& s, Bolt& b) {
  spec_fields(s, b.spec);
  list(s, b.spans, [](Stream& st, BoltSpan& span) {
    field(st, span.block);
    field(st, span.from);
    field(st, span.to);
  });
  list(s, b.node_at, [](Stream& st, double& at) { field(st, at); });
  list(s, b.ties, [](Stream& st, BoltTie& tie) {
    field(st, tie.block);
    vector3(st, tie.body_point);
    vector3(st, tie.installed);
  });
  Tendon& t = b.tendon;
  list(s, t.u, [](Stream& st, double& u) { field(st, u); });
  list(s, t.elements, [](Stream& st, Tendon::Element& e) {
    field(st, e.stiffness);
    field(st, e.plastic);
    field(st, e.force);
  });
  list(s, t.springs, [](Stream& st, Tendon::Spring& sp) {
    field(st, sp.node);
    field(st, sp.stiffness);
    field(st, sp.strength);
    field(st, sp.slip);
    field(st, sp.force);
  });
  field(s, t.yield_force);
  field(s, b.anchored_length);
  field(s, b.plastic_extension);
  field(s, b.axial_force);
  list(s, b.crossings, [](Stream& st, BoltCrossing& c) {
    field(st, c.block_a);
    field(st, c.block_b);
    vector3(st, c.body_a);
    vector3(st, c.body_b);
    field(st, c.at);
    vector3(st, c.plastic);
    vector3(st, c.force);
  });
  auto state = static_cast<std::uint8_t>(b.state);
  field(s, state);
  if (state > static_cast<std::uint8_t>(Bolt::State::removed))
    throw StateError("saved bolt is corrupt (unknown state)");
  b.state = static_cast<Bolt::State>(state);
  bolt_flag(s, b.yielded);
  field(s, b.largest_strain);
}

}  // namespace

void save_bolts(StateWriter& w, const std::vector<Bolt>& bolts) {
  // The shared function takes its bolts by reference (a few hundred bolts at most: a copy).
  std::vector<Bolt> copy = bolts;
  list(w, copy, bolt_fields<StateWriter>);
}

std::vector<Bolt> load_bolts(StateReader& r, std::size_t blocks) {
  std::vector<Bolt> bolts;
  list(r, bolts, bolt_fields<StateReader>);
  const auto known = [blocks](int block) {
    return block >= -1 && block < static_cast<std::int64_t>(blocks);
  };
  for (const Bolt& b : bolts) {
    bool ok = true;
    for (const BoltSpan& s : b.spans) ok = ok && known(s.block);
    for (const BoltTie& t : b.ties) ok = ok && known(t.block);
    for (const BoltCrossing& c : b.crossings) ok = ok && known(c.block_a) && known(c.block_b);
    if (!ok)
      throw StateError("saved bolt '" + b.spec.name + "' is tied to a block that is not there");
  }
  return bolts;
}

}  // namespace blockdem

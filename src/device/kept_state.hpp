// What the device engine keeps of a contact's state, and the law it evaluates through it. Each
// touching pair's state sits on the device twice (the last evaluation's and this one's,
// GatherTouches), so its size is a large part of the engine's memory: the frictional laws' state
// holds a rolling spring beside the tangential one, 40 bytes each, and most scenes roll without
// resistance. Where no pair of materials has rolling resistance, the engine keeps the tangential
// spring alone (TangentialOnly) and evaluates the law on a whole state made around it, whose
// rolling spring is zero before and after: the same operations, so the same bits, in half the
// room (docs/ARCHITECTURE.md, "The device engine").
#pragma once

#include "contact/contact_geometry.hpp"
#include "contact/frictional_spring.hpp"
#include "core/always_inline.hpp"
#include "core/host_device.hpp"

#include <type_traits>
#include <vector>

namespace yuxi::device {

// The law's own state, kept whole.
template <class Model> struct WholeState {
  using Coeffs = typename Model::Coeffs;
  using State = typename Model::State;
  YUXI_ALWAYS_INLINE YUXI_HD static ContactResult evaluate(const ContactGeometry& g,
                                                           const Coeffs& c, State& s) {
    return Model::evaluate(g, c, s);
  }
  YUXI_ALWAYS_INLINE YUXI_HD static double release(const Coeffs& c, State& s) {
    return Model::release(c, s);
  }
  static State kept(const State& whole) { return whole; }
  static State whole(const State& kept) { return kept; }
};

// A law whose state is TangentialRollingState (LinearSpringDashpot, HertzMindlin), run where no
// pair of materials resists rolling (Coeffs::rolling() false): its rolling spring stays zero.
template <class Model> struct TangentialOnly {
  static_assert(std::is_same_v<typename Model::State, TangentialRollingState>);
  using Coeffs = typename Model::Coeffs;
  struct State {
    SliderState tangential;
    bool operator==(const State&) const = default;
    // (as TangentialRollingState::mirrored: n turns over, and the tangential spring with it)
    YUXI_HD State mirrored() const {
      State m = *this;
      m.tangential.spring = -tangential.spring;
      return m;
    }
  };
  YUXI_ALWAYS_INLINE YUXI_HD static ContactResult evaluate(const ContactGeometry& g,
                                                           const Coeffs& c, State& s) {
    TangentialRollingState state = whole(s);
    const ContactResult r = Model::evaluate(g, c, state);
    s = kept(state);
    return r;
  }
  YUXI_ALWAYS_INLINE YUXI_HD static double release(const Coeffs& c, State& s) {
    TangentialRollingState state = whole(s);
    const double held = Model::release(c, state);
    s = kept(state);
    return held;
  }
  YUXI_HD static State kept(const TangentialRollingState& whole) { return State{whole.tangential}; }
  YUXI_HD static TangentialRollingState whole(const State& kept) {
    return TangentialRollingState{kept.tangential, SliderState{}};
  }
  // Whether a run can keep the tangential spring alone: no pair of materials resists rolling,
  // and no open contact holds a rolling spring.
  template <class Contacts>
  static bool fits(const std::vector<Coeffs>& coeffs, const Contacts& contacts) {
    for (const Coeffs& c : coeffs)
      if (c.rolling()) return false;
    for (const auto& c : contacts)
      if (!(c.state.rolling == SliderState{})) return false;
    return true;
  }
};

} // namespace yuxi::device

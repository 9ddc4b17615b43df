// A spring-dashpot-slider: the tangential (and rolling, and torsion) part of a contact.
//
//   s += u dt                       (u: relative velocity of this degree of freedom)
//   F  = -k s - eta u               while it sticks
//   |F_spring or F| <= mu |N|       Coulomb limit, two regimes: a sticking contact slides when
//                                   the limit with mu_s is exceeded; a sliding one keeps sliding
//                                   while the limit with mu_d is exceeded, at mu_d |N|.
// Where the Coulomb limit applies (CapOn):
//  spring:       to the spring force alone; the dashpot is added after (Li & Cai 2008,
//                docs/models/fish-basin.md section 5); sliding cuts the spring to the limit;
//  total:        to spring + dashpot; a sliding contact exerts exactly mu |N|, carried by the
//                spring alone, s = -F/k (LIGGGHTS, Luding 2008);
//  total_lammps: to spring + dashpot; the spring is rescaled as in LAMMPS gran/*/history,
//                s = -(F + eta u)/k. With a stiffness that grows during the contact (Mindlin)
//                and strong damping this stores the dashpot's excess in the spring and can
//                reverse the friction force for a few steps; use it only to match LAMMPS.
//
// Energy, exact for any stiffness history: each step the work done into the spring,
// (k_old s_old + k_new s_new)/2 . ds (the forces of the two half kicks of velocity Verlet),
// less the rise of its stored energy k |s|^2 / 2, is dissipated (zero while sticking at
// constant k), plus the dashpot's eta |u|^2 dt. Using the old stiffness for the old force
// matters where k changes fast, as Mindlin's k_t ~ delta^{1/2} does just before separation.
#pragma once

#include "core/always_inline.hpp"
#include "core/host_device.hpp"
#include "core/vec3.hpp"

#include <cmath>
#include <cstdint>

namespace yuxi {

enum class CapOn : std::uint8_t { spring, total, total_lammps };

// How the spring follows the turning contact frame.
//  rotate:  carry s into the new plane keeping its length (energy neutral), then add u dt;
//  project: add u dt, then drop the normal component (LAMMPS gran/hooke/history).
enum class Carry : std::uint8_t { rotate, project };

struct SliderState {
  Vec3 spring;               // s [length]
  std::uint32_t sliding = 0; // 1 while sliding
  // The four bytes before k, named so that they are always zero: states are saved as their
  // bytes (checkpoints, migration), and a saved state must not carry undefined bytes.
  std::uint32_t unused = 0;
  double k = 0.0; // the stiffness at the last step [force/length]
  bool operator==(const SliderState&) const = default;
  // k |s|^2 / 2 after the last step [energy] (computed: the state stays small, 40 bytes, and
  // the pair loop reads less memory)
  YUXI_HD double stored() const { return 0.5 * k * norm2(spring); }
};

// The springs of a frictional contact: tangential and (optional) rolling.
struct TangentialRollingState {
  SliderState tangential;
  SliderState rolling;
  bool operator==(const TangentialRollingState&) const = default;
  // The same contact seen from the partner: n turns over, so the tangential spring changes
  // sign; the rolling displacement -a n x (w_i - w_j) does not.
  YUXI_HD TangentialRollingState mirrored() const {
    TangentialRollingState m = *this;
    m.tangential.spring = -tangential.spring;
    return m;
  }
};

struct SliderLaw {
  double k = 0;    // stiffness [force/length]
  double eta = 0;  // dashpot coefficient, force = -eta u [force time/length]
  double mu_s = 0; // static friction coefficient
  double mu_d = 0; // dynamic friction coefficient
  CapOn cap = CapOn::spring;
};

struct SliderResult {
  Vec3 force;
  double dissipated = 0.0; // this step [energy]
};

// Keeps s in the plane normal to n with its length (tangential and rolling springs).
YUXI_HD inline Vec3 carry_in_plane(const Vec3& s, const Vec3& n) {
  const double len2 = norm2(s);
  if (len2 == 0.0) return s;
  const Vec3 p = s - dot(s, n) * n;
  const double p2 = norm2(p);
  return p2 == 0.0 ? Vec3{} : p * std::sqrt(len2 / p2);
}

// Keeps s along n with its length and sign (torsion spring).
YUXI_HD inline Vec3 carry_along(const Vec3& s, const Vec3& n) {
  const double along = dot(s, n);
  return (along >= 0 ? 1.0 : -1.0) * norm(s) * n;
}

// One step of the slider. `carried` is the spring already carried into the current frame.
YUXI_ALWAYS_INLINE YUXI_HD SliderResult slide(SliderState& st, const Vec3& carried, const Vec3& u,
                                              double normal, const SliderLaw& law, double dt) {
  SliderResult r;
  const Vec3 increment = u * dt;
  Vec3 spring = carried + increment;
  Vec3 damping = -law.eta * u;
  Vec3 f_spring = -law.k * spring;
  const Vec3 limited = law.cap == CapOn::spring ? f_spring : f_spring + damping;
  const double limit = (st.sliding ? law.mu_d : law.mu_s) * std::abs(normal);
  const double l2 = norm2(limited);
  if (l2 > limit * limit) {
    const Vec3 f_capped = limited * (law.mu_d * std::abs(normal) / std::sqrt(l2));
    switch (law.cap) {
    case CapOn::spring:
      f_spring = f_capped;
      break;
    case CapOn::total:
      f_spring = f_capped, damping = Vec3{};
      break;
    case CapOn::total_lammps:
      f_spring = f_capped - damping;
      break;
    }
    spring = law.k > 0 ? f_spring / -law.k : Vec3{};
    st.sliding = 1;
  } else {
    st.sliding = 0;
  }
  const double stored = 0.5 * law.k * norm2(spring);
  const double work_in = dot(0.5 * (st.k * carried + law.k * spring), increment);
  r.dissipated = work_in - (stored - st.stored()) - dot(damping, u) * dt;
  r.force = f_spring + damping;
  st.spring = spring;
  st.k = law.k;
  return r;
}

// The spring of a contact that opens: its energy is lost.
YUXI_HD inline double release(SliderState& st) {
  const double e = st.stored();
  st = SliderState{};
  return e;
}

// Both springs of a contact that opens.
YUXI_HD inline double release(TangentialRollingState& s) {
  const double e = release(s.tangential) + release(s.rolling);
  s = TangentialRollingState{};
  return e;
}

} // namespace yuxi

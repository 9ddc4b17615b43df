#include "sim/clump_bodies.hpp"

#include "core/always_inline.hpp"
#include "core/free_rotation.hpp"
#include "core/particle_energy.hpp"
#include "core/portable_math.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace yuxi {

namespace {

// Velocity Verlet's half kick of the centre and NO_SQUISH's of the momentum, over half_dt.
void half_kick(ClumpBody& b, double half_dt) {
  const double kick = half_dt / b.mass;
  b.v.x += b.force.x * kick, b.v.y += b.force.y * kick, b.v.z += b.force.z * kick;
  kick_rotor(b.q, b.p, b.torque, half_dt);
}

// One turn of NO_SQUISH's free rotation, about body axis `axis` by h, for every body. A body's
// five turns are a chain, each waiting on the sine and cosine before it; across bodies they are
// independent. So the bodies go in blocks: each block's angles, then the sine and cosine
// kernels over the whole block (one loop of plain arithmetic, which the compiler vectorises:
// two lanes with SSE2, four with AVX2, chosen at run time as in contact/linear_batch.hpp), then
// portable::sin_cos itself for any angle the kernels alone do not serve, then the turns. Every
// operation is the one rotate_about_body_axis() does, in its order, with no contraction into
// FMA (-ffp-contract=off): free_rotation()'s bits, on any processor.
constexpr std::size_t turn_block = 8;

YUXI_ALWAYS_INLINE void turn_bodies(ClumpBody* bodies, std::size_t n, int axis, double h) {
  for (std::size_t start = 0; start < n; start += turn_block) {
    const std::size_t m = std::min(turn_block, n - start);
    ClumpBody* b = bodies + start;
    double zeta[turn_block] = {}, s[turn_block], c[turn_block];
    for (std::size_t j = 0; j < m; ++j) {
      const double moment = axis == 1   ? b[j].inertia.x
                            : axis == 2 ? b[j].inertia.y
                                        : b[j].inertia.z;
      zeta[j] = turn_half_angle(b[j].q, b[j].p, axis, moment, h);
    }
    for (std::size_t j = 0; j < turn_block; ++j) {
      s[j] = portable::detail::sin_kernel(zeta[j]);
      c[j] = portable::detail::cos_kernel(zeta[j]);
    }
    for (std::size_t j = 0; j < m; ++j) {
      if (!portable::takes_kernels_alone(zeta[j])) {
        const portable::SinCos t = portable::sin_cos(zeta[j]);
        s[j] = t.sin, c[j] = t.cos;
      }
      turn_by(b[j].q, b[j].p, axis, s[j], c[j]);
    }
  }
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
__attribute__((target("avx2"))) void turn_bodies_avx2(ClumpBody* bodies, std::size_t n, int axis,
                                                      double h) {
  turn_bodies(bodies, n, axis, h);
}
#endif

void turn_all_bodies(std::vector<ClumpBody>& bodies, int axis, double h) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) return turn_bodies_avx2(bodies.data(), bodies.size(), axis, h);
#endif
  turn_bodies(bodies.data(), bodies.size(), axis, h);
}

// to = from, component by component. A whole Vec3 just computed in registers and assigned
// goes through the stack as one 16-byte and one 8-byte copy, whose 16-byte load waits for the
// two 8-byte stores it spans (a failed store-to-load forward, about a dozen cycles): in
// place_members that stall took 40 % of the loop.
YUXI_ALWAYS_INLINE void store(Vec3& to, const Vec3& from) {
  to.x = from.x, to.y = from.y, to.z = from.z;
}

} // namespace

Vec3 ClumpBody::angular_velocity() const {
  return lab_angular_velocity(q, p, inertia);
}

Vec3 ClumpBody::arm(std::size_t k) const {
  return to_lab(q, members[k]);
}

void ClumpBody::set_angular_velocity(const Vec3& omega) {
  const Vec3 w_body = to_body(q, omega);
  p = rotor_momentum(q, {inertia.x * w_body.x, inertia.y * w_body.y, inertia.z * w_body.z});
}

double ClumpBody::smallest_contact_mass() const {
  // A normal push on member k at p = b + r n has the lever p x n = b x n, whose component along
  // principal axis a is at most |e_a x b|, b's distance from that axis.
  double turning = 0.0;
  for (const Vec3& b : members) {
    const double about_x = b.y * b.y + b.z * b.z, about_y = b.x * b.x + b.z * b.z,
                 about_z = b.x * b.x + b.y * b.y;
    turning = std::max(turning, about_x / inertia.x + about_y / inertia.y + about_z / inertia.z);
  }
  return 1.0 / (1.0 / mass + turning);
}

PlacedClump make_clump(const ClumpShape& shape, double density, std::uint8_t material,
                       GlobalId first_id, const Vec3& x, const Quaternion& orientation,
                       const Vec3& v, const Vec3& omega) {
  if (!(density > 0.0) || !std::isfinite(density))
    throw std::invalid_argument(
        fmt::format("clump '{}': density {} is not positive and finite", shape.name, density));
  if (!is_unit(orientation))
    throw std::invalid_argument(
        fmt::format("clump '{}': the orientation is not a unit quaternion", shape.name));
  PlacedClump out;
  ClumpBody& b = out.body;
  b.id = first_id;
  b.mass = density * shape.volume;
  b.inertia = density * shape.inertia_per_density;
  b.x = x;
  b.v = v;
  b.q = orientation;
  b.set_angular_velocity(omega);
  b.material = material;
  double summed = 0.0; // the members' volumes, each whole (overlaps counted again)
  for (const SphereMember& m : shape.members) {
    b.members.push_back(m.centre);
    b.radii.push_back(m.radius);
    summed += m.radius * m.radius * m.radius;
  }
  for (std::size_t k = 0; k < b.members.size(); ++k) {
    ParticleSpec m;
    const Vec3 r = b.arm(k);
    m.position = x + r;
    m.velocity = v + cross(omega, r);
    m.angular_velocity = omega;
    m.radius = b.radii[k];
    m.mass = b.mass * (b.radii[k] * b.radii[k] * b.radii[k] / summed);
    m.material = material;
    m.spins = false; // (its rotation is its clump's)
    m.body = first_id;
    m.contact_mass = b.mass;
    out.members.push_back(m);
  }
  return out;
}

ParticleSpec lone_member_as_sphere(const PlacedClump& clump) {
  ParticleSpec p = clump.members.front();
  p.body = -1;
  p.spins = true;
  p.contact_mass = 0.0;
  return p;
}

void ClumpBodies::set(std::vector<ClumpBody> bodies) {
  for (std::size_t b = 1; b < bodies.size(); ++b)
    if (!(bodies[b - 1].id < bodies[b].id))
      throw std::invalid_argument(
          fmt::format("clump ids must ascend and differ (clump {} follows clump {})", bodies[b].id,
                      bodies[b - 1].id));
  bodies_ = std::move(bodies);
  forget_layout();
}

void ClumpBodies::index_members(const ParticleStore& s) {
  first_.assign(bodies_.size() + 1, 0);
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    first_[b + 1] = first_[b] + bodies_[b].members.size();
  constexpr auto missing = static_cast<std::uint32_t>(-1);
  member_index_.assign(first_.back(), missing);
  for (std::size_t i = 0; i < s.n_owned(); ++i) {
    if (s.body[i] < 0) continue;
    const std::size_t b = body_of(s, i);
    const auto k = static_cast<std::size_t>(s.gid[i] - bodies_[b].id);
    if (k >= bodies_[b].members.size() || member_index_[first_[b] + k] != missing)
      throw std::invalid_argument(
          fmt::format("grain {} is no member of clump {} ({} members, ids {} on)", s.gid[i],
                      bodies_[b].id, bodies_[b].members.size(), bodies_[b].id));
    member_index_[first_[b] + k] = static_cast<std::uint32_t>(i);
  }
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    for (std::size_t k = 0; k < bodies_[b].members.size(); ++k)
      if (member_index_[first_[b] + k] == missing)
        throw std::invalid_argument(fmt::format("member {} (grain {}) of clump {} is missing", k,
                                                bodies_[b].id + static_cast<GlobalId>(k),
                                                bodies_[b].id));
}

std::size_t ClumpBodies::body_of(const ParticleStore& s, std::size_t i) const {
  const GlobalId id = s.body[i];
  const auto at = std::lower_bound(bodies_.begin(), bodies_.end(), id,
                                   [](const ClumpBody& b, GlobalId g) { return b.id < g; });
  if (at == bodies_.end() || at->id != id)
    throw std::invalid_argument(
        fmt::format("grain {} names clump {}, which does not exist", s.gid[i], id));
  return static_cast<std::size_t>(at - bodies_.begin());
}

void ClumpBodies::forget_layout() {
  first_.clear(); // (until index_members)
  member_index_.clear();
  arms_ready_ = false;
}

void ClumpBodies::kick_drift(double dt, const Vec3& g_periodic, double& gravity_work) {
  const double half_dt = 0.5 * dt;
  arms_ready_ = false; // (the bodies turn)
  for (ClumpBody& b : bodies_) {
    half_kick(b, half_dt);
    b.x.x += b.v.x * dt, b.x.y += b.v.y * dt, b.x.z += b.v.z * dt;
    gravity_work += b.mass * dot(g_periodic, b.v) * dt; // M g_p . dX
  }
  // NO_SQUISH's free rotation (free_rotation(): R3 R2 R1 R2 R3), each turn for every body
  // before the next (turn_all_bodies()).
  turn_all_bodies(bodies_, 3, half_dt);
  turn_all_bodies(bodies_, 2, half_dt);
  turn_all_bodies(bodies_, 1, dt);
  turn_all_bodies(bodies_, 2, half_dt);
  turn_all_bodies(bodies_, 3, half_dt);
}

void ClumpBodies::final_kick(double dt) {
  for (ClumpBody& b : bodies_) half_kick(b, 0.5 * dt);
}

bool ClumpBodies::place_members(ParticleStore& s, double limit2, double* moved2) {
  if (!moved2 && arms_ready_) { // (velocities only, by the arms of the drift)
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      const ClumpBody& body = bodies_[b];
      const Vec3 omega = body.angular_velocity();
      for (std::size_t k = 0; k < body.members.size(); ++k) {
        const std::size_t m = first_[b] + k, i = member_index_[m];
        store(s.v[i], body.v + cross(omega, arms_[m]));
        store(s.w[i], omega);
      }
    }
    return false;
  }
  bool moved_far = false;
  if (moved2) arms_.resize(first_.back());
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const ClumpBody& body = bodies_[b];
    const Vec3 omega = body.angular_velocity();
    const Rotation turn = rotation_of(body.q); // (arm(k)'s bits, built once)
    for (std::size_t k = 0; k < body.members.size(); ++k) {
      const std::size_t m = first_[b] + k, i = member_index_[m];
      const Vec3 r = turn * body.members[k];
      store(s.v[i], body.v + cross(omega, r));
      store(s.w[i], omega);
      if (!moved2) continue;
      store(arms_[m], r);
      const Vec3 x = body.x + r;
      *moved2 = std::max(*moved2, norm2(x - s.x[i]));
      store(s.x[i], x);
      moved_far |= !(norm2(s.x[i] - s.x_build[i]) <= limit2); // NaN too
    }
  }
  if (moved2) arms_ready_ = true;
  return moved_far;
}

void ClumpBodies::gather_forces(const ParticleStore& s, const Vec3& gravity) {
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    ClumpBody& body = bodies_[b];
    Vec3 force = body.mass * gravity, torque;
    // Member k's arm: kept from the placing, or made anew (the same bits).
    const auto gather = [&](const auto& arm) {
      for (std::size_t k = 0; k < body.members.size(); ++k) {
        const std::size_t m = first_[b] + k, i = member_index_[m];
        force += s.f[i];
        torque += cross(arm(k, m), s.f[i]) + s.torque[i];
      }
    };
    if (arms_ready_) {
      gather([&](std::size_t, std::size_t m) { return arms_[m]; });
    } else {
      const Rotation turn = rotation_of(body.q); // (arm(k)'s bits, built once)
      gather([&](std::size_t k, std::size_t) { return turn * body.members[k]; });
    }
    body.force = force;
    body.torque = torque;
  }
}

void ClumpBodies::add_energies(EnergyBooks& e, const Vec3& g_potential) const {
  for (const ClumpBody& b : bodies_) {
    e.translational += translational_energy(b.mass, b.v);
    e.rotational += rotor_energy(b.q, b.p, b.inertia);
    e.gravitational -= b.mass * dot(g_potential, b.x);
    ++e.grains;
  }
}

double ClumpBodies::mechanical_energy(std::size_t b, const Vec3& g_potential) const {
  const ClumpBody& body = bodies_[b];
  return rigid_mechanical_energy(body.mass, body.x, body.v, body.q, body.p, body.inertia,
                                 g_potential);
}

void ClumpBodies::add(ClumpBody body) {
  if (!bodies_.empty() && !(bodies_.back().id < body.id))
    throw std::invalid_argument(fmt::format("a new clump's id {} is not above the last one's ({})",
                                            body.id, bodies_.back().id));
  bodies_.push_back(std::move(body));
  forget_layout();
}

std::vector<std::size_t> ClumpBodies::remove(const ParticleStore& s,
                                             std::span<const std::size_t> bodies) {
  std::vector<GlobalId> ids; // ascending, as the bodies
  for (const std::size_t b : bodies) ids.push_back(bodies_[b].id);
  std::vector<std::size_t> members;
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    if (s.body[i] >= 0 && std::binary_search(ids.begin(), ids.end(), s.body[i]))
      members.push_back(i);
  std::vector<ClumpBody> kept;
  kept.reserve(bodies_.size() - bodies.size());
  std::size_t next = 0;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (next < bodies.size() && bodies[next] == b) {
      ++next;
      continue;
    }
    kept.push_back(std::move(bodies_[b]));
  }
  set(std::move(kept));
  return members;
}

void ClumpBodies::wrap(const Box& box, ParticleStore& s) {
  std::vector<Vec3> shift(bodies_.size());
  bool any = false;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const Vec3 wrapped = box.wrap(bodies_[b].x);
    if (wrapped == bodies_[b].x) continue;
    shift[b] = wrapped - bodies_[b].x;
    bodies_[b].x = wrapped;
    any = true;
  }
  if (!any) return;
  // (found by their ids: escapes, outlets and inserts may have moved them since the last build)
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    if (s.body[i] >= 0) s.x[i] += shift[find(s.body[i])];
}

namespace {

// A body's fields in the order of a checkpoint, saved (Body const) or loaded.
template <class Archive, class Body> void transfer(Archive& ar, Body& b) {
  ar.value(b.id);
  ar.value(b.mass);
  ar.value(b.inertia);
  ar.value(b.x);
  ar.value(b.v);
  ar.value(b.q);
  ar.value(b.p);
  ar.value(b.force);
  ar.value(b.torque);
  ar.value(b.material);
  ar.value(b.shape);
  ar.vector(b.members);
  ar.vector(b.radii);
}

} // namespace

double ClumpBody::span() const {
  double r = 0.0;
  for (std::size_t k = 0; k < members.size(); ++k) r = std::max(r, norm(members[k]) + radii[k]);
  return 2.0 * r;
}

std::pair<double, GlobalId> ClumpBodies::widest() const {
  std::pair<double, GlobalId> widest{0.0, -1};
  for (const ClumpBody& b : bodies_)
    if (const double span = b.span(); span > widest.first) widest = {span, b.id};
  return widest;
}

double ClumpBodies::reach() const {
  double r = 0.0;
  for (const ClumpBody& b : bodies_) r = std::max(r, clump_reach(b.members));
  return r;
}

std::size_t ClumpBodies::find(GlobalId id) const {
  const auto at = std::lower_bound(bodies_.begin(), bodies_.end(), id,
                                   [](const ClumpBody& b, GlobalId g) { return b.id < g; });
  return at != bodies_.end() && at->id == id ? static_cast<std::size_t>(at - bodies_.begin())
                                             : bodies_.size();
}

std::string ClumpBodies::pack(std::size_t b) const {
  ArchiveWriter ar;
  transfer(ar, bodies_[b]);
  return ar.data();
}

void ClumpBodies::take_out(std::size_t b) {
  bodies_.erase(bodies_.begin() + static_cast<std::ptrdiff_t>(b));
  forget_layout();
}

void ClumpBodies::take_in(const std::string& bytes, const Vec3& shift) {
  ArchiveReader ar(bytes);
  ClumpBody body;
  transfer(ar, body);
  body.x += shift;
  const auto at = std::lower_bound(bodies_.begin(), bodies_.end(), body.id,
                                   [](const ClumpBody& b, GlobalId g) { return b.id < g; });
  if (at != bodies_.end() && at->id == body.id)
    throw std::logic_error(fmt::format("clump {} arrived twice", body.id));
  bodies_.insert(at, std::move(body));
  forget_layout();
}

void ClumpBodies::rename_shapes(const std::vector<std::string>& saved,
                                const std::vector<std::string>& now) {
  for (ClumpBody& b : bodies_) {
    if (b.shape < 0) continue;
    const auto k = static_cast<std::size_t>(b.shape);
    const auto at = k < saved.size() ? std::find(now.begin(), now.end(), saved[k]) : now.end();
    b.shape = at == now.end() ? -1 : static_cast<std::int32_t>(at - now.begin());
  }
}

void ClumpBodies::save(ArchiveWriter& ar) const {
  ar.value(static_cast<std::uint64_t>(bodies_.size()));
  for (const ClumpBody& b : bodies_) transfer(ar, b);
}

void ClumpBodies::load(ArchiveReader& ar) {
  std::uint64_t n = 0;
  ar.value(n);
  ar.check_room(n, sizeof(ClumpBody::id) + sizeof(double) * 26);
  std::vector<ClumpBody> bodies(n);
  for (ClumpBody& b : bodies) {
    transfer(ar, b);
    bool ok = std::isfinite(b.mass) && b.mass > 0 && is_finite(b.inertia) && b.inertia.x > 0 &&
              b.inertia.y > 0 && b.inertia.z > 0 && is_unit(b.q) && std::isfinite(b.p.w) &&
              is_finite(b.p.vector()) && is_finite(b.x) && is_finite(b.v) && is_finite(b.force) &&
              is_finite(b.torque) && !b.members.empty() && b.members.size() == b.radii.size() &&
              b.id >= 0 && b.shape >= -1;
    for (std::size_t k = 0; ok && k < b.members.size(); ++k)
      ok = is_finite(b.members[k]) && b.radii[k] > 0 && std::isfinite(b.radii[k]);
    if (!ok)
      throw std::invalid_argument(fmt::format(
          "clump {} of the checkpoint is impossible (mass, moments, members, orientation or a "
          "non-finite value)",
          b.id));
  }
  set(std::move(bodies));
}

} // namespace yuxi

#include "sim/contact_compute.hpp"

namespace yuxi {

ContactCompute::ContactCompute(AnyContactLaw law, Backend backend)
    : law_(std::move(law)), forces_(std::visit(
                                [backend](const auto& l) -> Forces {
                                  return ContactForces(l, backend != Backend::cpu_reference);
                                },
                                law_)),
      history_(std::visit([](auto& f) -> ContactStates* { return &f.history; }, forces_)),
      n_materials_(std::visit([](const auto& l) { return l.coeffs.n_materials(); }, law_)) {}

bool ContactCompute::has_pair(std::uint8_t a, std::uint8_t b) const {
  return std::visit([&](const auto& l) { return l.coeffs.has(a, b); }, law_);
}

const std::vector<WallLoad>& ContactCompute::plane_loads() const {
  return std::visit([](const auto& f) -> const std::vector<WallLoad>& { return f.plane_loads; },
                    forces_);
}

void ContactCompute::set_plane_loads(std::vector<WallLoad> loads) {
  std::visit([&](auto& f) { f.plane_loads = std::move(loads); }, forces_);
}

const DeepStarts& ContactCompute::deep_starts() const {
  return std::visit([](const auto& f) -> const DeepStarts& { return f.deep_starts; }, forces_);
}

void ContactCompute::compute_pairs(ParticleView s, const NeighborList& list, const NearPairs* near,
                                   const std::vector<PlaneWall>& planes, double t, double dt,
                                   bool particles_still, PairSet set) {
  std::visit(
      [&](auto& f) {
        f.compute(s, list, near, planes, t, dt, particles_still, tally_, record_, set);
      },
      forces_);
}

void ContactCompute::compute_shaped(ParticleView s, const NeighborList& list,
                                    const NearWallElements* near,
                                    const std::vector<ShapedWall>& shaped, double t, double dt,
                                    std::vector<WallLoad>& loads,
                                    std::vector<ElementForce>& elements) {
  std::visit(
      [&](auto& f) {
        f.compute_walls(s, list, near, shaped, t, dt, tally_, loads, elements, record_);
      },
      forces_);
}

void ContactCompute::size_for(const NeighborList& list, std::vector<ElementForce>& elements) {
  std::visit([&](auto& f) { f.size_for(list, elements); }, forces_);
}

} // namespace yuxi

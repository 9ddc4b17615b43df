// Balls hashed on cubic cells whose edge is at least the largest contact distance, to ask
// whether a new ball overlaps any of them: only those of the 27 cells around its centre can.
// For placing grains ([[fill]], [[insert]]); the simulation's own cells serve the contacts.
#pragma once

#include "core/vec3.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace yuxi {

class BallHash {
public:
  // `edge`: at least the largest sum of two radii asked about.
  explicit BallHash(double edge) : edge_(edge) {}
  void add(const Vec3& x, double r) {
    balls_.push_back({x, r});
    cells_[key(x)].push_back(static_cast<std::uint32_t>(balls_.size() - 1));
  }
  bool overlaps(const Vec3& x, double r) const {
    return visit_overlapping(x, r, [](std::size_t) { return true; });
  }
  // The first ball added that overlaps the ball (x, r), or `none`.
  static constexpr std::size_t none = ~std::size_t{0};
  std::size_t first_overlapping(const Vec3& x, double r) const {
    std::size_t first = none;
    visit_overlapping(x, r, [&](std::size_t b) {
      first = std::min(first, b);
      return false;
    });
    return first;
  }
  const Vec3& position(std::size_t b) const { return balls_[b].x; }
  double radius(std::size_t b) const { return balls_[b].r; }

private:
  // Calls `f(b)` for each ball b overlapping (x, r) until it returns true; returns whether it
  // did.
  template <class F> bool visit_overlapping(const Vec3& x, double r, F&& f) const {
    const auto c = cell(x);
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j)
        for (int k = -1; k <= 1; ++k) {
          const auto it = cells_.find(pack(c[0] + i, c[1] + j, c[2] + k));
          if (it == cells_.end()) continue;
          for (std::uint32_t b : it->second) {
            const double reach = r + balls_[b].r;
            if (norm2(balls_[b].x - x) < reach * reach && f(std::size_t{b})) return true;
          }
        }
    return false;
  }
  struct Ball {
    Vec3 x;
    double r;
  };
  std::array<std::int64_t, 3> cell(const Vec3& x) const {
    return {static_cast<std::int64_t>(std::floor(x.x / edge_)),
            static_cast<std::int64_t>(std::floor(x.y / edge_)),
            static_cast<std::int64_t>(std::floor(x.z / edge_))};
  }
  static std::uint64_t pack(std::int64_t i, std::int64_t j, std::int64_t k) {
    const auto u = [](std::int64_t v) {
      return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1FFFFF;
    };
    return u(i) | (u(j) << 21) | (u(k) << 42);
  }
  std::uint64_t key(const Vec3& x) const {
    const auto c = cell(x);
    return pack(c[0], c[1], c[2]);
  }
  double edge_;
  std::vector<Ball> balls_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

} // namespace yuxi

// The pair loop's first pass (core/overlap_scan.hpp) selects exactly the listed pairs that
// overlap, and exactly the non-overlapping ones that still hold a contact state, in list order,
// against a direct test of |x_i - x_j| < a_i + a_j (passing over the partners from a limit
// on, where asked); and the neighbour list's row index agrees with its row offsets.
#include "core/neighbor_list.hpp"
#include "core/overlap_scan.hpp"
#include "core/random.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace yuxi {
namespace {

struct Pairs {
  std::vector<Vec3> x;
  std::vector<double> radius;
  std::vector<std::uint32_t> row, partner, slot;
};

// n particles in a small cube, every pair listed; each pair holds a state with probability 1/2.
Pairs random_pairs(std::size_t n, std::uint64_t seed) {
  Random rng(seed);
  Pairs s;
  for (std::size_t i = 0; i < n; ++i) {
    s.x.push_back({rng.uniform(0.0, 4.0), rng.uniform(0.0, 4.0), rng.uniform(0.0, 4.0)});
    s.radius.push_back(rng.uniform(0.3, 0.9));
  }
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = i + 1; j < n; ++j) {
      s.row.push_back(i);
      s.partner.push_back(j);
      s.slot.push_back(rng.uniform(0.0, 1.0) < 0.5 ? 7u : no_slot);
    }
  return s;
}

TEST(OverlapScan, SelectsTheOverlappingPairsAndTheParted) {
  const Pairs s = random_pairs(60, 11);
  const auto n = static_cast<std::uint32_t>(s.row.size());
  std::size_t overlapping = 0, parted = 0;
  // Chunks of several sizes, starting anywhere; every partner, or only those below 40 (the
  // others standing for ghosts, whose pairs are scanned apart).
  for (const std::uint32_t limit : {every_partner, 40u})
    for (const std::uint32_t chunk : {1u, 3u, 64u, 256u, n})
      for (std::uint32_t begin = 0; begin < n; begin += chunk) {
        const std::uint32_t end = std::min(begin + chunk, n);
        std::vector<std::uint32_t> touching(end - begin), gone(end - begin);
        const OverlapScanCounts c =
            scan_overlaps(s.x.data(), s.radius.data(), s.row.data(), s.partner.data(),
                          s.slot.data(), begin, end, limit, touching.data(), gone.data());
        std::vector<std::uint32_t> want_touching, want_gone;
        for (std::uint32_t p = begin; p < end; ++p) {
          if (s.partner[p] >= limit) continue;
          const double dist = norm(s.x[s.row[p]] - s.x[s.partner[p]]);
          const bool overlaps = dist < s.radius[s.row[p]] + s.radius[s.partner[p]];
          if (overlaps) want_touching.push_back(p);
          if (!overlaps && s.slot[p] != no_slot) want_gone.push_back(p);
        }
        ASSERT_EQ(c.touching, want_touching.size());
        ASSERT_EQ(c.parted, want_gone.size());
        touching.resize(c.touching);
        gone.resize(c.parted);
        EXPECT_EQ(touching, want_touching);
        EXPECT_EQ(gone, want_gone);
        if (chunk == n && limit == every_partner) overlapping = c.touching, parted = c.parted;
      }
  // The sample has both kinds, and near misses.
  EXPECT_GT(overlapping, 50u);
  EXPECT_GT(parted, 50u);
  EXPECT_LT(overlapping, n / 2);
}

TEST(OverlapScan, ExactContactIsNotOverlap) {
  // Two spheres at exactly the sum of their radii (representable: 0.5 + 0.25 = 0.75).
  const std::vector<Vec3> x{{0.0, 0.0, 0.0}, {0.75, 0.0, 0.0}, {0.0, 0.7, 0.0}};
  const std::vector<double> radius{0.5, 0.25, 0.25};
  const std::vector<std::uint32_t> row{0, 0}, partner{1, 2}, slot{3, no_slot};
  std::uint32_t touching[2], gone[2];
  const std::uint32_t begin = 0, end = 2;
  const OverlapScanCounts c = scan_overlaps(x.data(), radius.data(), row.data(), partner.data(),
                                            slot.data(), begin, end, every_partner, touching, gone);
  ASSERT_EQ(c.touching, 1u);
  EXPECT_EQ(touching[0], 1u); // 0.7 < 0.75
  ASSERT_EQ(c.parted, 1u);
  EXPECT_EQ(gone[0], 0u); // touching exactly: apart, and it held a state
}

TEST(OverlapScan, RowIndexMatchesOffsets) {
  NeighborList list;
  list.offsets = {0, 2, 2, 5, 6};
  list.partners = {1, 2, 3, 0, 1, 2};
  list.index_rows();
  EXPECT_EQ(list.rows, (std::vector<std::uint32_t>{0, 0, 2, 2, 2, 3}));
}

} // namespace
} // namespace yuxi

// Linked cells: the half-shell stencil and binning.
#include "core/cell_grid.hpp"
#include "core/random.hpp"

#include <gtest/gtest.h>
#include <set>

namespace yuxi {
namespace {

TEST(CellGrid, HalfShellAndItsMirrorCoverAllNeighboursOnce) {
  std::set<std::array<int, 3>> seen;
  for (const auto& o : CellGrid::half_shell()) seen.insert(o);
  for (const auto& o : CellGrid::lower_shell()) seen.insert(o);
  EXPECT_EQ(seen.size(), 26u);
  EXPECT_FALSE(seen.contains({0, 0, 0}));
  for (const auto& o : CellGrid::half_shell()) {
    const std::array<int, 3> mirror{-o[0], -o[1], -o[2]};
    EXPECT_EQ(std::count(CellGrid::half_shell().begin(), CellGrid::half_shell().end(), mirror), 0)
        << "a half shell must not contain an offset and its mirror";
  }
}

TEST(CellGrid, EdgesAreAtLeastTheRequestedSizeAndBinningIsComplete) {
  Box box{{0, 0, 0}, {10, 7, 5}};
  CellGrid grid(box, 2.2);
  for (int a = 0; a < 3; ++a) EXPECT_GE(grid.edge()[a], 2.2);
  EXPECT_EQ(grid.dims()[0], 4 + 2); // floor(10 / 2.2) = 4 inner cells plus two halo layers

  Random rng(7);
  std::vector<Vec3> x(500);
  for (auto& p : x) p = {rng.uniform(-3, 13), rng.uniform(-3, 10), rng.uniform(-3, 8)};
  grid.bin(x);
  std::size_t total = 0;
  for (std::size_t c = 0; c < grid.n_cells(); ++c) {
    for (auto i : grid.particles_in(c)) EXPECT_EQ(grid.cell_index(x[i]), c);
    total += grid.particles_in(c).size();
  }
  EXPECT_EQ(total, x.size());
}

} // namespace
} // namespace yuxi

// The automatic rank layout: the factorisation of the rank count with the least sub-domain
// surface, over the region the particles occupy.
#include "domain/decomposition.hpp"

#include <gtest/gtest.h>

namespace yuxi {
namespace {

TEST(Layout, LeastSurfaceFactorisation) {
  using L = std::array<int, 3>;
  EXPECT_EQ(choose_layout({40, 20, 80}, 2), (L{1, 1, 2}));
  EXPECT_EQ(choose_layout({40, 20, 37.3}, 2), (L{2, 1, 1})); // the chute's bed: cut along x
  EXPECT_EQ(choose_layout({10, 10, 10}, 8), (L{2, 2, 2}));
  EXPECT_EQ(choose_layout({72, 72, 150}, 16, {0, 0, 1}), (L{4, 4, 1})); // the paper's layout
  EXPECT_THROW(choose_layout({10, 10, 10}, 6, {4, 0, 0}), std::invalid_argument);
}

} // namespace
} // namespace yuxi

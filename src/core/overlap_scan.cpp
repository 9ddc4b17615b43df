#include "core/overlap_scan.hpp"

namespace yuxi {
namespace {

// The scan over the pairs pair(begin), ..., pair(end - 1).
template <class PairAt>
OverlapScanCounts scan(const Vec3* x, const double* radius, const std::uint32_t* row,
                       const std::uint32_t* partner, const std::uint32_t* slot, PairAt pair,
                       std::uint32_t begin, std::uint32_t end, std::uint32_t* touching,
                       std::uint32_t* parted) {
  OverlapScanCounts c;
  for (std::uint32_t q = begin; q < end; ++q) {
    const std::uint32_t p = pair(q), i = row[p], j = partner[p];
    const Vec3 d = x[i] - x[j];
    const double touch = radius[i] + radius[j];
    const std::uint32_t hit = norm2(d) < touch * touch;
    touching[c.touching] = p;
    c.touching += hit;
    parted[c.parted] = p;
    c.parted += (hit ^ 1u) & static_cast<std::uint32_t>(slot[p] != no_slot);
  }
  return c;
}

} // namespace

OverlapScanCounts scan_overlaps(const Vec3* x, const double* radius, const std::uint32_t* row,
                                const std::uint32_t* partner, const std::uint32_t* slot,
                                std::uint32_t begin, std::uint32_t end, std::uint32_t* touching,
                                std::uint32_t* parted) {
  return scan(
      x, radius, row, partner, slot, [](std::uint32_t q) { return q; }, begin, end, touching,
      parted);
}

OverlapScanCounts scan_overlaps(const Vec3* x, const double* radius, const std::uint32_t* row,
                                const std::uint32_t* partner, const std::uint32_t* slot,
                                const std::uint32_t* pairs, std::uint32_t begin, std::uint32_t end,
                                std::uint32_t* touching, std::uint32_t* parted) {
  return scan(
      x, radius, row, partner, slot, [pairs](std::uint32_t q) { return pairs[q]; }, begin, end,
      touching, parted);
}

} // namespace yuxi

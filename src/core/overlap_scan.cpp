#include "core/overlap_scan.hpp"

namespace yuxi {
namespace {

// The scan over the pairs pair(begin), ..., pair(end - 1).
// (`limited`: whether partner_limit can pass any pair over; the scan of the near pairs, and of
// a list without its ghost pairs apart, skips the test.)
template <bool limited, class PairAt>
OverlapScanCounts scan(const Vec3* x, const double* radius, const std::uint32_t* row,
                       const std::uint32_t* partner, const std::uint32_t* slot, PairAt pair,
                       std::uint32_t begin, std::uint32_t end, std::uint32_t partner_limit,
                       std::uint32_t* touching, std::uint32_t* parted) {
  OverlapScanCounts c;
  for (std::uint32_t q = begin; q < end; ++q) {
    const std::uint32_t p = pair(q), i = row[p], j = partner[p];
    const Vec3 d = x[i] - x[j];
    const double touch = radius[i] + radius[j];
    const std::uint32_t mine = limited ? static_cast<std::uint32_t>(j < partner_limit) : 1u;
    const std::uint32_t close = norm2(d) < touch * touch;
    touching[c.touching] = p;
    c.touching += close & mine;
    parted[c.parted] = p;
    c.parted += (close ^ 1u) & mine & static_cast<std::uint32_t>(slot[p] != no_slot);
  }
  return c;
}

} // namespace

OverlapScanCounts scan_overlaps(const Vec3* x, const double* radius, const std::uint32_t* row,
                                const std::uint32_t* partner, const std::uint32_t* slot,
                                std::uint32_t begin, std::uint32_t end, std::uint32_t partner_limit,
                                std::uint32_t* touching, std::uint32_t* parted) {
  const auto at = [](std::uint32_t q) { return q; };
  return partner_limit == every_partner
             ? scan<false>(x, radius, row, partner, slot, at, begin, end, 0, touching, parted)
             : scan<true>(x, radius, row, partner, slot, at, begin, end, partner_limit, touching,
                          parted);
}

OverlapScanCounts scan_overlaps(const Vec3* x, const double* radius, const std::uint32_t* row,
                                const std::uint32_t* partner, const std::uint32_t* slot,
                                const std::uint32_t* pairs, std::uint32_t begin, std::uint32_t end,
                                std::uint32_t* touching, std::uint32_t* parted) {
  return scan<false>(
      x, radius, row, partner, slot, [pairs](std::uint32_t q) { return pairs[q]; }, begin, end, 0,
      touching, parted);
}

} // namespace yuxi

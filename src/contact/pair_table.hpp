// Coefficients for every pair of materials, symmetric: table(a, b) == table(b, a).
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

namespace yuxi {

template <class Coeffs> class PairTable {
public:
  explicit PairTable(std::size_t n_materials = 0)
      : n_(n_materials), entries_(n_materials * n_materials) {}

  std::size_t n_materials() const { return n_; }
  void set(std::size_t a, std::size_t b, const Coeffs& c) {
    check(a, b);
    entries_[a * n_ + b] = c;
    entries_[b * n_ + a] = c;
  }
  bool has(std::size_t a, std::size_t b) const { return a < n_ && b < n_ && entries_[a * n_ + b]; }
  // Unchecked lookup for the hot loop; has(a, b) must hold.
  const Coeffs& operator()(std::size_t a, std::size_t b) const { return *entries_[a * n_ + b]; }

private:
  void check(std::size_t a, std::size_t b) const {
    if (a >= n_ || b >= n_) throw std::out_of_range("material index out of range");
  }
  std::size_t n_;
  std::vector<std::optional<Coeffs>> entries_;
};

} // namespace yuxi

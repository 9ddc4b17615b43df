// erf(x) from a table: quintic Hermite interpolation between nodes 1/128 apart on [0, 6], each
// holding erf, its first and its second derivative (erf(x) = +-1 to double precision beyond:
// erfc(6) = 2e-17). Within 1e-15 of std::erf everywhere (a test), at a few multiplications.
//
// Why by hand: coarse-graining integrates a Gaussian along every contact's branch at every grid
// point it reaches (docs/coarse-graining.md, "Contact stress"), two erf a point; the C library's
// erf is the larger part of a sample's cost, and no packaged library offers a faster one at
// full precision.
#pragma once

namespace yuxi::analysis {

double table_erf(double x);

} // namespace yuxi::analysis

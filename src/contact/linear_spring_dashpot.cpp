#include "contact/linear_spring_dashpot.hpp"

#include "core/units.hpp"

#include <limits>

namespace yuxi {

double LinearSpringDashpot::contact_time(const Coeffs& c, double m_eff, double, double) {
  const double w2 = c.k_n / m_eff - 0.25 * c.gamma_n * c.gamma_n;
  return w2 > 0 ? pi / std::sqrt(w2) : std::numeric_limits<double>::infinity();
}

double LinearSpringDashpot::release(const Coeffs&, State& s) {
  const double e = yuxi::release(s.tangential) + yuxi::release(s.rolling);
  s = State{};
  return e;
}

} // namespace yuxi

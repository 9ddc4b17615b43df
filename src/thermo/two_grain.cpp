#include "thermo/two_grain.hpp"

#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <utility>

namespace yuxi::thermo {

Transport Transport::elastic(double d, double epsilon) {
  Transport t;
  t.gear_n = [d, epsilon](const ContactVariables& c) { return heaviside(c.delta / d, epsilon); };
  t.gear_t = t.gear_n;
  return t;
}

Transport Transport::example(const ExampleModel& p, double k, double m_eff, double d) {
  const ExampleCoefficients c = ExampleCoefficients::of(p, k, m_eff, d);
  Transport t;
  // (38) [TEXT]: G_n = G_t = gear Theta(delta/d), elasticity switched on only during overlap.
  t.gear_n = [c](const ContactVariables& v) { return c.gearbox(v.delta); };
  t.gear_t = t.gear_n;
  // (39) [RECON-L]: eta_n = eta_t, in the relaxation channel (it excites w_R head-on, Fig. 3(d)).
  const Coefficient viscosity = [c](const ContactVariables& v) { return c.viscosity(v.delta); };
  if (c.viscosity_to_heat) {
    t.eta_n_heat = t.eta_t_heat = viscosity;
  } else {
    t.eta_n_relax = t.eta_t_relax = viscosity;
  }
  // (40) [RECON-M]: lambda_t^T = Lambda sqrt(w_R), the granular-temperature-driven relaxation.
  if (c.lambda > 0) {
    t.lambda_t_heat = [c](const ContactVariables& v) { return c.relaxation_rate(v.w_relax); };
  }
  t.tau = c.tau; // (22)
  return t;
}

TwoGrainSetup TwoGrainSetup::example(const ExampleModel& p, double v0, double impact_parameter) {
  TwoGrainSetup s;
  s.xi = p.xi;
  s.epsilon = p.epsilon;
  s.v0 = v0;
  s.impact_parameter = impact_parameter;
  s.transport = Transport::example(p, s.k, s.m1 * s.m2 / (s.m1 + s.m2), s.a1 + s.a2);
  return s;
}

namespace {

namespace odeint = boost::numeric::odeint;

// The state. The two grains move freely apart from their contact, so the centre of mass moves
// at constant velocity and the state holds the relative motion in polar coordinates about grain
// 2: r_1 - r_2 = (d - delta)(cos angle, sin angle), v_1 - v_2 = vn n + vt t with n = (cos, sin),
// t = (-sin, cos) (section 2.1). Keeping delta itself as a variable keeps it accurate to the
// tolerance even when it is a millionth of d. Then the contact's variables: u_n, u_t, w_R, the
// heat Q and the part of Q released by the yield limit.
enum Slot : std::size_t { delta_, angle_, vn_, vt_, un_, ut_, relax_, heat_, yield_heat_, slots_ };
using State = std::array<double, slots_>;

// stick: inside the stable region (35); slip: on its boundary (the yield limit (41) active);
// apart: after separation, the contact is gone and only w_R decays.
enum class Phase { stick, slip, apart };

double value(const Coefficient& c, const ContactVariables& v) {
  return c ? c(v) : 0.0;
}

// What a state implies: spring forces, contact forces and the time derivatives.
struct Point {
  State x{};    // the physical state
  State rate{}; // its time derivative
  double pi_n = 0, pi_t = 0, fn = 0, ft = 0;
  double ut_rate_free = 0; // the rate of u_t by (31) alone, without the yield flow
};

class Collision {
public:
  explicit Collision(const TwoGrainSetup& s)
      : s_(s), d_(s.a1 + s.a2), mass_(s.m1 + s.m2), m_eff_(s.m1 * s.m2 / mass_),
        v_com_((s.m1 - s.m2) * s.v0 / mass_), sharp_(s.epsilon <= 0),
        delta_stop_(sharp_ ? 0.0 : -s.tail_widths * s.epsilon * d_) {
    validate();
    const double v = 2 * s.v0;
    const double length = std::pow(5 * m_eff_ * v * v / (4 * s.k), 0.4); // Hertz overlap
    const double energy = 0.5 * m_eff_ * v * v;
    scale_ = {length, length / d_, v, v, length, length, energy, energy, energy};
  }

  TwoGrainResult run();

private:
  using Stepper =
      decltype(odeint::make_dense_output(1.0, 1.0, odeint::runge_kutta_dopri5<State>()));

  struct Rhs {
    const Collision* c;
    void operator()(const State& y, State& dydt, double /*t*/) const {
      const Point p = c->evaluate(c->physical(y));
      for (std::size_t i = 0; i < slots_; ++i) dydt[i] = p.rate[i] / c->scale_[i];
    }
  };

  void validate() const {
    const auto positive = [](double x) { return x > 0 && std::isfinite(x); };
    if (!positive(s_.m1) || !positive(s_.m2) || !positive(s_.a1) || !positive(s_.a2) ||
        !positive(s_.k) || !positive(s_.xi) || !positive(s_.v0))
      throw std::invalid_argument("two-grain collision: masses, radii, k, xi and v0 must be > 0");
    if (!(std::abs(s_.impact_parameter) < 1))
      throw std::invalid_argument("two-grain collision: |impact parameter| must be < 1");
    if (!(s_.epsilon >= 0) || !(s_.tail_widths > 0) || !positive(s_.rel_tol) ||
        !positive(s_.abs_tol) || !(s_.after_separation >= 0) || !(s_.sample_interval >= 0))
      throw std::invalid_argument("two-grain collision: bad epsilon, tolerance or time");
    if (!s_.transport.gear_n || !s_.transport.gear_t)
      throw std::invalid_argument("two-grain collision: the gearbox G_n, G_t must be given");
    if (!(s_.transport.tau > 0))
      throw std::invalid_argument("two-grain collision: tau must be > 0");
  }

  State physical(const State& y) const {
    State x;
    for (std::size_t i = 0; i < slots_; ++i) x[i] = y[i] * scale_[i];
    return x;
  }
  State scaled(const State& x) const {
    State y;
    for (std::size_t i = 0; i < slots_; ++i) y[i] = x[i] / scale_[i];
    return y;
  }

  Point evaluate(const State& x) const;
  double elastic(const State& x) const {
    return elastic_energy(s_.k, s_.xi, x[un_], x[ut_] * x[ut_]); // (19)
  }
  double kinetic(const State& x) const {
    return 0.5 * mass_ * v_com_ * v_com_ + 0.5 * m_eff_ * (x[vn_] * x[vn_] + x[vt_] * x[vt_]);
  }
  double total(const State& x) const { return kinetic(x) + elastic(x) + x[relax_] + x[heat_]; }

  // The event functions, each positive once its event has happened.
  double separated(const State& x) const { return delta_stop_ - x[delta_]; }
  double beyond_yield(const State& x) const {
    return std::abs(x[ut_]) - yield_limit(s_.xi, x[un_]); // (35)
  }
  double sticks(const Point& p) const { // the yield flow would point outwards
    return slip_sign_ * (p.rate[ut_] - p.ut_rate_free);
  }

  State initial_state() const;
  Point at(const Stepper& st, double t) const {
    State y;
    st.calc_state(t, y);
    return evaluate(physical(y));
  }
  template <class F> static double locate(const F& f, double lo, double hi);
  template <class F> void track_max(const Stepper& st, double t0, double t1, double& best, F q);
  void observe(const Stepper& st, double t0, double t1);
  void check(const State& x);
  void sample(double t, const Point& p);
  void move_elastic_to_heat(State& x, double ut_new, bool yield);

  const TwoGrainSetup& s_;
  const double d_, mass_, m_eff_, v_com_;
  const bool sharp_;
  const double delta_stop_; // separation: delta below this (0 with a sharp step)
  State scale_;             // natural scale of each slot
  Phase phase_ = Phase::stick;
  double slip_sign_ = 1; // sign of u_t while sliding
  double next_sample_ = 0;
  double touch_ = NAN, release_ = NAN; // delta crossing 0 upwards and downwards
  double previous_mechanical_ = 0, previous_heat_ = 0;
  TwoGrainResult r_{};
};

Point Collision::evaluate(const State& x) const {
  Point p;
  p.x = x;
  const double delta = x[delta_], vn = x[vn_], vt = x[vt_], un = x[un_], ut = x[ut_];
  const double w_relax = x[relax_];
  const double r = d_ - delta;
  // Relative motion of the grains in polar coordinates (section 2.1, eqs. (2)-(4)):
  // delta' = -vn, m*(vn' - vt^2/r) = fn, m*(vt' + vn vt/r) = ft.
  p.rate[delta_] = -vn;
  p.rate[angle_] = vt / r;
  const double decay = w_relax / s_.transport.tau; // I = w_R / tau (22) [RECON-H]
  if (phase_ == Phase::apart) {
    p.rate[vn_] = vt * vt / r;
    p.rate[vt_] = -vn * vt / r;
    p.rate[relax_] = -decay;
    p.rate[heat_] = decay;
    return p;
  }
  // With a sharp step the contact phase uses the coefficients' values inside the contact, also
  // at delta = 0 itself and beyond it within the step that overshoots separation, which is
  // located afterwards: the right-hand side stays continuous through touching and separation.
  const double delta_seen =
      sharp_ ? std::max(delta, d_ * std::numeric_limits<double>::min()) : delta;
  const ContactVariables v{delta_seen, un, ut, w_relax};
  const Transport& tr = s_.transport;
  const double gear_n = tr.gear_n(v), gear_t = tr.gear_t(v);
  const double eta_n_heat = value(tr.eta_n_heat, v), eta_n_relax = value(tr.eta_n_relax, v);
  const double eta_t_heat = value(tr.eta_t_heat, v), eta_t_relax = value(tr.eta_t_relax, v);
  const double lambda_n_heat = value(tr.lambda_n_heat, v);
  const double lambda_n_relax = value(tr.lambda_n_relax, v);
  const double lambda_t_heat = value(tr.lambda_t_heat, v);
  const double lambda_t_relax = value(tr.lambda_t_relax, v);

  p.pi_n = normal_spring_force(s_.k, s_.xi, un, ut * ut);                         // (20) [RECON-H]
  p.pi_t = -tangential_stiffness(s_.k, s_.xi, un) * ut;                           // (21) [RECON-H]
  p.fn = gear_n * p.pi_n - (eta_n_heat + eta_n_relax) * vn;                       // (28) [RECON-H]
  p.ft = gear_t * p.pi_t - (eta_t_heat + eta_t_relax) * vt;                       // (29) [RECON-H]
  const double un_rate = gear_n * vn + (lambda_n_heat + lambda_n_relax) * p.pi_n; // (30)
  p.ut_rate_free = gear_t * vt + (lambda_t_heat + lambda_t_relax) * p.pi_t;       // (31)
  double ut_rate = p.ut_rate_free, yield_power = 0;
  if (phase_ == Phase::slip) {
    // (41) with lambda_Y -> infinity [EXT]: u_t = sign sqrt(2 xi)(-u_n) stays on the boundary
    // of (35); the yield flow Y = u_t' - (31) dissipates pi_t Y >= 0 into heat.
    ut_rate = -slip_sign_ * std::sqrt(2 * s_.xi) * un_rate;
    yield_power = p.pi_t * (ut_rate - p.ut_rate_free);
  }
  p.rate[vn_] = p.fn / m_eff_ + vt * vt / r;
  p.rate[vt_] = p.ft / m_eff_ - vn * vt / r;
  p.rate[un_] = un_rate;
  p.rate[ut_] = ut_rate;
  // (32) [RECON-H]: w_R' = eta_n^R vn^2 + eta_t^R vt^2 + lambda_n^R pi_n^2 + lambda_t^R pi_t^2 - I
  p.rate[relax_] = eta_n_relax * vn * vn + eta_t_relax * vt * vt +
                   lambda_n_relax * p.pi_n * p.pi_n + lambda_t_relax * p.pi_t * p.pi_t - decay;
  // (33) [RECON-H]: R = eta_n^T vn^2 + eta_t^T vt^2 + lambda_n^T pi_n^2 + lambda_t^T pi_t^2 + I,
  // plus the yield flow's dissipation.
  p.rate[heat_] = eta_n_heat * vn * vn + eta_t_heat * vt * vt + lambda_n_heat * p.pi_n * p.pi_n +
                  lambda_t_heat * p.pi_t * p.pi_t + decay + yield_power;
  p.rate[yield_heat_] = yield_power;
  return p;
}

State Collision::initial_state() const {
  // Grain 1 on the left moving at +v0 along x, grain 2 on the right at -v0, the centres offset
  // by b d across; the state starts where the contact starts.
  State x{};
  x[delta_] = delta_stop_;
  const double distance = d_ - delta_stop_, offset = s_.impact_parameter * d_;
  const double nx = -std::sqrt(distance * distance - offset * offset) / distance;
  const double ny = offset / distance;
  x[angle_] = std::atan2(ny, nx);
  x[vn_] = 2 * s_.v0 * nx;                                    // v = (2 v0, 0); vn = v.n
  x[vt_] = -2 * s_.v0 * ny;                                   // vt = v.t, t = (-ny, nx)
  x[un_] = -heaviside_primitive(delta_stop_, d_, s_.epsilon); // u_n = -Phi(delta) (section 5)
  return x;
}

// Bisection for an event function f on [lo, hi] with f(hi) > 0: the earliest time found with
// f > 0, as close to the crossing as doubles allow.
template <class F> double Collision::locate(const F& f, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = lo + 0.5 * (hi - lo);
    if (mid <= lo || mid >= hi) break;
    (f(mid) > 0 ? hi : lo) = mid;
  }
  return hi;
}

// Raises best to the maximum of q over [t0, t1] on the dense output: a coarse grid, then a
// golden-section search around its largest point.
template <class F>
void Collision::track_max(const Stepper& st, double t0, double t1, double& best, F q) {
  constexpr int n = 4;
  std::array<double, n + 1> value{};
  int top = 0;
  for (int i = 0; i <= n; ++i) {
    value[i] = q(at(st, i == n ? t1 : t0 + (t1 - t0) * i / n));
    if (value[i] > value[top]) top = i;
  }
  // Refine near the running maximum only; the slack covers a peak just inside a step whose
  // start point was the previous step's best.
  if (value[top] < best - 1e-6 * std::abs(best)) return;
  best = std::max(best, value[top]);
  double lo = t0 + (t1 - t0) * std::max(top - 1, 0) / n;
  double hi = top + 1 >= n ? t1 : t0 + (t1 - t0) * (top + 1) / n;
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
  double qa = q(at(st, a)), qb = q(at(st, b));
  for (int i = 0; i < 40; ++i) {
    if (qa > qb) {
      hi = b, b = a, qb = qa;
      a = hi - g * (hi - lo), qa = q(at(st, a));
    } else {
      lo = a, a = b, qa = qb;
      b = lo + g * (hi - lo), qb = q(at(st, b));
    }
  }
  best = std::max({best, qa, qb});
}

// Everything read off the dense output of the step [t0, t1] (t1 may be an event's time).
void Collision::observe(const Stepper& st, double t0, double t1) {
  if (s_.sample_interval > 0) {
    while (next_sample_ <= t1) {
      sample(next_sample_, at(st, next_sample_));
      next_sample_ += s_.sample_interval;
    }
  }
  track_max(st, t0, t1, r_.max_overlap, [](const Point& p) { return p.x[delta_]; });
  track_max(st, t0, t1, r_.peak_force, [](const Point& p) { return p.fn; });
  track_max(st, t0, t1, r_.peak_w_relax, [](const Point& p) { return p.x[relax_]; });
  const auto delta = [&](double t) { return at(st, t).x[delta_]; };
  const double d0 = delta(t0), d1 = delta(t1);
  if (d0 <= 0 && d1 > 0 && std::isnan(touch_)) touch_ = locate(delta, t0, t1);
  if (d0 > 0 && d1 <= 0) release_ = locate([&](double t) { return -delta(t); }, t0, t1);
}

// The books after each step or event.
void Collision::check(const State& x) {
  const double e = total(x), mechanical = kinetic(x) + elastic(x);
  r_.max_energy_error =
      std::max(r_.max_energy_error, std::abs(e - r_.initial_energy) / r_.initial_energy);
  r_.max_mechanical_rise = std::max(r_.max_mechanical_rise, mechanical - previous_mechanical_);
  const double round_off = 8 * std::numeric_limits<double>::epsilon() * r_.initial_energy;
  if (x[heat_] < previous_heat_ - round_off) r_.heat_monotone = false;
  r_.min_w_relax = std::min(r_.min_w_relax, x[relax_]);
  const double limit = yield_limit(s_.xi, x[un_]);
  if (limit > 0) r_.max_yield_ratio = std::max(r_.max_yield_ratio, std::abs(x[ut_]) / limit);
  previous_mechanical_ = mechanical;
  previous_heat_ = x[heat_];
}

void Collision::sample(double t, const Point& p) {
  const State& x = p.x;
  const double r = d_ - x[delta_], nx = std::cos(x[angle_]), ny = std::sin(x[angle_]);
  const double com = v_com_ * t, w1 = s_.m2 / mass_, w2 = s_.m1 / mass_;
  const double w_el = elastic(x), kin = kinetic(x);
  r_.series.push_back({t, com + w1 * r * nx, w1 * r * ny, com - w2 * r * nx, -w2 * r * ny,
                       x[delta_], p.fn, p.ft, x[un_], x[ut_], w_el, kin, kin + w_el, x[relax_],
                       x[heat_], kin + w_el + x[relax_] + x[heat_]});
}

// Sets u_t to ut_new and books the elastic energy released into heat.
void Collision::move_elastic_to_heat(State& x, double ut_new, bool yield) {
  const double before = elastic(x);
  x[ut_] = ut_new;
  const double released = before - elastic(x);
  x[heat_] += released;
  if (yield) x[yield_heat_] += released;
}

TwoGrainResult Collision::run() {
  State x = initial_state();
  const double vn_impact = x[vn_], vt_impact = x[vt_];
  r_.initial_energy = total(x);
  r_.max_overlap = r_.peak_force = r_.peak_w_relax = -std::numeric_limits<double>::infinity();
  r_.min_w_relax = 0;
  r_.heat_monotone = true;
  r_.restitution = r_.tangential_restitution = NAN;
  previous_mechanical_ = kinetic(x) + elastic(x);
  if (s_.sample_interval > 0) {
    sample(0, evaluate(x));
    next_sample_ = s_.sample_interval;
  }

  const double v = 2 * s_.v0;
  Stepper st =
      odeint::make_dense_output(s_.abs_tol, s_.rel_tol, odeint::runge_kutta_dopri5<State>());
  st.initialize(scaled(x), 0.0, 1e-3 * scale_[delta_] / v);
  const Rhs rhs{this};
  double t_final = std::numeric_limits<double>::infinity();
  constexpr int max_steps = 2'000'000, max_switches = 10'000;
  enum class Event { none, separation, yield, stick, end };

  for (;;) {
    if (++r_.steps > max_steps)
      throw std::runtime_error("two-grain collision: no separation after the maximum of steps");
    const std::pair<double, double> step = st.do_step(rhs);
    const double t0 = step.first, t1 = step.second;
    Event event = Event::none;
    double t_event = t1;
    const auto earlier = [&](Event e, double t) {
      if (event == Event::none || t < t_event) event = e, t_event = t;
    };
    const Point end = evaluate(physical(st.current_state()));
    if (phase_ == Phase::apart) {
      if (t1 >= t_final) earlier(Event::end, t_final);
    } else {
      const auto when = [&](auto f) {
        return locate([&](double t) { return f(at(st, t)); }, t0, t1);
      };
      if (separated(end.x) > 0)
        earlier(Event::separation, when([&](const Point& p) { return separated(p.x); }));
      if (s_.yield && phase_ == Phase::stick && beyond_yield(end.x) > 0)
        earlier(Event::yield, when([&](const Point& p) { return beyond_yield(p.x); }));
      if (s_.yield && phase_ == Phase::slip && sticks(end) > 0)
        earlier(Event::stick, when([&](const Point& p) { return sticks(p); }));
    }
    observe(st, t0, t_event);
    x = event == Event::none ? end.x : at(st, t_event).x;
    if (!std::all_of(x.begin(), x.end(), [](double c) { return std::isfinite(c); }))
      throw std::runtime_error("two-grain collision: the state became non-finite (outside the "
                               "stable region (35) the normal spring force diverges)");

    bool restart = event != Event::none;
    switch (event) {
    case Event::none:
      if (phase_ == Phase::slip && beyond_yield(x) > 0) { // round-off off the boundary
        move_elastic_to_heat(x, slip_sign_ * yield_limit(s_.xi, x[un_]), true);
        restart = true;
      }
      break;
    case Event::yield: { // (41): onto the boundary of (35), the released energy to heat
      const double rate = evaluate(x).ut_rate_free;
      slip_sign_ = x[ut_] != 0 ? std::copysign(1.0, x[ut_]) : std::copysign(1.0, rate);
      move_elastic_to_heat(x, slip_sign_ * yield_limit(s_.xi, x[un_]), true);
      phase_ = Phase::slip;
      ++r_.slip_phases;
      break;
    }
    case Event::stick:
      phase_ = Phase::stick;
      break;
    case Event::separation: {
      r_.restitution = -x[vn_] / vn_impact;
      if (s_.impact_parameter != 0) r_.tangential_restitution = x[vt_] / vt_impact;
      // The contact is gone: u_n -> 0 (exactly so with a sharp step), u_t reset, the elastic
      // energy left (none with a sharp step, ~e^{-2 n} with a soft tail) booked as heat.
      x[heat_] += elastic(x);
      x[un_] = x[ut_] = 0;
      phase_ = Phase::apart;
      t_final = t_event + s_.after_separation;
      if (s_.after_separation <= 0) event = Event::end;
      break;
    }
    case Event::end:
      break;
    }
    if (r_.slip_phases > max_switches)
      throw std::runtime_error("two-grain collision: stick and slip alternate without end");
    check(x); // after the event's mapping: the books and the invariants of the state as it goes on
    if (event == Event::end) {
      if (s_.sample_interval > 0 && (r_.series.empty() || r_.series.back().t < t_event))
        sample(t_event, evaluate(x));
      break;
    }
    if (restart) {
      st.initialize(scaled(x), t_event, st.current_time_step());
    }
  }

  r_.contact_time = release_ - touch_;
  r_.final_heat = x[heat_];
  r_.final_w_relax = x[relax_];
  r_.yield_heat = x[yield_heat_];
  return r_;
}

} // namespace

TwoGrainResult collide(const TwoGrainSetup& s) {
  return Collision(s).run();
}

} // namespace yuxi::thermo

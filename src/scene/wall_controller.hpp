// A wall whose velocity is controlled while the run goes (a piston, a confining plate): its
// controller is told, after every force evaluation, the force the grains put on the wall along
// its axis, and answers the wall's speed along that axis for the next step. The engine keeps the
// wall's displacement (checkpointed); the controller itself holds nothing the run must keep, so
// a controller with state (one written in Python) saves its own.
#pragma once

#include <algorithm>
#include <cmath>

namespace yuxi {

class WallController {
public:
  virtual ~WallController() = default;
  // `resisting`: the grains' force on the wall against its axis (positive when they push the
  // wall back) [force]; t the time [time]. Returns the speed along the axis [length/time].
  virtual double speed(double resisting, double t) = 0;
};

// Proportional control towards a target force: speed = gain (target - resisting), at most
// max_speed either way. With no grain touching, the wall advances at min(gain target,
// max_speed); it halts where the grains push back with the target force.
class ForceServo final : public WallController {
public:
  ForceServo(double target, double gain, double max_speed)
      : target_(target), gain_(gain), max_speed_(max_speed) {}
  double speed(double resisting, double) override {
    return std::clamp(gain_ * (target_ - resisting), -max_speed_, max_speed_);
  }
  double target() const { return target_; }
  double gain() const { return gain_; }
  double max_speed() const { return max_speed_; }

private:
  double target_, gain_, max_speed_;
};

// A speed set from outside between steps (`controlled = true` in a scene; the Python API's
// callbacks set it): it holds until set again.
class HeldSpeed final : public WallController {
public:
  explicit HeldSpeed(double speed = 0.0) : speed_(speed) {}
  double speed(double, double) override { return speed_; }
  void set(double speed) { speed_ = speed; }
  double held() const { return speed_; }

private:
  double speed_;
};

} // namespace yuxi

/* T-BAGS DEM toolkit: the force servo of the plate fix, a pure function of the force error.
   Velocity of the plate along its inward normal (toward the particles):
     v = clamp(kp e + ki (I + e dt), -vmax, vmax),   e = F_target - F_measured,
   with I += e dt only while unsaturated (anti-windup). On a packing of stiffness K the force
   responds as dF/dt = K v, so the closed loop is s^2 + kp K s + ki K = 0: proportional control
   alone already has no static error (the plant integrates), ki removes the lag under a steady
   disturbance (dilation while shearing). Choose kp K dt << 1 (stable step) and damping ratio
   zeta = (kp/2) sqrt(K/ki) >= 1 (no overshoot); zeta grows with load since K does, so tune at
   the lowest load. The fix moves the plate at vmax while it touches nothing. */
#ifndef TBAGS_LAW_SERVO_H
#define TBAGS_LAW_SERVO_H

#include <cmath>

namespace tbags {
namespace servo {

struct Controller {
  double kp = 0.0;          // m/s per N
  double ki = 0.0;          // m/s per N s
  double vmax = 0.0;        // m/s
  double integral = 0.0;    // N s

  // velocity toward the particles for a force error e = target - measured; saturated is set
  // when the speed limit is active
  double velocity(double e, double dt, bool &saturated)
  {
    const double trial = integral + e * dt;
    double v = kp * e + ki * trial;
    saturated = std::fabs(v) > vmax;
    if (saturated) v = std::copysign(vmax, v);
    else integral = trial;
    return v;
  }
};

}    // namespace servo
}    // namespace tbags
#endif

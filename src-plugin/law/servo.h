/* T-BAGS DEM toolkit: the force servo of the plate fix, a pure function of the force error.
   Velocity of the plate along its inward normal (toward the particles):
     v = clamp(kp e + ki (I + e dt), -vmax, vmax),   e = F_target - F_f,
   with I += e dt only while unsaturated (anti-windup) and F_f the measured force, low-pass
   filtered with time constant tau (F_f += alpha (F - F_f), alpha = dt / (tau + dt); tau = 0: no
   filter).
   Elastic loop: on a packing of stiffness K the force responds as dF/dt = K v, so the closed loop
   is s^2 + kp K s + ki K = 0: proportional control alone already has no static error (the plant
   integrates), ki removes the lag under a steady disturbance (dilation while shearing). Choose
   zeta = (kp/2) sqrt(K/ki) >= 1 (no overshoot); zeta grows with load since K does, so tune at
   the lowest load.
   The filter keeps the plate from following force noise at the scale of a few steps (contacts
   that make and break, a collapse at a slip event); keep tau well below the elastic loop's
   1 / (kp K). */
#ifndef TBAGS_LAW_SERVO_H
#define TBAGS_LAW_SERVO_H

#include <cmath>

namespace tbags {
namespace servo {

struct Controller {
  double kp = 0.0;          // m/s per N
  double ki = 0.0;          // m/s per N s
  double vmax = 0.0;        // m/s
  double tau = 0.0;         // s, time constant of the force filter (0: none)
  double integral = 0.0;    // N s
  double filtered = 0.0;    // N, the filtered force F_f
  bool primed = false;      // F_f holds a measurement (else the next one starts it)

  double alpha(double dt) const { return dt / (tau + dt); }

  // the filtered force after a new measurement F
  double measure(double F, double dt)
  {
    filtered = primed ? filtered + alpha(dt) * (F - filtered) : F;
    primed = true;
    return filtered;
  }

  // velocity toward the particles for a force error e = target - filtered force; saturated is
  // set when the speed limit is active
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

// Chatter of a force signal: the part that alternates from one step to the next with a steady
// phase (the signature of contacts at the edge of the time step's numerical stability). Each step
// gives c_n = (-1)^n (F_n - 2 F_{n-1} + F_{n-2}) / 4 for a 3-vector F, = A exactly for
// F = F_0 + A (-1)^n; A is the length of c's running mean over about 1 / RATE steps, beside the
// running mean of |F|. The sign makes the mean coherent: a steady alternation adds up, while a
// smooth force, white noise or the impacts of grains landing (no fixed phase) average out (white
// noise of amplitude s gives about s sqrt(RATE / 2), 0.02 s).
struct Chatter {
  static constexpr double RATE = 1e-3;    // weight of a new step in the running means
  double prev[2][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  long count = 0;               // steps seen since the last reset
  double mean[3] = {0.0, 0.0, 0.0};    // running mean of c
  double amplitude = 0.0;       // |mean| (force units)
  double magnitude = 0.0;       // running mean of |F|

  void add(const double f[3])
  {
    if (count >= 2) {
      const double sign = (count % 2) ? -0.25 : 0.25;
      const double w = count < 1.0 / RATE ? 1.0 / (count - 1.0) : RATE;
      double m2 = 0.0;
      for (int k = 0; k < 3; k++) {
        const double c = sign * (f[k] - 2.0 * prev[1][k] + prev[0][k]);
        mean[k] += w * (c - mean[k]);
        m2 += mean[k] * mean[k];
      }
      amplitude = std::sqrt(m2);
      magnitude += w * (std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]) - magnitude);
    }
    for (int k = 0; k < 3; k++) {
      prev[0][k] = prev[1][k];
      prev[1][k] = f[k];
    }
    count++;
  }
  // averaged over a full window and alternating by more than fraction of the force, or of a
  // reference force if that is larger (a servo's target: light first contacts do not count)
  bool chattering(double fraction, double reference = 0.0) const
  {
    return count > 1.0 / RATE && amplitude > fraction * std::fmax(magnitude, reference) &&
        magnitude > 0.0;
  }
  void reset()
  {
    count = 0;
    amplitude = magnitude = 0.0;
    mean[0] = mean[1] = mean[2] = 0.0;
  }
};

}    // namespace servo
}    // namespace tbags
#endif

/* T-BAGS DEM toolkit: the Hertz-Mindlin contact law with restitution damping, Coulomb friction
   and rolling resistance. Pure header, no LAMMPS types: used by pair gran/hertz/rolling and
   fix wall/gran/servo (a plate is a particle of infinite radius and mass), unit-tested alone.

   Per contact (overlap d = r_i + r_j - |x_i - x_j| > 0, unit normal n from j to i):
     a    = sqrt(R* d)                         contact radius, R* = R_i R_j / (R_i + R_j)
     F_ne = 4/3 E* a d                          Hertz
     F_nd = -2 sqrt(5/6) beta sqrt(S_n m*) v_n  S_n = 2 E* a,  beta = -ln e / sqrt(ln^2 e + pi^2)
     F_t  = -k_t xi - eta_t v_t                 k_t = 8 G* a,  eta_t = 2 sqrt(5/6) beta sqrt(k_t m*)
            |F_t| <= mu |F_n|, xi the elastic tangential displacement (history, rotated onto the
            tangent plane, reset to the Coulomb limit on sliding)
     rolling EPSD: M_r = R* n x F_r, F_r = -k_s xi_r with k_s = 2.25 mu_r^2 S_n so that the
            rolling stiffness is k_r = 2.25 mu_r^2 S_n R*^2 (Ai et al. 2011), |M_r| <= mu_r R* |F_n|
     rolling CDT:  |M_r| = mu_r R* |F_n| against the relative rolling velocity
   Algorithm order and conventions follow LAMMPS pair granular (hertz/material, mindlin,
   coeff_restitution, rolling sds) so the two agree to round-off where the physics is the same.
*/
#ifndef TBAGS_LAW_CONTACT_LAW_H
#define TBAGS_LAW_CONTACT_LAW_H

#include "vec3.h"

#include <cmath>

namespace tbags {
namespace contact {

enum Rolling : int { ROLLING_NONE = 0, ROLLING_EPSD = 1, ROLLING_CDT = 2 };

// history doubles per contact: tangential displacement (3) and, for EPSD, rolling displacement (3)
inline int history_size(int rolling) { return rolling == ROLLING_EPSD ? 6 : 3; }

// relative threshold below which the history is not rotated onto the tangent plane (as stock)
constexpr double FRAME_EPS = 1e-10;
constexpr double PI = 3.14159265358979323846;

// Hertz-Mindlin effective moduli of two materials (Young's modulus E, Poisson's ratio nu)
inline double mix_E(double E1, double nu1, double E2, double nu2)
{
  return 1.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2);
}
inline double mix_G(double E1, double nu1, double E2, double nu2)
{
  return 1.0 / (2.0 * (2.0 - nu1) * (1.0 + nu1) / E1 + 2.0 * (2.0 - nu2) * (1.0 + nu2) / E2);
}

// damping ratio for a coefficient of restitution e in (0,1]: -ln e / sqrt(ln^2 e + pi^2) >= 0
inline double restitution_beta(double e)
{
  const double l = std::log(e);
  return -l / std::sqrt(l * l + PI * PI);
}

// Per type-pair constants, computed once; the inner loop reads only this struct.
struct Params {
  double kn = 0.0;     // 4/3 E*          F_ne = kn a d
  double kt = 0.0;     // 8 G*            k_t  = kt a
  double cn = 0.0;     // 2 sqrt(5/6) beta sqrt(2 E*): eta_n = cn sqrt(m* a)
  double ct = 0.0;     // 2 sqrt(5/6) beta sqrt(8 G*): eta_t = ct sqrt(m* a)
  double mu = 0.0;     // sliding friction coefficient
  double mur = 0.0;    // rolling friction coefficient (dimensionless)
  double krs = 0.0;    // EPSD: k_s = krs a, krs = 2.25 mu_r^2 2 E*
  int rolling = ROLLING_NONE;
  bool limit_damping = false;    // clip attractive total normal force to zero
};

inline Params make_params(double Estar, double Gstar, double e, double mu, double mur, int rolling,
                          bool limit_damping)
{
  Params p;
  const double b = 2.0 * std::sqrt(5.0 / 6.0) * restitution_beta(e);
  p.kn = 4.0 / 3.0 * Estar;
  p.kt = 8.0 * Gstar;
  p.cn = b * std::sqrt(2.0 * Estar);
  p.ct = b * std::sqrt(8.0 * Gstar);
  p.mu = mu;
  p.mur = mur;
  p.rolling = mur > 0.0 ? rolling : ROLLING_NONE;
  p.krs = 2.25 * mur * mur * 2.0 * Estar;
  p.limit_damping = limit_damping;
  return p;
}

// Geometry and kinematics of one contact, as pointers into the caller's arrays.
struct Contact {
  const double *dx;             // x_i - x_j (for a wall: from the wall's contact point to x_i)
  double rsq;                   // |dx|^2
  double radsum;                // r_i + r_j (wall: r_i)
  double reff;                  // R*
  double meff;                  // m*
  double radi, radj;            // radii for the surface velocity (wall: radj = 0)
  const double *vi, *vj;        // velocities (wall: its velocity)
  const double *wi, *wj;        // angular velocities (wall: zero vector)
  bool wall;                    // torque lever arm r_i (wall) or r - d/2 (pair), as stock
  double dt;
};

struct Result {
  double f[3];                  // force on i (j gets -f)
  double ti[3], tj[3];          // torques on i and j
  double fn;                    // total normal force (elastic + damping), signed
  double fne;                   // elastic (Hertz) normal force
  double delta;                 // overlap
  double r;                     // centre distance
  double fs[3];                 // tangential force on i
  double fr[3];                 // rolling pseudo-force: M_r(i) = R* n x fr
};

inline bool touching(double rsq, double radsum) { return rsq < radsum * radsum; }

#if defined(__GNUC__)
#define TBAGS_INLINE inline __attribute__((always_inline))
#else
#define TBAGS_INLINE inline
#endif

// One contact, with the rolling model fixed at compile time (the styles dispatch once per
// compute). hist: 3 (or 6 for EPSD) doubles, updated when update is true.
template <int ROLL>
TBAGS_INLINE void compute_t(const Params &p, const Contact &c, double *hist, bool update, Result &o)
{
  using namespace vec;
  const double r = std::sqrt(c.rsq);
  const double rinv = 1.0 / r;
  const double delta = c.radsum - r;
  const double n[3] = {c.dx[0] * rinv, c.dx[1] * rinv, c.dx[2] * rinv};

  // relative velocity at the contact point
  double vr[3];
  sub(c.vi, c.vj, vr);
  const double vnnr = dot(vr, n);
  const double wr[3] = {c.radi * c.wi[0] + c.radj * c.wj[0], c.radi * c.wi[1] + c.radj * c.wj[1],
                        c.radi * c.wi[2] + c.radj * c.wj[2]};
  double wxn[3];
  cross(wr, n, wxn);
  double vtr[3];
  for (int k = 0; k < 3; k++) vtr[k] = vr[k] - vnnr * n[k] - wxn[k];

  // normal: Hertz + restitution damping
  const double a = std::sqrt(c.reff * delta);
  const double fne = p.kn * a * delta;
  const double sqma = std::sqrt(c.meff * a);
  double fn = fne - p.cn * sqma * vnnr;
  if (p.limit_damping && fn < 0.0) fn = 0.0;
  const double fncrit = std::fabs(fn);

  // tangential: incremental Mindlin spring + damping, Coulomb cap
  const double damp_t = p.ct * sqma;
  const double kts = p.kt * a;
  const double fscrit = p.mu * fncrit;
  if (update) {
    if (std::fabs(dot(hist, n)) * kts > FRAME_EPS * fscrit) rotate_onto_plane(hist, n);
    for (int k = 0; k < 3; k++) hist[k] += c.dt * vtr[k];
  }
  for (int k = 0; k < 3; k++) o.fs[k] = -damp_t * vtr[k] - kts * hist[k];
  const double fs2 = dot(o.fs, o.fs);
  if (fs2 > fscrit * fscrit) {    // sliding: |fs| > mu |F_n| (squares: no sqrt when sticking)
    const double magfs = std::sqrt(fs2);
    if (len(hist) != 0.0) {
      const double s = fscrit / magfs;
      for (int k = 0; k < 3; k++) hist[k] = -(s * o.fs[k] + damp_t * vtr[k]) / kts;
      scale(s, o.fs);
    } else {
      zero(o.fs);
    }
  }

  for (int k = 0; k < 3; k++) o.f[k] = fn * n[k] + o.fs[k];
  double tor[3];
  cross(n, o.fs, tor);
  const double armi = c.wall ? c.radi : c.radi - 0.5 * delta;
  const double armj = c.radj - 0.5 * delta;
  for (int k = 0; k < 3; k++) {
    o.ti[k] = -armi * tor[k];
    o.tj[k] = -armj * tor[k];
  }

  // rolling resistance
  zero(o.fr);
  if (ROLL != ROLLING_NONE && p.rolling != ROLLING_NONE) {
    double relrot[3];
    sub(c.wi, c.wj, relrot);
    double vrl[3];
    cross(relrot, n, vrl);
    scale(c.reff, vrl);
    const double frcrit = p.mur * fncrit;
    if (ROLL == ROLLING_EPSD) {
      double *hr = hist + 3;
      const double ks = p.krs * a;
      if (update) {
        if (std::fabs(dot(hr, n)) * ks > FRAME_EPS * frcrit) rotate_onto_plane(hr, n);
        for (int k = 0; k < 3; k++) hr[k] += c.dt * vrl[k];
      }
      for (int k = 0; k < 3; k++) o.fr[k] = -ks * hr[k];
      const double fr2 = dot(o.fr, o.fr);
      if (fr2 > frcrit * frcrit) {
        const double s = frcrit / std::sqrt(fr2);
        for (int k = 0; k < 3; k++) hr[k] = -s * o.fr[k] / ks;
        scale(s, o.fr);
      }
    } else {    // CDT: constant magnitude against the rolling velocity
      const double vl = len(vrl);
      if (vl > 0.0)
        for (int k = 0; k < 3; k++) o.fr[k] = -frcrit * vrl[k] / vl;
    }
    double troll[3];
    cross(n, o.fr, troll);
    for (int k = 0; k < 3; k++) {
      o.ti[k] += c.reff * troll[k];
      o.tj[k] -= c.reff * troll[k];
    }
  }

  o.fn = fn;
  o.fne = fne;
  o.delta = delta;
  o.r = r;
}

// One contact, rolling model from the parameters (tests, the plate fix, single()).
inline void compute(const Params &p, const Contact &c, double *hist, bool update, Result &o)
{
  if (p.rolling == ROLLING_EPSD) compute_t<ROLLING_EPSD>(p, c, hist, update, o);
  else if (p.rolling == ROLLING_CDT) compute_t<ROLLING_CDT>(p, c, hist, update, o);
  else compute_t<ROLLING_NONE>(p, c, hist, update, o);
}

}    // namespace contact
}    // namespace tbags
#endif

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

// Effective mass m* = m_i m_j / (m_i + m_j) and radius R* = R_i R_j / (R_i + R_j) of a pair,
// with one division for both (q = 1 / ((m_i + m_j)(R_i + R_j))). A frozen particle (fix
// freeze) is one of infinite mass: the caller then takes the other's mass for m*.
TBAGS_INLINE void effective(double mi, double mj, double radi, double radj, double &meff,
                            double &reff)
{
  const double msum = mi + mj, radsum = radi + radj;
  const double q = 1.0 / (msum * radsum);
  meff = mi * mj * radsum * q;
  reff = radi * radj * msum * q;
}

// The same with the frozen-particle rule: a mass given negative marks a particle of fix freeze
// (infinite mass), and m* is then the other particle's mass. Used by the pair's single() and batch.
TBAGS_INLINE void effective_frozen(double mi_signed, double mj_signed, double radi, double radj,
                                   double &meff, double &reff)
{
  const double mi = std::fabs(mi_signed), mj = std::fabs(mj_signed);
  effective(mi, mj, radi, radj, meff, reff);
  meff = mi_signed < 0.0 ? mj : meff;
  meff = mj_signed < 0.0 ? mi : meff;
}

// One contact as values, branch-free (conditions are selects), so that the pair style can run
// it over a batch of contacts in SIMD lanes; every other entry point calls it too.
// In: dx = x_i - x_j (wall: as Contact), vr = v_i - v_j, angular velocities wi, wj.
// In/out: ht (tangential) and hr (rolling, EPSD) history. UPDATE: integrate the history
// (rotate onto the tangent plane, add the increment); the Coulomb reset applies regardless.
// clip: p.limit_damping; rolling acts where p.mur > 0 (make_params: p.rolling is then ROLL).
struct LaneOut {
  vec::V3 f, ti, tj, fs, fr;
  double fn, fne, delta, r;
};

// Normal force of contact_lane: the Hertz force fne plus restitution damping against the normal
// relative velocity vnnr (n . (v_i - v_j)), clipped at zero with clip; sqma = sqrt(m* a).
TBAGS_INLINE double normal_force(const Params &p, bool clip, double meff, double a, double fne,
                                 double vnnr, double &sqma)
{
  sqma = std::sqrt(meff * a);
  const double fn = fne - p.cn * sqma * vnnr;
  return (clip & (fn < 0.0)) ? 0.0 : fn;
}

// Geometry of contact_lane: unit normal n, normal and tangential relative velocity vnnr and vtr
// at the contact point, contact radius a and the Hertz force (o.fne, o.delta, o.r set).
TBAGS_INLINE void contact_geometry(const Params &p, const vec::V3 &dx, double rsq, double radsum,
                                   double reff, double radi, double radj, const vec::V3 &vr,
                                   const vec::V3 &wi, const vec::V3 &wj, LaneOut &o, vec::V3 &n,
                                   double &vnnr, vec::V3 &vtr, double &a)
{
  using namespace vec;
  const double r = std::sqrt(rsq);
  const double rinv = 1.0 / r;
  const double delta = radsum - r;
  n = rinv * dx;

  // relative velocity at the contact point
  vnnr = dot(vr, n);
  const V3 wr = radi * wi + radj * wj;
  vtr = (vr - vnnr * n) - cross(wr, n);

  // normal: Hertz
  a = std::sqrt(reff * delta);
  o.fne = p.kn * a * delta;
  o.delta = delta;
  o.r = r;
}

// Geometry and normal part of contact_lane (below): unit normal n, tangential relative velocity
// vtr at the contact point, contact radius a, sqrt(m* a) and the normal force (o.fn, o.fne,
// o.delta, o.r set).
TBAGS_INLINE void contact_lane_n(const Params &p, bool clip, const vec::V3 &dx, double rsq,
                                 double radsum, double reff, double meff, double radi, double radj,
                                 const vec::V3 &vr, const vec::V3 &wi, const vec::V3 &wj,
                                 LaneOut &o, vec::V3 &n, vec::V3 &vtr, double &a, double &sqma)
{
  double vnnr;
  contact_geometry(p, dx, rsq, radsum, reff, radi, radj, vr, wi, wj, o, n, vnnr, vtr, a);
  o.fn = normal_force(p, clip, meff, a, o.fne, vnnr, sqma);
}

// A spring history h (stiffness k, force cap crit) rotated onto the tangent plane of the unit
// normal n when it has a normal part (relative to the cap, as stock): onto_plane(), or with
// FAST only its series; big (FAST): the tilt was too large for the series, the result is then
// not the law's.
template <bool FAST>
TBAGS_INLINE vec::V3 rotate_history(const vec::V3 &h, const vec::V3 &n, double k, double crit,
                                    bool &big)
{
  using namespace vec;
  const bool rot = std::fabs(dot(h, n)) * k > FRAME_EPS * crit;
  bool small = true;
  const V3 hp = FAST ? onto_plane_series(h, n, small) : onto_plane(h, n);
  big = rot & !small;
  return select(rot, hp, h);
}

// Tangential spring history of contact_lane (UPDATE): rotated onto the tangent plane and
// integrated. FAST (the pair's SIMD loop): the rotation only by the series; returns true when
// the tilt is too large for it (rare): the caller must then redo the contact without FAST,
// from the old history. When it returns false, ht is bit for bit the full law's.
template <bool FAST = false>
TBAGS_INLINE bool tangential_history(const Params &p, const vec::V3 &n, const vec::V3 &vtr,
                                     double a, double fn, double dt, vec::V3 &ht)
{
  bool big = false;    // the rotation needs onto_plane_exact()
  ht = rotate_history<FAST>(ht, n, p.kt * a, p.mu * std::fabs(fn), big) + dt * vtr;
  return FAST && big;
}

// Tangential force of contact_lane from the (integrated) history: incremental Mindlin spring +
// damping, Coulomb cap (the history reset on sliding); o.f, o.ti, o.tj (without rolling), o.fs;
// o.fr zero.
TBAGS_INLINE void tangential_force(const Params &p, const vec::V3 &n, const vec::V3 &vtr,
                                   double a, double sqma, double fn, double delta, double radi,
                                   double radj, bool wall, vec::V3 &ht, LaneOut &o)
{
  using namespace vec;
  const double damp_t = p.ct * sqma;
  const double kts = p.kt * a;
  const double fscrit = p.mu * std::fabs(fn);
  V3 fs = (-damp_t) * vtr - kts * ht;
  const double fs2 = dot(fs, fs);
  // sliding: |fs| > mu |F_n| (squares: no sqrt when sticking)
  const bool slide = fs2 > fscrit * fscrit;
  const bool hnz = dot(ht, ht) != 0.0;    // |xi| != 0
  const double s = fscrit / std::sqrt(fs2);
  // on sliding, xi such that the spring + damping force is the capped force
  ht = select(slide & hnz, (-1.0 / kts) * (s * fs + damp_t * vtr), ht);
  fs = select(slide, hnz ? s * fs : V3{0.0, 0.0, 0.0}, fs);

  o.f = fn * n + fs;
  const V3 tor = cross(n, fs);
  const double armi = wall ? radi : radi - 0.5 * delta;
  const double armj = radj - 0.5 * delta;
  o.ti = (-armi) * tor;
  o.tj = (-armj) * tor;
  o.fr = V3{0.0, 0.0, 0.0};
  o.fs = fs;
}

// Tangential part of contact_lane, from contact_lane_n()'s results: the history (UPDATE) and
// the force; FAST as tangential_history().
template <bool UPDATE, bool FAST = false>
TBAGS_INLINE bool contact_lane_t(const Params &p, const vec::V3 &n, const vec::V3 &vtr, double a,
                                 double sqma, double fn, double delta, double radi, double radj,
                                 bool wall, double dt, vec::V3 &ht, LaneOut &o)
{
  const bool redo = UPDATE && tangential_history<FAST>(p, n, vtr, a, fn, dt, ht);
  tangential_force(p, n, vtr, a, sqma, fn, delta, radi, radj, wall, ht, o);
  return redo;
}

// Normal and tangential part of contact_lane: o without rolling (o.fr zero), and what the
// rolling part needs: the unit normal n and the contact radius a (|F_n| is fabs(o.fn)).
template <bool UPDATE>
TBAGS_INLINE void contact_lane_nt(const Params &p, bool clip, const vec::V3 &dx, double rsq,
                                  double radsum, double reff, double meff, double radi, double radj,
                                  const vec::V3 &vr, const vec::V3 &wi, const vec::V3 &wj, bool wall,
                                  double dt, vec::V3 &ht, LaneOut &o, vec::V3 &n, double &a)
{
  vec::V3 vtr;
  double sqma;
  contact_lane_n(p, clip, dx, rsq, radsum, reff, meff, radi, radj, vr, wi, wj, o, n, vtr, a, sqma);
  contact_lane_t<UPDATE>(p, n, vtr, a, sqma, o.fn, o.delta, radi, radj, wall, dt, ht, o);
}

// EPSD rolling history of contact_lane (UPDATE): rotated onto the tangent plane and integrated
// with the rolling velocity R* (w_i - w_j) x n where rolling acts (p.mur > 0; ALLON: known), else
// left as it was. FAST: as tangential_history() (returns whether the exact rotation was needed
// where rolling acts).
template <bool ALLON = false, bool FAST = false>
TBAGS_INLINE bool rolling_history(const Params &p, const vec::V3 &n, double a, double fncrit,
                                  double reff, const vec::V3 &wi, const vec::V3 &wj, double dt,
                                  vec::V3 &hr)
{
  using namespace vec;
  const bool on = ALLON || p.mur > 0.0;
  const V3 vrl = reff * cross(wi - wj, n);
  bool big = false;
  const V3 h = rotate_history<FAST>(hr, n, p.krs * a, p.mur * fncrit, big) + dt * vrl;
  hr = select(on, h, hr);
  return FAST && (on & big);
}

// Rolling resistance of contact_lane (ROLL not ROLLING_NONE) from n, a, fncrit = |F_n| and, for
// EPSD, the integrated history hr (rolling_history()): the rolling pseudo-force fr and the
// torque troll = R* n x fr (i gets +troll, j -troll); EPSD: the cap |fr| <= mu_r |F_n| (hr
// rescaled to it); CDT: |fr| = mu_r |F_n| against the rolling velocity. on: rolling acts
// (p.mur > 0), else fr and troll are zero and hr is left as it was.
template <int ROLL, bool ALLON = false>
TBAGS_INLINE void rolling_force(const Params &p, const vec::V3 &n, double a, double fncrit,
                                double reff, const vec::V3 &wi, const vec::V3 &wj, vec::V3 &hr,
                                vec::V3 &fr, vec::V3 &troll, bool &on)
{
  using namespace vec;
  on = ALLON || p.mur > 0.0;
  const double frcrit = p.mur * fncrit;
  if (ROLL == ROLLING_EPSD) {
    const double ks = p.krs * a;
    V3 h = hr;
    fr = (-ks) * h;
    const double fr2 = dot(fr, fr);
    const bool cap = fr2 > frcrit * frcrit;
    const double sr = frcrit / std::sqrt(fr2);
    h = select(cap, sr * h, h);    // the spring at the cap: -ks (sr h) = sr fr
    fr = select(cap, sr * fr, fr);
    hr = select(on, h, hr);
  } else {    // CDT: constant magnitude against the rolling velocity
    const V3 vrl = reff * cross(wi - wj, n);
    const double vl = std::sqrt(dot(vrl, vrl));
    fr = select(vl > 0.0, (-frcrit / vl) * vrl, V3{0.0, 0.0, 0.0});
  }
  fr = select(on, fr, V3{0.0, 0.0, 0.0});
  troll = reff * cross(n, fr);
}

// Rolling part of contact_lane: the history (EPSD, UPDATE), then the force; FAST as
// rolling_history().
template <int ROLL, bool UPDATE, bool ALLON = false, bool FAST = false>
TBAGS_INLINE bool contact_lane_roll(const Params &p, const vec::V3 &n, double a, double fncrit,
                                    double reff, const vec::V3 &wi, const vec::V3 &wj, double dt,
                                    vec::V3 &hr, vec::V3 &fr, vec::V3 &troll, bool &on)
{
  const bool redo = ROLL == ROLLING_EPSD && UPDATE &&
      rolling_history<ALLON, FAST>(p, n, a, fncrit, reff, wi, wj, dt, hr);
  rolling_force<ROLL, ALLON>(p, n, a, fncrit, reff, wi, wj, hr, fr, troll, on);
  return redo;
}

// ALLON: the caller knows p.mur > 0 for this contact (rolling acts; no per-lane test)
template <int ROLL, bool UPDATE, bool ALLON = false>
TBAGS_INLINE void contact_lane(const Params &p, bool clip, const vec::V3 &dx, double rsq, double radsum,
                               double reff, double meff, double radi, double radj,
                               const vec::V3 &vr, const vec::V3 &wi, const vec::V3 &wj, bool wall,
                               double dt, vec::V3 &ht, vec::V3 &hr, LaneOut &o)
{
  using namespace vec;
  V3 n;
  double a;
  contact_lane_nt<UPDATE>(p, clip, dx, rsq, radsum, reff, meff, radi, radj, vr, wi, wj, wall, dt,
                          ht, o, n, a);
  if (ROLL != ROLLING_NONE) {
    V3 troll;
    bool on;
    contact_lane_roll<ROLL, UPDATE, ALLON>(p, n, a, std::fabs(o.fn), reff, wi, wj, dt, hr, o.fr,
                                           troll, on);
    o.ti = select(on, o.ti + troll, o.ti);
    o.tj = select(on, o.tj - troll, o.tj);
  }
}

// One contact, with the rolling model fixed at compile time. hist: 3 (or 6 for EPSD) doubles,
// integrated when update is true.
template <int ROLL>
TBAGS_INLINE void compute_t(const Params &p, const Contact &c, double *hist, bool update, Result &o)
{
  using namespace vec;
  const V3 vr = load3(c.vi) - load3(c.vj);
  V3 ht = load3(hist);
  V3 hr = ROLL == ROLLING_EPSD ? load3(hist + 3) : V3{0.0, 0.0, 0.0};
  LaneOut lo;
  if (update)
    contact_lane<ROLL, true>(p, p.limit_damping, load3(c.dx), c.rsq, c.radsum, c.reff, c.meff, c.radi, c.radj, vr,
                             load3(c.wi), load3(c.wj), c.wall, c.dt, ht, hr, lo);
  else
    contact_lane<ROLL, false>(p, p.limit_damping, load3(c.dx), c.rsq, c.radsum, c.reff, c.meff, c.radi, c.radj, vr,
                              load3(c.wi), load3(c.wj), c.wall, c.dt, ht, hr, lo);
  store3(ht, hist);
  if (ROLL == ROLLING_EPSD) store3(hr, hist + 3);
  store3(lo.f, o.f);
  store3(lo.ti, o.ti);
  store3(lo.tj, o.tj);
  store3(lo.fs, o.fs);
  store3(lo.fr, o.fr);
  o.fn = lo.fn;
  o.fne = lo.fne;
  o.delta = lo.delta;
  o.r = lo.r;
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

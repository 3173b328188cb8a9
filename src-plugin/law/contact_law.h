/* T-BAGS DEM toolkit: the Hertz-Mindlin contact law with restitution damping, Coulomb friction
   and rolling resistance. Pure header, no LAMMPS types: the constants and the stages of the
   law, each a branch-free function of values (conditions are selects) so that a contact can run
   in a SIMD lane; contact_chain.h chains them, once, for pair gran/hertz/rolling and fix
   wall/gran/servo (a plate is a particle of infinite radius and mass). Unit-tested alone.

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
  // the rolling radius R_r (rolling_radius()): 1 (R_i + R_j)/2, 0 R*; a double, not a bool: the
  // SIMD loops gather it per contact (a byte gather kept the geometry loop from vectorising: +26 %
  // instructions per contact-step)
  double roll_mean = 0.0;
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
  double reff;                  // R*
  double meff;                  // m*
  double radi, radj;            // radii for the surface velocity (wall: radj = 0)
  const double *vi, *vj;        // velocities (wall: its velocity)
  const double *wi, *wj;        // angular velocities (wall: zero vector)
  bool wall;                    // torque lever arm r_i (wall) or r - d/2 (pair), as stock
  double dt;
  // implicit damping (fix wall/gran/servo: 'damping implicit'; hm = 0: the half step's
  // velocities, as stock): vdi, wdi are i's velocities at the end of the step predicted from the
  // forces on i so far (v + dt/2 f/m, w + dt/2 t/I), hm = dt/2 / m_i (implicit_velocity())
  const double *vdi = nullptr, *wdi = nullptr;
  double hm = 0.0;
};

// Implicit damping of one direction: the relative velocity u that the damping acts against is
// the end of the step's, u = u_pred + hm (f_el - eta u), where u_pred is predicted from the
// other forces on the particle, f_el is the contact's elastic force and hm = dt/2 / m the velocity
// change per unit force of the direction's mode mass m (normal: m_i; tangential, the sphere's
// rotation included: m_i / TANGENTIAL_COMPLIANCE). The damped contact then keeps the undamped
// stability limit, omega dt < 2, where the half step's velocity (stock) turns unstable at
// omega dt = 1.0 for the tangential mode of a no-slip contact (damping ratio 0.78 at
// restitution 0.2).
TBAGS_INLINE double implicit_velocity(double u_pred, double f_el, double eta, double hm)
{
  return (u_pred + hm * f_el) / (1.0 + eta * hm);
}
TBAGS_INLINE vec::V3 implicit_velocity(const vec::V3 &u_pred, const vec::V3 &f_el, double eta,
                                       double hm)
{
  using namespace vec;
  return (1.0 / (1.0 + eta * hm)) * (u_pred + hm * f_el);
}
// a particle's moment of inertia over m r^2: a solid sphere (as fix nve/sphere); its contact point
// under a tangential force F moves by F (1/m + r^2/I) = 3.5 F/m (lever arm r)
constexpr double SPHERE_INERTIA = 0.4;
constexpr double TANGENTIAL_COMPLIANCE = 1.0 + 1.0 / SPHERE_INERTIA;
static_assert(TANGENTIAL_COMPLIANCE == 3.5, "a solid sphere: 1 + 1/0.4");

struct Result {
  double f[3];                  // force on i (j gets -f)
  double ti[3], tj[3];          // torques on i and j
  double fn;                    // total normal force (elastic + damping), signed
  double fne;                   // elastic (Hertz) normal force
  double delta;                 // overlap
  double r;                     // centre distance
  double fs[3];                 // tangential force on i
  double fr[3];                 // rolling pseudo-force: M_r(i) = R_r n x fr
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

// The rolling radius R_r: the lever arm of the rolling resistance, in its relative velocity
// R_r (w_i - w_j) x n, its torque R_r n x F_r, hence its cap mu_r R_r |F_n| and its stiffness
// k_s R_r^2. R* (EPSD as Ai et al. 2011, LAMMPS's rolling sds) or, p.roll_mean, the mean radius
// (R_i + R_j)/2 (YADE's Mindlin law with its Rmean): twice R* for equal spheres, where it is the
// law of R* with twice mu_r (k_s grows with mu_r^2). A plate has no radius: R_r = R_i (= R*) there.
TBAGS_INLINE double rolling_radius(const Params &p, double reff, double radi, double radj,
                                   bool wall)
{
  const double mean = 0.5 * (radi + radj);
  return (p.roll_mean > 0.0 && !wall) ? mean : reff;
}

// The stages' outputs for one contact (contact_geometry() and tangential_force() fill them).
// Everywhere below: dx = x_i - x_j (a plate: as Contact), vr = v_i - v_j, angular velocities
// wi, wj; ht (tangential) and hr (rolling, EPSD) the history; clip: p.limit_damping; rolling
// acts where p.mur > 0 (make_params: p.rolling is then the model).
struct LaneOut {
  vec::V3 f, ti, tj, fs, fr;
  double fn, fne, delta, r;
};

// Normal force (stage 2): the Hertz force fne plus restitution damping against the normal
// relative velocity vnnr (n . (v_i - v_j)), clipped at zero with clip; sqma = sqrt(m* a).
TBAGS_INLINE double normal_force(const Params &p, bool clip, double meff, double a, double fne,
                                 double vnnr, double &sqma)
{
  sqma = std::sqrt(meff * a);
  const double fn = fne - p.cn * sqma * vnnr;
  return (clip & (fn < 0.0)) ? 0.0 : fn;
}

// The relative velocity at the contact point of unit normal n (from j to i): its normal part
// vnnr and tangential part vtr.
TBAGS_INLINE void contact_velocity(const vec::V3 &n, double radi, double radj, const vec::V3 &vr,
                                   const vec::V3 &wi, const vec::V3 &wj, double &vnnr,
                                   vec::V3 &vtr)
{
  using namespace vec;
  vnnr = dot(vr, n);
  const V3 wr = radi * wi + radj * wj;
  vtr = (vr - vnnr * n) - cross(wr, n);
}

// Geometry (stage 1): unit normal n, normal and tangential relative velocity vnnr and vtr
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
  contact_velocity(n, radi, radj, vr, wi, wj, vnnr, vtr);

  // normal: Hertz
  a = std::sqrt(reff * delta);
  o.fne = p.kn * a * delta;
  o.delta = delta;
  o.r = r;
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

// Tangential spring history (stage 3, when the history is integrated): rotated onto the tangent plane and
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

// Tangential force (stage 4) from the (integrated) history: incremental Mindlin spring +
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

// EPSD rolling history (stage 5, when the history is integrated): rotated onto the tangent plane
// and integrated with the rolling velocity R_r (w_i - w_j) x n (rr = R_r, rolling_radius()) where
// rolling acts (p.mur > 0; ALLON: known), else left as it was. FAST: as tangential_history()
// (returns whether the exact rotation was needed where rolling acts).
template <bool ALLON = false, bool FAST = false>
TBAGS_INLINE bool rolling_history(const Params &p, const vec::V3 &n, double a, double fncrit,
                                  double rr, const vec::V3 &wi, const vec::V3 &wj, double dt,
                                  vec::V3 &hr)
{
  using namespace vec;
  const bool on = ALLON || p.mur > 0.0;
  const V3 vrl = rr * cross(wi - wj, n);
  bool big = false;
  const V3 h = rotate_history<FAST>(hr, n, p.krs * a, p.mur * fncrit, big) + dt * vrl;
  hr = select(on, h, hr);
  return FAST && (on & big);
}

// Rolling resistance (stage 6; ROLL not ROLLING_NONE) from n, a, fncrit = |F_n| and, for
// EPSD, the integrated history hr (rolling_history()): the rolling pseudo-force fr and the
// torque troll = R_r n x fr (rr = R_r, rolling_radius(); i gets +troll, j -troll); EPSD: the
// cap |fr| <= mu_r |F_n| (hr rescaled to it); CDT: |fr| = mu_r |F_n| against the rolling
// velocity. on: rolling acts (p.mur > 0), else fr and troll are zero and hr is left as it was.
template <int ROLL, bool ALLON = false>
TBAGS_INLINE void rolling_force(const Params &p, const vec::V3 &n, double a, double fncrit,
                                double rr, const vec::V3 &wi, const vec::V3 &wj, vec::V3 &hr,
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
    const V3 vrl = rr * cross(wi - wj, n);
    const double vl = std::sqrt(dot(vrl, vrl));
    fr = select(vl > 0.0, (-frcrit / vl) * vrl, V3{0.0, 0.0, 0.0});
  }
  fr = select(on, fr, V3{0.0, 0.0, 0.0});
  troll = rr * cross(n, fr);
}

}    // namespace contact
}    // namespace tbags
#endif

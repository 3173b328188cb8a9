/* T-BAGS DEM toolkit: the Hertz-Mindlin contact law with restitution damping, Coulomb friction
   and rolling resistance. Pure header, no LAMMPS types: the constants (Params, per type pair),
   one contact's input (Touch) and State, and the stages of the law, each a branch-free function
   f(Params, State, history) (conditions are selects) so that a contact can run in a SIMD lane:
   geometry, normal_force, tangential_history, tangential_force, contact_forces, the rolling
   sub-models (NoRolling, EpsdRolling, CdtRolling: history and force) and rolling_torque, the
   twisting sub-model (TwistingSds) and twisting_torque, and the implicit damping's
   implicit_normal and implicit_tangential. contact_chain.h chains them, once,
   for pair gran/hertz/rolling and fix wall/gran/servo (a plate is a particle of infinite radius
   and mass). Unit-tested alone.

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
     twisting SDS: M_t = -k_tw theta - c_tw (w_i - w_j).n, |M_t| <= mu_tw |F_n|, theta the
            integrated twist angle (reset to the cap on slipping)
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
  // twisting (TwistingSds, where ktw > 0): stiffness (N m/rad), damping (N m s/rad), the cap's
  // lever (m: |M_t| <= mutw |F_n|)
  double ktw = 0.0, ctw = 0.0, mutw = 0.0;
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

// One contact as the host gives it (the pair's batch, the plate fix): dx = x_i - x_j (a plate:
// from its contact point to x_i), vr = v_i - v_j, the angular velocities, the radii (a plate's:
// 0), m* and R* (effective(), effective_frozen(); a plate: m_i and r_i).
struct Touch {
  vec::V3 dx, vr, wi, wj;
  double radi, radj, meff, reff;
};

// What the stages share about one contact: geometry() fills it, normal_force() adds fn and
// sqma; the tangential and rolling stages read it. A value (no stage keeps its address): the
// batch's loops rebuild it from their lanes and the vectoriser keeps its fields in registers.
struct State {
  vec::V3 n;        // unit normal, from j to i
  vec::V3 vt;       // tangential relative velocity of the contact points
  vec::V3 vroll;    // rolling velocity R_r (w_i - w_j) x n
  double wt = 0.0;    // twisting (relative spin) rate (w_i - w_j) . n
  double vn;        // normal relative velocity n . (v_i - v_j)
  double r;         // centre distance
  double delta;     // overlap
  double a;         // contact radius sqrt(R* delta)
  double meff;      // m*
  double rr;        // rolling radius R_r (rolling_radius())
  double fne;       // elastic (Hertz) normal force
  double fn = 0.0;      // total normal force (elastic + damping), normal_force()
  double sqma = 0.0;    // sqrt(m* a), normal_force()
};

// The relative velocity of the contact points of t at the unit normal n (from j to i): its
// normal part vn and tangential part vt (written in place: a returned pair, copied into the
// State as a whole, kept the geometry loop from vectorising).
TBAGS_INLINE void contact_velocity(const vec::V3 &n, const Touch &t, double &vn, vec::V3 &vt)
{
  using namespace vec;
  vn = dot(t.vr, n);
  const V3 wr = t.radi * t.wi + t.radj * t.wj;
  vt = (t.vr - vn * n) - cross(wr, n);
}

// Stage 1, geometry and Hertz force: the state of a touching contact (wall: t is a plate's).
TBAGS_INLINE State geometry(const Params &p, const Touch &t, bool wall)
{
  using namespace vec;
  State s;
  // r^2 as (dx0^2 + dx1^2) + dx2^2: the same bits as the host's touching test
  s.r = std::sqrt(dot(t.dx, t.dx));
  const double rinv = 1.0 / s.r;
  s.delta = (t.radi + t.radj) - s.r;
  s.n = rinv * t.dx;
  contact_velocity(s.n, t, s.vn, s.vt);
  s.a = std::sqrt(t.reff * s.delta);
  s.fne = p.kn * s.a * s.delta;
  s.meff = t.meff;
  s.rr = rolling_radius(p, t.reff, t.radi, t.radj, wall);
  s.vroll = s.rr * cross(t.wi - t.wj, s.n);
  s.wt = dot(t.wi - t.wj, s.n);
  return s;
}

// Stage 2, normal force: Hertz plus restitution damping against s.vn, clipped at zero with clip
// (p.limit_damping); sets s.fn and s.sqma = sqrt(m* a).
TBAGS_INLINE void normal_force(const Params &p, bool clip, State &s)
{
  s.sqma = std::sqrt(s.meff * s.a);
  const double fn = s.fne - p.cn * s.sqma * s.vn;
  s.fn = (clip & (fn < 0.0)) ? 0.0 : fn;
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

// Stage 3, tangential history (when integrated): ht rotated onto the tangent plane and
// integrated with s.vt. FAST (the pair's SIMD loop): the rotation only by the series; returns
// true when the tilt was too large for it (rare): the caller must then redo the contact without
// FAST, from the old history. When it returns false, ht is bit for bit the full law's.
template <bool FAST = false>
TBAGS_INLINE bool tangential_history(const Params &p, const State &s, double dt, vec::V3 &ht)
{
  bool big = false;
  ht = rotate_history<FAST>(ht, s.n, p.kt * s.a, p.mu * std::fabs(s.fn), big) + dt * s.vt;
  return FAST && big;
}

// Stage 4, tangential force from the (integrated) history ht: incremental Mindlin spring and
// damping against s.vt, Coulomb cap |F_t| <= mu |F_n| (ht reset to the cap on sliding).
TBAGS_INLINE vec::V3 tangential_force(const Params &p, const State &s, vec::V3 &ht)
{
  using namespace vec;
  const double damp_t = p.ct * s.sqma;
  const double kts = p.kt * s.a;
  const double fscrit = p.mu * std::fabs(s.fn);
  V3 fs = (-damp_t) * s.vt - kts * ht;
  const double fs2 = dot(fs, fs);
  // sliding: |fs| > mu |F_n| (squares: no sqrt when sticking)
  const bool slide = fs2 > fscrit * fscrit;
  const bool hnz = dot(ht, ht) != 0.0;    // |xi| != 0
  const double c = fscrit / std::sqrt(fs2);
  // on sliding, xi such that the spring + damping force is the capped force
  ht = select(slide & hnz, (-1.0 / kts) * (c * fs + damp_t * s.vt), ht);
  return select(slide, hnz ? c * fs : V3{0.0, 0.0, 0.0}, fs);
}

// The force on i (j gets its opposite) and the torques of the normal and tangential forces on
// i and j (lever arm r - delta/2, a plate's particle r_i, as stock).
struct Forces {
  vec::V3 f, ti, tj;
};
TBAGS_INLINE Forces contact_forces(const State &s, const vec::V3 &fs, double radi, double radj,
                                   bool wall)
{
  using namespace vec;
  const V3 tor = cross(s.n, fs);
  const double armi = wall ? radi : radi - 0.5 * s.delta;
  const double armj = radj - 0.5 * s.delta;
  return Forces{s.fn * s.n + fs, (-armi) * tor, (-armj) * tor};
}

// Implicit damping (fix wall/gran/servo 'damping implicit'): the damping acts against the end
// of the step's relative velocity (implicit_velocity()) instead of the half step's. Predicted:
// the contact-point velocities from i's velocities at the end of the step predicted from the
// forces on i so far (contact_velocity() of them), and hm = dt/2 / m_i. The two stages replace
// s.vn before normal_force() and s.vt after tangential_history(), before tangential_force().
struct Predicted {
  double vn;
  vec::V3 vt;
  double hm;
};
TBAGS_INLINE void implicit_normal(const Params &p, const Predicted &q, State &s)
{
  s.vn = implicit_velocity(q.vn, s.fne, p.cn * std::sqrt(s.meff * s.a), q.hm);
}
TBAGS_INLINE void implicit_tangential(const Params &p, const Predicted &q, const vec::V3 &ht,
                                      State &s)
{
  s.vt = implicit_velocity(q.vt, (-p.kt * s.a) * ht, p.ct * s.sqma, TANGENTIAL_COMPLIANCE * q.hm);
}

// Stages 5 and 6, the rolling resistance: one sub-model per Rolling value, each with its
// history size, the history's integration (history(), when integrated) and the rolling
// pseudo-force fr (force()); the torque is rolling_torque(). Rolling acts where p.mur > 0
// (ALLON: known to, for every contact): elsewhere fr is zero and the history is left as it was.
// FAST: as tangential_history() (returns whether the exact rotation was needed where rolling acts).
template <bool ALLON = false> TBAGS_INLINE bool rolling_acts(const Params &p)
{
  return ALLON || p.mur > 0.0;
}

struct NoRolling {
  static constexpr int HISTORY = 0;
};

// EPSD (Ai et al. 2011): a spring of stiffness k_s = krs a on the rolling displacement hr,
// capped at mu_r |F_n| (hr rescaled to the cap).
struct EpsdRolling {
  static constexpr int HISTORY = 3;
  template <bool ALLON = false, bool FAST = false>
  static TBAGS_INLINE bool history(const Params &p, const State &s, double dt, vec::V3 &hr)
  {
    using namespace vec;
    const bool on = rolling_acts<ALLON>(p);
    bool big = false;
    const V3 h = rotate_history<FAST>(hr, s.n, p.krs * s.a, p.mur * std::fabs(s.fn), big) +
        dt * s.vroll;
    hr = select(on, h, hr);
    return FAST && (on & big);
  }
  template <bool ALLON = false>
  static TBAGS_INLINE vec::V3 force(const Params &p, const State &s, vec::V3 &hr)
  {
    using namespace vec;
    const bool on = rolling_acts<ALLON>(p);
    const double frcrit = p.mur * std::fabs(s.fn);
    const V3 fr = (-p.krs * s.a) * hr;
    const double fr2 = dot(fr, fr);
    const bool cap = fr2 > frcrit * frcrit;
    const double c = frcrit / std::sqrt(fr2);
    hr = select(on & cap, c * hr, hr);    // the spring at the cap: -k_s (c hr) = c fr
    return select(on, select(cap, c * fr, fr), V3{0.0, 0.0, 0.0});
  }
};

// CDT: a moment of constant magnitude mu_r R_r |F_n| against the rolling velocity; no history.
struct CdtRolling {
  static constexpr int HISTORY = 0;
  template <bool ALLON = false>
  static TBAGS_INLINE vec::V3 force(const Params &p, const State &s, vec::V3 &)
  {
    using namespace vec;
    const bool on = rolling_acts<ALLON>(p);
    const double vl = std::sqrt(dot(s.vroll, s.vroll));
    const V3 fr = select(vl > 0.0, (-p.mur * std::fabs(s.fn) / vl) * s.vroll, V3{0.0, 0.0, 0.0});
    return select(on, fr, V3{0.0, 0.0, 0.0});
  }
};

// Stage 7, the twisting resistance (LAMMPS's "twisting sds"; YADE's Mindlin law has the same
// spring without the cap): a torsional spring and dashpot on the relative spin about the normal,
// s.wt, with the twist angle theta as history, integrated first (history(), when integrated),
// then the moment M_t = -k_tw theta - c_tw s.wt, capped at mu_tw |F_n| (theta then reset so that
// spring and dashpot give the cap, as LAMMPS does); twisting_torque(): i gets M_t n, j -M_t n.
// Acts where p.ktw > 0 (the host refuses a cap without a spring).
struct TwistingSds {
  static constexpr int HISTORY = 1;
  static TBAGS_INLINE void history(const Params &p, const State &s, double dt, double &theta)
  {
    theta = p.ktw > 0.0 ? theta + s.wt * dt : theta;
  }
  static TBAGS_INLINE double moment(const Params &p, const State &s, double &theta)
  {
    const double m = -p.ktw * theta - p.ctw * s.wt;
    const double sign = (s.wt > 0.0) - (s.wt < 0.0);
    const double crit = p.mutw * std::fabs(s.fn);
    const bool cap = (p.ktw > 0.0) & (std::fabs(m) > crit);
    theta = cap ? (crit * sign - p.ctw * s.wt) / p.ktw : theta;
    return p.ktw > 0.0 ? (cap ? -crit * sign : m) : 0.0;
  }
};
TBAGS_INLINE vec::V3 twisting_torque(const State &s, double m) { return m * s.n; }

template <int ROLL> struct RollingModel { using type = NoRolling; };
template <> struct RollingModel<ROLLING_EPSD> { using type = EpsdRolling; };
template <> struct RollingModel<ROLLING_CDT> { using type = CdtRolling; };

// The rolling torque on i (j gets its opposite): R_r n x fr.
TBAGS_INLINE vec::V3 rolling_torque(const State &s, const vec::V3 &fr)
{
  return s.rr * vec::cross(s.n, fr);
}

}    // namespace contact
}    // namespace tbags
#endif

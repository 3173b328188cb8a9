/* T-BAGS DEM toolkit: the yarn bond law, pure header with no LAMMPS types (used by bond_style
   bpm/yarn and bond_style yarn, unit-tested alone).

   A cylindrical solid bond of diameter d between particle centres, length r0 when first seen:
     strain          eps = (r - r0) / r0
     axial force     F = A sigma(eps) for eps > 0, A = pi d^2 / 4; F = 0 for eps <= 0 (never pushes)
                     sigma from a strain-stress table, linear between points (or a force table)
     plastic option  unloading along the initial modulus E0 from the largest strain reached:
                     sigma = max(0, sigma(eps_max) - E0 (eps_max - eps)) for eps < eps_max
     break           eps > eps_break
     shear, bending, twisting (incremental, Potyondy-Cundall parallel bond, acting in any axial
     state): dF_s = k_s du_s, dM_b = k_b dtheta_b, dM_t = k_t dtheta_t with
                     k_s = kappa G A / r0, k_b = E I / r0, k_t = G J / r0,
                     I = pi d^4 / 64, J = pi d^4 / 32, G = E / (2 (1 + nu))
     damping         F_d = g_n v_n (tension only) + g_s v_s,  M_d = g_r (w_j - w_i)
   Forces and moments act at the bond centre; on i: F, torque M + (r/2) n x F; on j: -F,
   torque -M + (r/2) n x F, with n the unit vector from i to j (momentum and angular momentum
   are conserved).
   The stages (kinematics, integrate, axial_force, forces) are chained once, over one bond or a
   batch, in law/yarn_chain.h.
*/
#ifndef TBAGS_LAW_YARN_LAW_H
#define TBAGS_LAW_YARN_LAW_H

#include "piecewise.h"
#include "vec3.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tbags {
namespace yarn {

constexpr double PI = 3.14159265358979323846;

// strain-stress (or strain-force) curve, strains increasing from 0
struct Curve {
  std::vector<double> eps, val;
  double slope0() const { return (val[1] - val[0]) / (eps[1] - eps[0]); }
  // linear interpolation; beyond the last point the last segment is extended
  double at(double e) const { return piecewise_linear(eps, val, e); }
  // integral of the curve from 0 to e (for the bond potential energy)
  double integral(double e) const
  {
    double s = 0.0;
    for (size_t k = 1; k < eps.size() && eps[k - 1] < e; k++) {
      const double b = std::min(e, eps[k]);
      s += 0.5 * (val[k - 1] + at(b)) * (b - eps[k - 1]);
    }
    if (e > eps.back()) s += 0.5 * (val.back() + at(e)) * (e - eps.back());
    return s;
  }
};

// returns an empty string when the curve is usable, else what is wrong
inline const char *check_curve(const Curve &c)
{
  if (c.eps.size() < 2) return "needs at least 2 points";
  if (c.eps[0] != 0.0 || c.val[0] != 0.0) return "must start at strain 0 with stress 0";
  for (size_t k = 1; k < c.eps.size(); k++) {
    if (!(c.eps[k] > c.eps[k - 1])) return "strains must increase strictly";
    if (c.val[k] < 0.0) return "stresses must not be negative";
  }
  if (!(c.slope0() > 0.0)) return "the first segment must have a positive slope";
  return "";
}

struct Params {
  const Curve *curve = nullptr;
  bool force_table = false;    // curve gives force (N), not stress (Pa)
  double d = 0.0;              // bond diameter (m)
  double E = 0.0;              // Young's modulus for bending/shear/twist (Pa)
  double nu = 0.0;             // Poisson's ratio (G = E / 2(1+nu))
  double kappa = 0.0;          // shear coefficient (0.9 for a circular section)
  double eps_break = 0.0;      // break strain
  double gn = 0.0, gs = 0.0, gr = 0.0;    // damping: N s/m, N s/m, N m s
  bool plastic = false;

  double area() const { return PI * d * d / 4.0; }
  double inertia() const { return PI * d * d * d * d / 64.0; }
  double polar() const { return PI * d * d * d * d / 32.0; }
  double shear_modulus() const { return E / (2.0 * (1.0 + nu)); }
};

// history per bond
enum { R0 = 0, EPSMAX = 1, FS = 2, MB = 5, MT = 8, NHISTORY = 9 };

// strain of a bond of length r and rest length r0, and whether it breaks at that strain
inline double strain(double r, double r0)
{
  return (r - r0) / r0;
}
inline bool breaks(const Params &p, double eps)
{
  return eps > p.eps_break;
}

// the axial force with the dashpot beside the yarn: g_n v_n added while stretched only (a slack
// yarn carries nothing); fax from axial_force(), vn the stretching rate (m/s)
inline double axial_damped(const Params &p, double fax, double eps, double vn)
{
  return fax + (eps > 0.0 ? p.gn * vn : 0.0);
}

// axial force (N) for strain eps; eps_max is the largest strain reached (updated when asked)
inline double axial_force(const Params &p, double eps, double *eps_max, bool update)
{
  if (eps <= 0.0) return 0.0;
  const double scale = p.force_table ? 1.0 : p.area();
  if (!p.plastic) return scale * p.curve->at(eps);
  double emax = *eps_max;
  if (eps >= emax) {
    if (update) *eps_max = eps;
    return scale * p.curve->at(eps);
  }
  const double s = p.curve->at(emax) - p.curve->slope0() * (emax - eps);
  return s > 0.0 ? scale * s : 0.0;
}

// elastic energy stored in the axial spring at strain eps (elastic option), J
inline double axial_energy(const Params &p, double eps, double r0)
{
  if (eps <= 0.0) return 0.0;
  const double scale = p.force_table ? 1.0 : p.area();
  return scale * r0 * p.curve->integral(eps);
}

// The law's stages for one bond, as values (law/yarn_chain.h chains them over one bond or a
// batch). rows: i's and j's positions, velocities and angular velocities.

// the incremental springs' constants times r0 (k_s = ks / r0, ...), from the same expressions
// in the same order as k_s = kappa G A / r0, k_b = E I / r0, k_t = G J / r0
struct Springs {
  double ks, kb, kt;
};
inline Springs springs(const Params &p)
{
  const double G = p.shear_modulus();
  return {p.kappa * G * p.area(), p.E * p.inertia(), G * p.polar()};
}

// stage 1: geometry and the relative motion of the bond's ends, at the bond centre
struct Motion {
  vec::V3 n;       // unit vector from i to j
  vec::V3 vs;      // sliding velocity of j's end relative to i's, normal to n
  vec::V3 wrel;    // w_j - w_i
  vec::V3 wb;      // its bending part (normal to n)
  double r, eps;   // length, strain
  double vn, wt;   // stretching rate, twisting rate
};
TBAGS_INLINE Motion kinematics(const vec::V3 &xi, const vec::V3 &xj, const vec::V3 &vi,
                               const vec::V3 &vj, const vec::V3 &wi, const vec::V3 &wj, double r0)
{
  using namespace vec;
  Motion m;
  const V3 dx = xj - xi;
  m.r = std::sqrt(dot(dx, dx));
  m.n = V3{dx.x / m.r, dx.y / m.r, dx.z / m.r};
  m.eps = strain(m.r, r0);
  const double h = 0.5 * m.r;
  const V3 vrel = (vj - vi) - h * (cross(wj, m.n) + cross(wi, m.n));
  m.vn = dot(vrel, m.n);
  m.vs = vrel - m.vn * m.n;
  m.wrel = wj - wi;
  m.wt = dot(m.wrel, m.n);
  m.wb = m.wrel - m.wt * m.n;
  return m;
}

// stage 2 (integrating steps only): shear force fs and bending moment mb turned into the plane
// normal to the bond, then the increments k_s v_s dt, k_b w_b dt, k_t w_t dt (mt: twisting moment)
TBAGS_INLINE void integrate(const Springs &k, const Motion &m, double r0, double dt, vec::V3 &fs,
                            vec::V3 &mb, double &mt)
{
  using namespace vec;
  fs = onto_plane(fs, m.n);
  mb = onto_plane(mb, m.n);
  const double ks = k.ks / r0, kb = k.kb / r0, kt = k.kt / r0;
  fs = fs + dt * (ks * m.vs);
  mb = mb + dt * (kb * m.wb);
  mt = mt + kt * m.wt * dt;
}

// stage 4 (after the axial force fax, stage 3: axial_force()): force on i, torques on i and j
// (forces and moments act at the bond centre)
TBAGS_INLINE void forces(const Params &p, const Motion &m, double fax, const vec::V3 &fs,
                         const vec::V3 &mb, double mt, vec::V3 &f, vec::V3 &ti, vec::V3 &tj)
{
  using namespace vec;
  const double fn = axial_damped(p, fax, m.eps, m.vn);
  f = fn * m.n + fs + p.gs * m.vs;
  const V3 mom = mb + mt * m.n + p.gr * m.wrel;
  const V3 arm = (0.5 * m.r) * cross(m.n, f);
  ti = mom + arm;
  tj = arm - mom;
}

}    // namespace yarn
}    // namespace tbags
#endif

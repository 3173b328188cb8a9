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
*/
#ifndef TBAGS_LAW_YARN_LAW_H
#define TBAGS_LAW_YARN_LAW_H

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
  double at(double e) const
  {
    if (e <= eps.front()) return val.front();
    const size_t n = eps.size();
    size_t k = std::upper_bound(eps.begin(), eps.end(), e) - eps.begin();
    if (k >= n) k = n - 1;
    const double t = (e - eps[k - 1]) / (eps[k] - eps[k - 1]);
    return val[k - 1] + t * (val[k] - val[k - 1]);
  }
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

struct Bond {
  const double *xi, *xj, *vi, *vj, *wi, *wj;
  double dt;
};

struct Result {
  double f[3];      // force on i (j gets -f)
  double ti[3], tj[3];
  double eps, fax;  // strain and axial force (tension positive)
  double r;
  bool broken;
};

// one bond step; hist holds NHISTORY doubles (hist[R0] > 0). Inlined into the bond loops: the
// result stays in registers (15 % less bond time on the bag decks than a call)
TBAGS_INLINE void compute(const Params &p, const Bond &b, double *hist, bool update, Result &o)
{
  using namespace vec;
  double dx[3];
  sub(b.xj, b.xi, dx);
  const double r = len(dx);
  const double n[3] = {dx[0] / r, dx[1] / r, dx[2] / r};
  const double r0 = hist[R0];
  const double eps = strain(r, r0);
  o.r = r;
  o.eps = eps;
  o.broken = breaks(p, eps);

  // relative velocity of j's bond end with respect to i's, at the bond centre
  const double h = 0.5 * r;
  double wixn[3], wjxn[3];
  cross(b.wi, n, wixn);
  cross(b.wj, n, wjxn);
  double vrel[3];
  for (int k = 0; k < 3; k++) vrel[k] = b.vj[k] - b.vi[k] - h * (wjxn[k] + wixn[k]);
  const double vn = dot(vrel, n);
  double vs[3];
  for (int k = 0; k < 3; k++) vs[k] = vrel[k] - vn * n[k];
  double wrel[3];
  sub(b.wj, b.wi, wrel);
  const double wt = dot(wrel, n);
  double wb[3];
  for (int k = 0; k < 3; k++) wb[k] = wrel[k] - wt * n[k];

  // incremental shear force and bending moment (kept in the plane normal to the bond)
  double *fs = hist + FS, *mb = hist + MB;
  const double G = p.shear_modulus();
  if (update) {
    rotate_onto_plane(fs, n);
    rotate_onto_plane(mb, n);
    const double ks = p.kappa * G * p.area() / r0;
    const double kb = p.E * p.inertia() / r0;
    const double kt = G * p.polar() / r0;
    for (int k = 0; k < 3; k++) {
      fs[k] += ks * vs[k] * b.dt;
      mb[k] += kb * wb[k] * b.dt;
    }
    hist[MT] += kt * wt * b.dt;
  }

  o.fax = axial_force(p, eps, hist + EPSMAX, update);
  const double fn = axial_damped(p, o.fax, eps, vn);
  double m[3];
  for (int k = 0; k < 3; k++) {
    o.f[k] = fn * n[k] + fs[k] + p.gs * vs[k];
    m[k] = mb[k] + hist[MT] * n[k] + p.gr * wrel[k];
  }
  double nxf[3];
  cross(n, o.f, nxf);
  for (int k = 0; k < 3; k++) {
    o.ti[k] = m[k] + h * nxf[k];
    o.tj[k] = -m[k] + h * nxf[k];
  }
}

}    // namespace yarn
}    // namespace tbags
#endif

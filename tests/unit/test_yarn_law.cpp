// Unit tests of law/yarn_law.h against closed forms (no LAMMPS).
#include "law/yarn_chain.h"
#include "yarn_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace tbags::yarn;

namespace {
constexpr double REL = 1e-12;
void expect_rel(double got, double want, double rel = REL)
{
  EXPECT_NEAR(got, want, rel * std::fabs(want)) << "got " << got << " want " << want;
}

Curve pp() { return yarn_fixtures::tape(); }
Params params(const Curve &c) { return yarn_fixtures::yarn(c); }

struct Two {
  double xi[3] = {0, 0, 0}, xj[3] = {0.005, 0, 0};
  double vi[3] = {0, 0, 0}, vj[3] = {0, 0, 0}, wi[3] = {0, 0, 0}, wj[3] = {0, 0, 0};
  Bond b(double dt = 1e-6)
  {
    Bond k;
    k.xi = xi; k.xj = xj; k.vi = vi; k.vj = vj; k.wi = wi; k.wj = wj; k.dt = dt;
    return k;
  }
};
}    // namespace

TEST(YarnCurve, InterpolationAndChecks)
{
  Curve c = pp();
  EXPECT_STREQ(check_curve(c), "");
  expect_rel(c.at(0.05), 3.2e9 * 0.05 * (1 - 1.953125 * 0.05));
  // halfway between two points: the chord
  expect_rel(c.at(0.055), 0.5 * (c.val[5] + c.val[6]));
  Curve bad = c;
  bad.eps[3] = bad.eps[2];
  EXPECT_STRNE(check_curve(bad), "");
  bad = c;
  bad.val[4] = -1.0;
  EXPECT_STRNE(check_curve(bad), "");
}

TEST(YarnCurve, IntegralIsTheAreaUnderTheChords)
{
  Curve c;
  c.eps = {0.0, 0.1, 0.2};
  c.val = {0.0, 1.0, 1.5};
  expect_rel(c.integral(0.1), 0.05);
  expect_rel(c.integral(0.2), 0.05 + 0.125);
  expect_rel(c.integral(0.15), 0.05 + 0.5 * (1.0 + 1.25) * 0.05);
}

TEST(YarnAxial, TensionFollowsTheTableCompressionIsZero)
{
  Curve c = pp();
  Params p = params(c);
  double emax = 0.0;
  for (double e : {0.001, 0.03, 0.0777, 0.15}) expect_rel(axial_force(p, e, &emax, true), p.area() * c.at(e));
  EXPECT_EQ(axial_force(p, 0.0, &emax, true), 0.0);
  EXPECT_EQ(axial_force(p, -0.05, &emax, true), 0.0);
  p.force_table = true;
  expect_rel(axial_force(p, 0.03, &emax, false), c.at(0.03));
}

TEST(YarnAxial, PlasticUnloadingAlongTheInitialModulus)
{
  Curve c = pp();
  Params p = params(c);
  p.plastic = true;
  double emax = 0.0;
  axial_force(p, 0.10, &emax, true);
  expect_rel(emax, 0.10);
  const double want = p.area() * (c.at(0.10) - c.slope0() * 0.02);
  expect_rel(axial_force(p, 0.08, &emax, true), want);
  EXPECT_DOUBLE_EQ(emax, 0.10);
  // slack below the permanent strain
  // slack below the permanent strain eps_max - sigma(eps_max)/E0 = 0.0179
  EXPECT_EQ(axial_force(p, 0.017, &emax, true), 0.0);
  EXPECT_GT(axial_force(p, 0.019, &emax, true), 0.0);
  // reloading beyond the largest strain follows the curve again
  expect_rel(axial_force(p, 0.11, &emax, true), p.area() * c.at(0.11));
}

TEST(YarnBond, BreakStrain)
{
  Curve c = pp();
  Params p = params(c);
  Two t;
  double hist[NHISTORY] = {0.005};
  Result o;
  t.xj[0] = 0.005 * 1.159;
  compute(p, t.b(), hist, true, o);
  EXPECT_FALSE(o.broken);
  t.xj[0] = 0.005 * 1.161;
  compute(p, t.b(), hist, true, o);
  EXPECT_TRUE(o.broken);
}

TEST(YarnBond, AxialForcePullsTheParticlesTogether)
{
  Curve c = pp();
  Params p = params(c);
  Two t;
  t.xj[0] = 0.0055;    // 10 % strain
  double hist[NHISTORY] = {0.005};
  Result o;
  compute(p, t.b(), hist, true, o);
  expect_rel(o.eps, 0.1);
  expect_rel(o.f[0], p.area() * c.at(0.1));    // on i, toward j
  EXPECT_EQ(o.ti[1], 0.0);
  t.xj[0] = 0.0045;    // compressed
  compute(p, t.b(), hist, true, o);
  EXPECT_EQ(o.f[0], 0.0);
}

TEST(YarnBond, BendingTwistingShearStiffness)
{
  Curve c = pp();
  Params p = params(c);
  const double r0 = 0.005, dt = 1e-6, G = p.E / (2 * (1 + p.nu));
  Two t;
  t.wj[2] = 2.0;     // bending about z
  t.wj[0] = 3.0;     // twisting about the bond axis x
  double hist[NHISTORY] = {r0};
  Result o;
  compute(p, t.b(dt), hist, true, o);
  expect_rel(hist[MB + 2], p.E * p.inertia() / r0 * 2.0 * dt);
  expect_rel(hist[MT], G * p.polar() / r0 * 3.0 * dt);
  // moments on i equal +M, on j -M (no bond force here except shear from the end velocities)
  Two s;
  s.vj[1] = 0.01;    // pure shear displacement of j
  double h2[NHISTORY] = {r0};
  compute(p, s.b(dt), h2, true, o);
  const double ks = p.kappa * G * p.area() / r0;
  expect_rel(o.f[1], ks * 0.01 * dt);
  // torques from the shear force acting at the bond centre: (r/2) n x F on both
  expect_rel(o.ti[2], 0.5 * r0 * o.f[1]);
  expect_rel(o.tj[2], 0.5 * r0 * o.f[1]);
}

TEST(YarnBond, MomentumAndAngularMomentumBalance)
{
  Curve c = pp();
  Params p = params(c);
  p.gn = 1e-3; p.gs = 2e-3; p.gr = 1e-6;
  Two t;
  t.xj[0] = 0.0052; t.xj[1] = 0.0007; t.xj[2] = -0.0003;
  t.vi[0] = 0.1; t.vj[1] = -0.2; t.wi[2] = 5.0; t.wj[0] = -3.0; t.wj[1] = 7.0;
  double hist[NHISTORY] = {0.005, 0, 1e-3, -2e-3, 5e-4, 1e-5, 2e-5, -1e-5, 3e-6};
  Result o;
  compute(p, t.b(), hist, true, o);
  // total torque about the origin: x_i x F_i + x_j x F_j + t_i + t_j = 0
  double L[3], a[3], b[3], mf[3] = {-o.f[0], -o.f[1], -o.f[2]};
  tbags::vec::cross(t.xi, o.f, a);
  tbags::vec::cross(t.xj, mf, b);
  for (int k = 0; k < 3; k++) L[k] = a[k] + b[k] + o.ti[k] + o.tj[k];
  const double scale = std::fabs(o.ti[0]) + std::fabs(o.ti[1]) + std::fabs(o.ti[2]);
  for (int k = 0; k < 3; k++) EXPECT_NEAR(L[k], 0.0, 1e-12 * scale);
}

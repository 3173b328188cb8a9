// Unit tests of law/contact_law.h against closed forms (no LAMMPS).
#include "law/contact_chain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace tbags::contact;

namespace {
constexpr double REL = 1e-12;
const double E_SAND = 1.8e9, NU = 0.1;

void expect_rel(double got, double want, double rel = REL)
{
  EXPECT_NEAR(got, want, rel * std::fabs(want)) << "got " << got << " want " << want;
}

struct Pair2 {
  double xi[3] = {0, 0, 0}, xj[3] = {0, 0, 0};
  double vi[3] = {0, 0, 0}, vj[3] = {0, 0, 0}, wi[3] = {0, 0, 0}, wj[3] = {0, 0, 0};
  double ri = 2.5e-3, rj = 2.5e-3, mi = 1e-4, mj = 1e-4;
  double dx[3];
  Contact c() {
    Contact k;
    for (int d = 0; d < 3; d++) dx[d] = xi[d] - xj[d];
    k.dx = dx;
    k.reff = ri * rj / (ri + rj);
    k.meff = mi * mj / (mi + mj);
    k.radi = ri;
    k.radj = rj;
    k.vi = vi; k.vj = vj; k.wi = wi; k.wj = wj;
    k.wall = false;
    k.dt = 1e-6;
    return k;
  }
};

Params sand(double e = 0.2, double mu = 0.31, double mur = 0.05, int roll = ROLLING_EPSD)
{
  return make_params(mix_E(E_SAND, NU, E_SAND, NU), mix_G(E_SAND, NU, E_SAND, NU), e, mu, mur,
                     roll, false);
}
}    // namespace

TEST(Mixing, SameMaterial)
{
  expect_rel(mix_E(E_SAND, NU, E_SAND, NU), E_SAND / (2.0 * (1.0 - NU * NU)));
  expect_rel(mix_G(E_SAND, NU, E_SAND, NU), E_SAND / (4.0 * (2.0 - NU) * (1.0 + NU)));
}

TEST(Mixing, TwoMaterialsHertzMindlin)
{
  // 1/E* = sum (1-v^2)/E ; 1/G* = sum (2-v)/G with G = E/(2(1+v))
  const double E1 = 0.75e9, v1 = 0.1, E2 = 200e9, v2 = 0.3;
  const double G1 = E1 / (2 * (1 + v1)), G2 = E2 / (2 * (1 + v2));
  expect_rel(mix_E(E1, v1, E2, v2), 1.0 / ((1 - v1 * v1) / E1 + (1 - v2 * v2) / E2));
  expect_rel(mix_G(E1, v1, E2, v2), 1.0 / ((2 - v1) / G1 + (2 - v2) / G2));
}

TEST(Mixing, EffectiveMassAndRadius)
{
  for (const double k : {1.0, 0.37, 5.2, 1e-3}) {
    const double mi = 1.3e-4, mj = mi * k, ri = 2.1e-3, rj = ri * std::cbrt(k);
    double meff, reff;
    effective(mi, mj, ri, rj, meff, reff);
    expect_rel(meff, mi * mj / (mi + mj), 4e-16);
    expect_rel(reff, ri * rj / (ri + rj), 4e-16);
  }
}

TEST(Normal, HertzForceOverlap)
{
  const Params p = sand(1.0);    // e = 1: no damping
  for (double d : {1e-7, 1e-6, 1e-5, 5e-5}) {
    for (double rj : {2.5e-3, 1.8e-3}) {
      Pair2 s;
      s.rj = rj;
      s.xi[2] = s.ri + rj - d;
      Contact c = s.c();
      double hist[6] = {0};
      Result o;
      compute(p, c, hist, true, o);
      const double Rs = s.ri * rj / (s.ri + rj);
      const double Es = E_SAND / (2 * (1 - NU * NU));
      const double want = 4.0 / 3.0 * Es * std::sqrt(Rs) * std::pow(d, 1.5);
      expect_rel(o.delta, d, 1e-9);    // overlap from positions: round-off of x only
      // force as a function of the overlap the law saw
      expect_rel(o.fne, 4.0 / 3.0 * Es * std::sqrt(Rs) * std::pow(o.delta, 1.5));
      expect_rel(o.f[2], o.fne);
      expect_rel(o.fne, want, 1e-8);
      EXPECT_DOUBLE_EQ(o.f[0], 0.0);
    }
  }
}

TEST(Normal, RestitutionDampingCoefficient)
{
  const double e = 0.5;
  const Params p = sand(e);
  Pair2 s;
  const double d = 2e-5;
  s.xi[2] = s.ri + s.rj - d;
  s.vi[2] = -0.1;    // approaching
  Contact c = s.c();
  double hist[6] = {0};
  Result o;
  compute(p, c, hist, true, o);
  const double Es = E_SAND / (2 * (1 - NU * NU));
  const double Rs = s.ri * s.rj / (s.ri + s.rj);
  const double a = std::sqrt(Rs * o.delta);
  const double beta = -std::log(e) / std::sqrt(std::log(e) * std::log(e) + M_PI * M_PI);
  const double eta = 2.0 * std::sqrt(5.0 / 6.0) * beta * std::sqrt(2.0 * Es * a * c.meff);
  expect_rel(o.fn - o.fne, eta * 0.1);
}

// head-on collision integrated with velocity Verlet at 1/2000 of the contact time:
// the measured rebound ratio equals the input e (the damping form is built for it)
TEST(Normal, CollisionRestitution)
{
  for (double e : {0.2, 0.5, 0.9}) {
    for (double rj : {2.5e-3, 1.25e-3}) {
      const Params p = sand(e, 0.31, 0.0, ROLLING_NONE);
      const double rho = 2650, ri = 2.5e-3;
      const double mi = rho * 4.0 / 3.0 * M_PI * ri * ri * ri, mj = rho * 4.0 / 3.0 * M_PI * rj * rj * rj;
      const double v0 = 0.5;
      double zi = ri + rj, vi = -v0 * mj / (mi + mj), vj = v0 * mi / (mi + mj), zj = 0.0;
      const double dt = 2e-9;
      double fprev = 0.0;
      bool was_in = false;
      for (int step = 0; step < 2000000; step++) {
        // half kick, drift, force, half kick
        vi += 0.5 * dt * fprev / mi;
        vj -= 0.5 * dt * fprev / mj;
        zi += dt * vi;
        zj += dt * vj;
        double f = 0.0;
        if (zi - zj < ri + rj) {
          was_in = true;
          Pair2 s;
          s.ri = ri; s.rj = rj; s.mi = mi; s.mj = mj;
          s.xi[2] = zi; s.xj[2] = zj; s.vi[2] = vi; s.vj[2] = vj;
          Contact c = s.c();
          c.dt = dt;
          double hist[6] = {0};
          Result o;
          compute(p, c, hist, true, o);
          f = o.f[2];
        } else if (was_in) {
          break;
        }
        vi += 0.5 * dt * f / mi;
        vj -= 0.5 * dt * f / mj;
        fprev = f;
      }
      const double e_meas = (vi - vj) / v0;
      EXPECT_NEAR(e_meas, e, 0.005 * e) << "e=" << e << " rj=" << rj;
    }
  }
}

TEST(Tangential, MindlinStiffnessFirstStep)
{
  const Params p = sand(1.0, 0.5, 0.0, ROLLING_NONE);
  Pair2 s;
  const double d = 1e-5;
  s.xi[2] = s.ri + s.rj - d;
  s.vi[0] = 0.01;
  Contact c = s.c();
  double hist[6] = {0};
  Result o;
  compute(p, c, hist, true, o);
  const double Gs = E_SAND / (4 * (2 - NU) * (1 + NU));
  const double a = std::sqrt(c.reff * o.delta);
  expect_rel(hist[0], 0.01 * c.dt);
  expect_rel(o.fs[0], -8.0 * Gs * a * 0.01 * c.dt);
  // torque on both: -(r - d/2) n x fs
  expect_rel(o.ti[1], -(s.ri - 0.5 * o.delta) * o.fs[0]);
  expect_rel(o.tj[1], -(s.rj - 0.5 * o.delta) * o.fs[0]);
}

TEST(Tangential, CoulombCapAndHistoryReset)
{
  const double mu = 0.31;
  const Params p = sand(1.0, mu, 0.0, ROLLING_NONE);
  Pair2 s;
  s.xi[2] = s.ri + s.rj - 1e-5;
  Contact c = s.c();
  double hist[6] = {1e-3, 5e-4, 0.0};    // far beyond the elastic limit
  Result o;
  compute(p, c, hist, true, o);
  const double fs = std::hypot(o.fs[0], o.fs[1]);
  expect_rel(fs, mu * o.fn);
  // history rescaled so that k_t |xi| equals the cap
  const double kts = p.kt * std::sqrt(c.reff * o.delta);
  expect_rel(kts * std::hypot(hist[0], hist[1]), mu * o.fn);
  expect_rel(hist[1] / hist[0], 0.5);
}

TEST(Tangential, NoSlipFrictionDoesNotOverflow)
{
  const Params p = sand(0.2, 1e10, 0.05);
  Pair2 s;
  s.xi[2] = s.ri + s.rj - 1e-5;
  s.vi[0] = 3.0;
  s.wi[1] = 100.0;
  Contact c = s.c();
  double hist[6] = {1e-3, 0, 0, 0, 0, 0};
  Result o;
  for (int k = 0; k < 10; k++) compute(p, c, hist, true, o);
  for (int k = 0; k < 3; k++) {
    EXPECT_TRUE(std::isfinite(o.f[k]));
    EXPECT_TRUE(std::isfinite(o.ti[k]));
  }
  // elastic: |fs| = k_t |xi| + damping, no cap
  EXPECT_GT(std::fabs(o.fs[0]), 0.31 * o.fn);
}

TEST(Tangential, HistoryRotatedOntoTangentPlaneKeepsLength)
{
  const Params p = sand(1.0, 0.5, 0.0, ROLLING_NONE);
  Pair2 s;
  s.xi[2] = s.ri + s.rj - 1e-5;
  Contact c = s.c();
  double hist[6] = {3e-7, 0.0, 4e-7};    // has a normal component
  Result o;
  compute(p, c, hist, true, o);
  EXPECT_NEAR(hist[2], 0.0, 1e-22);
  expect_rel(std::hypot(hist[0], hist[1]), 5e-7);
}

// The series rotation (no square root) agrees with the exact one to round-off wherever it
// claims to apply, and hands a large tilt and a zero history to the exact one.
TEST(Tangential, SeriesRotationMatchesExact)
{
  using namespace tbags::vec;
  const V3 n0{0.3, -0.5, 0.8};
  const V3 n = (1.0 / std::sqrt(dot(n0, n0))) * n0;
  const V3 t0 = cross(n, V3{1.0, 0.0, 0.0});
  const V3 t = (1.0 / std::sqrt(dot(t0, t0))) * t0;    // in the tangent plane
  int used = 0;
  for (double tilt : {0.0, 1e-9, 1e-6, 3e-5, 9.9e-4, 1.1e-3, 1e-2, 0.5}) {
    const V3 a = 2e-7 * t + (2e-7 * tilt) * n;    // (a.n)^2 / |a|^2 about tilt^2
    bool small;
    const V3 s = onto_plane_series(a, n, small);
    const V3 e = onto_plane_exact(a, n);
    const V3 o = onto_plane(a, n);
    EXPECT_EQ(small, tilt * tilt / (1.0 + tilt * tilt) < TILT_SERIES) << tilt;
    const V3 want = small ? s : e;
    EXPECT_EQ(o.x, want.x);
    EXPECT_EQ(o.y, want.y);
    EXPECT_EQ(o.z, want.z);
    if (small) {
      used++;
      const V3 d = s - e;
      EXPECT_LT(std::sqrt(dot(d, d) / dot(e, e)), 4e-16) << tilt;
      EXPECT_NEAR(dot(s, n), 0.0, 1e-22);
      expect_rel(std::sqrt(dot(s, s)), std::sqrt(dot(a, a)), 4e-16);
    }
  }
  EXPECT_EQ(used, 5);
  bool small = true;
  onto_plane_series(V3{0.0, 0.0, 0.0}, n, small);
  EXPECT_FALSE(small);
  const V3 z = onto_plane(V3{0.0, 0.0, 0.0}, n);
  EXPECT_EQ(dot(z, z), 0.0);
}

// The pair's fast path (FAST) gives the full law's bits unless it says it cannot: here a
// sticking contact (the same), a sliding one and one at the rolling cap (the same: the caps are
// in the fast path), and a large tangential or rolling history tilt (handed back).
TEST(ContactLaw, FastPathIsTheFullLawOrSaysSo)
{
  using namespace tbags::vec;
  const Params p = sand();
  const V3 n{0.0, 0.0, 1.0}, wi{0.0, 0.0, 0.0};
  const double a = std::sqrt(1.25e-3 * 1e-5), sqma = std::sqrt(5e-5 * a), fn = 10.0;
  struct Case {
    V3 ht, vt, hr, wj;
    bool redo_t, redo_r;
  };
  const Case cases[] = {
      {{1e-8, 0.0, 0.0}, {1e-3, 0.0, 0.0}, {1e-9, 0.0, 0.0}, {0.0, 0.0, 0.0}, false, false},
      {{1e-4, 0.0, 0.0}, {1e-3, 0.0, 0.0}, {1e-9, 0.0, 0.0}, {0.0, 0.0, 0.0}, false, false},
      {{1e-8, 0.0, 1e-9}, {1e-3, 0.0, 0.0}, {1e-9, 0.0, 0.0}, {0.0, 0.0, 0.0}, true, false},
      {{1e-8, 0.0, 0.0}, {1e-3, 0.0, 0.0}, {1e-3, 0.0, 0.0}, {0.0, 0.0, 0.0}, false, false},
      {{1e-8, 0.0, 0.0}, {1e-3, 0.0, 0.0}, {1e-9, 0.0, 1e-10}, {0.0, 0.0, 0.0}, false, true},
  };
  // the contact's state (a sticking contact of two 2.5 mm spheres, 10 um overlap)
  auto state = [&](const Case &k) {
    State s;
    s.n = n;
    s.vt = k.vt;
    s.rr = 1.25e-3;
    s.vroll = s.rr * cross(wi - k.wj, n);
    s.vn = 0.0;
    s.delta = 1e-5;
    s.r = 5e-3 - s.delta;
    s.a = a;
    s.meff = 5e-5;
    s.fne = s.fn = fn;
    s.sqma = sqma;
    return s;
  };
  // the tangential and rolling stages, the history integrated with or without the fast path
  auto tangential = [&](bool fast, const Case &k, V3 &h, Forces &o) {
    const State s = state(k);
    const bool redo = fast ? tangential_history<true>(p, s, 1e-6, h) : tangential_history<false>(p, s, 1e-6, h);
    o = contact_forces(s, tangential_force(p, s, h), 2.5e-3, 2.5e-3, false);
    return redo;
  };
  auto rolling = [&](bool fast, const Case &k, V3 &h, V3 &fr, V3 &tr) {
    const State s = state(k);
    const bool redo = fast ? EpsdRolling::history<false, true>(p, s, 1e-6, h)
                           : EpsdRolling::history<false, false>(p, s, 1e-6, h);
    fr = EpsdRolling::force(p, s, h);
    tr = rolling_torque(s, fr);
    return redo;
  };
  for (const Case &k : cases) {
    V3 h1 = k.ht, h2 = k.ht;
    Forces o1, o2;
    const bool redo = tangential(true, k, h1, o1);
    tangential(false, k, h2, o2);
    EXPECT_EQ(redo, k.redo_t);
    if (!redo) {
      EXPECT_EQ(h1.x, h2.x);
      EXPECT_EQ(h1.z, h2.z);
      EXPECT_EQ(o1.f.x, o2.f.x);
      EXPECT_EQ(o1.ti.y, o2.ti.y);
    }
    V3 r1 = k.hr, r2 = k.hr, fr1, fr2, tr1, tr2;
    const bool redo_r = rolling(true, k, r1, fr1, tr1);
    rolling(false, k, r2, fr2, tr2);
    EXPECT_EQ(redo_r, k.redo_r);
    if (!redo_r) {
      EXPECT_EQ(r1.x, r2.x);
      EXPECT_EQ(tr1.y, tr2.y);
    }
  }
}

TEST(Rolling, EpsdStiffnessAndCap)
{
  const double mur = 0.05;
  const Params p = sand(1.0, 0.31, mur, ROLLING_EPSD);
  Pair2 s;
  s.xi[2] = s.ri + s.rj - 1e-5;
  s.wi[0] = 1.0;    // relative rotation about x
  Contact c = s.c();
  double hist[6] = {0};
  Result o;
  compute(p, c, hist, true, o);
  const double a = std::sqrt(c.reff * o.delta);
  const double Es = E_SAND / (2 * (1 - NU * NU));
  const double kn = 2.0 * Es * a;    // S_n
  const double kr = 2.25 * kn * mur * mur * c.reff * c.reff;
  const double theta = 1.0 * c.dt;
  // fr = -k_s R* (w x n) dt and M_r = R* n x fr: |M_r| = k_r theta
  expect_rel(std::fabs(c.reff * o.fr[1]), kr * theta);
  // cap: huge accumulated rolling angle
  double hist2[6] = {0, 0, 0, 0, 1.0, 0};
  compute(p, c, hist2, true, o);
  expect_rel(c.reff * std::hypot(o.fr[0], o.fr[1]), mur * c.reff * o.fn);
}

TEST(Rolling, CdtConstantTorque)
{
  const double mur = 0.05;
  const Params p = sand(1.0, 0.31, mur, ROLLING_CDT);
  Pair2 s;
  s.xi[2] = s.ri + s.rj - 1e-5;
  for (double w : {1e-3, 1.0, 100.0}) {
    s.wi[1] = w;
    s.wj[1] = -w;    // pure relative rolling, no sliding of the contact point
    Contact c = s.c();
    double hist[6] = {0};
    Result o;
    compute(p, c, hist, true, o);
    // torque magnitude mu_r R* F_n opposing the relative rotation (about y)
    const double M = mur * c.reff * o.fn;
    const double roll_i = o.ti[1] - (-(s.ri - 0.5 * o.delta)) * (o.fs[0]);
    expect_rel(roll_i, -M, 1e-10);
  }
}

TEST(Rolling, NoneHasNoRollingTorque)
{
  const Params p = sand(1.0, 0.31, 0.05, ROLLING_NONE);
  Pair2 s;
  s.xi[2] = s.ri + s.rj - 1e-5;
  s.wi[1] = 1.0;
  s.wj[1] = -1.0;
  Contact c = s.c();
  double hist[6] = {0};
  Result o;
  compute(p, c, hist, true, o);
  EXPECT_EQ(o.fr[0], 0.0);
  EXPECT_EQ(o.fr[1], 0.0);
}

// rolling_radius mean (YADE's Rmean) against effective (R*): the law of R_r everywhere in the
// rolling model (velocity, torque, cap, stiffness)
namespace {
Params with_radius(Params p, bool mean)
{
  p.roll_mean = mean ? 1.0 : 0.0;
  return p;
}
// torques on i and j over n steps of two equal spheres rolling on each other about y (w_j = -w_i:
// the contact point does not slide, so the torques are the rolling resistance alone)
std::vector<double> rolling_torques(const Params &p, Pair2 s, int n)
{
  std::vector<double> t;
  double hist[6] = {0};
  s.xi[2] = s.ri + s.rj - 1e-5;
  s.wi[1] = 1.5; s.wj[1] = -1.5;
  for (int k = 0; k < n; k++) {
    Contact c = s.c();
    Result o;
    compute(p, c, hist, true, o);
    t.insert(t.end(), {o.ti[0], o.ti[1], o.tj[0], o.tj[1]});
  }
  return t;
}
}    // namespace

TEST(Rolling, MeanRadiusIsEffectiveWithTwiceMurForEqualSpheres)
{
  // equal spheres: (R+R)/2 = 2 R*, and k_s grows with mu_r^2, so mean with mu_r is effective
  // with 2 mu_r: the same torques, elastic (first steps) and at the cap (later: 2000 steps of
  // 1e-6 s at 3 rad/s roll 6 mrad, far past the elastic limit of about 0.1 mrad)
  for (int roll : {ROLLING_EPSD, ROLLING_CDT}) {
    const auto a = rolling_torques(with_radius(sand(0.2, 0.31, 0.05, roll), true), Pair2(), 2000);
    const auto b = rolling_torques(with_radius(sand(0.2, 0.31, 0.10, roll), false), Pair2(), 2000);
    const auto c = rolling_torques(with_radius(sand(0.2, 0.31, 0.05, roll), false), Pair2(), 2000);
    for (size_t k = 0; k < a.size(); k++) expect_rel(a[k], b[k], 1e-9);
    EXPECT_GT(std::fabs(a.back() - c.back()), 0.5 * std::fabs(c.back()));    // and not mu_r's
  }
}

TEST(Rolling, MeanRadiusOfUnequalSpheres)
{
  // R_i = 2.5, R_j = 1.5 mm: R* = 0.9375 mm, (R_i+R_j)/2 = 2 mm. First step (elastic): |M_r| =
  // k_s R_r^2 theta; at the cap (a huge rolling history): |M_r| = mu_r R_r |F_n|
  const double mur = 0.05;
  Pair2 s;
  s.rj = 1.5e-3;
  s.xi[2] = s.ri + s.rj - 1e-5;
  s.wi[0] = 1.0;
  for (bool mean : {false, true}) {
    const Params p = with_radius(sand(1.0, 0.31, mur, ROLLING_EPSD), mean);
    Contact c = s.c();
    const double rr = mean ? 0.5 * (s.ri + s.rj) : c.reff;
    double hist[6] = {0};
    Result o;
    compute(p, c, hist, true, o);
    const double a = std::sqrt(c.reff * o.delta);
    const double ks = 2.25 * mur * mur * 2.0 * mix_E(E_SAND, NU, E_SAND, NU) * a;
    expect_rel(std::fabs(rr * o.fr[1]), ks * rr * rr * c.dt);
    double hist2[6] = {0, 0, 0, 0, 1.0, 0};
    compute(p, c, hist2, true, o);
    expect_rel(rr * std::hypot(o.fr[0], o.fr[1]), mur * rr * o.fn);
  }
}

TEST(Rolling, MeanRadiusAtAPlateIsTheParticles)
{
  // a plate has no radius: R_r = R_i under both conventions (the same bits)
  const Params pe = with_radius(sand(0.2, 0.31, 0.05, ROLLING_EPSD), false);
  const Params pm = with_radius(pe, true);
  const double ri = 2.5e-3;
  double dx[3] = {0, 0, ri - 1e-5}, z[3] = {0, 0, 0}, w[3] = {0, 3.0, 0};
  Contact c;
  c.dx = dx; c.reff = ri; c.meff = 1e-4;
  c.radi = ri; c.radj = 0.0; c.vi = z; c.vj = z; c.wi = w; c.wj = z; c.wall = true; c.dt = 1e-6;
  double h1[6] = {0}, h2[6] = {0};
  Result a, b;
  for (int k = 0; k < 50; k++) {
    compute(pe, c, h1, true, a);
    compute(pm, c, h2, true, b);
  }
  EXPECT_EQ(a.ti[1], b.ti[1]);
  EXPECT_NE(a.ti[1], 0.0);
}

TEST(Wall, InfiniteRadiusAndMass)
{
  // wall contact: R* = r_i, lever arm r_i; E* from the particle and plate materials
  const double Es = mix_E(E_SAND, NU, 200e9, NU);
  const Params p = make_params(Es, mix_G(E_SAND, NU, 200e9, NU), 1.0, 0.3, 0.0, ROLLING_NONE, false);
  const double ri = 2.5e-3, d = 1e-5;
  double dx[3] = {0, 0, ri - d}, v[3] = {0.01, 0, 0}, z[3] = {0, 0, 0};
  Contact c;
  c.dx = dx; c.reff = ri; c.meff = 1e-4;
  c.radi = ri; c.radj = 0.0; c.vi = v; c.vj = z; c.wi = z; c.wj = z; c.wall = true; c.dt = 1e-6;
  double hist[6] = {0};
  Result o;
  compute(p, c, hist, true, o);
  expect_rel(o.fne, 4.0 / 3.0 * Es * std::sqrt(ri) * std::pow(o.delta, 1.5));
  expect_rel(o.ti[1], -ri * o.fs[0]);
}

// The by-value helpers of the branch-free lane law give the same bits as the pointer ones.
TEST(ContactLaw, ValueHelpersMatchPointerHelpers)
{
  using namespace tbags::vec;
  const double n0[3] = {0.3, -0.5, 0.8};
  const double s = 1.0 / std::sqrt(dot(n0, n0));
  const double n[3] = {n0[0] * s, n0[1] * s, n0[2] * s};
  const double cases[][3] = {{1e-5, 2e-6, -3e-6}, {0.0, 0.0, 0.0}, {n[0], n[1], n[2]},
                             {-4e-7, 9e-7, 1e-8}};
  for (const auto &c : cases) {
    double a[3] = {c[0], c[1], c[2]};
    rotate_onto_plane(a, n);
    const V3 b = onto_plane(load3(c), load3(n));
    EXPECT_EQ(a[0], b.x);
    EXPECT_EQ(a[1], b.y);
    EXPECT_EQ(a[2], b.z);
    double x[3];
    cross(c, n, x);
    const V3 y = cross(load3(c), load3(n));
    EXPECT_EQ(x[0], y.x);
    EXPECT_EQ(x[1], y.y);
    EXPECT_EQ(x[2], y.z);
    EXPECT_EQ(dot(c, n), dot(load3(c), load3(n)));
  }
  const V3 p{1, 2, 3}, q{4, 5, 6};
  EXPECT_EQ(select(true, p, q).y, 2.0);
  EXPECT_EQ(select(false, p, q).y, 5.0);
}

namespace {
// A sphere on a plate (below it, normal +z): mass m, radius r; Contact with the plate.
struct OnPlate {
  double r = 2.5e-3, m = 2.9e-5, dt = 1e-6;
  double dx[3] = {0, 0, 0}, v[3] = {0, 0, 0}, w[3] = {0, 0, 0}, z[3] = {0, 0, 0};
  double vd[3] = {0, 0, 0}, wd[3] = {0, 0, 0};
  Contact c(double height, bool implicit, const double *fother)
  {
    dx[2] = height;
    Contact k;
    k.dx = dx; k.reff = r; k.meff = m; k.radi = r; k.radj = 0.0;
    k.vi = v; k.vj = z; k.wi = w; k.wj = z; k.wall = true; k.dt = dt;
    if (implicit) {    // as fix wall/gran/servo: the velocities predicted from the forces so far
      const double hm = 0.5 * dt / m;
      for (int d = 0; d < 3; d++) {
        vd[d] = v[d] + hm * fother[d];
        wd[d] = w[d];
      }
      k.vdi = vd; k.wdi = wd; k.hm = hm;
    }
    return k;
  }
};
Params bag_on_steel(double e)
{
  return make_params(mix_E(0.75e9, 0.1, 200e9, 0.1), mix_G(0.75e9, 0.1, 200e9, 0.1), e, 1e10,
                     0.0, ROLLING_NONE, false);
}
}    // namespace

// Implicit damping against the closed form: the damping forces act against the end of the step's
// contact velocities, u = (u_pred + hm f_el) / (1 + eta hm), normal (hm = dt/2/m) and
// tangential (3.5 hm: the sphere's rotation); without hm the same bits as the stock call.
TEST(Wall, ImplicitDampingClosedForm)
{
  const Params p = bag_on_steel(0.2);
  OnPlate s;
  s.dt = 3e-6;
  s.v[0] = 2e-3; s.v[1] = -1e-3; s.v[2] = -4e-3;
  s.w[1] = 0.5;
  const double fother[3] = {0.3, 0.1, -0.8};
  const double d = 8e-6;
  double h0[6] = {2e-7, -1e-7, 0, 0, 0, 0};
  double h[6], he[6];
  std::copy(h0, h0 + 6, h);
  std::copy(h0, h0 + 6, he);
  Result o, oe, ox;
  const Contact ce = s.c(s.r - d, false, fother);
  compute(p, ce, he, true, oe);
  const Contact ci = s.c(s.r - d, true, fother);
  compute(p, ci, h, true, o);

  const double a = std::sqrt(s.r * d), hm = 0.5 * s.dt / s.m;
  const double fne = p.kn * a * d, etan = p.cn * std::sqrt(s.m * a), etat = p.ct * std::sqrt(s.m * a);
  // normal (+z): u_pred = v_z + hm f_z
  const double un = (s.v[2] + hm * fother[2] + hm * fne) / (1.0 + etan * hm);
  expect_rel(o.fn, fne - etan * un);
  // tangential: the history integrated with the half step's velocity (v_t - r w x n), the
  // damping against the predicted one (no predicted spin change here)
  const double vt[2] = {s.v[0] - s.r * s.w[1], s.v[1] + s.r * s.w[0]};
  const double vtp[2] = {vt[0] + hm * fother[0], vt[1] + hm * fother[1]};
  for (int k = 0; k < 2; k++) {
    const double hk = h0[k] + s.dt * vt[k];
    expect_rel(h[k], hk);
    const double ut = (vtp[k] - 3.5 * hm * p.kt * a * hk) / (1.0 + etat * 3.5 * hm);
    expect_rel(o.fs[k], -p.kt * a * hk - etat * ut);
  }
  // the two schemes differ (this case is stiff enough to tell them apart)
  EXPECT_GT(std::fabs(o.fs[0] - oe.fs[0]), 1e-3 * std::fabs(oe.fs[0]));
  // hm = 0 with predicted velocities given: the stock bits
  Contact cz = ci;
  cz.hm = 0.0;
  std::copy(h0, h0 + 6, h);
  compute(p, cz, h, true, ox);
  for (int k = 0; k < 3; k++) {
    EXPECT_EQ(ox.f[k], oe.f[k]);
    EXPECT_EQ(ox.ti[k], oe.ti[k]);
    EXPECT_EQ(h[k], he[k]);
  }
}

namespace {
// A no-slip sphere pressed onto a plate by a constant force, its tangential contact mode excited,
// integrated as LAMMPS does (nve/sphere: half kick, drift, forces, half kick; the plate's force
// last, as a fix's post_force). Returns the largest |tangential contact velocity| over the last
// `tail` of nsteps, relative to the initial one; omega_dt: the tangential mode's omega dt.
double tangential_mode(bool implicit, double omega_dt, int nsteps, int tail = 200)
{
  const Params p = bag_on_steel(0.2);
  OnPlate s;
  const double F0 = 5.0;    // N pressing the sphere down: its overlap sets the stiffness
  const double d0 = std::pow(F0 / (p.kn * std::sqrt(s.r)), 2.0 / 3.0);
  const double kt = p.kt * std::sqrt(s.r * d0);
  s.dt = omega_dt / std::sqrt(TANGENTIAL_COMPLIANCE * kt / s.m);
  const double I = SPHERE_INERTIA * s.m * s.r * s.r;
  double zpos = s.r - d0, hist[6] = {0, 0, 0, 0, 0, 0};
  const double u0 = 1e-4;
  s.v[0] = u0;
  double f[3] = {0, 0, -F0}, t[3] = {0, 0, 0}, worst = 0.0;
  for (int step = 0; step < nsteps; step++) {
    for (int k = 0; k < 3; k++) {
      s.v[k] += 0.5 * s.dt * f[k] / s.m;
      s.w[k] += 0.5 * s.dt * t[k] / I;
    }
    zpos += s.dt * s.v[2];
    const double fext[3] = {0, 0, -F0};
    Result o;
    const Contact c = s.c(zpos, implicit, fext);
    compute(p, c, hist, true, o);
    for (int k = 0; k < 3; k++) {
      f[k] = fext[k] + o.f[k];
      t[k] = o.ti[k];
      s.v[k] += 0.5 * s.dt * f[k] / s.m;
      s.w[k] += 0.5 * s.dt * t[k] / I;
    }
    if (!std::isfinite(s.v[0]) || std::fabs(s.v[0]) > 1e3 * u0) return 1e300;
    if (step >= nsteps - tail) worst = std::max(worst, std::fabs(s.v[0] - s.r * s.w[1]) / u0);
  }
  return worst;
}
}    // namespace

// The no-slip contact's tangential mode (damping ratio 0.78) is unstable above omega dt = 1.0
// with the half step's velocities (stock) and stable up to the undamped limit 2 with implicit
// damping; at a small step the two schemes give the same motion.
TEST(Wall, ImplicitDampingStableAtTwiceTheStep)
{
  EXPECT_LT(tangential_mode(false, 0.9, 4000), 1e-3);    // stock, below its limit: decays
  EXPECT_GT(tangential_mode(false, 1.1, 4000), 1.0);     // stock, above it: grows
  EXPECT_LT(tangential_mode(true, 1.1, 4000), 1e-3);     // implicit: decays
  EXPECT_LT(tangential_mode(true, 1.9, 4000), 1e-3);
  EXPECT_GT(tangential_mode(true, 2.1, 4000), 1.0);      // the undamped limit stays
  // the same physics: at small steps the velocity after the same time (0.5/omega, while it
  // decays) agrees, and the difference halves with the step (both schemes are first order in
  // the damping's velocity)
  const double e1 = tangential_mode(false, 0.01, 50, 1), i1 = tangential_mode(true, 0.01, 50, 1);
  const double e2 = tangential_mode(false, 0.005, 100, 1), i2 = tangential_mode(true, 0.005, 100, 1);
  EXPECT_GT(e1, 0.2);
  EXPECT_NEAR(i1, e1, 0.02 * e1);
  EXPECT_LT(std::fabs(i2 - e2), 0.6 * std::fabs(i1 - e1));
}

// Twisting (TwistingSds, LAMMPS's "twisting sds"): the geometry's twist rate is the relative spin
// about the normal; the moment is the spring on the integrated angle plus the dashpot, and at the
// cap mu_tw |F_n| it stays there with the angle reset so that the next elastic step starts from
// the cap; no twisting without a spring.
TEST(Twisting, SdsSpringDashpotAndCap)
{
  Params p = sand();
  p.ktw = 2e-4;     // N m/rad
  p.ctw = 1e-8;     // N m s/rad
  p.mutw = 1e-4;    // m: cap 1e-4 |F_n|
  Touch t;
  t.dx = tbags::vec::V3{0.0, 0.0, 5e-3 - 1e-5};    // n = +z
  t.vr = tbags::vec::V3{0.0, 0.0, 0.0};
  t.wi = tbags::vec::V3{0.3, 0.0, 4.0};
  t.wj = tbags::vec::V3{0.0, -0.2, 1.0};
  t.radi = t.radj = 2.5e-3;
  t.meff = 5e-5;
  t.reff = 1.25e-3;
  State s = geometry(p, t, false);
  expect_rel(s.wt, 3.0, 1e-15);    // (w_i - w_j) . n: only the spin about z
  normal_force(p, false, s);
  const double dt = 1e-6, fn = std::fabs(s.fn);
  double theta = 0.0;
  for (int k = 1; k <= 5; k++) {    // elastic: M = -k theta - c w_t, theta = k dt w_t
    TwistingSds::history(p, s, dt, theta);
    const double m = TwistingSds::moment(p, s, theta);
    expect_rel(theta, k * dt * 3.0, 1e-12);
    expect_rel(m, -p.ktw * k * dt * 3.0 - p.ctw * 3.0, 1e-12);
  }
  // past the cap: the moment is the cap against the spin, the angle such that spring and
  // dashpot give it
  theta = 10.0;
  double m = TwistingSds::moment(p, s, theta);
  const double crit = p.mutw * fn;
  expect_rel(m, -crit, 1e-12);
  expect_rel(-p.ktw * theta - p.ctw * s.wt, -crit, 1e-12);
  // the torque on i along the normal (j gets its opposite)
  const tbags::vec::V3 ti = twisting_torque(s, m);
  EXPECT_EQ(ti.x, 0.0);
  expect_rel(ti.z, -crit, 1e-12);
  // opposite spin, opposite cap
  s.wt = -3.0;
  theta = -10.0;
  expect_rel(TwistingSds::moment(p, s, theta), crit, 1e-12);
  // no spring: no twisting, the angle kept
  p.ktw = 0.0;
  theta = 0.5;
  TwistingSds::history(p, s, dt, theta);
  EXPECT_EQ(TwistingSds::moment(p, s, theta), 0.0);
  EXPECT_EQ(theta, 0.5);
}

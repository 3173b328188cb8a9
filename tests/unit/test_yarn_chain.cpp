// Unit tests of law/yarn_chain.h: a batch of bonds gives, bit for bit, what the yarn law's stages
// (yarn_law.h) chained by hand for one bond give (history integrated or not, elastic or plastic,
// stretched, slack and breaking bonds, histories that turn by more than the rotation's series
// allows), and so does compute() for one bond.

#include "law/yarn_chain.h"
#include "yarn_fixtures.h"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <random>

using namespace tbags::yarn;
using tbags::row3;
using tbags::vec::V3;

namespace {

// The stages chained by hand, one bond (the reference): history h (NHISTORY) updated when
// integrating; f, ti, tj, eps, fax, broken out.
struct Ref {
  V3 f, ti, tj;
  double eps, fax;
  bool broken;
};
Ref reference_bond(const Params &p, bool update, const V3 &xi, const V3 &xj, const V3 &vi,
                   const V3 &vj, const V3 &wi, const V3 &wj, double dt, double *h)
{
  const Motion m = kinematics(xi, xj, vi, vj, wi, wj, h[R0]);
  V3 fs{h[FS], h[FS + 1], h[FS + 2]}, mb{h[MB], h[MB + 1], h[MB + 2]};
  double mt = h[MT];
  if (update) integrate(springs(p), m, h[R0], dt, fs, mb, mt);
  h[FS] = fs.x, h[FS + 1] = fs.y, h[FS + 2] = fs.z;
  h[MB] = mb.x, h[MB + 1] = mb.y, h[MB + 2] = mb.z;
  h[MT] = mt;
  Ref o;
  o.eps = m.eps;
  o.broken = breaks(p, m.eps);
  o.fax = axial_force(p, m.eps, &h[EPSMAX], update);
  forces(p, m, o.fax, fs, mb, mt, o.f, o.ti, o.tj);
  return o;
}

// the fixtures' yarn with damping, breaking at 12 % (some random bonds break), elastic or plastic
Params params(const Curve &c, bool plastic)
{
  Params p = yarn_fixtures::yarn(c);
  p.eps_break = 0.12;
  p.gn = 1e-3, p.gs = 2e-3, p.gr = 1e-8;
  p.plastic = plastic;
  return p;
}

// A random bond in column l: rest length 5 mm, strain -5 % to +15 % (slack, stretched, some
// broken), ends moving up to 1 m/s and spinning up to 300 rad/s, a history of springs that
// leans out of the bond's normal plane by up to `tilt` (radians; above about 1e-3 the rotation
// needs its exact form) and a largest strain reached.
template <int W> void random_bond(Lanes<W> &b, int l, std::mt19937_64 &g, double tilt)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0), s(-0.05, 0.15);
  const double r0 = 0.005;
  V3 n{u(g), u(g), u(g)};
  n = (1.0 / std::sqrt(tbags::vec::dot(n, n))) * n;
  const V3 xi{u(g) * 0.01, u(g) * 0.01, u(g) * 0.01};
  const V3 xj = xi + (r0 * (1.0 + s(g))) * n;
  for (int k = 0; k < 3; k++) {
    b.xi[k][l] = k == 0 ? xi.x : k == 1 ? xi.y : xi.z;
    b.xj[k][l] = k == 0 ? xj.x : k == 1 ? xj.y : xj.z;
    b.vi[k][l] = u(g), b.vj[k][l] = u(g);
    b.wi[k][l] = 300 * u(g), b.wj[k][l] = 300 * u(g);
  }
  b.h[R0][l] = r0;
  b.h[EPSMAX][l] = 0.1 * std::fabs(u(g));
  // spring histories in the plane normal to n, leaning out by up to tilt
  for (int base : {int(FS), int(MB)}) {
    V3 a{u(g), u(g), u(g)};
    a = a - tbags::vec::dot(a, n) * n;
    a = a + (tilt * std::fabs(u(g)) * std::sqrt(tbags::vec::dot(a, a))) * n;
    const double scale = base == FS ? 1.0 : 1e-3;
    b.h[base][l] = scale * a.x, b.h[base + 1][l] = scale * a.y, b.h[base + 2][l] = scale * a.z;
  }
  b.h[MT][l] = 1e-4 * u(g);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

void expect_same(const V3 &a, const V3 &b, const char *what, int l)
{
  EXPECT_TRUE(same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z))
      << what << " of bond " << l << ": " << a.x << " " << a.y << " " << a.z << " against " << b.x
      << " " << b.y << " " << b.z;
}

// n bonds through the batch and through the reference: every output and history, bit for bit
template <bool UPDATE> void check_batch(bool plastic, double tilt, int n, unsigned seed)
{
  const Curve c = yarn_fixtures::tape();
  const Params p = params(c, plastic);
  std::mt19937_64 g(seed);
  auto b = std::make_unique<Batch>();
  for (int l = 0; l < n; l++) random_bond(*b, l, g, tilt);
  auto in = std::make_unique<Batch>(*b);
  const double dt = 1e-6;
  chain<UPDATE>(p, *b, n, dt);
  int nbroken = 0, nslack = 0;
  for (int l = 0; l < n; l++) {
    double h[NHISTORY];
    for (int k = 0; k < NHISTORY; k++) h[k] = in->h[k][l];
    const Ref r = reference_bond(p, UPDATE, row3(in->xi, l), row3(in->xj, l), row3(in->vi, l),
                                 row3(in->vj, l), row3(in->wi, l), row3(in->wj, l), dt, h);
    expect_same(row3(b->f, l), r.f, "force", l);
    expect_same(row3(b->ti, l), r.ti, "torque on i", l);
    expect_same(row3(b->tj, l), r.tj, "torque on j", l);
    EXPECT_TRUE(same_bits(b->eps[l], r.eps) && same_bits(b->fax[l], r.fax)) << "bond " << l;
    EXPECT_EQ(bool(b->broken[l]), r.broken) << "bond " << l;
    for (int k = 0; k < NHISTORY; k++) EXPECT_TRUE(same_bits(b->h[k][l], h[k])) << "history " << k;
    nbroken += r.broken;
    nslack += r.eps <= 0.0;
  }
  // the random bonds cover the cases
  EXPECT_GT(nbroken, 0);
  EXPECT_GT(nslack, 0);
}

}    // namespace

TEST(YarnChain, BatchIsTheStagesChainedByHand)
{
  for (int n : {32, 29})    // a full batch and the last, partial one of a list
    for (unsigned seed : {1u, 2u, 3u}) {
      check_batch<true>(false, 1e-4, n, seed);
      check_batch<true>(true, 1e-4, n, seed);
      check_batch<false>(false, 1e-4, n, seed);
    }
}

TEST(YarnChain, HistoriesThatTurnFarNeedTheExactRotation)
{
  // a tilt of 0.05 rad: the rotation's series does not hold, onto_plane() takes the exact form
  check_batch<true>(false, 0.05, 32, 7);
  check_batch<true>(true, 0.05, 32, 8);
}

TEST(YarnChain, OneBondIsTheBatchsLane)
{
  const Curve c = yarn_fixtures::tape();
  const Params p = params(c, true);
  std::mt19937_64 g(11);
  auto b = std::make_unique<Batch>();
  for (int l = 0; l < 32; l++) random_bond(*b, l, g, 1e-4);
  auto in = std::make_unique<Batch>(*b);
  chain<true>(p, *b, 32, 1e-6);
  for (int l = 0; l < 32; l++) {
    double xi[3], xj[3], vi[3], vj[3], wi[3], wj[3], h[NHISTORY];
    for (int k = 0; k < 3; k++) {
      xi[k] = in->xi[k][l], xj[k] = in->xj[k][l], vi[k] = in->vi[k][l], vj[k] = in->vj[k][l];
      wi[k] = in->wi[k][l], wj[k] = in->wj[k][l];
    }
    for (int k = 0; k < NHISTORY; k++) h[k] = in->h[k][l];
    Result o;
    compute(p, Bond{xi, xj, vi, vj, wi, wj, 1e-6}, h, true, o);
    expect_same(V3{o.f[0], o.f[1], o.f[2]}, row3(b->f, l), "force", l);
    expect_same(V3{o.ti[0], o.ti[1], o.ti[2]}, row3(b->ti, l), "torque on i", l);
    expect_same(V3{o.tj[0], o.tj[1], o.tj[2]}, row3(b->tj, l), "torque on j", l);
    EXPECT_EQ(o.broken, bool(b->broken[l]));
    for (int k = 0; k < NHISTORY; k++) EXPECT_TRUE(same_bits(b->h[k][l], h[k])) << "history " << k;
  }
}

// Unit tests of law/contact_chain.h: the batch gives, bit for bit, what the law's stages
// (contact_law.h) chained by hand for one contact give, for every rolling model and every
// variant of the batch (history update, one set of constants or one per contact, special-bond
// factors, fast path, frozen particles, twisting), and so does compute() for one contact and a
// plate.

#include "law/contact_chain.h"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <random>

using namespace tbags::contact;
using tbags::row3;
using tbags::vec::V3;

namespace {

// What the reference gives for one contact.
struct Out {
  V3 f, ti, tj, fs, fr;
  double fn, fne, delta, r;
};

// The stages chained by hand, one contact (the reference): its outputs, ht, hr and the twist
// angle tw updated.
template <int ROLL, bool UPDATE, bool TWIST = false>
Out reference_contact(const Params &p, bool clip, const Touch &t, bool wall, double dt, V3 &ht,
                      V3 &hr, double &tw)
{
  using Rolling = typename RollingModel<ROLL>::type;
  State s = geometry(p, t, wall);
  normal_force(p, clip, s);
  if (UPDATE) tangential_history(p, s, dt, ht);
  const V3 fs = tangential_force(p, s, ht);
  const Forces c = contact_forces(s, fs, t.radi, t.radj, wall);
  Out o{c.f, c.ti, c.tj, fs, V3{0.0, 0.0, 0.0}, s.fn, s.fne, s.delta, s.r};
  if constexpr (ROLL != ROLLING_NONE) {
    if constexpr (Rolling::HISTORY > 0)
      if (UPDATE) Rolling::history(p, s, dt, hr);
    o.fr = Rolling::force(p, s, hr);
    const V3 troll = rolling_torque(s, o.fr);
    const bool on = rolling_acts(p);
    o.ti = tbags::vec::select(on, o.ti + troll, o.ti);
    o.tj = tbags::vec::select(on, o.tj - troll, o.tj);
  }
  if constexpr (TWIST) {
    if (UPDATE) TwistingSds::history(p, s, dt, tw);
    const V3 ttw = twisting_torque(s, TwistingSds::moment(p, s, tw));
    o.ti = o.ti + ttw;
    o.tj = o.tj - ttw;
  }
  return o;
}

// Two materials (sand and a yarn-like polymer), rolling on in the first and both ways for the
// second when mur2 is 0; limit_damping as given; twist: a twisting spring in the first (its
// cap reached by some contacts), none in the second.
struct Materials {
  Params p[2];
  Materials(int roll, double mur2, bool clip, bool twist = false)
  {
    p[0] = make_params(mix_E(1.8e9, 0.1, 1.8e9, 0.1), mix_G(1.8e9, 0.1, 1.8e9, 0.1), 0.2, 0.31, 0.05,
                       roll, clip);
    p[1] = make_params(mix_E(1.8e9, 0.1, 0.9e9, 0.3), mix_G(1.8e9, 0.1, 0.9e9, 0.3), 0.6, 0.5, mur2,
                       roll, clip);
    if (twist) {
      p[0].ktw = 1e-3;
      p[0].ctw = 1e-9;
      p[0].mutw = 2e-8;
    }
  }
};

// A random touching contact in column l (overlap up to 2 % of the radius sum, speeds up to
// 1 m/s, spins up to 300 rad/s, a history of the tangential and rolling springs that leans out
// of the tangent plane by tilt), masses negative (frozen) now and then.
void random_contact(Batch &b, int l, std::mt19937_64 &g, const Params *p, double tilt, bool frozen)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  const double ri = 2e-3 + 1e-3 * pos(g), rj = 2e-3 + 1e-3 * pos(g);
  V3 n{u(g), u(g), u(g)};
  n = (1.0 / std::sqrt(tbags::vec::dot(n, n))) * n;
  const double r = (ri + rj) * (1.0 - 0.02 * pos(g)) + 1e-9;
  b.i[l] = l;
  b.j[l] = l + 100;
  b.hist[l] = nullptr;
  b.p[l] = p;
  b.dx[0][l] = r * n.x;
  b.dx[1][l] = r * n.y;
  b.dx[2][l] = r * n.z;
  b.radi[l] = ri;
  b.radj[l] = rj;
  b.mi[l] = 1e-4 * (0.5 + pos(g)) * ((frozen && l % 7 == 3) ? -1.0 : 1.0);
  b.mj[l] = 1e-4 * (0.5 + pos(g)) * ((frozen && l % 5 == 1) ? -1.0 : 1.0);
  b.factor[l] = (l % 3 == 0) ? 0.5 : 1.0;
  for (int k = 0; k < 3; k++) {
    b.vr[k][l] = u(g);
    b.wi[k][l] = 300.0 * u(g);
    b.wj[k][l] = 300.0 * u(g);
  }
  // history: in the tangent plane plus tilt times its length along n (sliding or sticking)
  for (int s = 0; s < 2; s++) {
    V3 h{1e-5 * u(g), 1e-5 * u(g), 1e-5 * u(g)};
    h = h - tbags::vec::dot(h, n) * n;
    h = h + (tilt * std::sqrt(tbags::vec::dot(h, h))) * n;
    b.h[3 * s][l] = h.x;
    b.h[3 * s + 1][l] = h.y;
    b.h[3 * s + 2][l] = h.z;
  }
  b.h[6][l] = 1e-3 * u(g);    // a twist angle (EPSD's twist row; else row 3 is it)
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The batch of n contacts against reference_contact() per contact; returns batch_law's redo flag.
template <int ROLL, bool UPDATE, bool SAME, bool SPECIAL, bool FAST, bool TWIST = false>
bool check_batch(const Materials &m, int n, double tilt, bool clip, unsigned seed)
{
  auto b = std::make_unique<Batch>();
  std::mt19937_64 g(seed);
  const Params *same = SAME ? &m.p[0] : nullptr;
  for (int l = 0; l < n; l++)
    random_contact(*b, l, g, SAME ? same : &m.p[l % 2], tilt, true);
  const auto in = std::make_unique<Batch>(*b);
  const double dt = 1e-6;
  const bool redo =
      batch_law<ROLL, UPDATE, SAME, SPECIAL, FAST, ExplicitDamping, TWIST>(*b, n, dt, clip, same);
  constexpr int TW = twist_row(ROLL);
  if (FAST && redo) return true;
  for (int l = 0; l < n; l++) {
    const Batch &a = *in;
    const Params &p = SAME ? *same : *a.p[l];
    // the frozen-particle rule written out: a frozen particle's partner's mass is m*
    const double mi = std::fabs(a.mi[l]), mj = std::fabs(a.mj[l]);
    double meff, reff;
    effective(mi, mj, a.radi[l], a.radj[l], meff, reff);
    if (a.mi[l] < 0.0) meff = mj;
    if (a.mj[l] < 0.0) meff = mi;
    const V3 dx = row3(a.dx, l);
    V3 ht = row3(a.h, l), hr = row3(a.h + 3, l);
    double tw = a.h[TW][l];
    const Out o = reference_contact<ROLL, UPDATE, TWIST>(
        p, clip, Touch{dx, row3(a.vr, l), row3(a.wi, l), row3(a.wj, l), a.radi[l], a.radj[l], meff, reff},
        false, dt, ht, hr, tw);
    if (TWIST)
      EXPECT_TRUE(same_bits(b->h[TW][l], tw)) << "twist angle of contact " << l << ": batch "
                                               << b->h[TW][l] << ", by hand " << tw;
    const double fl = SPECIAL ? a.factor[l] : 1.0;
    const V3 want[5] = {fl * o.f, fl * o.ti, fl * o.tj, ht, hr};
    const V3 got[5] = {row3(b->f, l), row3(b->ti, l), row3(b->tj, l), row3(b->h, l),
                       row3(b->h + 3, l)};
    const char *what[5] = {"f", "ti", "tj", "tangential history", "rolling history"};
    for (int k = 0; k < (ROLL == ROLLING_EPSD ? 5 : 4); k++) {
      EXPECT_TRUE(same_bits(got[k].x, want[k].x) && same_bits(got[k].y, want[k].y) &&
                  same_bits(got[k].z, want[k].z))
          << what[k] << " of contact " << l << ": batch (" << got[k].x << ", " << got[k].y << ", "
          << got[k].z << "), stages chained by hand (" << want[k].x << ", " << want[k].y << ", " << want[k].z
          << ")";
    }
  }
  return redo;
}

template <int ROLL, bool TWIST = false> void check_all_variants(double mur2, bool clip)
{
  const Materials m(ROLL, mur2, clip, TWIST);
  // 29 contacts (a partial last vector); histories tilted out of the plane by 1e-2 (the exact
  // rotation; the fast path reports it), 1e-4 (its series) and 1e-9 (no rotation where the
  // spring force is small)
  const double tilts[3] = {1e-2, 1e-4, 1e-9};
  for (double tilt : tilts) {
    check_batch<ROLL, true, false, false, false, TWIST>(m, 29, tilt, clip, 1);
    check_batch<ROLL, true, false, true, false, TWIST>(m, 29, tilt, clip, 2);
    check_batch<ROLL, false, false, false, false, TWIST>(m, 29, tilt, clip, 3);
    check_batch<ROLL, false, false, true, false, TWIST>(m, 29, tilt, clip, 4);
    check_batch<ROLL, true, false, true, true, TWIST>(m, 29, tilt, clip, 6);
    check_batch<ROLL, false, false, false, true, TWIST>(m, 29, tilt, clip, 8);
    if (ROLL == ROLLING_NONE || mur2 > 0.0) {    // one set for all contacts: rolling on for all
      check_batch<ROLL, true, true, false, false, TWIST>(m, 29, tilt, clip, 5);
      check_batch<ROLL, true, true, false, true, TWIST>(m, 29, tilt, clip, 7);
    }
  }
}
}    // namespace

TEST(Chain, EpsdEqualsContactLane) { check_all_variants<ROLLING_EPSD>(0.1, false); }
TEST(Chain, EpsdRollingOffForOneMaterial) { check_all_variants<ROLLING_EPSD>(0.0, false); }
TEST(Chain, CdtEqualsContactLane) { check_all_variants<ROLLING_CDT>(0.1, false); }
TEST(Chain, NoneEqualsContactLane) { check_all_variants<ROLLING_NONE>(0.0, false); }
TEST(Chain, LimitDampingEqualsContactLane) { check_all_variants<ROLLING_EPSD>(0.1, true); }
// twisting after each rolling model (the special factor then applied in its loop)
TEST(Chain, TwistingEpsdEqualsContactLane) { check_all_variants<ROLLING_EPSD, true>(0.1, false); }
TEST(Chain, TwistingCdtEqualsContactLane) { check_all_variants<ROLLING_CDT, true>(0.1, false); }
TEST(Chain, TwistingNoneEqualsContactLane) { check_all_variants<ROLLING_NONE, true>(0.0, false); }

// The fast path: a tilt the series cannot take must be reported (the caller then redoes the
// batch without it); a small one must not, and then gives the law's bits (checked above).
TEST(Chain, FastPathReportsLargeTilt)
{
  const Materials m(ROLLING_EPSD, 0.1, false);
  EXPECT_TRUE((check_batch<ROLLING_EPSD, true, false, false, true>(m, 29, 1e-2, false, 9)));
  EXPECT_FALSE((check_batch<ROLLING_EPSD, true, false, false, true>(m, 29, 1e-9, false, 10)));
}

// compute(), one contact (the plate fix, single()), is the same chain: every output, a pair of
// particles and a plate (radius 0, torque arm r_i), history integrated or not.
template <int ROLL, bool TWIST = false> void check_one_contact(bool update)
{
  const Materials m(ROLL, 0.1, false, TWIST);
  constexpr int TW = twist_row(ROLL);
  std::mt19937_64 g(11);
  for (int k = 0; k < 40; k++) {
    auto b = std::make_unique<Batch>();
    random_contact(*b, 0, g, &m.p[k % 2], k % 3 ? 1e-9 : 1e-2, false);
    const bool wall = k % 4 == 0;
    const double radj = wall ? 0.0 : b->radj[0];
    double meff, reff;
    effective(b->mi[0], b->mj[0], b->radi[0], b->radj[0], meff, reff);
    if (wall) {
      meff = b->mi[0];
      reff = b->radi[0];
    }
    // radi + radj the overlap's radius sum: a plate contact at the same overlap
    double dx[3];
    const double shrink = wall ? b->radi[0] / (b->radi[0] + b->radj[0]) : 1.0;
    for (int d = 0; d < 3; d++) dx[d] = shrink * b->dx[d][0];
    double vi[3], vj[3] = {0.0, 0.0, 0.0}, wi[3], wj[3], hist[7];
    for (int d = 0; d < 3; d++) {
      vi[d] = b->vr[d][0];
      wi[d] = b->wi[d][0];
      wj[d] = wall ? 0.0 : b->wj[d][0];
      hist[d] = b->h[d][0];
      hist[3 + d] = b->h[3 + d][0];
    }
    hist[6] = b->h[6][0];
    Contact c;
    c.dx = dx;
    c.reff = reff;
    c.meff = meff;
    c.radi = b->radi[0];
    c.radj = radj;
    c.vi = vi;
    c.vj = vj;
    c.wi = wi;
    c.wj = wj;
    c.wall = wall;
    c.dt = 1e-6;
    Result o;
    compute(m.p[k % 2], c, hist, update, o);
    V3 ht = row3(b->h, 0), hr = row3(b->h + 3, 0);
    double tw = b->h[TW][0];
    using tbags::vec::load3;
    const Touch t{load3(dx), load3(vi), load3(wi), load3(wj), c.radi, radj, meff, reff};
    // compute() twists where the constants have a twisting spring
    const Params &p = m.p[k % 2];
    const Out want = (p.ktw > 0.0)
        ? (update ? reference_contact<ROLL, true, true>(p, false, t, wall, 1e-6, ht, hr, tw)
                  : reference_contact<ROLL, false, true>(p, false, t, wall, 1e-6, ht, hr, tw))
        : (update ? reference_contact<ROLL, true>(p, false, t, wall, 1e-6, ht, hr, tw)
                  : reference_contact<ROLL, false>(p, false, t, wall, 1e-6, ht, hr, tw));
    EXPECT_TRUE(same_bits(hist[TW], p.ktw > 0.0 ? tw : b->h[TW][0])) << "twist angle of contact " << k;
    const V3 w[7] = {want.f, want.ti, want.tj, want.fs, want.fr, ht, hr};
    const double *got[7] = {o.f, o.ti, o.tj, o.fs, o.fr, hist, hist + 3};
    for (int q = 0; q < (ROLL == ROLLING_EPSD ? 7 : 6); q++)
      EXPECT_TRUE(same_bits(got[q][0], w[q].x) && same_bits(got[q][1], w[q].y) &&
                  same_bits(got[q][2], w[q].z))
          << "output " << q << " of contact " << k << (wall ? " (plate)" : "");
    EXPECT_TRUE(same_bits(o.fn, want.fn) && same_bits(o.fne, want.fne) &&
                same_bits(o.delta, want.delta) && same_bits(o.r, want.r));
  }
}

TEST(Chain, OneContactEpsd) { check_one_contact<ROLLING_EPSD>(true); check_one_contact<ROLLING_EPSD>(false); }
TEST(Chain, OneContactCdt) { check_one_contact<ROLLING_CDT>(true); check_one_contact<ROLLING_CDT>(false); }
TEST(Chain, OneContactNone) { check_one_contact<ROLLING_NONE>(true); check_one_contact<ROLLING_NONE>(false); }
TEST(Chain, OneContactTwisting)
{
  check_one_contact<ROLLING_EPSD, true>(true);
  check_one_contact<ROLLING_EPSD, true>(false);
  check_one_contact<ROLLING_NONE, true>(true);
}

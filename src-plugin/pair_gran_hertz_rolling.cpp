/* ----------------------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   pair_style gran/hertz/rolling: Hertz-Mindlin contact with restitution damping, a friction
   matrix and rolling resistance. The physics is in law/contact_law.h; this file gathers
   neighbours, keeps the contact history and scatters forces.
------------------------------------------------------------------------- */

#include "pair_gran_hertz_rolling.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix.h"
#include "fix_dummy.h"
#include "fix_neigh_history.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#ifdef TBAGS_HAVE_AVX2_CLONE
#include <immintrin.h>
#endif


using namespace LAMMPS_NS;
namespace law = tbags::contact;

static const char *STYLE = "Pair style gran/hertz/rolling";
// the candidate list is rebuilt once an atom has moved this fraction of the candidate skin since
// the build: two atoms then approached by at most 2 x 0.49 = 0.98 skins, so a pair left out
// (farther apart than r_i + r_j + skin) is still 0.02 skins from touching
static constexpr double CAND_MOVE_LIMIT = 0.49;

PairGranHertzRolling::PairGranHertzRolling(LAMMPS *lmp) :
    Pair(lmp), rolling(law::ROLLING_NONE), limit_damping(false), size_history(3),
    history_model(-1), ntypes1(0),
    freeze_group_bit(0), neighprev(0), Emod(nullptr), poiss(nullptr), matflag(nullptr),
    maxrad(nullptr), mu(nullptr), mur(nullptr), cor(nullptr), fix_history(nullptr),
    packx(nullptr), packv(nullptr), npack(0), ncand(0), x0(nullptr), nx0(0), cand_nall(0),
    cand_lastcall(-1), cskin(0.0), cand_lim2(0.0)
{
  kernel_choice = KERNEL_AUTO;
  simd_avx2 = 0;
  simd_logged = -1;
  contact_skin = 0.25;
  single_enable = 1;
  no_virial_fdotr_compute = 1;
  centroidstressflag = CENTROID_NOTAVAIL;
  finitecutflag = 1;
  restartinfo = 1;
  writedata = 1;
  // svector: fs(3) |fs| fr(3) |fr| 0 dx dy dz  (as pair granular), then overlap and F_n
  nondefault_history_transfer = 1;    // rolling history keeps its sign (transfer_history)
  single_extra = 14;
  svector = new double[single_extra];
  // placeholder so FixNeighHistory ends up in input-script order (as pair granular does)
  fix_dummy = dynamic_cast<FixDummy *>(
      modify->add_fix("NEIGH_HISTORY_GHR_DUMMY all DUMMY"));
}

PairGranHertzRolling::~PairGranHertzRolling()
{
  delete[] svector;
  free(packx);
  free(packv);
  free(x0);
  if (!fix_history && modify->get_fix_by_id("NEIGH_HISTORY_GHR_DUMMY"))
    modify->delete_fix("NEIGH_HISTORY_GHR_DUMMY");
  else if (fix_history && modify->get_fix_by_id("NEIGH_HISTORY_GHR"))
    modify->delete_fix("NEIGH_HISTORY_GHR");
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(Emod);
    memory->destroy(poiss);
    memory->destroy(matflag);
    memory->destroy(maxrad);
    memory->destroy(mu);
    memory->destroy(mur);
    memory->destroy(cor);
  }
}

/* ---------------------------------------------------------------------- */

void PairGranHertzRolling::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  ntypes1 = n + 1;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  memory->create(Emod, n + 1, "pair:Emod");
  memory->create(poiss, n + 1, "pair:poiss");
  memory->create(matflag, n + 1, "pair:matflag");
  memory->create(maxrad, n + 1, "pair:maxrad");
  memory->create(mu, n + 1, n + 1, "pair:mu");
  memory->create(mur, n + 1, n + 1, "pair:mur");
  memory->create(cor, n + 1, n + 1, "pair:cor");
  for (int i = 0; i <= n; i++) {
    Emod[i] = poiss[i] = maxrad[i] = 0.0;
    matflag[i] = 0;
    for (int j = 0; j <= n; j++) {
      // diagonal marked set so that init_style(), not Pair::init()'s generic message,
      // reports a type without coefficients (matflag tracks what pair_coeff gave)
      setflag[i][j] = (i == j) ? 1 : 0;
      mu[i][j] = mur[i][j] = cor[i][j] = -1.0;
    }
  }
  law.assign((size_t) (n + 1) * (n + 1), law::Params());
}

/* ----------------------------------------------------------------------
   pair_style gran/hertz/rolling epsd|cdt|none [limit_damping]
------------------------------------------------------------------------- */

void PairGranHertzRolling::settings(int narg, char **arg)
{
  if (narg < 1)
    error->all(FLERR, "{}: missing rolling model; write 'pair_style gran/hertz/rolling epsd' "
               "(or cdt, none)", STYLE);
  if (strcmp(arg[0], "epsd") == 0) rolling = law::ROLLING_EPSD;
  else if (strcmp(arg[0], "cdt") == 0) rolling = law::ROLLING_CDT;
  else if (strcmp(arg[0], "none") == 0) rolling = law::ROLLING_NONE;
  else
    error->all(FLERR, "{}: unknown rolling model '{}'; use epsd, cdt or none", STYLE, arg[0]);
  limit_damping = false;
  kernel_choice = KERNEL_AUTO;
  contact_skin = 0.25;
  for (int iarg = 1; iarg < narg; iarg++) {
    if (strcmp(arg[iarg], "limit_damping") == 0) {
      limit_damping = true;
    } else if (strcmp(arg[iarg], "kernel") == 0) {
      if (iarg + 1 >= narg) error->all(FLERR, "{}: kernel needs auto, avx2 or baseline", STYLE);
      const std::string k = arg[++iarg];
      if (k == "auto") kernel_choice = KERNEL_AUTO;
      else if (k == "avx2") kernel_choice = KERNEL_AVX2;
      else if (k == "baseline") kernel_choice = KERNEL_BASELINE;
      else error->all(FLERR, "{}: kernel must be auto, avx2 or baseline, not '{}'", STYLE, k);
    } else if (strcmp(arg[iarg], "contact_skin") == 0) {
      if (iarg + 1 >= narg)
        error->all(FLERR, "{}: contact_skin needs a fraction of the neighbor skin", STYLE);
      contact_skin = utils::numeric(FLERR, arg[++iarg], false, lmp);
      if (contact_skin < 0.0)
        error->all(FLERR, "{}: contact_skin must be a fraction >= 0 of the neighbor skin (got {})",
                   STYLE, contact_skin);
    } else {
      error->all(FLERR, "{}: unknown keyword '{}'; use limit_damping, kernel or contact_skin",
                 STYLE, arg[iarg]);
    }
  }
  size_history = law::history_size(rolling);
}

/* ----------------------------------------------------------------------
   pair_coeff I J [material E nu] [friction mu] [rolling mu_r] [restitution e]
   material only with I == J; for I == J friction and restitution (and rolling unless the
   model is none) are required; for I != J, values not given mix from the diagonal.
------------------------------------------------------------------------- */

void PairGranHertzRolling::coeff(int narg, char **arg)
{
  if (narg < 3)
    error->all(FLERR, "{}: pair_coeff needs I J and coefficients, e.g. 'pair_coeff 1 1 material "
               "1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2'", STYLE);
  if (!allocated) allocate();

  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);

  double E = -1.0, nu = 0.0, f = -1.0, fr = -1.0, e = -1.0;
  bool has_mat = false;
  for (int iarg = 2; iarg < narg;) {
    const std::string kw = arg[iarg];
    auto need = [&](int n) {
      if (iarg + n >= narg)
        error->all(FLERR, "{}: pair_coeff keyword '{}' needs {} value(s)", STYLE, kw, n);
    };
    if (kw == "material") {
      need(2);
      E = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      nu = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      if (E <= 0.0)
        error->all(FLERR, "{}: Young's modulus must be > 0 (got {}); give it in Pa with units si",
                   STYLE, E);
      if (nu <= -1.0 || nu >= 0.5)
        error->all(FLERR, "{}: Poisson's ratio must be in (-1, 0.5) (got {})", STYLE, nu);
      has_mat = true;
      iarg += 3;
    } else if (kw == "friction") {
      need(1);
      f = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (f < 0.0) error->all(FLERR, "{}: friction must be >= 0 (got {})", STYLE, f);
      iarg += 2;
    } else if (kw == "rolling") {
      need(1);
      fr = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (fr < 0.0) error->all(FLERR, "{}: rolling friction mu_r must be >= 0 (got {})", STYLE, fr);
      iarg += 2;
    } else if (kw == "restitution") {
      need(1);
      e = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (e <= 0.0 || e > 1.0)
        error->all(FLERR, "{}: coefficient of restitution must be in (0, 1] (got {})", STYLE, e);
      iarg += 2;
    } else {
      error->all(FLERR, "{}: unknown pair_coeff keyword '{}'; use material, friction, rolling, "
                 "restitution", STYLE, kw);
    }
  }

  if (has_mat && (MAX(ilo, jlo) > MIN(ihi, jhi)))
    error->all(FLERR, "{}: 'material' sets a type's E and nu: give it in 'pair_coeff I I' (or * *), "
               "not for the pair {} {}", STYLE, arg[0], arg[1]);
  int count = 0;
  for (int i = ilo; i <= ihi; i++) {
    for (int j = MAX(jlo, i); j <= jhi; j++) {
      if (i == j) {
        if (!has_mat && !matflag[i])
          error->all(FLERR, "{}: pair_coeff {} {} needs 'material E nu' for type {}", STYLE, i, i, i);
        if (f < 0.0 || e < 0.0 || (rolling != law::ROLLING_NONE && fr < 0.0))
          error->all(FLERR, "{}: pair_coeff {} {} needs friction, restitution{}", STYLE, i, i,
                     rolling != law::ROLLING_NONE ? " and rolling" : "");
        if (has_mat) {
          Emod[i] = E;
          poiss[i] = nu;
          matflag[i] = 1;
        }
      }
      if (f >= 0.0) mu[i][j] = f;
      if (fr >= 0.0) mur[i][j] = fr;
      if (e >= 0.0) cor[i][j] = e;
      if (rolling == law::ROLLING_NONE && fr < 0.0) mur[i][j] = 0.0;
      if (i != j) mixed_flag = 0;    // write_data: off-diagonal values need 'pair ij'
      setflag[i][j] = 1;
      count++;
    }
  }
  if (count == 0) error->all(FLERR, "{}: pair_coeff {} {} sets no type pair", STYLE, arg[0], arg[1]);
}

/* ---------------------------------------------------------------------- */

void PairGranHertzRolling::init_style()
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "{} requires per-atom radius, rmass, omega and torque: use atom_style "
               "sphere or bpm/sphere", STYLE);
  if (comm->ghost_velocity == 0)
    error->all(FLERR, "{} requires ghost atoms to store velocity: add 'comm_modify vel yes'", STYLE);
  for (int i = 1; i <= atom->ntypes; i++)
    if (!matflag[i])
      error->all(FLERR, "{}: type {} has no material: write 'pair_coeff {} {} material E nu "
                 "friction mu{} restitution e'", STYLE, i, i, i, rolling ? " rolling mu_r" : "");

  neighbor->add_request(this, NeighConst::REQ_SIZE | NeighConst::REQ_HISTORY);

  if (fix_history == nullptr) {
    fix_history = dynamic_cast<FixNeighHistory *>(
        modify->replace_fix("NEIGH_HISTORY_GHR_DUMMY",
                            "NEIGH_HISTORY_GHR all NEIGH_HISTORY/TBAGS " +
                                std::to_string(size_history),
                            1));
    fix_history->pair = this;
  } else {
    fix_history = dynamic_cast<FixNeighHistory *>(modify->get_fix_by_id("NEIGH_HISTORY_GHR"));
    if (!fix_history) error->all(FLERR, "{}: could not find its neighbor history fix", STYLE);
    // pair_style re-issued with another rolling model (LAMMPS then only calls settings()): the
    // store holds the old model's records, of another size and meaning; start a new one, in place
    if (history_model != rolling || fix_history->get_dnum() != size_history) {
      if (comm->me == 0)
        error->warning(FLERR, "{}: the rolling model changed since the last run: the contact "
                       "histories start again from zero", STYLE);
      // (replace_fix needs the new ID free: the old store is renamed first)
      delete[] fix_history->id;
      fix_history->id = utils::strdup("NEIGH_HISTORY_GHR_OLD");
      fix_history = dynamic_cast<FixNeighHistory *>(modify->replace_fix(
          "NEIGH_HISTORY_GHR_OLD", "NEIGH_HISTORY_GHR all NEIGH_HISTORY/TBAGS " + std::to_string(size_history), 1));
      fix_history->pair = this;
    }
  }
  history_model = rolling;

  auto fixlist = modify->get_fix_by_style("^freeze");
  if (fixlist.size() > 1) error->all(FLERR, "{}: only one fix freeze is allowed", STYLE);
  freeze_group_bit = fixlist.empty() ? 0 : fixlist.front()->groupbit;
  for (const auto &ifix : modify->get_fix_list())
    if (ifix->rigid_flag)
      error->all(FLERR, "{} does not support rigid bodies (fix {}); use pair granular", STYLE,
                 ifix->style);

  // per-type largest radius sets the cutoffs (atoms inserted later must not be larger)
  std::vector<double> onerad(atom->ntypes + 1, 0.0);
  for (int i = 0; i < atom->nlocal; i++)
    onerad[atom->type[i]] = MAX(onerad[atom->type[i]], atom->radius[i]);
  MPI_Allreduce(&onerad[1], &maxrad[1], atom->ntypes, MPI_DOUBLE, MPI_MAX, world);

  // candidate list (see the header): its skin a fraction of the neighbor skin (contact_skin,
  // 1/4 by default; 0: none, the whole list every step; the results are the same bits)
  cskin = contact_skin * neighbor->skin;
  cand_lim2 = (CAND_MOVE_LIMIT * cskin) * (CAND_MOVE_LIMIT * cskin);
  cand_nall = 0;

  choose_kernel();
}

/* ----------------------------------------------------------------------
   the build of the batch law that runs (keyword kernel): AVX2 where the plugin has it and the
   CPU runs it (auto), or as asked; logged whenever it changes
------------------------------------------------------------------------- */

void PairGranHertzRolling::choose_kernel()
{
#ifdef TBAGS_HAVE_AVX2_CLONE
  const bool have = __builtin_cpu_supports("avx2");
  const char *why = have ? "" : "this CPU has no AVX2";
#else
  const bool have = false;
  const char *why = "this plugin was built without the AVX2 kernel";
#endif
  if (kernel_choice == KERNEL_AVX2 && !have)
    error->all(FLERR, "{}: kernel avx2 is not available ({}); use kernel auto or baseline", STYLE,
               why);
  simd_avx2 = (have && kernel_choice != KERNEL_BASELINE) ? 1 : 0;
  if (simd_avx2 != simd_logged && comm->me == 0)
    utils::logmesg(lmp, "{}: batch kernel {} (kernel {}{}{})\n", STYLE,
                   simd_avx2 ? "avx2, 4 contacts per vector" : "baseline x86-64, 2 contacts per vector",
                   kernel_choice == KERNEL_AUTO ? "auto" : kernel_choice == KERNEL_AVX2 ? "avx2" : "baseline",
                   (!have && kernel_choice == KERNEL_AUTO) ? ": " : "",
                   (!have && kernel_choice == KERNEL_AUTO) ? why : "");
  simd_logged = simd_avx2;
}

/* ---------------------------------------------------------------------- */

double PairGranHertzRolling::init_one(int i, int j)
{
  auto pick = [&](double **v, const char *what) {
    double x = v[MIN(i, j)][MAX(i, j)];
    if (x < 0.0) x = sqrt(v[i][i] * v[j][j]);    // geometric mixing from the diagonal
    if (!(x >= 0.0)) error->all(FLERR, "{}: no {} for types {} {}", STYLE, what, i, j);
    return x;
  };
  if (setflag[i][i] == 0 || setflag[j][j] == 0) {
    const int t = setflag[i][i] ? j : i;
    error->all(FLERR, "{}: missing 'pair_coeff {} {} material E nu friction mu ...'", STYLE, t, t);
  }
  const double Es = law::mix_E(Emod[i], poiss[i], Emod[j], poiss[j]);
  const double Gs = law::mix_G(Emod[i], poiss[i], Emod[j], poiss[j]);
  const law::Params p = law::make_params(Es, Gs, pick(cor, "restitution"), pick(mu, "friction"),
                                         pick(mur, "rolling friction"), rolling, limit_damping);
  law[i * ntypes1 + j] = law[j * ntypes1 + i] = p;

  double cut = maxrad[i] + maxrad[j];
  if (cut <= 0.0) {
    for (int k = 1; k <= atom->ntypes; k++) cut = MAX(cut, 2.0 * maxrad[k]);
  }
  return cut;
}

/* ---------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   pass 2: the law over the batch, one contact per SIMD lane (m* as set_contact()).
   Built twice: for the x86-64 baseline (SSE2, 2 lanes) and for AVX2 (4 lanes, chosen at run
   time); neither contracts to FMA, so both give the same bits as the scalar law.
------------------------------------------------------------------------- */

namespace {
using Batch = PairGranHertzRolling::Batch;
typedef double v4d __attribute__((vector_size(32), may_alias));    // AtomX, aligned

// UNI: one set of constants for all lanes, pu, with rolling on (mu_r > 0) or off for all; else
// constants b.p per lane. FAC: special-bond factors b.factor per lane (never with UNI).
// FAST: the law's fast path (tangential_history, rolling_history); returns whether a lane needs
// the full law, which is then to be run over the batch again, from the old history
// (hist_rows()).
template <int ROLL, bool UPDATE, bool UNI, bool FAC, bool FAST>
TBAGS_INLINE bool law_lanes(Batch &b, int n, double dt, bool clip, const law::Params *pu)
{
  // 64 bits like the lanes: a 32-bit flag makes the vectoriser take 8 lanes (and spill)
  long long redo = 0;
  using tbags::vec::V3;
  // five loops (shorter dependency chains and fewer live values in each, so no spills): normal,
  // tangential history and force, rolling history and force; contact_lane() is them in one
#if defined(_OPENMP) || defined(TBAGS_OPENMP_SIMD)
#pragma omp simd
#endif
  for (int l = 0; l < n; l++) {
    // masses packed negative for frozen atoms (fix freeze): m* is then the other's mass
    const double mis = b.mi[l], mjs = b.mj[l];
    const double mi = std::fabs(mis), mj = std::fabs(mjs);
    const double radi = b.radi[l], radj = b.radj[l], radsum = radi + radj;
    double meff, reff;
    law::effective(mi, mj, radi, radj, meff, reff);
    meff = mis < 0.0 ? mj : meff;
    meff = mjs < 0.0 ? mi : meff;
    // r^2 and r_i + r_j as in the gather (same operations, same bits)
    const double dx0 = b.dx[0][l], dx1 = b.dx[1][l], dx2 = b.dx[2][l];
    const double rsq = dx0 * dx0 + dx1 * dx1 + dx2 * dx2;
    law::LaneOut o;
    V3 nv, vt;
    double vnnr, a;
    law::contact_geometry(UNI ? *pu : *b.p[l], V3{dx0, dx1, dx2}, rsq, radsum, reff, radi, radj,
                          V3{b.vr[0][l], b.vr[1][l], b.vr[2][l]},
                          V3{b.wi[0][l], b.wi[1][l], b.wi[2][l]},
                          V3{b.wj[0][l], b.wj[1][l], b.wj[2][l]}, o, nv, vnnr, vt, a);
    b.n[0][l] = nv.x;
    b.n[1][l] = nv.y;
    b.n[2][l] = nv.z;
    b.vt[0][l] = vt.x;
    b.vt[1][l] = vt.y;
    b.vt[2][l] = vt.z;
    b.a[l] = a;
    b.meff[l] = meff;
    b.fne[l] = o.fne;
    b.vnnr[l] = vnnr;
    b.delta[l] = o.delta;
    b.reff[l] = reff;
  }
  // the normal damping (its square root here, where the divider has time) and the tangential
  // history; the tangential force in the next loop: fewer live values in each loop
#if defined(_OPENMP) || defined(TBAGS_OPENMP_SIMD)
#pragma omp simd reduction(| : redo)
#endif
  for (int l = 0; l < n; l++) {
    double sqma;
    const double a = b.a[l];
    const double fn = law::normal_force(UNI ? *pu : *b.p[l], clip, b.meff[l], a, b.fne[l],
                                        b.vnnr[l], sqma);
    b.sqma[l] = sqma;
    b.fn[l] = fn;
    if (UPDATE) {
      V3 ht{b.h[0][l], b.h[1][l], b.h[2][l]};
      redo |= law::tangential_history<FAST>(UNI ? *pu : *b.p[l],
                                            V3{b.n[0][l], b.n[1][l], b.n[2][l]},
                                            V3{b.vt[0][l], b.vt[1][l], b.vt[2][l]}, a, fn, dt,
                                            ht);
      b.h[0][l] = ht.x;
      b.h[1][l] = ht.y;
      b.h[2][l] = ht.z;
    }
  }
#if defined(_OPENMP) || defined(TBAGS_OPENMP_SIMD)
#pragma omp simd
#endif
  for (int l = 0; l < n; l++) {
    V3 ht{b.h[0][l], b.h[1][l], b.h[2][l]};
    law::LaneOut o;
    const double fn = b.fn[l];
    law::tangential_force(UNI ? *pu : *b.p[l], V3{b.n[0][l], b.n[1][l], b.n[2][l]},
                          V3{b.vt[0][l], b.vt[1][l], b.vt[2][l]}, b.a[l], b.sqma[l], fn,
                          b.delta[l], b.radi[l], b.radj[l], false, ht, o);
    b.h[0][l] = ht.x;
    b.h[1][l] = ht.y;
    b.h[2][l] = ht.z;
    const double fl = FAC ? b.factor[l] : 1.0;    // special-bond factors (FAC), else none
    b.f[0][l] = o.f.x * fl;
    b.f[1][l] = o.f.y * fl;
    b.f[2][l] = o.f.z * fl;
    if (ROLL == law::ROLLING_NONE) {
      b.ti[0][l] = o.ti.x * fl;
      b.ti[1][l] = o.ti.y * fl;
      b.ti[2][l] = o.ti.z * fl;
      b.tj[0][l] = o.tj.x * fl;
      b.tj[1][l] = o.tj.y * fl;
      b.tj[2][l] = o.tj.z * fl;
    } else {    // the rolling loop adds its torque, then the factor
      b.ti[0][l] = o.ti.x;
      b.ti[1][l] = o.ti.y;
      b.ti[2][l] = o.ti.z;
      b.tj[0][l] = o.tj.x;
      b.tj[1][l] = o.tj.y;
      b.tj[2][l] = o.tj.z;
    }
  }
  if (ROLL == law::ROLLING_NONE) return redo != 0;
  if (ROLL == law::ROLLING_EPSD && UPDATE) {    // the rolling history, then the force
#if defined(_OPENMP) || defined(TBAGS_OPENMP_SIMD)
#pragma omp simd reduction(| : redo)
#endif
    for (int l = 0; l < n; l++) {
      V3 hr{b.h[3][l], b.h[4][l], b.h[5][l]};
      redo |= law::rolling_history<UNI, FAST>(
          UNI ? *pu : *b.p[l], V3{b.n[0][l], b.n[1][l], b.n[2][l]}, b.a[l], std::fabs(b.fn[l]),
          b.reff[l], V3{b.wi[0][l], b.wi[1][l], b.wi[2][l]},
          V3{b.wj[0][l], b.wj[1][l], b.wj[2][l]}, dt, hr);
      b.h[3][l] = hr.x;
      b.h[4][l] = hr.y;
      b.h[5][l] = hr.z;
    }
  }
#if defined(_OPENMP) || defined(TBAGS_OPENMP_SIMD)
#pragma omp simd
#endif
  for (int l = 0; l < n; l++) {
    V3 hr{0.0, 0.0, 0.0};
    if (ROLL == law::ROLLING_EPSD) hr = V3{b.h[3][l], b.h[4][l], b.h[5][l]};
    V3 fr, troll;
    bool on;
    law::rolling_force<ROLL, UNI>(UNI ? *pu : *b.p[l], V3{b.n[0][l], b.n[1][l], b.n[2][l]},
                                  b.a[l], std::fabs(b.fn[l]), b.reff[l],
                                  V3{b.wi[0][l], b.wi[1][l], b.wi[2][l]},
                                  V3{b.wj[0][l], b.wj[1][l], b.wj[2][l]}, hr, fr, troll, on);
    if (ROLL == law::ROLLING_EPSD) {
      b.h[3][l] = hr.x;
      b.h[4][l] = hr.y;
      b.h[5][l] = hr.z;
    }
    const V3 ti{b.ti[0][l], b.ti[1][l], b.ti[2][l]}, tj{b.tj[0][l], b.tj[1][l], b.tj[2][l]};
    const V3 tis = tbags::vec::select(on, ti + troll, ti), tjs = tbags::vec::select(on, tj - troll, tj);
    const double fl = FAC ? b.factor[l] : 1.0;
    b.ti[0][l] = tis.x * fl;
    b.ti[1][l] = tis.y * fl;
    b.ti[2][l] = tis.z * fl;
    b.tj[0][l] = tjs.x * fl;
    b.tj[1][l] = tjs.y * fl;
    b.tj[2][l] = tjs.z * fl;
  }
  return redo != 0;
}

template <int ROLL, bool UPDATE, bool UNI, bool FAC, bool FAST>
bool law_lanes_base(Batch &b, int n, double dt, bool clip, const law::Params *pu)
{
  return law_lanes<ROLL, UPDATE, UNI, FAC, FAST>(b, n, dt, clip, pu);
}

#ifdef TBAGS_HAVE_AVX2_CLONE
template <int ROLL, bool UPDATE, bool UNI, bool FAC, bool FAST>
__attribute__((target("avx2"))) bool law_lanes_avx2(Batch &b, int n, double dt, bool clip,
                                                    const law::Params *pu)
{
  return law_lanes<ROLL, UPDATE, UNI, FAC, FAST>(b, n, dt, clip, pu);
}
#endif

/* ----------------------------------------------------------------------
   contact history between its per-contact records (NH doubles at b.hist[l]) and the batch
   rows b.h[k][l]: data movement only; with AVX2, 4 contacts at a time (4x4 transposes)
------------------------------------------------------------------------- */

template <int NH> void hist_rows_scalar(Batch &b, int l0, int n)
{
  for (int l = l0; l < n; l++)
    for (int k = 0; k < NH; k++) b.h[k][l] = b.hist[l][k];
}

template <int NH> void rows_hist_scalar(Batch &b, int l0, int n)
{
  for (int l = l0; l < n; l++)
    for (int k = 0; k < NH; k++) b.hist[l][k] = b.h[k][l];
}

#ifdef TBAGS_HAVE_AVX2_CLONE
template <int NH> TBAGS_TARGET_AVX2 void hist_rows_avx2(Batch &b, int n)
{
  int l = 0;
  for (; l + 4 <= n; l += 4) {
    const double *p0 = b.hist[l], *p1 = b.hist[l + 1], *p2 = b.hist[l + 2], *p3 = b.hist[l + 3];
    if (NH == 6) {
      const __m256d a0 = _mm256_loadu_pd(p0), a1 = _mm256_loadu_pd(p1);
      const __m256d a2 = _mm256_loadu_pd(p2), a3 = _mm256_loadu_pd(p3);
      const __m256d t0 = _mm256_unpacklo_pd(a0, a1), t1 = _mm256_unpackhi_pd(a0, a1);
      const __m256d t2 = _mm256_unpacklo_pd(a2, a3), t3 = _mm256_unpackhi_pd(a2, a3);
      _mm256_storeu_pd(&b.h[0][l], _mm256_permute2f128_pd(t0, t2, 0x20));
      _mm256_storeu_pd(&b.h[1][l], _mm256_permute2f128_pd(t1, t3, 0x20));
      _mm256_storeu_pd(&b.h[2][l], _mm256_permute2f128_pd(t0, t2, 0x31));
      _mm256_storeu_pd(&b.h[3][l], _mm256_permute2f128_pd(t1, t3, 0x31));
      const __m128d c0 = _mm_loadu_pd(p0 + 4), c1 = _mm_loadu_pd(p1 + 4);
      const __m128d c2 = _mm_loadu_pd(p2 + 4), c3 = _mm_loadu_pd(p3 + 4);
      _mm256_storeu_pd(&b.h[4][l], _mm256_insertf128_pd(_mm256_castpd128_pd256(
          _mm_unpacklo_pd(c0, c1)), _mm_unpacklo_pd(c2, c3), 1));
      _mm256_storeu_pd(&b.h[5][l], _mm256_insertf128_pd(_mm256_castpd128_pd256(
          _mm_unpackhi_pd(c0, c1)), _mm_unpackhi_pd(c2, c3), 1));
    } else {
      const __m128d c0 = _mm_loadu_pd(p0), c1 = _mm_loadu_pd(p1);
      const __m128d c2 = _mm_loadu_pd(p2), c3 = _mm_loadu_pd(p3);
      _mm256_storeu_pd(&b.h[0][l], _mm256_insertf128_pd(_mm256_castpd128_pd256(
          _mm_unpacklo_pd(c0, c1)), _mm_unpacklo_pd(c2, c3), 1));
      _mm256_storeu_pd(&b.h[1][l], _mm256_insertf128_pd(_mm256_castpd128_pd256(
          _mm_unpackhi_pd(c0, c1)), _mm_unpackhi_pd(c2, c3), 1));
      const __m128d s01 = _mm_loadh_pd(_mm_load_sd(p0 + 2), p1 + 2);
      const __m128d s23 = _mm_loadh_pd(_mm_load_sd(p2 + 2), p3 + 2);
      _mm256_storeu_pd(&b.h[2][l], _mm256_insertf128_pd(_mm256_castpd128_pd256(s01), s23, 1));
    }
  }
  hist_rows_scalar<NH>(b, l, n);
}

template <int NH> TBAGS_TARGET_AVX2 void rows_hist_avx2(Batch &b, int n)
{
  int l = 0;
  for (; l + 4 <= n; l += 4) {
    double *p0 = b.hist[l], *p1 = b.hist[l + 1], *p2 = b.hist[l + 2], *p3 = b.hist[l + 3];
    const __m256d r0 = _mm256_loadu_pd(&b.h[0][l]), r1 = _mm256_loadu_pd(&b.h[1][l]);
    const __m256d t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1);
    if (NH == 6) {
      const __m256d r2 = _mm256_loadu_pd(&b.h[2][l]), r3 = _mm256_loadu_pd(&b.h[3][l]);
      const __m256d t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);
      _mm256_storeu_pd(p0, _mm256_permute2f128_pd(t0, t2, 0x20));
      _mm256_storeu_pd(p1, _mm256_permute2f128_pd(t1, t3, 0x20));
      _mm256_storeu_pd(p2, _mm256_permute2f128_pd(t0, t2, 0x31));
      _mm256_storeu_pd(p3, _mm256_permute2f128_pd(t1, t3, 0x31));
      const __m256d r4 = _mm256_loadu_pd(&b.h[4][l]), r5 = _mm256_loadu_pd(&b.h[5][l]);
      const __m256d w0 = _mm256_unpacklo_pd(r4, r5), w1 = _mm256_unpackhi_pd(r4, r5);
      _mm_storeu_pd(p0 + 4, _mm256_castpd256_pd128(w0));
      _mm_storeu_pd(p1 + 4, _mm256_castpd256_pd128(w1));
      _mm_storeu_pd(p2 + 4, _mm256_extractf128_pd(w0, 1));
      _mm_storeu_pd(p3 + 4, _mm256_extractf128_pd(w1, 1));
    } else {
      _mm_storeu_pd(p0, _mm256_castpd256_pd128(t0));
      _mm_storeu_pd(p1, _mm256_castpd256_pd128(t1));
      _mm_storeu_pd(p2, _mm256_extractf128_pd(t0, 1));
      _mm_storeu_pd(p3, _mm256_extractf128_pd(t1, 1));
      const __m256d r2 = _mm256_loadu_pd(&b.h[2][l]);
      const __m128d lo = _mm256_castpd256_pd128(r2), hi = _mm256_extractf128_pd(r2, 1);
      _mm_store_sd(p0 + 2, lo);
      _mm_storeh_pd(p1 + 2, lo);
      _mm_store_sd(p2 + 2, hi);
      _mm_storeh_pd(p3 + 2, hi);
    }
  }
  rows_hist_scalar<NH>(b, l, n);
}
#endif

#ifdef TBAGS_HAVE_AVX2_CLONE
/* ----------------------------------------------------------------------
   pass 3 for AVX2 (no energy/virial tally): each contact's f, t_i, t_j as one 4-double vector
   (4x4 transposes of the batch rows), added to j's 3 doubles with one 4-wide load, operation
   and store: the 4th lane, the next atom's x component, gets x - (+0) or x + (-0), i.e. its
   own value (j + 1 < nmax: inside the arrays; in order, so nothing is lost). i's sums stay in
   registers over its run of contacts (j is never i). The same additions in the same order as
   batch_scatter(): the same bits.
------------------------------------------------------------------------- */

TBAGS_TARGET_AVX2 TBAGS_INLINE __m256d load3_avx2(const double *p)
{
  return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p)), _mm_load_sd(p + 2), 1);
}

TBAGS_TARGET_AVX2 TBAGS_INLINE void store3_avx2(double *p, __m256d v)
{
  _mm_storeu_pd(p, _mm256_castpd256_pd128(v));
  _mm_store_sd(p + 2, _mm256_extractf128_pd(v, 1));
}

// rows r0, r1, r2 (4 contacts each) and a constant 4th row z: c[k] = (r0[k], r1[k], r2[k], z)
TBAGS_TARGET_AVX2 TBAGS_INLINE void rows3_cols(const double *r0, const double *r1,
                                               const double *r2, __m256d z, __m256d c[4])
{
  const __m256d a0 = _mm256_loadu_pd(r0), a1 = _mm256_loadu_pd(r1), a2 = _mm256_loadu_pd(r2);
  const __m256d t0 = _mm256_unpacklo_pd(a0, a1), t1 = _mm256_unpackhi_pd(a0, a1);
  const __m256d t2 = _mm256_unpacklo_pd(a2, z), t3 = _mm256_unpackhi_pd(a2, z);
  c[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
  c[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
  c[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
  c[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
}

template <int NEWTON>
TBAGS_TARGET_AVX2 __attribute__((noinline)) void scatter_avx2(const Batch &b, int n, double *f,
                                                              double *torque, int nlocal, int nmax)
{
  const __m256d pz = _mm256_setzero_pd(), mz = _mm256_set1_pd(-0.0);
  const int jlast = nmax - 1;    // j < jlast: the 4th lane is inside the arrays
  int i = b.i[0];
  double *fip = f + 3 * (std::ptrdiff_t) i, *tip = torque + 3 * (std::ptrdiff_t) i;
  __m256d fi = load3_avx2(fip), ti = load3_avx2(tip);
  for (int l0 = 0; l0 < n; l0 += 4) {    // rows hold N (multiple of 4) entries
    __m256d cf[4], cti[4], ctj[4];
    rows3_cols(&b.f[0][l0], &b.f[1][l0], &b.f[2][l0], pz, cf);
    rows3_cols(&b.ti[0][l0], &b.ti[1][l0], &b.ti[2][l0], pz, cti);
    rows3_cols(&b.tj[0][l0], &b.tj[1][l0], &b.tj[2][l0], mz, ctj);
    const int m = n - l0 < 4 ? n - l0 : 4;
    for (int k = 0; k < m; k++) {
      const int l = l0 + k;
      const int il = b.i[l];
      if (il != i) {
        store3_avx2(fip, fi);
        store3_avx2(tip, ti);
        i = il;
        fip = f + 3 * (std::ptrdiff_t) i;
        tip = torque + 3 * (std::ptrdiff_t) i;
        fi = load3_avx2(fip);
        ti = load3_avx2(tip);
      }
      fi = _mm256_add_pd(fi, cf[k]);
      ti = _mm256_add_pd(ti, cti[k]);
      const int j = b.j[l];
      if (NEWTON || j < nlocal) {
        const std::ptrdiff_t j3 = 3 * (std::ptrdiff_t) j;
        if (__builtin_expect(j < jlast, 1)) {
          _mm256_storeu_pd(f + j3, _mm256_sub_pd(_mm256_loadu_pd(f + j3), cf[k]));
          _mm256_storeu_pd(torque + j3, _mm256_add_pd(_mm256_loadu_pd(torque + j3), ctj[k]));
        } else {
          store3_avx2(f + j3, _mm256_sub_pd(load3_avx2(f + j3), cf[k]));
          store3_avx2(torque + j3, _mm256_add_pd(load3_avx2(torque + j3), ctj[k]));
        }
      }
    }
  }
  store3_avx2(fip, fi);
  store3_avx2(tip, ti);
}
#endif

template <int NH> inline void hist_rows(Batch &b, int n, bool avx2)
{
#ifdef TBAGS_HAVE_AVX2_CLONE
  if (avx2) return hist_rows_avx2<NH>(b, n);
#endif
  hist_rows_scalar<NH>(b, 0, n);
}

template <int NH> inline void rows_hist(Batch &b, int n, bool avx2)
{
#ifdef TBAGS_HAVE_AVX2_CLONE
  if (avx2) return rows_hist_avx2<NH>(b, n);
#endif
  rows_hist_scalar<NH>(b, 0, n);
}

// pu: the constants of all lanes (UNI above), else nullptr (per-lane b.p); FAC: per-lane
// special-bond factors b.factor (never with pu). FAST: as law_lanes().
template <int ROLL, bool UPDATE, bool FAC, bool FAST>
bool batch_law(Batch &b, int n, double dt, bool clip, bool avx2, const law::Params *pu)
{
#ifdef TBAGS_HAVE_AVX2_CLONE
  if (avx2) {
    if (!FAC && pu) return law_lanes_avx2<ROLL, UPDATE, true, false, FAST>(b, n, dt, clip, pu);
    return law_lanes_avx2<ROLL, UPDATE, false, FAC, FAST>(b, n, dt, clip, pu);
  }
#endif
  if (!FAC && pu) return law_lanes_base<ROLL, UPDATE, true, false, FAST>(b, n, dt, clip, pu);
  return law_lanes_base<ROLL, UPDATE, false, FAC, FAST>(b, n, dt, clip, pu);
}
}    // namespace

void PairGranHertzRolling::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  if (!batch) batch.reset(new Batch());    // zeroed: whole 4-row groups are read
  const bool upd = update->setupflag == 0;
  // special-bond bits in the neighbor list: only with bonds and special factors other than 0, 1
  const bool sb = atom->molecular != Atom::ATOMIC &&
      (neighbor->special_flag[1] == 2 || neighbor->special_flag[2] == 2 ||
       neighbor->special_flag[3] == 2);
  sb ? eval_rolling<true>(upd) : eval_rolling<false>(upd);
}

template <bool SB> void PairGranHertzRolling::eval_rolling(bool upd)
{
  if (rolling == law::ROLLING_EPSD) upd ? eval<law::ROLLING_EPSD, true, SB>() : eval<law::ROLLING_EPSD, false, SB>();
  else if (rolling == law::ROLLING_CDT) upd ? eval<law::ROLLING_CDT, true, SB>() : eval<law::ROLLING_CDT, false, SB>();
  else upd ? eval<law::ROLLING_NONE, true, SB>() : eval<law::ROLLING_NONE, false, SB>();
}

/* ----------------------------------------------------------------------
   the constants of all type pairs when they are all the same (e.g. pair_coeff * *), else null
------------------------------------------------------------------------- */

const law::Params *PairGranHertzRolling::uniform_params() const
{
  const law::Params &p = law[ntypes1 + 1];
  for (int i = 1; i < ntypes1; i++)
    for (int j = 1; j < ntypes1; j++) {
      const law::Params &q = law[i * ntypes1 + j];
      if (q.kn != p.kn || q.kt != p.kt || q.cn != p.cn || q.ct != p.ct || q.mu != p.mu ||
          q.mur != p.mur || q.krs != p.krs || q.rolling != p.rolling ||
          q.limit_damping != p.limit_damping)
        return nullptr;
    }
  return &p;
}

/* ----------------------------------------------------------------------
   the kernel's per-atom data of local and ghost atoms, packed into two aligned records;
   returns whether the candidate list is still valid: no atom moved more than CAND_MOVE_LIMIT cskin
   and no radius changed since its build (same atoms)
------------------------------------------------------------------------- */

TBAGS_INLINE bool PairGranHertzRolling::pack_atoms()
{
  const int nall = atom->nlocal + atom->nghost;
  if (nall > npack) {
    free(packx);
    free(packv);
    npack = (nall + nall / 8 + 64) & ~1;    // even: whole 64-byte lines
    packx = static_cast<AtomX *>(aligned_alloc(64, sizeof(AtomX) * (size_t) npack));
    packv = static_cast<AtomV *>(aligned_alloc(64, sizeof(AtomV) * (size_t) npack));
    if (!packx || !packv) error->one(FLERR, "{}: out of memory packing {} atoms", STYLE, nall);
  }
  const double *x = atom->x[0];
  const double *v = atom->v[0];
  const double *omega = atom->omega[0];
  const double *radius = atom->radius;
  const double *rmass = atom->rmass;
  const int *type = atom->type;
  const int *mask = atom->mask;
  const int frzbit = freeze_group_bit;
  AtomX *__restrict px = packx;
  AtomV *__restrict pv = packv;
  // whole records as 4-double vectors: 3 values of atom i and one of i+1 loaded, the last
  // replaced (so the last atom, whose neighbour in memory may not exist, is done by itself)
  typedef double v4du __attribute__((vector_size(32), aligned(8), may_alias));
  typedef double v4da __attribute__((vector_size(32), may_alias));
  auto tf = [&](int i) {    // the type in the last 8 bytes of AtomV
    const unsigned long long b = (unsigned int) type[i];
    double d;
    memcpy(&d, &b, sizeof d);
    return d;
  };
  // the mass, negative for atoms in the fix freeze group
  auto ms = [&](int i) { return (mask[i] & frzbit) ? -rmass[i] : rmass[i]; };
  static_assert(sizeof(AtomV) == 64 && offsetof(AtomV, type) == 56, "AtomV layout");
  // the candidate list's check (chk): the largest squared displacement since its build, and
  // whether a radius changed
  const bool chk = cand_nall == nall;
  const AtomX *__restrict ox = x0;
  double mx = 0.0, mr = 0.0;
  // frz: a fix freeze group exists (else no mask read)
  auto rec = [&](int i, bool frz, bool ck) __attribute__((always_inline)) {
    v4du a = *reinterpret_cast<const v4du *>(x + 3 * i);
    a[3] = radius[i];
    *reinterpret_cast<v4da *>(&px[i]) = a;
    if (ck) {
      const v4d d = a - *reinterpret_cast<const v4da *>(&ox[i]), dd = d * d;
      const double m = dd[0] + dd[1] + dd[2];
      mx = mx > m ? mx : m;
      mr = mr > dd[3] ? mr : dd[3];
    }
    v4du b = *reinterpret_cast<const v4du *>(v + 3 * i);
    b[3] = frz ? ms(i) : rmass[i];
    reinterpret_cast<v4da *>(&pv[i])[0] = b;
    v4du c = *reinterpret_cast<const v4du *>(omega + 3 * i);
    c[3] = tf(i);
    reinterpret_cast<v4da *>(&pv[i])[1] = c;
  };
  if (frzbit) {
    if (chk) for (int i = 0; i < nall - 1; i++) rec(i, true, true);
    else for (int i = 0; i < nall - 1; i++) rec(i, true, false);
  } else {
    if (chk) for (int i = 0; i < nall - 1; i++) rec(i, false, true);
    else for (int i = 0; i < nall - 1; i++) rec(i, false, false);
  }
  if (nall > 0) {
    const int i = nall - 1;
    px[i].x[0] = x[3 * i];
    px[i].x[1] = x[3 * i + 1];
    px[i].x[2] = x[3 * i + 2];
    px[i].r = radius[i];
    pv[i].v[0] = v[3 * i];
    pv[i].v[1] = v[3 * i + 1];
    pv[i].v[2] = v[3 * i + 2];
    pv[i].m = ms(i);
    pv[i].w[0] = omega[3 * i];
    pv[i].w[1] = omega[3 * i + 1];
    pv[i].w[2] = omega[3 * i + 2];
    pv[i].type = type[i];
    pv[i].pad = 0;
    if (chk) {
      const AtomX &o = ox[i];
      const double d0 = px[i].x[0] - o.x[0], d1 = px[i].x[1] - o.x[1], d2 = px[i].x[2] - o.x[2];
      const double m = d0 * d0 + d1 * d1 + d2 * d2;
      mx = mx > m ? mx : m;
      if (px[i].r != o.r) mr = 1.0;
    }
  }
  // the candidate list still holds every pair that can touch
  return chk && mx <= cand_lim2 && mr == 0.0;
}

/* ----------------------------------------------------------------------
   pass 1: walk the candidate list (or, when it must be rebuilt, the whole neighbor list,
   building it), reset the history of separated pairs and gather the touching ones into the
   batch; when full, run the law over it and scatter the result. Either walk visits every
   pair that can touch in neighbor-list order: the same contacts, the same bits.
   SB: the list may hold special-bond bits (else every factor is 1 and j needs no mask).
------------------------------------------------------------------------- */

template <int ROLL, bool UPDATE, bool SB> void PairGranHertzRolling::eval()
{
  // one set of constants for all contacts (UNI in law_lanes), else per contact
  const law::Params *puni = uniform_params();
  if (SB || (puni && ROLL != law::ROLLING_NONE && !(puni->mur > 0.0))) puni = nullptr;
#ifdef TBAGS_HAVE_AVX2_CLONE
  if (simd_avx2)
    return puni ? eval_avx2<ROLL, UPDATE, SB, true>(puni) : eval_avx2<ROLL, UPDATE, SB, false>(puni);
#endif
  puni ? eval_body<ROLL, UPDATE, SB, true>(puni) : eval_body<ROLL, UPDATE, SB, false>(puni);
}

// packing and gather built for AVX2 too (no FMA: the same bits as the baseline build)
template <int ROLL, bool UPDATE, bool SB, bool UNI>
void PairGranHertzRolling::eval_avx2(const law::Params *puni)
{
  eval_body<ROLL, UPDATE, SB, UNI>(puni);
}

// UNI: puni (not null) holds the constants of all contacts
template <int ROLL, bool UPDATE, bool SB, bool UNI>
TBAGS_INLINE void PairGranHertzRolling::eval_body(const law::Params *puni)
{
  if (list->inum == 0) return;
  const int nall = atom->nlocal + atom->nghost;
  // the candidate list holds every pair that can touch (else it is rebuilt in this pass)
  const bool valid = pack_atoms() && update->setupflag == 0 &&
      neighbor->lastcall == cand_lastcall;
  Batch &b = *batch;
  const AtomX *__restrict px = packx;
  const AtomV *__restrict pv = packv;
  const double *special_lj = force->special_lj;

  const int inum = list->inum;
  const int *ilist = list->ilist;
  int **firsttouch = fix_history->firstflag;
  double **firsthistory = fix_history->firstvalue;

  constexpr int NH = ROLL == law::ROLLING_EPSD ? 6 : 3;    // history doubles per contact
  auto flush = [&](int n) {
    hist_rows<NH>(b, n, simd_avx2);
    // the fast path; in the rare batch where a contact needs the full law, all again with it
    if (batch_law<ROLL, UPDATE, SB, true>(b, n, update->dt, limit_damping, simd_avx2, puni)) {
      hist_rows<NH>(b, n, simd_avx2);
      batch_law<ROLL, UPDATE, SB, false>(b, n, update->dt, limit_damping, simd_avx2, puni);
    }
    rows_hist<NH>(b, n, simd_avx2);
#ifdef TBAGS_HAVE_AVX2_CLONE
    if (simd_avx2 && !evflag) {
      if (force->newton_pair) scatter_avx2<1>(b, n, atom->f[0], atom->torque[0], atom->nlocal, atom->nmax);
      else scatter_avx2<0>(b, n, atom->f[0], atom->torque[0], atom->nlocal, atom->nmax);
      return;
    }
#endif
    if (force->newton_pair) evflag ? batch_scatter<NH, 1, 1>(n) : batch_scatter<NH, 1, 0>(n);
    else evflag ? batch_scatter<NH, 0, 1>(n) : batch_scatter<NH, 0, 0>(n);
  };

  int n = 0;
  // atom i's values for its contacts
  struct I {
    int i;
    v4d xi4;    // (x_i, -r_i): (x_i, -r_i) - (x_j, r_j) is dx and -(r_i + r_j)
    double vi0, vi1, vi2, wi0, wi1, wi2, mi;
    const law::Params *prow;
  };
  const v4d flip = {1.0, 1.0, 1.0, -1.0};
  auto atom_i = [&](int i) __attribute__((always_inline)) {
    const AtomV &ai = pv[i];
    return I{i, *reinterpret_cast<const v4d *>(&px[i]) * flip, ai.v[0], ai.v[1], ai.v[2],
             ai.w[0], ai.w[1], ai.w[2], ai.m, &law[ai.type * ntypes1]};
  };
  // r^2 as (dx0^2 + dx1^2) + dx2^2 < (r_i + r_j)^2 exactly, from d = (x_i, -r_i) - (x_j, r_j):
  // the same test as touching()
  auto touching = [](const v4d d) __attribute__((always_inline)) {
    const v4d dd = d * d;
    return dd[0] + dd[1] + dd[2] < dd[3];
  };
  auto forget = [](double *hist) __attribute__((always_inline)) {
    for (int k = 0; k < NH; k++) hist[k] = 0.0;
  };
  // a touching neighbour j of i into the batch (flushed when full)
  auto gather = [&](const I &c, int j, double factor_lj, double *hist, const v4d d)
      __attribute__((always_inline)) {
    __builtin_prefetch(hist, 1);    // read at the flush, written back after the law
    const AtomV &bj = pv[j];
    b.i[n] = c.i;
    b.j[n] = j;
    b.hist[n] = hist;
    if (!UNI) b.p[n] = &c.prow[bj.type];
    b.dx[0][n] = d[0];
    b.dx[1][n] = d[1];
    b.dx[2][n] = d[2];
    b.radi[n] = -c.xi4[3];
    b.radj[n] = px[j].r;
    b.mi[n] = c.mi;
    b.mj[n] = bj.m;
    if (SB) b.factor[n] = factor_lj;
    b.vr[0][n] = c.vi0 - bj.v[0];
    b.vr[1][n] = c.vi1 - bj.v[1];
    b.vr[2][n] = c.vi2 - bj.v[2];
    b.wi[0][n] = c.wi0;
    b.wi[1][n] = c.wi1;
    b.wi[2][n] = c.wi2;
    b.wj[0][n] = bj.w[0];
    b.wj[1][n] = bj.w[1];
    b.wj[2][n] = bj.w[2];
    if (++n == Batch::N) {
      flush(n);
      n = 0;
    }
  };

  if (valid) {    // the candidates only, as one flat list (no branch per atom i)
    Cand *cd = cand.data();
    for (int k = 0; k < ncand; k++) {
      Cand &ck = cd[k];
      {    // the candidate 8 ahead (the list is padded past its end)
        const int jp = cd[k + 8].j & NEIGHMASK;
        __builtin_prefetch(&px[jp]);
        __builtin_prefetch(&pv[jp]);
      }
      const int jc = ck.j;
      const int j = jc & NEIGHMASK;
      const double factor_lj = SB ? special_lj[sbmask(jc)] : 1.0;
      const I c = atom_i(ck.i);
      const v4d d = c.xi4 - *reinterpret_cast<const v4d *>(&px[j]);
      // the touch flag kept in the candidate (CAND_TOUCH), the list's set when it changes
      if (!touching(d)) {
        if (jc & CAND_TOUCH) {    // was touching: forget
          ck.j = jc & ~CAND_TOUCH;
          *ck.touch = 0;
          forget(ck.hist);
        }
        continue;
      }
      if (!(jc & CAND_TOUCH)) {
        ck.j = jc | CAND_TOUCH;
        *ck.touch = 1;
      }
      gather(c, j, factor_lj, ck.hist, d);
    }
  } else {    // the whole neighbor list, building the candidate list
    const int *numneigh = list->numneigh;
    int **firstneigh = list->firstneigh;
    int nc = 0;
    for (int ii = 0; ii < inum; ii++) {
      const int i = ilist[ii];
      const I c = atom_i(i);
      const int *jlist = firstneigh[i];
      const int jnum = numneigh[i];
      int *touch = firsttouch[i];
      double *allhistory = firsthistory[i];
      if (cand.size() < (size_t) (nc + jnum)) cand.resize(2 * cand.size() + jnum);
      Cand *cd = cand.data();
      for (int jj = 0; jj < jnum; jj++) {
        const int jraw = jlist[jj];
        int j = jraw;
        double factor_lj = 1.0;
        if (SB) {
          factor_lj = special_lj[sbmask(j)];
          j &= NEIGHMASK;
          if (factor_lj == 0.0) continue;
        }
        __builtin_prefetch(&pv[j]);
        const v4d d = c.xi4 - *reinterpret_cast<const v4d *>(&px[j]);
        // a candidate: |dx| < r_i + r_j + cskin (else as a separated pair)
        const double rc = cskin - d[3];
        const bool cnd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < rc * rc;
        double *hist = &allhistory[NH * jj];
        const bool t = touching(d);
        if (cnd) cd[nc++] = Cand{i, t ? jraw | CAND_TOUCH : jraw, hist, &touch[jj]};
        if (!t) {
          if (touch[jj]) {    // was touching: forget (not-touching pairs stay untouched)
            touch[jj] = 0;
            forget(hist);
          }
          continue;
        }
        touch[jj] = 1;
        gather(c, j, factor_lj, hist, d);
      }
    }
    ncand = nc;
    if (cand.size() < (size_t) nc + 8) cand.resize(nc + 8);
    for (int k = nc; k < nc + 8; k++) cand[k] = Cand{0, 0, nullptr, nullptr};    // prefetched
    cand_nall = 0;    // no skin: the whole list every step (no positions kept)
    if (cskin > 0.0) {
      if (nx0 < nall) {
        free(x0);
        nx0 = npack;
        x0 = static_cast<AtomX *>(aligned_alloc(64, sizeof(AtomX) * (size_t) nx0));
        if (!x0) error->one(FLERR, "{}: out of memory for {} atoms", STYLE, nx0);
      }
      memcpy(x0, px, sizeof(AtomX) * (size_t) nall);
      cand_nall = nall;
    }
    cand_lastcall = neighbor->lastcall;
  }
  if (n) flush(n);
}

/* ----------------------------------------------------------------------
   pass 3: forces, torques and history back, in neighbor-list order
------------------------------------------------------------------------- */

template <int NH, int NEWTON, int EVFLAG> void PairGranHertzRolling::batch_scatter(int n)
{
  const Batch &b = *batch;
  double *__restrict f = atom->f[0];
  double *__restrict torque = atom->torque[0];
  const int nlocal = atom->nlocal;
  // f and torque of i summed in registers over its run of contacts: the same additions in the
  // same order as updating the arrays each time (j is never i)
  for (int l = 0; l < n;) {
    const int i = b.i[l];
    double *fi = f + 3 * i, *ti = torque + 3 * i;
    double fi0 = fi[0], fi1 = fi[1], fi2 = fi[2];
    double ti0 = ti[0], ti1 = ti[1], ti2 = ti[2];
    do {
      const int j = b.j[l];
      const double f0 = b.f[0][l], f1 = b.f[1][l], f2 = b.f[2][l];
      fi0 += f0;
      fi1 += f1;
      fi2 += f2;
      ti0 += b.ti[0][l];
      ti1 += b.ti[1][l];
      ti2 += b.ti[2][l];
      if (NEWTON || j < nlocal) {
        double *fj = f + 3 * j, *tj = torque + 3 * j;
        fj[0] -= f0;
        fj[1] -= f1;
        fj[2] -= f2;
        tj[0] += b.tj[0][l];
        tj[1] += b.tj[1][l];
        tj[2] += b.tj[2][l];
      }
      if (EVFLAG)
        ev_tally_xyz(i, j, nlocal, NEWTON, 0.0, 0.0, f0, f1, f2, b.dx[0][l], b.dx[1][l],
                     b.dx[2][l]);
    } while (++l < n && b.i[l] == i);
    fi[0] = fi0;
    fi[1] = fi1;
    fi[2] = fi2;
    ti[0] = ti0;
    ti[1] = ti1;
    ti[2] = ti2;
  }
}

/* ----------------------------------------------------------------------
   single(): force along the line of centres / r (as pair granular) and svector:
   fs(3) |fs| fr(3) |fr| 0 dx dy dz overlap F_n
------------------------------------------------------------------------- */

double PairGranHertzRolling::single(int i, int j, int itype, int jtype, double rsq,
                                    double /*factor_coul*/, double factor_lj, double &fforce)
{
  fforce = 0.0;
  for (int m = 0; m < single_extra; m++) svector[m] = 0.0;
  if (factor_lj == 0.0) return 0.0;
  const double radsum = atom->radius[i] + atom->radius[j];
  if (!law::touching(rsq, radsum)) return 0.0;
  if (!fix_history || !fix_history->firstvalue)
    error->one(FLERR, "{}: single() needs the contact history; run at least 0 steps first", STYLE);

  // find j in i's neighbor list to read the stored history (copied: single() changes nothing)
  double hist[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const int jnum = list->numneigh[i];
  const int *jlist = list->firstneigh[i];
  bool found = false;
  for (int jj = 0; jj < jnum; jj++) {
    neighprev++;
    if (neighprev >= jnum) neighprev = 0;
    if ((jlist[neighprev] & NEIGHMASK) == j) {
      found = true;
      break;
    }
  }
  if (found) {
    const double *h = &fix_history->firstvalue[i][size_history * neighprev];
    for (int k = 0; k < size_history; k++) hist[k] = h[k];
  } else if (j < atom->nlocal) {
    // a list of another ordering (compute pair/local's own) may name the pair the other way
    // round: the history is then stored with j, as seen from j
    const int knum = list->numneigh[j];
    const int *klist = list->firstneigh[j];
    for (int kk = 0; kk < knum; kk++)
      if ((klist[kk] & NEIGHMASK) == i) {
        transfer_history(&fix_history->firstvalue[j][size_history * kk], hist, 0, 0);
        break;
      }
  }

  double **x = atom->x;
  double dx[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
  law::Contact c;
  set_contact(i, j, dx, rsq, radsum, c);
  c.wall = false;
  c.dt = update->dt;
  law::Result o;
  law::compute(params(itype, jtype), c, hist, false, o);

  fforce = factor_lj * o.fn / o.r;
  for (int k = 0; k < 3; k++) {
    svector[k] = factor_lj * o.fs[k];
    svector[4 + k] = factor_lj * o.fr[k];
    svector[9 + k] = dx[k];
  }
  svector[3] = factor_lj * tbags::vec::len(o.fs);
  svector[7] = factor_lj * tbags::vec::len(o.fr);
  svector[12] = o.delta;
  svector[13] = factor_lj * o.fn;
  return 0.0;
}

/* ----------------------------------------------------------------------
   history as seen from j (newton off, FixNeighHistory): the tangential displacement
   integrates v_t, which changes sign with i <-> j; the rolling displacement integrates
   R* (w_i - w_j) x n, where both factors change sign, so it is kept.
------------------------------------------------------------------------- */

void PairGranHertzRolling::transfer_history(double *source, double *target, int, int)
{
  for (int k = 0; k < 3; k++) target[k] = -source[k];
  for (int k = 3; k < size_history; k++) target[k] = source[k];
}

double PairGranHertzRolling::atom2cut(int i)
{
  return 2.0 * atom->radius[i];
}

double PairGranHertzRolling::radii2cut(double r1, double r2)
{
  return r1 + r2;
}


/* ----------------------------------------------------------------------
   bytes of the per-type tables and of the kernel's buffers: the packed atom records (their
   aligned_alloc, not memory->smalloc: the kernel's records need 32/64-byte alignment whatever
   LAMMPS_MEMALIGN the LAMMPS build chose), the candidate list and the batch
------------------------------------------------------------------------- */

double PairGranHertzRolling::memory_usage()
{
  double bytes = Pair::memory_usage();
  const double nt = atom->ntypes + 1.0;
  // setflag, cutsq, mu, mur, cor per type pair; Emod, poiss, maxrad, matflag per type; the law
  if (allocated) bytes += nt * nt * (4 * sizeof(double) + sizeof(int)) + nt * (3 * sizeof(double) + sizeof(int));
  bytes += (double) law.capacity() * sizeof(law::Params);
  bytes += (double) npack * (sizeof(AtomX) + sizeof(AtomV)) + (double) nx0 * sizeof(AtomX);
  bytes += (double) cand.capacity() * sizeof(Cand);
  if (batch) bytes += sizeof(Batch);
  return bytes;
}

void *PairGranHertzRolling::extract(const char *str, int &dim)
{
  dim = 0;
  if (strcmp(str, "kernel_avx2") == 0) return (void *) &simd_avx2;    // 1: the AVX2 build runs
  dim = 1;
  if (strcmp(str, "E") == 0) return (void *) Emod;
  if (strcmp(str, "nu") == 0) return (void *) poiss;
  dim = 2;
  if (strcmp(str, "mu") == 0) return (void *) mu;
  if (strcmp(str, "mu_r") == 0) return (void *) mur;
  if (strcmp(str, "restitution") == 0) return (void *) cor;
  return nullptr;
}

/* ---------------------------------------------------------------------- */

// restart settings: the rolling model plus SETTINGS_V2 marks the record that also holds the kernel
// choice and the contact skin (files of tbags 0.3 and before hold the model and limit_damping only)
static constexpr int SETTINGS_V2 = 16;

void PairGranHertzRolling::write_restart_settings(FILE *fp)
{
  int head[3] = {rolling + SETTINGS_V2, limit_damping ? 1 : 0, kernel_choice};
  fwrite(head, sizeof(int), 3, fp);
  fwrite(&contact_skin, sizeof(double), 1, fp);
}

void PairGranHertzRolling::read_restart_settings(FILE *fp)
{
  int head[3] = {0, 0, KERNEL_AUTO};
  if (comm->me == 0) {
    utils::sfread(FLERR, head, sizeof(int), 2, fp, nullptr, error);
    if (head[0] >= SETTINGS_V2) {
      utils::sfread(FLERR, &head[2], sizeof(int), 1, fp, nullptr, error);
      utils::sfread(FLERR, &contact_skin, sizeof(double), 1, fp, nullptr, error);
      head[0] -= SETTINGS_V2;
    }
  }
  MPI_Bcast(head, 3, MPI_INT, 0, world);
  MPI_Bcast(&contact_skin, 1, MPI_DOUBLE, 0, world);
  rolling = head[0];
  limit_damping = head[1] != 0;
  kernel_choice = head[2];
  size_history = law::history_size(rolling);
}

void PairGranHertzRolling::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  for (int i = 1; i <= atom->ntypes; i++) {
    fwrite(&matflag[i], sizeof(int), 1, fp);
    fwrite(&Emod[i], sizeof(double), 1, fp);
    fwrite(&poiss[i], sizeof(double), 1, fp);
    for (int j = i; j <= atom->ntypes; j++) {
      fwrite(&setflag[i][j], sizeof(int), 1, fp);
      fwrite(&mu[i][j], sizeof(double), 1, fp);
      fwrite(&mur[i][j], sizeof(double), 1, fp);
      fwrite(&cor[i][j], sizeof(double), 1, fp);
    }
  }
}

void PairGranHertzRolling::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  const int me = comm->me;
  for (int i = 1; i <= atom->ntypes; i++) {
    if (me == 0) {
      utils::sfread(FLERR, &matflag[i], sizeof(int), 1, fp, nullptr, error);
      utils::sfread(FLERR, &Emod[i], sizeof(double), 1, fp, nullptr, error);
      utils::sfread(FLERR, &poiss[i], sizeof(double), 1, fp, nullptr, error);
    }
    MPI_Bcast(&matflag[i], 1, MPI_INT, 0, world);
    MPI_Bcast(&Emod[i], 1, MPI_DOUBLE, 0, world);
    MPI_Bcast(&poiss[i], 1, MPI_DOUBLE, 0, world);
    for (int j = i; j <= atom->ntypes; j++) {
      if (me == 0) {
        utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
        utils::sfread(FLERR, &mu[i][j], sizeof(double), 1, fp, nullptr, error);
        utils::sfread(FLERR, &mur[i][j], sizeof(double), 1, fp, nullptr, error);
        utils::sfread(FLERR, &cor[i][j], sizeof(double), 1, fp, nullptr, error);
      }
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
      MPI_Bcast(&mu[i][j], 1, MPI_DOUBLE, 0, world);
      MPI_Bcast(&mur[i][j], 1, MPI_DOUBLE, 0, world);
      MPI_Bcast(&cor[i][j], 1, MPI_DOUBLE, 0, world);
    }
  }
}

/* ----------------------------------------------------------------------
   write_data: 'Pair Coeffs' (type I) and 'PairIJ Coeffs' (I J), read back by pair_coeff
------------------------------------------------------------------------- */

void PairGranHertzRolling::write_data(FILE *fp)
{
  for (int i = 1; i <= atom->ntypes; i++)
    utils::print(fp, "{} material {:.17g} {:.17g} friction {:.17g} rolling {:.17g} restitution {:.17g}\n",
                 i, Emod[i], poiss[i], mu[i][i], mur[i][i], cor[i][i]);
}

void PairGranHertzRolling::write_data_all(FILE *fp)
{
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      const law::Params &p = params(i, j);
      if (i == j)
        utils::print(fp, "{} {} material {:.17g} {:.17g}", i, j, Emod[i], poiss[i]);
      else
        utils::print(fp, "{} {}", i, j);
      utils::print(fp, " friction {:.17g} rolling {:.17g} restitution {:.17g}\n",
                   mu[i][j] >= 0.0 ? mu[i][j] : p.mu, mur[i][j] >= 0.0 ? mur[i][j] : p.mur,
                   cor[i][j] >= 0.0 ? cor[i][j] : sqrt(cor[i][i] * cor[j][j]));
    }
}

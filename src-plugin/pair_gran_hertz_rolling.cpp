/* ----------------------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   pair_style gran/hertz/rolling: Hertz-Mindlin contact with restitution damping, a friction
   matrix and rolling resistance. The physics is in law/contact_law.h, its batch form in
   law/contact_chain.h; compute() is in pair_gran_hertz_rolling_kernel.cpp. This file: the
   style's settings, coefficients, init, single(), restart and data files (about 590 lines, most
   of them the keyword parsing and its error messages, which name the command and the fix).
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
#include <cstdlib>
#include <cstring>

using namespace LAMMPS_NS;
namespace law = tbags::contact;

// the candidate list is rebuilt once an atom has moved this fraction of the candidate skin since
// the build: two atoms then approached by at most 2 x 0.49 = 0.98 skins, so a pair left out
// (farther apart than r_i + r_j + skin) is still 0.02 skins from touching
static constexpr double CAND_MOVE_LIMIT = 0.49;

PairGranHertzRolling::PairGranHertzRolling(LAMMPS *lmp) :
    Pair(lmp), rolling(law::ROLLING_NONE), limit_damping(false), roll_mean(false), twisting(false),
    size_history(3), history_model(-1), ntypes1(0),
    freeze_group_bit(0), neighprev(0), Emod(nullptr), poiss(nullptr), matflag(nullptr),
    maxrad(nullptr), mu(nullptr), mur(nullptr), cor(nullptr), ktw(nullptr), ctw(nullptr),
    mutw(nullptr), fix_history(nullptr),
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
    memory->destroy(ktw);
    memory->destroy(ctw);
    memory->destroy(mutw);
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
  memory->create(ktw, n + 1, n + 1, "pair:ktw");
  memory->create(ctw, n + 1, n + 1, "pair:ctw");
  memory->create(mutw, n + 1, n + 1, "pair:mutw");
  for (int i = 0; i <= n; i++) {
    Emod[i] = poiss[i] = maxrad[i] = 0.0;
    matflag[i] = 0;
    for (int j = 0; j <= n; j++) {
      // diagonal marked set so that init_style(), not Pair::init()'s generic message,
      // reports a type without coefficients (matflag tracks what pair_coeff gave)
      setflag[i][j] = (i == j) ? 1 : 0;
      mu[i][j] = mur[i][j] = cor[i][j] = -1.0;
      ktw[i][j] = ctw[i][j] = mutw[i][j] = -1.0;
    }
  }
  law.assign((size_t) (n + 1) * (n + 1), law::Params());
}

/* ----------------------------------------------------------------------
   pair_style gran/hertz/rolling epsd|cdt|none [limit_damping] [rolling_radius effective|mean]
     [twisting none|sds] [kernel auto|avx2|baseline] [contact_skin f]
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
  roll_mean = false;
  twisting = false;
  kernel_choice = KERNEL_AUTO;
  contact_skin = 0.25;
  for (int iarg = 1; iarg < narg; iarg++) {
    if (strcmp(arg[iarg], "limit_damping") == 0) {
      limit_damping = true;
    } else if (strcmp(arg[iarg], "rolling_radius") == 0) {
      const std::string r = iarg + 1 < narg ? arg[++iarg] : "";
      if (r == "effective") roll_mean = false;
      else if (r == "mean") roll_mean = true;
      else
        error->all(FLERR, "{}: rolling_radius must be effective (R* = RiRj/(Ri+Rj)) or mean "
                   "((Ri+Rj)/2), not '{}'", STYLE, r);
    } else if (strcmp(arg[iarg], "twisting") == 0) {
      const std::string t = iarg + 1 < narg ? arg[++iarg] : "";
      if (t == "none") twisting = false;
      else if (t == "sds") twisting = true;
      else
        error->all(FLERR, "{}: twisting must be none or sds (a torsional spring, dashpot and cap "
                   "set by 'pair_coeff I J ... twisting k_tw c_tw mu_tw'), not '{}'", STYLE, t);
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
      error->all(FLERR, "{}: unknown keyword '{}'; use limit_damping, rolling_radius, twisting, "
                 "kernel or contact_skin", STYLE, arg[iarg]);
    }
  }
  size_history = law::history_size(rolling, twisting);
}

/* ----------------------------------------------------------------------
   pair_coeff I J [material E nu] [friction mu] [rolling mu_r] [restitution e]
     [twisting k_tw c_tw mu_tw]
   material only with I == J; for I == J friction and restitution (and rolling unless the
   model is none, twisting with twisting sds) are required; for I != J, values not given mix
   from the diagonal (geometric mean).
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

  double E = -1.0, nu = 0.0, f = -1.0, fr = -1.0, e = -1.0, tk = -1.0, tc = -1.0, tm = -1.0;
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
    } else if (kw == "twisting") {
      need(3);
      if (!twisting)
        error->all(FLERR, "{}: pair_coeff keyword 'twisting' needs 'twisting sds' in the "
                   "pair_style command", STYLE);
      tk = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      tc = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      tm = utils::numeric(FLERR, arg[iarg + 3], false, lmp);
      if (tk <= 0.0 || tc < 0.0 || tm < 0.0)
        error->all(FLERR, "{}: twisting needs a stiffness k_tw > 0 (N m/rad), a damping c_tw >= 0 "
                   "(N m s/rad) and a cap coefficient mu_tw >= 0 (m; |M_t| <= mu_tw |F_n|), got "
                   "{} {} {}", STYLE, tk, tc, tm);
      iarg += 4;
    } else {
      error->all(FLERR, "{}: unknown pair_coeff keyword '{}'; use material, friction, rolling, "
                 "restitution{}", STYLE, kw, twisting ? ", twisting" : "");
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
        if (twisting && tk < 0.0)
          error->all(FLERR, "{}: pair_coeff {} {} needs 'twisting k_tw c_tw mu_tw' (pair_style "
                     "... twisting sds)", STYLE, i, i);
        if (has_mat) {
          Emod[i] = E;
          poiss[i] = nu;
          matflag[i] = 1;
        }
      }
      if (f >= 0.0) mu[i][j] = f;
      if (fr >= 0.0) mur[i][j] = fr;
      if (e >= 0.0) cor[i][j] = e;
      if (tk >= 0.0) {
        ktw[i][j] = tk;
        ctw[i][j] = tc;
        mutw[i][j] = tm;
      }
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
    if (history_model != history_key() || fix_history->get_dnum() != size_history) {
      if (comm->me == 0)
        error->warning(FLERR, "{}: the rolling or twisting model changed since the last run: the "
                       "contact histories start again from zero", STYLE);
      // (replace_fix needs the new ID free: the old store is renamed first)
      delete[] fix_history->id;
      fix_history->id = utils::strdup("NEIGH_HISTORY_GHR_OLD");
      fix_history = dynamic_cast<FixNeighHistory *>(modify->replace_fix(
          "NEIGH_HISTORY_GHR_OLD", "NEIGH_HISTORY_GHR all NEIGH_HISTORY/TBAGS " + std::to_string(size_history), 1));
      fix_history->pair = this;
    }
  }
  history_model = history_key();

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
    utils::logmesg(lmp, "{}: batch kernel {} (kernel {}{}{}); rolling radius {}; twisting {}\n", STYLE,
                   simd_avx2 ? "avx2, 4 contacts per vector" : "baseline x86-64, 2 contacts per vector",
                   kernel_choice == KERNEL_AUTO ? "auto" : kernel_choice == KERNEL_AVX2 ? "avx2" : "baseline",
                   (!have && kernel_choice == KERNEL_AUTO) ? ": " : "",
                   (!have && kernel_choice == KERNEL_AUTO) ? why : "",
                   roll_mean ? "mean (Ri+Rj)/2" : "effective R*", twisting ? "sds" : "none");
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
  law::Params p = law::make_params(Es, Gs, pick(cor, "restitution"), pick(mu, "friction"),
                                   pick(mur, "rolling friction"), rolling, limit_damping);
  p.roll_mean = roll_mean ? 1.0 : 0.0;
  if (twisting) {
    p.ktw = pick(ktw, "twisting stiffness");
    p.ctw = pick(ctw, "twisting damping");
    p.mutw = pick(mutw, "twisting cap");
  }
  law[i * ntypes1 + j] = law[j * ntypes1 + i] = p;

  double cut = maxrad[i] + maxrad[j];
  if (cut <= 0.0) {
    for (int k = 1; k <= atom->ntypes; k++) cut = MAX(cut, 2.0 * maxrad[k]);
  }
  return cut;
}

/* ---------------------------------------------------------------------- */

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
  double hist[7] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
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
  set_contact(i, j, dx, c);
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
   R* (w_i - w_j) x n and the twist angle (w_i - w_j) . n, where both factors change sign, so
   they are kept.
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
  // setflag, cutsq, mu, mur, cor, ktw, ctw, mutw per type pair; Emod, poiss, maxrad, matflag per
  // type; the law
  if (allocated) bytes += nt * nt * (7 * sizeof(double) + sizeof(int)) + nt * (3 * sizeof(double) + sizeof(int));
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
  if (strcmp(str, "k_twist") == 0) return (void *) ktw;
  return nullptr;
}

/* ---------------------------------------------------------------------- */

// restart settings: the rolling model plus SETTINGS_V4 marks the record that also holds the kernel
// choice, the contact skin, the rolling radius and twisting; SETTINGS_V3 all but twisting,
// SETTINGS_V2 the kernel and skin only (before rolling_radius); files of tbags 0.3 and before
// hold the model and limit_damping only. With twisting, each type pair's record ends with its
// twisting coefficients.
static constexpr int SETTINGS_V2 = 16;
static constexpr int SETTINGS_V3 = 32;
static constexpr int SETTINGS_V4 = 64;

void PairGranHertzRolling::write_restart_settings(FILE *fp)
{
  int head[3] = {rolling + SETTINGS_V4, limit_damping ? 1 : 0, kernel_choice};
  fwrite(head, sizeof(int), 3, fp);
  fwrite(&contact_skin, sizeof(double), 1, fp);
  const int flags[2] = {roll_mean ? 1 : 0, twisting ? 1 : 0};
  fwrite(flags, sizeof(int), 2, fp);
}

void PairGranHertzRolling::read_restart_settings(FILE *fp)
{
  int head[5] = {0, 0, KERNEL_AUTO, 0, 0};
  if (comm->me == 0) {
    utils::sfread(FLERR, head, sizeof(int), 2, fp, nullptr, error);
    const int version = head[0] >= SETTINGS_V4 ? 4 : head[0] >= SETTINGS_V3 ? 3 : head[0] >= SETTINGS_V2 ? 2 : 1;
    if (version >= 2) {
      utils::sfread(FLERR, &head[2], sizeof(int), 1, fp, nullptr, error);
      utils::sfread(FLERR, &contact_skin, sizeof(double), 1, fp, nullptr, error);
    }
    if (version >= 3) utils::sfread(FLERR, &head[3], sizeof(int), 1, fp, nullptr, error);
    if (version >= 4) utils::sfread(FLERR, &head[4], sizeof(int), 1, fp, nullptr, error);
    head[0] -= version == 4 ? SETTINGS_V4 : version == 3 ? SETTINGS_V3 : version == 2 ? SETTINGS_V2 : 0;
  }
  MPI_Bcast(head, 5, MPI_INT, 0, world);
  MPI_Bcast(&contact_skin, 1, MPI_DOUBLE, 0, world);
  rolling = head[0];
  limit_damping = head[1] != 0;
  kernel_choice = head[2];
  roll_mean = head[3] != 0;
  twisting = head[4] != 0;
  size_history = law::history_size(rolling, twisting);
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
      if (twisting) {
        fwrite(&ktw[i][j], sizeof(double), 1, fp);
        fwrite(&ctw[i][j], sizeof(double), 1, fp);
        fwrite(&mutw[i][j], sizeof(double), 1, fp);
      }
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
        if (twisting) {
          utils::sfread(FLERR, &ktw[i][j], sizeof(double), 1, fp, nullptr, error);
          utils::sfread(FLERR, &ctw[i][j], sizeof(double), 1, fp, nullptr, error);
          utils::sfread(FLERR, &mutw[i][j], sizeof(double), 1, fp, nullptr, error);
        }
      }
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
      MPI_Bcast(&mu[i][j], 1, MPI_DOUBLE, 0, world);
      MPI_Bcast(&mur[i][j], 1, MPI_DOUBLE, 0, world);
      MPI_Bcast(&cor[i][j], 1, MPI_DOUBLE, 0, world);
      MPI_Bcast(&ktw[i][j], 1, MPI_DOUBLE, 0, world);
      MPI_Bcast(&ctw[i][j], 1, MPI_DOUBLE, 0, world);
      MPI_Bcast(&mutw[i][j], 1, MPI_DOUBLE, 0, world);
    }
  }
}

/* ----------------------------------------------------------------------
   write_data: 'Pair Coeffs' (type I) and 'PairIJ Coeffs' (I J), read back by pair_coeff
------------------------------------------------------------------------- */

void PairGranHertzRolling::write_data(FILE *fp)
{
  for (int i = 1; i <= atom->ntypes; i++) {
    utils::print(fp, "{} material {:.17g} {:.17g} friction {:.17g} rolling {:.17g} restitution {:.17g}",
                 i, Emod[i], poiss[i], mu[i][i], mur[i][i], cor[i][i]);
    if (twisting) utils::print(fp, " twisting {:.17g} {:.17g} {:.17g}", ktw[i][i], ctw[i][i], mutw[i][i]);
    utils::print(fp, "\n");
  }
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
      utils::print(fp, " friction {:.17g} rolling {:.17g} restitution {:.17g}",
                   mu[i][j] >= 0.0 ? mu[i][j] : p.mu, mur[i][j] >= 0.0 ? mur[i][j] : p.mur,
                   cor[i][j] >= 0.0 ? cor[i][j] : sqrt(cor[i][i] * cor[j][j]));
      if (twisting) utils::print(fp, " twisting {:.17g} {:.17g} {:.17g}", p.ktw, p.ctw, p.mutw);
      utils::print(fp, "\n");
    }
}

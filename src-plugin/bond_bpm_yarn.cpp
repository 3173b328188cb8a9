/* ----------------------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   bond_style bpm/yarn: adapter between BondBPM (breaking, bond history, special lists,
   store/local) and the yarn law (law/yarn_law.h), run over batches of bonds of one type
   (law/yarn_chain.h): gather, the law in SIMD lanes, then history, breaks and forces in
   bond-list order.
------------------------------------------------------------------------- */

#include "bond_bpm_yarn.h"
#include "simd_target.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_bond_history.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
namespace yarn = tbags::yarn;

// the chain over a batch, built for the baseline and for AVX2 (simd_target.h); the same bits
namespace {
template <bool UPDATE> void chain_baseline(const yarn::Params &p, yarn::Batch &b, int n, double dt)
{
  yarn::chain<UPDATE>(p, b, n, dt);
}
#ifdef TBAGS_HAVE_AVX2_CLONE
template <bool UPDATE>
TBAGS_TARGET_AVX2 void chain_avx2(const yarn::Params &p, yarn::Batch &b, int n, double dt)
{
  yarn::chain<UPDATE>(p, b, n, dt);
}
#endif
void run_chain(const yarn::Params &p, yarn::Batch &b, int n, double dt, bool integrate, bool avx2)
{
#ifdef TBAGS_HAVE_AVX2_CLONE
  if (avx2) return integrate ? chain_avx2<true>(p, b, n, dt) : chain_avx2<false>(p, b, n, dt);
#endif
  return integrate ? chain_baseline<true>(p, b, n, dt) : chain_baseline<false>(p, b, n, dt);
}
}    // namespace

static const char *STYLE = "Bond style bpm/yarn";

BondBPMYarn::BondBPMYarn(LAMMPS *lmp) : BondBPM(lmp)
{
  partial_flag = 1;
  writedata = 1;
  nhistory = yarn::NHISTORY;
  update_flag = 1;    // the history (shear force, moments, largest strain) changes every step
  id_fix_bond_history = utils::strdup("HISTORY_BPM_YARN");
  // svector for compute bond/local b1..b8: strain, axial force, |shear force|, |bending
  // moment|, twisting moment, the bond's whole force on its atom of lower ID (x, y, z)
  single_extra = 8;
  svector = new double[single_extra];
}

BondBPMYarn::~BondBPMYarn()
{
  delete[] svector;
  if (allocated) memory->destroy(setflag);
}

void BondBPMYarn::allocate()
{
  allocated = 1;
  const int n = atom->nbondtypes;
  memory->create(setflag, n + 1, "bond:setflag");
  for (int i = 0; i <= n; i++) setflag[i] = 0;
  coeffs.clear();
  coeffs.resize(n + 1);
}

/* ----------------------------------------------------------------------
   bond_style bpm/yarn [overlay/pair yes|no] [break yes|no] [store/local ...]
                       [kernel auto|baseline]
------------------------------------------------------------------------- */

void BondBPMYarn::settings(int narg, char **arg)
{
  create_history_store();
  BondBPM::settings(narg, arg);
  // BondBPM leaves the words it does not know, one by one: ours is "kernel" and its value
  std::string kernel = "auto";
  for (size_t k = 0; k < leftover_iarg.size(); k++) {
    const int i = leftover_iarg[k];
    if (strcmp(arg[i], "kernel") == 0) {
      if (k + 1 >= leftover_iarg.size() || leftover_iarg[k + 1] != i + 1)
        error->all(FLERR, "{}: kernel needs a value: auto or baseline", STYLE);
      kernel = arg[i + 1];
      if (kernel != "auto" && kernel != "baseline")
        error->all(FLERR, "{}: kernel {} is not known; use auto or baseline", STYLE, kernel);
      k++;
    } else {
      error->all(FLERR, "{}: unknown keyword '{}'; use overlay/pair, break, store/local or kernel",
                 STYLE, arg[i]);
    }
  }
  kernel_baseline = kernel == "baseline";
}

void BondBPMYarn::coeff(int narg, char **arg)
{
  if (!allocated) allocate();
  int ilo, ihi;
  utils::bounds(FLERR, arg[0], 1, atom->nbondtypes, ilo, ihi, error);
  YarnCoeff c;
  parse_yarn_coeff(lmp, STYLE, narg, arg, c);
  for (int i = ilo; i <= ihi; i++) {
    coeffs[i] = c;
    setflag[i] = 1;
  }
}

void BondBPMYarn::init_style()
{
  create_history_store();    // after read_restart, which does not call settings()
  BondBPM::init_style();
  // the chain's build: AVX2 where the CPU has it, unless kernel baseline (also after
  // read_restart, which does not call settings())
#ifdef TBAGS_HAVE_AVX2_CLONE
  const int avx2 = !kernel_baseline && __builtin_cpu_supports("avx2");
#else
  const int avx2 = 0;
#endif
  if (comm->me == 0 && avx2 != kernel_avx2)
    utils::logmesg(lmp, "{}: batch kernel {}\n", STYLE, avx2 ? "avx2" : "baseline");
  kernel_avx2 = avx2;
  if (!atom->quat_flag || !atom->radius_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "{} requires atom_style bpm/sphere (radius, omega, torque, quat); for other "
               "atom styles use bond_style yarn", STYLE);
  if (comm->ghost_velocity == 0)
    error->all(FLERR, "{} requires ghost velocities: add 'comm_modify vel yes'", STYLE);
  // the law is incremental (no particle orientations): any integrator of rotations will do
  if (modify->get_fix_by_style("^nve/sphere").empty() &&
      modify->get_fix_by_style("^nve/bpm/sphere").empty() && comm->me == 0 && !warned_integrator++)
    error->warning(FLERR, "{}: particles with bending/twisting bonds need their rotations "
                   "integrated: fix nve/sphere (or nve/bpm/sphere)", STYLE);
}

/* ----------------------------------------------------------------------
   the bonds' history store: ours (fix_bond_history_tbags.h, a checkpoint leaves the run as it
   was), in the place BondBPM keeps for LAMMPS's, before BondBPM would create that one
------------------------------------------------------------------------- */

void BondBPMYarn::create_history_store()
{
  if (fix_bond_history) return;
  Fix *fix = modify->replace_fix(id_fix_dummy_history,
                                 fmt::format("{} all BOND_HISTORY/TBAGS {} {}", id_fix_bond_history,
                                             update_flag, nhistory), 1);
  fix_bond_history = dynamic_cast<FixBondHistory *>(fix);
  delete[] id_fix_dummy_history;
  id_fix_dummy_history = nullptr;
}

/* ----------------------------------------------------------------------
   first call: store every bond's rest length (the type's r0 if given, else its length now) and
   zero its history
------------------------------------------------------------------------- */

void BondBPMYarn::store_data()
{
  double **x = atom->x;
  for (int i = 0; i < atom->nlocal; i++) {
    for (int m = 0; m < atom->num_bond[i]; m++) {
      if (atom->bond_type[i][m] < 0) continue;
      const int j = atom->map(atom->bond_atom[i][m]);
      if (j == -1) error->one(FLERR, "{}: bonded atom {} is missing", STYLE, atom->bond_atom[i][m]);
      double d[3] = {x[j][0] - x[i][0], x[j][1] - x[i][1], x[j][2] - x[i][2]};
      domain->minimum_image(d[0], d[1], d[2]);
      const double now = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      fix_bond_history->update_atom_value(i, m, yarn::R0, coeffs[atom->bond_type[i][m]].rest_length(now));
      for (int k = 1; k < yarn::NHISTORY; k++) fix_bond_history->update_atom_value(i, m, k, 0.0);
    }
  }
  fix_bond_history->post_neighbor();
}

/* ---------------------------------------------------------------------- */

void BondBPMYarn::compute(int eflag, int vflag)
{
  if (!fix_bond_history->stored_flag) {
    fix_bond_history->stored_flag = true;
    store_data();
  }
  if (hybrid_flag) fix_bond_history->compress_history();
  ev_init(eflag, vflag);

  // flat arrays: atom i's values at 3 i (no row pointer to load per atom)
  const double *x = atom->x[0], *v = atom->v[0], *omega = atom->omega[0];
  const tagint *tag = atom->tag;
  int **bondlist = neighbor->bondlist;
  const int nbondlist = neighbor->nbondlist;
  double **bondstore = fix_bond_history->bondstore;
  if (!batch) batch.reset(new yarn::Batch);
  yarn::Batch &b = *batch;

  // runs of up to Batch::N consecutive bonds of one type go through the law together; their
  // forces are applied in list order (the sums of a bond-by-bond loop, bit for bit)
  int nb = 0, btype = 0;
  for (int n = 0; n < nbondlist; n++) {
    const int type = bondlist[n][2];
    if (type <= 0) continue;
    if (nb > 0 && type != btype) {
      flush(nb, btype);
      nb = 0;
    }
    btype = type;
    // order by tag: both copies of a bond across ranks (newton off) compute the same numbers
    // (selected without a branch: which atom of a bond has the lower tag is a coin toss)
    const int a1 = bondlist[n][0], a2 = bondlist[n][1];
    const bool swap = tag[a2] < tag[a1];
    const int i1 = swap ? a2 : a1, i2 = swap ? a1 : a2;
    const double *x1 = x + 3 * i1, *x2 = x + 3 * i2;
    double *hist = bondstore[n];
    if (!(hist[yarn::R0] > 0.0)) {    // a bond created after the first step
      double d[3] = {x2[0] - x1[0], x2[1] - x1[1], x2[2] - x1[2]};
      hist[yarn::R0] = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (int k = 1; k < yarn::NHISTORY; k++) hist[k] = 0.0;
    }
    for (int k = 0; k < 3; k++) {
      b.xi[k][nb] = x1[k], b.xj[k][nb] = x2[k];
      b.vi[k][nb] = v[3 * i1 + k], b.vj[k][nb] = v[3 * i2 + k];
      b.wi[k][nb] = omega[3 * i1 + k], b.wj[k][nb] = omega[3 * i2 + k];
    }
    for (int k = 0; k < yarn::NHISTORY; k++) b.h[k][nb] = hist[k];
    lane_bond[nb] = n;
    lane_i[nb] = i1;
    lane_j[nb] = i2;
    if (++nb == yarn::Batch::N) {
      flush(nb, btype);
      nb = 0;
    }
  }
  if (nb > 0) flush(nb, btype);
  if (hybrid_flag) fix_bond_history->uncompress_history();
}

/* ----------------------------------------------------------------------
   the law over the batch's nb bonds (of type btype), then, in list order: history back,
   breaks, forces and torques, energy and virial
------------------------------------------------------------------------- */

void BondBPMYarn::flush(int nb, int btype)
{
  yarn::Batch &b = *batch;
  const yarn::Params &p = coeffs[btype].p;
  run_chain(p, b, nb, update->dt, update->setupflag == 0, kernel_avx2);
  // flat arrays, as in compute(): atom i's values at 3 i
  const double *x = atom->x[0];
  double *f = atom->f[0], *torque = atom->torque[0];
  int **bondlist = neighbor->bondlist;
  double **bondstore = fix_bond_history->bondstore;
  const int nlocal = atom->nlocal;
  const int newton_bond = force->newton_bond;
  for (int l = 0; l < nb; l++) {
    const int n = lane_bond[l], i1 = lane_i[l], i2 = lane_j[l];
    double *hist = bondstore[n];
    for (int k = 0; k < yarn::NHISTORY; k++) hist[k] = b.h[k][l];
    if (b.broken[l] && break_flag) {
      bondlist[n][2] = 0;
      process_broken(i1, i2);
      continue;
    }
    if (newton_bond || i1 < nlocal) {
      for (int k = 0; k < 3; k++) {
        f[3 * i1 + k] += b.f[k][l];
        torque[3 * i1 + k] += b.ti[k][l];
      }
    }
    if (newton_bond || i2 < nlocal) {
      for (int k = 0; k < 3; k++) {
        f[3 * i2 + k] -= b.f[k][l];
        torque[3 * i2 + k] += b.tj[k][l];
      }
    }
    if (evflag) {
      const double ebond = eflag_either ? yarn::axial_energy(p, b.eps[l], hist[yarn::R0]) : 0.0;
      // ev_tally_xyz: del = x1 - x2 and the force on atom 1
      ev_tally_xyz(i1, i2, nlocal, newton_bond, ebond, b.f[0][l], b.f[1][l], b.f[2][l],
                   x[3 * i1] - x[3 * i2], x[3 * i1 + 1] - x[3 * i2 + 1],
                   x[3 * i1 + 2] - x[3 * i2 + 2]);
    }
  }
}

/* ----------------------------------------------------------------------
   history of the bond i-j from the owning atom's stored values
------------------------------------------------------------------------- */

bool BondBPMYarn::bond_history(int i, int j, double *hist)
{
  for (int a = 0; a < 2; a++) {
    const int own = a == 0 ? i : j, other = a == 0 ? j : i;
    if (own >= atom->nlocal) continue;
    for (int m = 0; m < atom->num_bond[own]; m++)
      if (atom->bond_atom[own][m] == atom->tag[other]) {
        for (int k = 0; k < yarn::NHISTORY; k++) hist[k] = fix_bond_history->get_atom_value(own, m, k);
        return true;
      }
  }
  return false;
}

/* ----------------------------------------------------------------------
   single(): energy of the axial spring, fforce along the bond (tension < 0 as LAMMPS bonds:
   F = fforce * del with del = x_i - x_j); svector: strain, axial force, |F_s|, |M_b|, M_t, and
   the whole force (axial, shear, damping) on the atom of lower ID
------------------------------------------------------------------------- */

double BondBPMYarn::single(int type, double rsq, int i, int j, double &fforce)
{
  fforce = 0.0;
  for (int k = 0; k < single_extra; k++) svector[k] = 0.0;
  if (type <= 0) return 0.0;
  if (atom->tag[j] < atom->tag[i]) std::swap(i, j);
  double hist[yarn::NHISTORY];
  if (!bond_history(i, j, hist) || !(hist[yarn::R0] > 0.0)) return 0.0;
  yarn::Result o;
  yarn::compute(coeffs[type].p, bond_state(i, j), hist, false, o);
  const double r = sqrt(rsq);
  fforce = -o.fax / r;    // attractive in tension
  svector[0] = o.eps;
  svector[1] = o.fax;
  svector[2] = tbags::vec::len(hist + yarn::FS);
  svector[3] = tbags::vec::len(hist + yarn::MB);
  svector[4] = hist[yarn::MT];
  for (int k = 0; k < 3; k++) svector[5 + k] = o.f[k];
  return yarn::axial_energy(coeffs[type].p, o.eps, hist[yarn::R0]);
}

/* ---------------------------------------------------------------------- */

void BondBPMYarn::write_restart(FILE *fp)
{
  BondBPM::write_restart(fp);
  for (int i = 1; i <= atom->nbondtypes; i++) write_yarn_coeff(fp, coeffs[i]);
}

void BondBPMYarn::read_restart(FILE *fp)
{
  BondBPM::read_restart(fp);
  allocate();
  for (int i = 1; i <= atom->nbondtypes; i++) {
    read_yarn_coeff(lmp, fp, coeffs[i]);
    setflag[i] = coeffs[i].set ? 1 : 0;
  }
}

void BondBPMYarn::write_data(FILE *fp)
{
  for (int i = 1; i <= atom->nbondtypes; i++) {
    const YarnCoeff &c = coeffs[i];
    utils::print(fp, "{} table {} {} diameter {:.17g} poisson {:.17g} E {:.17g} shear {:.17g} "
                 "break {:.17g} damping {:.17g} {:.17g} {:.17g} unload {}{}\n", i, c.file, c.keyword,
                 c.p.d, c.p.nu, c.p.E, c.p.kappa, c.p.eps_break, c.p.gn, c.p.gs, c.p.gr,
                 c.p.plastic ? "plastic" : "elastic",
                 c.r0 > 0.0 ? fmt::format(" r0 {:.17g}", c.r0) : std::string());
  }
}

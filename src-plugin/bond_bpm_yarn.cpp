/* ----------------------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   bond_style bpm/yarn: adapter between BondBPM (breaking, bond history, special lists,
   store/local) and the yarn law (law/yarn_law.h).
------------------------------------------------------------------------- */

#include "bond_bpm_yarn.h"

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

static const char *STYLE = "Bond style bpm/yarn";

BondBPMYarn::BondBPMYarn(LAMMPS *lmp) : BondBPM(lmp)
{
  partial_flag = 1;
  writedata = 1;
  nhistory = yarn::NHISTORY;
  update_flag = 1;    // the history (shear force, moments, largest strain) changes every step
  id_fix_bond_history = utils::strdup("HISTORY_BPM_YARN");
  // svector for compute bond/local b1..b5: strain, axial force, |shear force|, |bending
  // moment|, twisting moment
  single_extra = 5;
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
------------------------------------------------------------------------- */

void BondBPMYarn::settings(int narg, char **arg)
{
  BondBPM::settings(narg, arg);
  for (int i : leftover_iarg)
    error->all(FLERR, "{}: unknown keyword '{}'; use overlay/pair, break or store/local", STYLE,
               arg[i]);
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
  BondBPM::init_style();
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
   first call: store the length of every bond (r0) and zero its history
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
      fix_bond_history->update_atom_value(i, m, yarn::R0, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
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

  double **x = atom->x;
  double **f = atom->f;
  double **torque = atom->torque;
  const tagint *tag = atom->tag;
  int **bondlist = neighbor->bondlist;
  const int nbondlist = neighbor->nbondlist;
  const int nlocal = atom->nlocal;
  const int newton_bond = force->newton_bond;
  double **bondstore = fix_bond_history->bondstore;
  const bool update_hist = update->setupflag == 0;

  yarn::Result o;
  for (int n = 0; n < nbondlist; n++) {
    if (bondlist[n][2] <= 0) continue;
    int i1 = bondlist[n][0], i2 = bondlist[n][1];
    const int type = bondlist[n][2];
    // order by tag: both copies of a bond across ranks (newton off) compute the same numbers
    if (tag[i2] < tag[i1]) std::swap(i1, i2);
    double *hist = bondstore[n];
    if (!(hist[yarn::R0] > 0.0)) {    // a bond created after the first step
      double d[3] = {x[i2][0] - x[i1][0], x[i2][1] - x[i1][1], x[i2][2] - x[i1][2]};
      hist[yarn::R0] = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (int k = 1; k < yarn::NHISTORY; k++) hist[k] = 0.0;
    }
    const yarn::Params &p = coeffs[type].p;
    yarn::compute(p, bond_state(i1, i2), hist, update_hist, o);
    if (o.broken && break_flag) {
      bondlist[n][2] = 0;
      process_broken(i1, i2);
      continue;
    }
    if (newton_bond || i1 < nlocal) {
      for (int k = 0; k < 3; k++) {
        f[i1][k] += o.f[k];
        torque[i1][k] += o.ti[k];
      }
    }
    if (newton_bond || i2 < nlocal) {
      for (int k = 0; k < 3; k++) {
        f[i2][k] -= o.f[k];
        torque[i2][k] += o.tj[k];
      }
    }
    if (evflag) {
      const double ebond = eflag ? yarn::axial_energy(p, o.eps, hist[yarn::R0]) : 0.0;
      // ev_tally_xyz: del = x1 - x2 and the force on atom 1
      ev_tally_xyz(i1, i2, nlocal, newton_bond, ebond, o.f[0], o.f[1], o.f[2],
                   x[i1][0] - x[i2][0], x[i1][1] - x[i2][1], x[i1][2] - x[i2][2]);
    }
  }
  if (hybrid_flag) fix_bond_history->uncompress_history();
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
   F = fforce * del with del = x_i - x_j); svector: strain, axial force, |F_s|, |M_b|, M_t
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
                 "break {:.17g} damping {:.17g} {:.17g} {:.17g} unload {}\n", i, c.file, c.keyword,
                 c.p.d, c.p.nu, c.p.E, c.p.kappa, c.p.eps_break, c.p.gn, c.p.gs, c.p.gr,
                 c.p.plastic ? "plastic" : "elastic");
  }
}

/* T-BAGS DEM toolkit, LIGGGHTS adapter: bond_style bpm/yarn (see the header). The physics is
   law/yarn_chain.h's compute(), one bond at a time (the same bits as the LAMMPS plugin's batch). */

#include "bond_bpm_yarn.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix_bond_history_yarn.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstring>
#include <string>
#include <utility>

using namespace LAMMPS_NS;
namespace yarn = tbags::yarn;

static const char STYLE[] = "bond_style bpm/yarn";
static const char HISTORY_ID[] = "tbags_yarn_history";

BondBPMYarn::BondBPMYarn(LAMMPS *lmp) : Bond(lmp), history(NULL), nbroken(0) {}

BondBPMYarn::~BondBPMYarn()
{
  if (allocated) memory->destroy(setflag);
}

void BondBPMYarn::allocate()
{
  allocated = 1;
  memory->create(setflag, atom->nbondtypes + 1, "bond:setflag");
  for (int i = 0; i <= atom->nbondtypes; i++) setflag[i] = 0;
  coeffs.resize(atom->nbondtypes + 1);
}

void BondBPMYarn::coeff(int narg, char **arg)
{
  if (!allocated) allocate();
  int lo, hi;
  force->bounds(arg[0], atom->nbondtypes, lo, hi);
  YarnCoeff c;
  parse_yarn_coeff(lmp, STYLE, narg, arg, c);
  for (int t = lo; t <= hi; t++) {
    coeffs[t] = c;
    setflag[t] = 1;
  }
}

void BondBPMYarn::init_style()
{
  if (!atom->radius_flag || !atom->omega_flag || !atom->torque_flag || !atom->molecular)
    error->all(FLERR, "bond_style bpm/yarn needs spheres with bonds: atom_style hybrid granular molecular");
  if (force->newton_bond)
    error->all(FLERR, "bond_style bpm/yarn needs newton_bond off (each rank computes the bonds of "
               "its atoms): newton on off");
  if (comm->ghost_velocity == 0)
    error->all(FLERR, "bond_style bpm/yarn needs ghost velocities: communicate single vel yes");
  make_history();
}

// the history store, created once with a slot per bond of each atom (restored from a restart
// file when one was read: same ID and style)
void BondBPMYarn::make_history()
{
  int ifix = modify->find_fix(HISTORY_ID);
  if (ifix >= 0) {
    history = static_cast<FixBondHistoryYarn *>(modify->fix[ifix]);
    if (history->slots() < atom->bond_per_atom)
      error->all(FLERR, "bond_style bpm/yarn: more bonds per atom than when the run began");
    return;
  }
  std::string nslot = std::to_string(atom->bond_per_atom), nhist = std::to_string(yarn::NHISTORY);
  const char *arg[5] = {HISTORY_ID, "all", "bond/history/yarn", nslot.c_str(), nhist.c_str()};
  modify->add_fix(5, const_cast<char **>(arg));
  history = static_cast<FixBondHistoryYarn *>(modify->fix[modify->find_fix(HISTORY_ID)]);
}

// the index of the bond own-other among atom own's bonds (own local), or -1
int BondBPMYarn::bond_index(int own, int other) const
{
  const int tagother = atom->tag[other];
  for (int m = 0; m < atom->num_bond[own]; m++)
    if (atom->bond_atom[own][m] == tagother) return m;
  return -1;
}

// the history slot of the bond own-other on atom own (local), or NULL
double *BondBPMYarn::slot_of(int own, int other)
{
  const int m = bond_index(own, other);
  return m < 0 ? NULL : history->slot(own, m);
}

// the law's view of the bond i-j
tbags::yarn::Bond BondBPMYarn::bond_state(int i, int j) const
{
  tbags::yarn::Bond b;
  b.xi = atom->x[i], b.xj = atom->x[j], b.vi = atom->v[i], b.vj = atom->v[j];
  b.wi = atom->omega[i], b.wj = atom->omega[j];
  b.dt = update->dt;
  return b;
}

void BondBPMYarn::compute(int eflag, int vflag)
{
  if (eflag || vflag) ev_setup(eflag, vflag);
  else evflag = 0;
  double **x = atom->x, **f = atom->f, **torque = atom->torque;
  int *tag = atom->tag;
  int **bondlist = neighbor->bondlist;
  const int nbondlist = neighbor->nbondlist, nlocal = atom->nlocal;
  const bool update_history = update->setupflag == 0;
  for (int n = 0; n < nbondlist; n++) {
    const int type = bondlist[n][2];
    if (type <= 0) continue;
    int i1 = bondlist[n][0], i2 = bondlist[n][1];
    // order by tag: both ranks of a bond across a boundary compute the same numbers
    if (tag[i2] < tag[i1]) std::swap(i1, i2);
    double *h1 = i1 < nlocal ? slot_of(i1, i2) : NULL;
    double *h2 = i2 < nlocal ? slot_of(i2, i1) : NULL;
    double *hist = h1 ? h1 : h2;
    if (!hist) error->one(FLERR, "bond_style bpm/yarn: a bond without its history slot");
    if (!(hist[yarn::R0] > 0.0)) {    // first seen: its rest length (the type's r0, else now)
      const double d[3] = {x[i2][0] - x[i1][0], x[i2][1] - x[i1][1], x[i2][2] - x[i1][2]};
      hist[yarn::R0] = coeffs[type].rest_length(sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
      for (int k = 1; k < yarn::NHISTORY; k++) hist[k] = 0.0;
    }
    yarn::Result o;
    yarn::compute(coeffs[type].p, bond_state(i1, i2), hist, update_history, o);
    if (h1 && h2) memcpy(h2, h1, sizeof(double) * yarn::NHISTORY);
    if (o.broken) {
      // the bond's type 0 on each local end (the other rank does the same for its end)
      for (int e = 0; e < 2; e++) {
        const int own = e ? i2 : i1, other = e ? i1 : i2;
        const int m = own < nlocal ? bond_index(own, other) : -1;
        if (m >= 0) atom->bond_type[own][m] = 0;
      }
      bondlist[n][2] = 0;
      if (i1 < nlocal) nbroken++;
      continue;
    }
    if (i1 < nlocal)
      for (int k = 0; k < 3; k++) f[i1][k] += o.f[k], torque[i1][k] += o.ti[k];
    if (i2 < nlocal)
      for (int k = 0; k < 3; k++) f[i2][k] -= o.f[k], torque[i2][k] += o.tj[k];
    if (evflag) {
      // the axial part as a central force (the virial of the shear force is left out)
      const double ebond = eflag ? yarn::axial_energy(coeffs[type].p, o.eps, hist[yarn::R0]) : 0.0;
      ev_tally(i1, i2, nlocal, 0, ebond, o.r > 0.0 ? -o.fax / o.r : 0.0, x[i1][0] - x[i2][0],
               x[i1][1] - x[i2][1], x[i1][2] - x[i2][2]);
    }
  }
}

double BondBPMYarn::equilibrium_distance(int)
{
  return 0.0;    // the rest length is per bond (its first length)
}

void BondBPMYarn::write_restart(FILE *fp)
{
  for (int t = 1; t <= atom->nbondtypes; t++) write_yarn_coeff(fp, coeffs[t]);
}

void BondBPMYarn::read_restart(FILE *fp)
{
  allocate();
  for (int t = 1; t <= atom->nbondtypes; t++) {
    read_yarn_coeff(lmp, fp, coeffs[t]);
    setflag[t] = coeffs[t].set ? 1 : 0;
  }
}

// single(): the axial spring's energy; fforce along the bond (tension < 0: F = fforce * del)
double BondBPMYarn::single(int type, double, int i, int j, double &fforce)
{
  fforce = 0.0;
  if (type <= 0 || !history) return 0.0;
  if (atom->tag[j] < atom->tag[i]) std::swap(i, j);
  double *h = i < atom->nlocal ? slot_of(i, j) : (j < atom->nlocal ? slot_of(j, i) : NULL);
  if (!h || !(h[yarn::R0] > 0.0)) return 0.0;
  double hist[yarn::NHISTORY];
  memcpy(hist, h, sizeof(hist));
  yarn::Result o;
  yarn::compute(coeffs[type].p, bond_state(i, j), hist, false, o);
  fforce = o.r > 0.0 ? -o.fax / o.r : 0.0;
  return yarn::axial_energy(coeffs[type].p, o.eps, hist[yarn::R0]);
}

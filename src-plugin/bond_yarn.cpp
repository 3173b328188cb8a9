/* ----------------------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   bond_style yarn: adapter of the axial yarn law (law/yarn_law.h) for plain bonds.
------------------------------------------------------------------------- */

#include "bond_yarn.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "neighbor.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
namespace yarn = tbags::yarn;

static const char *STYLE = "Bond style yarn";

BondYarn::BondYarn(LAMMPS *lmp) : Bond(lmp)
{
  writedata = 1;
  // a broken bond is turned off (negative type, as delete_bonds does), so the style keeps the
  // default topology settings and mixes with any other style in bond_style hybrid
  single_extra = 2;    // b1 strain, b2 axial force
  svector = new double[single_extra];
}

BondYarn::~BondYarn()
{
  delete[] svector;
  if (allocated) memory->destroy(setflag);
}

void BondYarn::allocate()
{
  allocated = 1;
  const int n = atom->nbondtypes;
  memory->create(setflag, n + 1, "bond:setflag");
  for (int i = 0; i <= n; i++) setflag[i] = 0;
  coeffs.clear();
  coeffs.resize(n + 1);
}

// bond_coeff T table FILE KEYWORD diameter D r0 R0 [break EPS] [damping GN]
void BondYarn::coeff(int narg, char **arg)
{
  if (!allocated) allocate();
  int ilo, ihi;
  utils::bounds(FLERR, arg[0], 1, atom->nbondtypes, ilo, ihi, error);
  YarnCoeff c;
  parse_yarn_coeff(lmp, STYLE, narg, arg, c, true);
  for (int i = ilo; i <= ihi; i++) {
    coeffs[i] = c;
    setflag[i] = 1;
  }
}

void BondYarn::init_style()
{
  for (int i = 1; i <= atom->nbondtypes; i++)
    if (setflag[i] && coeffs[i].p.gn > 0.0 && comm->ghost_velocity == 0)
      error->all(FLERR, "{}: damping needs ghost velocities: add 'comm_modify vel yes'", STYLE);
}

double BondYarn::equilibrium_distance(int i)
{
  return coeffs[i].r0;
}

double BondYarn::axial(int type, double r, double vn, double &eps) const
{
  const yarn::Params &p = coeffs[type].p;
  eps = yarn::strain(r, coeffs[type].r0);
  double emax = 0.0;
  return yarn::axial_damped(p, yarn::axial_force(p, eps, &emax, false), eps, vn);
}

/* ---------------------------------------------------------------------- */

void BondYarn::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  int **bondlist = neighbor->bondlist;
  const int nbondlist = neighbor->nbondlist;
  const int nlocal = atom->nlocal;
  const int newton_bond = force->newton_bond;

  for (int n = 0; n < nbondlist; n++) {
    const int i1 = bondlist[n][0], i2 = bondlist[n][1], type = bondlist[n][2];
    if (type <= 0) continue;
    const double del[3] = {x[i1][0] - x[i2][0], x[i1][1] - x[i2][1], x[i1][2] - x[i2][2]};
    const double r = sqrt(del[0] * del[0] + del[1] * del[1] + del[2] * del[2]);
    // rate of stretching: relative velocity of 2 from 1 along the bond
    const double vn = -((v[i1][0] - v[i2][0]) * del[0] + (v[i1][1] - v[i2][1]) * del[1] +
                        (v[i1][2] - v[i2][2]) * del[2]) / r;
    double eps;
    const double fax = axial(type, r, vn, eps);
    if (yarn::breaks(coeffs[type].p, eps)) {
      // turn the bond off where it is stored (both copies with newton_bond off)
      bondlist[n][2] = -type;
      for (int i : {i1, i2}) {
        if (i >= nlocal) continue;
        const tagint other = atom->tag[i == i1 ? i2 : i1];
        for (int m = 0; m < atom->num_bond[i]; m++)
          if (atom->bond_atom[i][m] == other && atom->bond_type[i][m] == type)
            atom->bond_type[i][m] = -type;
      }
      continue;
    }
    const double fbond = -fax / r;    // LAMMPS convention: F on 1 = fbond * del
    if (newton_bond || i1 < nlocal)
      for (int k = 0; k < 3; k++) f[i1][k] += del[k] * fbond;
    if (newton_bond || i2 < nlocal)
      for (int k = 0; k < 3; k++) f[i2][k] -= del[k] * fbond;
    if (evflag) {
      const double ebond = eflag ? yarn::axial_energy(coeffs[type].p, eps, coeffs[type].r0) : 0.0;
      ev_tally(i1, i2, nlocal, newton_bond, ebond, fbond, del[0], del[1], del[2]);
    }
  }
}

double BondYarn::single(int type, double rsq, int, int, double &fforce)
{
  fforce = svector[0] = svector[1] = 0.0;
  if (type <= 0) return 0.0;    // broken (turned off) bond
  const double r = sqrt(rsq);
  double eps;
  const double fax = axial(type, r, 0.0, eps);
  fforce = -fax / r;
  svector[0] = eps;
  svector[1] = fax;
  return yarn::axial_energy(coeffs[type].p, eps, coeffs[type].r0);
}

/* ---------------------------------------------------------------------- */

void BondYarn::write_restart(FILE *fp)
{
  for (int i = 1; i <= atom->nbondtypes; i++) {
    write_yarn_coeff(fp, coeffs[i]);    // r0 included
  }
}

void BondYarn::read_restart(FILE *fp)
{
  allocate();
  for (int i = 1; i <= atom->nbondtypes; i++) {
    read_yarn_coeff(lmp, fp, coeffs[i]);
    setflag[i] = coeffs[i].set ? 1 : 0;
  }
}

void BondYarn::write_data(FILE *fp)
{
  for (int i = 1; i <= atom->nbondtypes; i++) {
    const YarnCoeff &c = coeffs[i];
    utils::print(fp, "{} table {} {} diameter {:.17g} r0 {:.17g} break {:.17g} damping {:.17g}\n", i,
                 c.file, c.keyword, c.p.d, c.r0, c.p.eps_break, c.p.gn);
  }
}

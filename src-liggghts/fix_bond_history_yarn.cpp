/* T-BAGS DEM toolkit, LIGGGHTS adapter: per-bond history of the yarn bonds (see the header).
   Arguments (written by bond_style bpm/yarn): ID all bond/history/yarn NSLOT NHIST */

#include "fix_bond_history_yarn.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "memory.h"

#include <cstring>

using namespace LAMMPS_NS;

FixBondHistoryYarn::FixBondHistoryYarn(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), hist(NULL)
{
  if (narg != 5) error->all(FLERR, "fix bond/history/yarn is created by bond_style bpm/yarn, not by hand");
  nslot = force->inumeric(FLERR, arg[3]);
  nhist = force->inumeric(FLERR, arg[4]);
  if (nslot < 1 || nhist < 1) error->all(FLERR, "fix bond/history/yarn: bad sizes");
  restart_peratom = 1;
  grow_arrays(atom->nmax);
  atom->add_callback(0);
  atom->add_callback(1);
  for (int i = 0; i < atom->nmax; i++) memset(hist[i], 0, sizeof(double) * nslot * nhist);
}

FixBondHistoryYarn::~FixBondHistoryYarn()
{
  atom->delete_callback(id, 0);
  atom->delete_callback(id, 1);
  memory->destroy(hist);
}

void FixBondHistoryYarn::grow_arrays(int nmax)
{
  memory->grow(hist, nmax, nslot * nhist, "bond/history/yarn:hist");
}

void FixBondHistoryYarn::copy_arrays(int i, int j, int)
{
  memcpy(hist[j], hist[i], sizeof(double) * nslot * nhist);
}

int FixBondHistoryYarn::pack_exchange(int i, double *buf)
{
  memcpy(buf, hist[i], sizeof(double) * nslot * nhist);
  return nslot * nhist;
}

int FixBondHistoryYarn::unpack_exchange(int nlocal, double *buf)
{
  memcpy(hist[nlocal], buf, sizeof(double) * nslot * nhist);
  return nslot * nhist;
}

// restart: the count first (LAMMPS's convention for per-atom restart data), then the values
int FixBondHistoryYarn::pack_restart(int i, double *buf)
{
  buf[0] = nslot * nhist + 1;
  memcpy(buf + 1, hist[i], sizeof(double) * nslot * nhist);
  return nslot * nhist + 1;
}

void FixBondHistoryYarn::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  if (static_cast<int>(extra[nlocal][m]) != nslot * nhist + 1)
    error->one(FLERR, "bond_style bpm/yarn: the restart file's bond history has another size "
               "(bond slots per atom changed)");
  memcpy(hist[nlocal], &extra[nlocal][m + 1], sizeof(double) * nslot * nhist);
}

int FixBondHistoryYarn::size_restart(int)
{
  return nslot * nhist + 1;
}

int FixBondHistoryYarn::maxsize_restart()
{
  return nslot * nhist + 1;
}

double FixBondHistoryYarn::memory_usage()
{
  return (double) atom->nmax * nslot * nhist * sizeof(double);
}

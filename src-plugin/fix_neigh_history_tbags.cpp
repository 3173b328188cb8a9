/* ----------------------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   fix NEIGH_HISTORY/TBAGS: see the header
------------------------------------------------------------------------- */

#include "fix_neigh_history_tbags.h"

#include "comm.h"
#include "update.h"

#include <cstdio>

using namespace LAMMPS_NS;

void FixNeighHistoryTbags::write_restart(FILE *fp)
{
  // during a run or minimization (restart command): copy the list's history to the atoms;
  // between runs they hold it already and the list may name other ghost atoms by now
  if (update->whichflag != 0) pre_exchange();
  if (comm->me == 0) {
    int size = 0;
    fwrite(&size, sizeof(int), 1, fp);
  }
}

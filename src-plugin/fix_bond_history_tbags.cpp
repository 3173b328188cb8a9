/* ----------------------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   fix BOND_HISTORY/TBAGS: see the header
------------------------------------------------------------------------- */

#include "fix_bond_history_tbags.h"

#include "update.h"
#include "utils.h"

using namespace LAMMPS_NS;

FixBondHistoryTbags::FixBondHistoryTbags(LAMMPS *lmp, int narg, char **arg) :
    FixBondHistory(lmp, narg, arg)
{
  delete[] style;
  style = utils::strdup("BOND_HISTORY");
}

// a run starts with the bond list current (just built, or kept by 'run ... pre no'): the next
// reneighboring copies the history to the atoms before they move
void FixBondHistoryTbags::setup(int)
{
  updated_bond_flag = 1;
}

void FixBondHistoryTbags::min_setup(int)
{
  updated_bond_flag = 1;
}

// the end of a run: the atoms carry the current history; the flag is cleared, so nothing
// between runs (write_restart, the next setup) copies from a list that may be stale by then
void FixBondHistoryTbags::post_run()
{
  pre_exchange();
}

void FixBondHistoryTbags::write_restart(FILE *fp)
{
  const int during_run = update->whichflag != 0;
  FixBondHistory::write_restart(fp);    // copies to the atoms if the flag is set, clears it
  // during a run the list stays the run's: the next reneighboring must copy again
  if (during_run) updated_bond_flag = 1;
}

/* -*- c++ -*- ----------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   fix NEIGH_HISTORY/TBAGS: the contact history store of pair gran/hertz/rolling (internal,
   created by the pair). LAMMPS's fix NEIGH_HISTORY with one change: a write_restart command
   between runs keeps the history that the end of the run stored with the atoms.

   Why: the write_restart command wraps atoms into the box and rebuilds the ghost atoms
   (domain->pbc(), comm->exchange(), comm->borders()) before the fixes write their restart
   data, and FixNeighHistory::write_restart() then copies the history from the neighbor list
   to the atoms again (pre_exchange()). That list is the run's: its ghost indices now name other
   atoms whenever an atom left the box since the last reneighboring, and the contacts across a
   periodic boundary lose their history (the run after the write_restart differs from the same
   run without it). Between runs the atoms already carry the current history (post_run() stored
   it), so it is not copied again; during a run (the restart command) the list is current and
   the copy is made as before.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_NEIGH_HISTORY_TBAGS_H
#define LMP_FIX_NEIGH_HISTORY_TBAGS_H

#include "fix_neigh_history.h"

namespace LAMMPS_NS {

class FixNeighHistoryTbags : public FixNeighHistory {
 public:
  FixNeighHistoryTbags(class LAMMPS *lmp, int narg, char **arg) :
      FixNeighHistory(lmp, narg, arg)
  {
  }
  void write_restart(FILE *) override;
};

}    // namespace LAMMPS_NS

#endif

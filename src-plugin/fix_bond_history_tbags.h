/* -*- c++ -*- ----------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   fix BOND_HISTORY/TBAGS: the bond history store of bond_style bpm/yarn (internal, created by
   the bond style). LAMMPS's fix BOND_HISTORY with two changes, so that a checkpoint leaves the
   run as it was:

   - During a run (the restart command), LAMMPS's write_restart() copies the bonds' history to
     the atoms (pre_exchange()), which also clears the flag that tells the next reneighboring to
     copy it again. That copy was then skipped, and post_neighbor() reloaded every bond's history
     as it was at the checkpoint: the shear springs, moments and largest strain of the steps in
     between were lost, once after each checkpoint. Here the flag is kept.
   - Between runs, the write_restart command has moved the atoms between ranks and rebuilt the
     ghosts before it writes, so the run's bond list no longer names the right atoms. Here the
     end of each run stores the history with the atoms (post_run()), and the write_restart
     command does not copy it again (as the pair's NEIGH_HISTORY/TBAGS).

   The fix answers to LAMMPS's style name, BOND_HISTORY, in restart files and style searches
   (delete_bonds, delete_atoms and BondBPM find every bond history store by it): restart files
   written before and after this fix read both ways.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_BOND_HISTORY_TBAGS_H
#define LMP_FIX_BOND_HISTORY_TBAGS_H

#include "fix_bond_history.h"

namespace LAMMPS_NS {

class FixBondHistoryTbags : public FixBondHistory {
 public:
  FixBondHistoryTbags(class LAMMPS *, int, char **);
  void setup(int) override;
  void min_setup(int) override;
  void post_run() override;
  void write_restart(FILE *) override;
};

}    // namespace LAMMPS_NS

#endif

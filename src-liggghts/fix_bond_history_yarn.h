/* -*- c++ -*- T-BAGS DEM toolkit, LIGGGHTS adapter: the yarn bonds' history (law/yarn_law.h:
   r0, largest strain, shear force, bending and twisting moments), NHISTORY doubles per bond
   slot of each atom, moved with the atom between ranks and written to restart files. Created
   by bond_style bpm/yarn (ID tbags_yarn_history); not a user command. With newton_bond off
   both ends of a bond hold a copy; the rank of each end updates its own. */
#ifdef FIX_CLASS
FixStyle(bond/history/yarn,FixBondHistoryYarn)
#else
#ifndef LMP_FIX_BOND_HISTORY_YARN_H
#define LMP_FIX_BOND_HISTORY_YARN_H

#include "fix.h"

namespace LAMMPS_NS {

class FixBondHistoryYarn : public Fix {
 public:
  FixBondHistoryYarn(class LAMMPS *, int, char **);
  ~FixBondHistoryYarn();
  int setmask() { return 0; }
  double *slot(int i, int m) { return hist[i] + m * nhist; }
  int slots() const { return nslot; }

  void grow_arrays(int);
  void copy_arrays(int, int, int);
  int pack_exchange(int, double *);
  int unpack_exchange(int, double *);
  int pack_restart(int, double *);
  void unpack_restart(int, int);
  int size_restart(int);
  int maxsize_restart();
  double memory_usage();

 private:
  int nslot, nhist;     // bond slots per atom (bond_per_atom), doubles per bond
  double **hist;        // per atom: nslot x nhist
};

}    // namespace LAMMPS_NS
#endif
#endif

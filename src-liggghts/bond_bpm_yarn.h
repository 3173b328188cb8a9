/* -*- c++ -*- T-BAGS DEM toolkit, LIGGGHTS adapter: bond_style bpm/yarn, the yarn bond of
   law/yarn_law.h (tension-only table, bending, twisting, breaking) for LIGGGHTS, with the same
   bond_coeff line as the LAMMPS plugin's bpm/yarn (yarn_table.cpp parses both):
     bond_style bpm/yarn
     bond_coeff T table FILE KEYWORD diameter D poisson NU [E E] [shear KAPPA] [break EPS]
                [damping GN GS GR] [unload elastic|plastic]
   Needs spheres that carry bonds (atom_style hybrid granular molecular), newton_bond off (each
   rank computes the bonds of its atoms; both ends keep the history, fix bond/history/yarn) and
   the rotations integrated (fix nve/sphere). A bond's rest length is its length when first
   computed; a broken bond gets type 0 on both ends and is skipped. */
#ifdef BOND_CLASS
BondStyle(bpm/yarn,BondBPMYarn)
#else
#ifndef LMP_BOND_BPM_YARN_LIGGGHTS_H
#define LMP_BOND_BPM_YARN_LIGGGHTS_H

#include "bond.h"
#include "law/yarn_chain.h"
#include "yarn_table.h"

#include <vector>

namespace LAMMPS_NS {

class BondBPMYarn : public Bond {
 public:
  BondBPMYarn(class LAMMPS *);
  ~BondBPMYarn();
  void compute(int, int);
  void coeff(int, char **);
  void init_style();
  double equilibrium_distance(int);
  void write_restart(FILE *);
  void read_restart(FILE *);
  double single(int, double, int, int, double &);

  int broken() const { return nbroken; }    // bonds broken on this rank so far

 private:
  std::vector<YarnCoeff> coeffs;    // per bond type
  class FixBondHistoryYarn *history;
  int nbroken;
  void allocate();
  int bond_index(int own, int other) const;
  double *slot_of(int own, int other);
  tbags::yarn::Bond bond_state(int i, int j) const;
  void make_history();
};

}    // namespace LAMMPS_NS
#endif
#endif

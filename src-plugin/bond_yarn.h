/* -*- c++ -*- ----------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   bond_style yarn: the axial, tension-only yarn law (law/yarn_law.h) for any atom style with
   bonds (fibres, cloth, nets), usable in bond_style hybrid, with single() and bond_write.
------------------------------------------------------------------------- */

#ifndef LMP_BOND_YARN_H
#define LMP_BOND_YARN_H

#include "bond.h"
#include "yarn_table.h"

#include <vector>

namespace LAMMPS_NS {

class BondYarn : public Bond {
 public:
  BondYarn(class LAMMPS *);
  ~BondYarn() override;
  void compute(int, int) override;
  void coeff(int, char **) override;
  void init_style() override;
  double equilibrium_distance(int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_data(FILE *) override;
  double single(int, double, int, int, double &) override;

 protected:
  std::vector<YarnCoeff> coeffs;
  void allocate();
  // axial force (tension positive) and strain of a bond of the given type and length
  double axial(int type, double r, double vn, double &eps) const;
};

}    // namespace LAMMPS_NS

#endif

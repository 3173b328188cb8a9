/* -*- c++ -*- T-BAGS DEM toolkit: reading yarn strain-stress tables (LAMMPS table-file format)
   and the bond_coeff keywords shared by bond_style bpm/yarn and bond_style yarn. */
#ifndef LMP_TBAGS_YARN_TABLE_H
#define LMP_TBAGS_YARN_TABLE_H

#include "law/yarn_law.h"
#include "pointers.h"

#include <memory>
#include <string>

namespace LAMMPS_NS {

// one bond type's yarn coefficients: the curve and the law's parameters
struct YarnCoeff {
  std::string file, keyword;
  // the curve is shared by the copies of a coefficient set (one bond_coeff line for a range of
  // types), so that p.curve stays valid when the set is copied or its vector grows
  std::shared_ptr<tbags::yarn::Curve> curve = std::make_shared<tbags::yarn::Curve>();
  tbags::yarn::Params p;    // p.curve points at *curve
  double r0 = -1.0;    // rest length of every bond of the type (m); <= 0: its length when first seen
  bool set = false;

  YarnCoeff() { p.curve = curve.get(); }
  // a bond's rest length, given its length 'now' when first seen: the type's r0 if set
  double rest_length(double now) const { return r0 > 0.0 ? r0 : now; }
};

// Parse 'bond_coeff T table FILE KEYWORD diameter D poisson NU [E E] [shear KAPPA]
// [break EPS] [damping GN GS GR] [unload elastic|plastic] [r0 R0]' from arg[1..]; 'style' names
// the bond style in messages. axial_only (bond_style yarn): the axial law only, 'r0 R0'
// required, 'damping GN' (axial) and no bending, shear, twisting or plastic keywords.
void parse_yarn_coeff(LAMMPS *lmp, const char *style, int narg, char **arg, YarnCoeff &c,
                      bool axial_only = false);

// Read the section KEYWORD of a yarn table file:
//   KEYWORD
//   N n [FORCE]        (FORCE: second column in N instead of Pa)
//   (blank line)
//   1 strain stress
//   ...
void read_yarn_table(LAMMPS *lmp, const char *style, const std::string &file,
                     const std::string &keyword, tbags::yarn::Curve &curve, bool &force_table);

// restart I/O of one YarnCoeff (proc 0 writes; all read through a broadcast)
void write_yarn_coeff(FILE *fp, const YarnCoeff &c);
void read_yarn_coeff(LAMMPS *lmp, FILE *fp, YarnCoeff &c);

}    // namespace LAMMPS_NS
#endif

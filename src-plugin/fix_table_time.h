/* ----------------------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   fix table/time: a value tabulated against time in a file (e.g. a displacement history),
   interpolated at every step for equal-style variables (doc/fix_table_time.rst).
------------------------------------------------------------------------- */
#ifdef FIX_CLASS
// clang-format off
FixStyle(table/time,FixTableTime);
// clang-format on
#else

#ifndef LMP_FIX_TABLE_TIME_H
#define LMP_FIX_TABLE_TIME_H

#include "fix.h"
#include "law/time_table.h"

#include <string>

namespace LAMMPS_NS {

class FixTableTime : public Fix {
 public:
  FixTableTime(class LAMMPS *, int, char **);
  int setmask() override;
  double compute_scalar() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

 private:
  tbags::TimeTable table;
  std::string file;
  double scale = 1.0;
  bigint start = 0;      // the step at which the table's time is 0

  double value_at_step(bigint step) const;
  void read_table(double limit);
};

}    // namespace LAMMPS_NS

#endif
#endif

/* ----------------------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   fix table/time: the file's reading and checks, the value at a step, restart of its start.
   The table and its checks are in law/time_table.h.
------------------------------------------------------------------------- */

#include "fix_table_time.h"

#include "parse_words.h"

#include "comm.h"
#include "error.h"
#include "update.h"

#include <cmath>
#include <cstring>
#include <fstream>

using namespace LAMMPS_NS;
using namespace FixConst;

static constexpr int NVECTOR = 5;    // compute_vector's outputs

/* ----------------------------------------------------------------------
   fix ID group table/time FILE keyword value ...
     FILE: two columns per line, time (in time units, from 0, strictly increasing) and value;
           '#' comments and blank lines skipped
     scale S        values are multiplied by S (e.g. 0.001: a file in mm, a deck in m)
     limit L        refuse a table whose largest |value| (after scale) is beyond L (> 0; the
                    message gives both in the file's units)
     start N|next   the step at which the table's time is 0 (default next: the step after this
                    command; a restart of the fix keeps its own)
------------------------------------------------------------------------- */

FixTableTime::FixTableTime(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  if (narg < 4) error->all(FLERR, "fix table/time: needs a file: fix ID group table/time FILE [scale S] [limit L] [start N|next]");
  file = arg[3];
  double limit = 0.0;
  start = update->ntimestep + 1;
  for (int i = 4; i < narg; i += 2) {
    const std::string key = arg[i];
    if (i + 1 >= narg) error->all(FLERR, "fix table/time: keyword {} needs a value", key);
    if (key == "scale") {
      scale = utils::numeric(FLERR, arg[i + 1], false, lmp);
      if (!(scale != 0.0) || !std::isfinite(scale))
        error->all(FLERR, "fix table/time: scale must be a finite non-zero number (got {})", arg[i + 1]);
    } else if (key == "limit") {
      limit = utils::numeric(FLERR, arg[i + 1], false, lmp);
      if (!(limit > 0.0)) error->all(FLERR, "fix table/time: limit must be > 0 (got {})", arg[i + 1]);
    } else if (key == "start") {
      if (strcmp(arg[i + 1], "next") != 0) {
        start = utils::bnumeric(FLERR, arg[i + 1], false, lmp);
        if (start < 0) error->all(FLERR, "fix table/time: start must be a step >= 0 or next (got {})", arg[i + 1]);
      }
    } else {
      error->all(FLERR, "fix table/time: unknown keyword {} (scale, limit, start)", key);
    }
  }
  read_table(limit);

  scalar_flag = 1;
  vector_flag = 1;
  size_vector = NVECTOR;
  global_freq = 1;
  extscalar = 0;
  extvector = 0;
  restart_global = 1;
  if (comm->me == 0)
    utils::logmesg(lmp, "Fix table/time {}: {} rows from {}, time 0 to {}, largest |value| {} (scale {}); time 0 at step {}\n",
                   id, table.t.size(), file, table.duration(), scale * table.largest(), scale, start);
}

// rank 0 reads and checks the file; every rank gets the table
void FixTableTime::read_table(double limit)
{
  std::string what;
  int line_no = 0;
  if (comm->me == 0) {
    std::ifstream in(file);
    if (!in) {
      what = "the file is missing or unreadable";
    } else {
      std::string line;
      while (what.empty() && std::getline(in, line)) {
        line_no++;
        const auto w = tbags::words(line);
        if (w.empty()) continue;
        what = tbags::add_time_row(table, w, tbags::to_number);
      }
      if (what.empty()) {
        line_no = 0;
        what = tbags::check_time_table(table, limit > 0.0 ? limit / std::fabs(scale) : 0.0);
      }
    }
  }
  // every rank stops with rank 0's reason
  int n = (int) what.size();
  MPI_Bcast(&n, 1, MPI_INT, 0, world);
  if (n) {
    what.resize(n);
    MPI_Bcast(&what[0], n, MPI_CHAR, 0, world);
    MPI_Bcast(&line_no, 1, MPI_INT, 0, world);
    const std::string where = line_no ? fmt::format(" line {}", line_no) : std::string();
    error->all(FLERR, "fix table/time: {}{}: {}", file, where, what);
  }
  int rows = (int) table.t.size();
  MPI_Bcast(&rows, 1, MPI_INT, 0, world);
  table.t.resize(rows);
  table.y.resize(rows);
  MPI_Bcast(table.t.data(), rows, MPI_DOUBLE, 0, world);
  MPI_Bcast(table.y.data(), rows, MPI_DOUBLE, 0, world);
}

int FixTableTime::setmask()
{
  return 0;
}

double FixTableTime::value_at_step(bigint step) const
{
  return scale * table.at((double) (step - start) * update->dt);
}

// the value at the current step
double FixTableTime::compute_scalar()
{
  return value_at_step(update->ntimestep);
}

// 1 the value at the current step, 2 at the next step, 3 the table's last time, 4 its largest
// |value|, 5 the step at which its time is 0
double FixTableTime::compute_vector(int i)
{
  switch (i) {
    case 0: return value_at_step(update->ntimestep);
    case 1: return value_at_step(update->ntimestep + 1);
    case 2: return table.duration();
    case 3: return scale * table.largest();
    default: return (double) start;
  }
}

void FixTableTime::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    double list[1] = {(double) start};
    int size = sizeof(list);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), 1, fp);
  }
}

// a restarted fix of the same ID keeps the start of the run that wrote the restart
void FixTableTime::restart(char *buf)
{
  start = (bigint) ((double *) buf)[0];
}

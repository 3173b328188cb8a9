/* T-BAGS DEM toolkit: a value tabulated against time (fix table/time): parsing and checks of the
   file's lines, the value at a time (pure, unit-tested). */
#ifndef TBAGS_LAW_TIME_TABLE_H
#define TBAGS_LAW_TIME_TABLE_H

#include "piecewise.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace tbags {

struct TimeTable {
  std::vector<double> t, y;

  // linear between the points; the first value before the first time, the last after the last
  double at(double time) const { return piecewise_linear(t, y, std::min(time, t.back())); }
  double duration() const { return t.back(); }
  double largest() const
  {
    double m = 0.0;
    for (double v : y) m = std::max(m, std::fabs(v));
    return m;
  }
};

// adds a line's words (time and value; '#' comments and blank lines are skipped by the caller)
// to the table; returns "" or what is wrong with the line
inline std::string add_time_row(TimeTable &tab, const std::vector<std::string> &w,
                                bool (*number)(const char *, double &))
{
  if (w.size() != 2)
    return "needs two columns, time and value (found " + std::to_string(w.size()) + ")";
  double t, y;
  if (!number(w[0].c_str(), t)) return "time '" + w[0] + "' is not a finite number";
  if (!number(w[1].c_str(), y)) return "value '" + w[1] + "' is not a finite number";
  if (tab.t.empty() && t != 0.0) return "the first time must be 0 (got " + w[0] + ")";
  if (!tab.t.empty() && !(t > tab.t.back()))
    return "time " + w[0] + " does not increase (the row before is at " +
        std::to_string(tab.t.back()) + ")";
  tab.t.push_back(t);
  tab.y.push_back(y);
  return "";
}

// the whole table: "" or what is wrong with it
inline std::string check_time_table(const TimeTable &tab, double limit)
{
  if (tab.t.size() < 2) return "needs at least two rows";
  if (limit > 0.0 && tab.largest() > limit)
    return "its largest |value| " + std::to_string(tab.largest()) + " is beyond the limit " +
        std::to_string(limit);
  return "";
}

}    // namespace tbags

#endif

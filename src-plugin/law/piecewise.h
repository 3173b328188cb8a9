/* T-BAGS DEM toolkit: a piecewise-linear function of tabulated points (pure, unit-tested).
   Used by the yarn's force-strain curve (yarn_law.h) and fix table/time's history (time_table.h). */
#ifndef TBAGS_LAW_PIECEWISE_H
#define TBAGS_LAW_PIECEWISE_H

#include <algorithm>
#include <cstddef>
#include <vector>

namespace tbags {

// y(x) through the points (xs[k], ys[k]), xs strictly increasing, at least 2 points: ys[0] at and
// before xs[0]; beyond the last point the last segment is extended
inline double piecewise_linear(const std::vector<double> &xs, const std::vector<double> &ys, double x)
{
  if (x <= xs.front()) return ys.front();
  const std::size_t n = xs.size();
  std::size_t k = std::upper_bound(xs.begin(), xs.end(), x) - xs.begin();
  if (k >= n) k = n - 1;
  const double t = (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
  return ys[k - 1] + t * (ys[k] - ys[k - 1]);
}

}    // namespace tbags

#endif

// Fixtures of the yarn law's unit tests: a tape-like curve and the bond constants around it.
#ifndef TBAGS_TEST_YARN_FIXTURES_H
#define TBAGS_TEST_YARN_FIXTURES_H

#include "law/yarn_law.h"

namespace yarn_fixtures {

// sigma = E0 eps (1 - a eps), E0 = 3.2 GPa, a = 1.953125, sampled every 0.01 to 0.16
inline tbags::yarn::Curve tape()
{
  tbags::yarn::Curve c;
  for (int k = 0; k <= 16; k++) {
    const double e = 0.01 * k;
    c.eps.push_back(e);
    c.val.push_back(3.2e9 * e * (1 - 1.953125 * e));
  }
  return c;
}

// a 1 mm yarn of that curve: E its initial modulus, nu 0.3, kappa 0.9, breaking at 16 %
inline tbags::yarn::Params yarn(const tbags::yarn::Curve &c)
{
  tbags::yarn::Params p;
  p.curve = &c;
  p.d = 1e-3;
  p.E = c.slope0();
  p.nu = 0.3;
  p.kappa = 0.9;
  p.eps_break = 0.16;
  return p;
}

}    // namespace yarn_fixtures
#endif

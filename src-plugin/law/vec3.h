/* T-BAGS DEM toolkit: small inline 3-vector helpers shared by the laws (no LAMMPS types). */
#ifndef TBAGS_LAW_VEC3_H
#define TBAGS_LAW_VEC3_H

#include <cmath>

namespace tbags {
namespace vec {

inline double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double len(const double *a) { return std::sqrt(dot(a, a)); }
inline void scale(double s, double *a) { a[0] *= s; a[1] *= s; a[2] *= s; }
inline void copy(const double *a, double *b) { b[0] = a[0]; b[1] = a[1]; b[2] = a[2]; }
inline void zero(double *a) { a[0] = a[1] = a[2] = 0.0; }
inline void sub(const double *a, const double *b, double *c)
{
  c[0] = a[0] - b[0]; c[1] = a[1] - b[1]; c[2] = a[2] - b[2];
}
inline void cross(const double *a, const double *b, double *c)
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}
// Remove the component of a along the unit vector n and restore a's length
// (rotation of a history vector onto the current tangent plane).
inline void rotate_onto_plane(double *a, const double *n)
{
  const double an = dot(a, n);
  const double mag = len(a);
  a[0] -= an * n[0]; a[1] -= an * n[1]; a[2] -= an * n[2];
  const double prj = len(a);
  scale(prj > 0.0 ? mag / prj : 0.0, a);
}

}    // namespace vec
}    // namespace tbags
#endif

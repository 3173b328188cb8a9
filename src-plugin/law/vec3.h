/* T-BAGS DEM toolkit: small inline 3-vector helpers shared by the laws (no LAMMPS types). */
#ifndef TBAGS_LAW_VEC3_H
#define TBAGS_LAW_VEC3_H

#include <cmath>

// forced inlining of the laws' hot functions into their loops (values stay in registers), down to
// the vector helpers below: a large caller (a whole contact in LIGGGHTS's pair) otherwise
// exhausts GCC's inlining budget and calls each + - * dot out of line
#if defined(__GNUC__)
#define TBAGS_INLINE inline __attribute__((always_inline))
#else
#define TBAGS_INLINE inline
#endif

namespace tbags {
namespace vec {

TBAGS_INLINE double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
TBAGS_INLINE double len(const double *a) { return std::sqrt(dot(a, a)); }
TBAGS_INLINE void cross(const double *a, const double *b, double *c)
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

// 3-vector by value, for the branch-free contact kernel (the compiler keeps it in registers
// and can run the kernel over several contacts in SIMD lanes). Same operation order as above.
struct V3 {
  double x, y, z;
};
TBAGS_INLINE V3 load3(const double *a) { return V3{a[0], a[1], a[2]}; }
TBAGS_INLINE void store3(const V3 &a, double *b) { b[0] = a.x; b[1] = a.y; b[2] = a.z; }
TBAGS_INLINE V3 operator+(const V3 &a, const V3 &b) { return V3{a.x + b.x, a.y + b.y, a.z + b.z}; }
TBAGS_INLINE V3 operator-(const V3 &a, const V3 &b) { return V3{a.x - b.x, a.y - b.y, a.z - b.z}; }
TBAGS_INLINE V3 operator*(double s, const V3 &a) { return V3{s * a.x, s * a.y, s * a.z}; }
TBAGS_INLINE double dot(const V3 &a, const V3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
TBAGS_INLINE V3 cross(const V3 &a, const V3 &b)
{
  return V3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
TBAGS_INLINE V3 select(bool c, const V3 &a, const V3 &b)
{
  return V3{c ? a.x : b.x, c ? a.y : b.y, c ? a.z : b.z};
}
// Rotation of a history vector a onto the current tangent plane (unit normal n): remove the
// component along n and restore a's length, s b with b = a - (a.n) n and
// s = |a| / |b| = (1 - x)^(-1/2), x = (a.n)^2 / |a|^2.
// onto_plane_exact(): s = sqrt(|a|^2 / |b|^2), one square root and one division; 0 when
// nothing is left.
TBAGS_INLINE V3 onto_plane_exact(const V3 &a, const V3 &n)
{
  const double an = dot(a, n);
  const double mag2 = dot(a, a);
  const V3 b = a - an * n;
  const double prj2 = dot(b, b);
  const double s = prj2 > 0.0 ? std::sqrt(mag2 / prj2) : 0.0;
  return s * b;
}
// Below this tilt x the series 1 + x/2 + 3x^2/8 is s to round-off (the next term, 5/16 x^3,
// is under 3.2e-19 relative). A contact's normal turns by far less than this per time step.
constexpr double TILT_SERIES = 1e-6;
// onto_plane_series(): s by the series, one division and no square root; small: x is below
// TILT_SERIES (false for a = 0), i.e. the result is onto_plane()'s.
TBAGS_INLINE V3 onto_plane_series(const V3 &a, const V3 &n, bool &small)
{
  const double an = dot(a, n);
  const double x = an * an / dot(a, a);
  small = x < TILT_SERIES;
  return (1.0 + x * (0.5 + 0.375 * x)) * (a - an * n);
}
// onto_plane(): the series for a small tilt, else exact (forced inline: the bond law's lanes
// vectorise over it)
TBAGS_INLINE V3 onto_plane(const V3 &a, const V3 &n)
{
  bool small;
  const V3 b = onto_plane_series(a, n, small);
  return small ? b : onto_plane_exact(a, n);
}
// onto_plane() in place on a 3-array (the bond laws' history)
TBAGS_INLINE void rotate_onto_plane(double *a, const double *n) { store3(onto_plane(load3(a), load3(n)), a); }

}    // namespace vec
}    // namespace tbags
#endif

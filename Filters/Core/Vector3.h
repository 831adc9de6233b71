// MeshLOD core: the few operations on 3-vectors (double[3]) that the algorithms share.
#ifndef meshlod_Vector3_h
#define meshlod_Vector3_h

#include <cmath>

namespace meshlod
{
inline void Subtract(const double u[3], const double v[3], double out[3])
{
  out[0] = u[0] - v[0];
  out[1] = u[1] - v[1];
  out[2] = u[2] - v[2];
}

inline void Cross(const double u[3], const double v[3], double out[3])
{
  out[0] = u[1] * v[2] - u[2] * v[1];
  out[1] = u[2] * v[0] - u[0] * v[2];
  out[2] = u[0] * v[1] - u[1] * v[0];
}

inline double Dot(const double u[3], const double v[3])
{
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

inline double Distance2(const double u[3], const double v[3])
{
  double d[3];
  Subtract(u, v, d);
  return Dot(d, d);
}

// Normal (not normalised) of triangle (a, b, c): twice its area along its unit normal.
inline void Normal(const double a[3], const double b[3], const double c[3], double n[3])
{
  double u[3], v[3];
  Subtract(b, a, u);
  Subtract(c, a, v);
  Cross(u, v, n);
}

// A power of two near 1 / length^2 (1 for a length of 0). Squared lengths and areas of a mesh
// that long, times it, fit single precision whatever the mesh's size (in world units they
// overflow for a mesh 1e20 across and vanish for one 1e-20 across), and a power of two changes
// no rounding, so what is computed from them is the same at every scale.
inline double SquaredLengthUnit(double length)
{
  return length > 0.0 ? std::ldexp(1.0, -2 * std::ilogb(length)) : 1.0;
}
} // namespace meshlod

#endif

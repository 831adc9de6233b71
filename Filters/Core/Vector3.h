// MeshLOD core: the few operations on 3-vectors (double[3]) that the algorithms share.
#ifndef meshlod_Vector3_h
#define meshlod_Vector3_h

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
} // namespace meshlod

#endif

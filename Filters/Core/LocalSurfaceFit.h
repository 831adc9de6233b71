// Local least-squares quadratic height field over a triangle (Gieng et al., "Smooth
// Hierarchical Surface Triangulations", section 4).
//
// In a frame with origin c (the triangle's centroid), two orthonormal in-plane axes u, v and the
// unit normal n, each point p_j becomes (u_j, v_j, d_j); the fit is
//   f(u, v) = c20 u^2 + c11 u v + c02 v^2 + c10 u + c01 v + c00
// from the 6x6 normal equations. The collapse point is c + f(0, 0) n and the principal
// curvatures of the graph of f at (0, 0) give the curvature term of the triangle's weight.
#ifndef meshlod_LocalSurfaceFit_h
#define meshlod_LocalSurfaceFit_h

#include "vtkFiltersMeshLODModule.h"

namespace meshlod
{
struct VTKFILTERSMESHLOD_EXPORT SurfaceFitResult
{
  bool Valid = false;              // false when the normal equations are (nearly) singular
  double Height = 0.0;             // f(0, 0), in world units along the normal
  double AbsoluteCurvature = 0.0;  // |kappa1| + |kappa2| at (0, 0), in 1 / world units
  double Kappa1 = 0.0, Kappa2 = 0.0;
  /// The frame (origin, u and v axes, the given normal n) and f's coefficients in world units:
  /// f(u, v) = C[0] u^2 + C[1] u v + C[2] v^2 + C[3] u + C[4] v + C[5].
  double Origin[3] = { 0, 0, 0 };
  double U[3] = { 1, 0, 0 }, V[3] = { 0, 1, 0 }, N[3] = { 0, 0, 1 };
  double C[6] = { 0, 0, 0, 0, 0, 0 };
  /// x in the frame: (u, v) in the plane and d along the normal.
  void Frame(const double* x, double& u, double& v, double& d) const
  {
    // Summed in locals: written through the references at every step, the sums went to memory
    // and back (x may lie where they point).
    double su = 0.0, sv = 0.0, sd = 0.0;
    for (int i = 0; i < 3; ++i)
    {
      const double r = x[i] - this->Origin[i];
      su += r * this->U[i];
      sv += r * this->V[i];
      sd += r * this->N[i];
    }
    u = su;
    v = sv;
    d = sd;
  }
  double At(double u, double v) const
  {
    return this->C[0] * u * u + this->C[1] * u * v + this->C[2] * v * v + this->C[3] * u +
      this->C[4] * v + this->C[5];
  }
};

/// Fit f to `count` points (xyz triples). `scale` (e.g. the triangle's mean edge length) makes
/// the local coordinates of order one so that the normal equations stay well conditioned.
VTKFILTERSMESHLOD_EXPORT SurfaceFitResult FitQuadraticHeightField(const double origin[3],
  const double normal[3], const double* xyz, int count, double scale);

} // namespace meshlod

#endif

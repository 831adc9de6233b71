// Plane quadrics (Garland-Heckbert error metric) stored compactly, with a well-conditioned
// minimiser.
//
// Q(x) = sum_i w_i (n_i . x + d_i)^2 for planes n_i . x + d_i = 0 with unit normals. The ten
// distinct entries of the symmetric 4x4 matrix are kept, plus the total weight so that Q can be
// turned into an RMS distance: sqrt(Q(x) / Weight).
#ifndef meshlod_QuadricMetric_h
#define meshlod_QuadricMetric_h

#include "vtkFiltersMeshLODModule.h"

namespace meshlod
{
struct VTKFILTERSMESHLOD_EXPORT Quadric
{
  // Row-major upper triangle of the 4x4 matrix.
  double A00 = 0, A01 = 0, A02 = 0, A11 = 0, A12 = 0, A22 = 0; // n n^T
  double B0 = 0, B1 = 0, B2 = 0;                               // d n
  double C = 0;                                                // d^2
  double Weight = 0;

  /// The quadric of the plane through `point` with unit normal `normal`, times `weight`.
  static Quadric FromPlane(const double normal[3], const double point[3], double weight)
  {
    Quadric q;
    const double d = -(normal[0] * point[0] + normal[1] * point[1] + normal[2] * point[2]);
    q.A00 = weight * normal[0] * normal[0];
    q.A01 = weight * normal[0] * normal[1];
    q.A02 = weight * normal[0] * normal[2];
    q.A11 = weight * normal[1] * normal[1];
    q.A12 = weight * normal[1] * normal[2];
    q.A22 = weight * normal[2] * normal[2];
    q.B0 = weight * d * normal[0];
    q.B1 = weight * d * normal[1];
    q.B2 = weight * d * normal[2];
    q.C = weight * d * d;
    q.Weight = weight;
    return q;
  }

  Quadric& operator+=(const Quadric& o)
  {
    this->A00 += o.A00;
    this->A01 += o.A01;
    this->A02 += o.A02;
    this->A11 += o.A11;
    this->A12 += o.A12;
    this->A22 += o.A22;
    this->B0 += o.B0;
    this->B1 += o.B1;
    this->B2 += o.B2;
    this->C += o.C;
    this->Weight += o.Weight;
    return *this;
  }

  friend Quadric operator+(Quadric a, const Quadric& b) { return a += b; }

  /// Q(x), clamped at 0 against round-off.
  double Evaluate(const double x[3]) const
  {
    const double ax0 = this->A00 * x[0] + this->A01 * x[1] + this->A02 * x[2];
    const double ax1 = this->A01 * x[0] + this->A11 * x[1] + this->A12 * x[2];
    const double ax2 = this->A02 * x[0] + this->A12 * x[1] + this->A22 * x[2];
    const double value = x[0] * (ax0 + 2.0 * this->B0) + x[1] * (ax1 + 2.0 * this->B1) +
      x[2] * (ax2 + 2.0 * this->B2) + this->C;
    return value > 0.0 ? value : 0.0;
  }

  /// Root-mean-square distance to the planes, sqrt(Q(x) / Weight).
  double RmsDistance(const double x[3]) const;

  /// The point minimising Q, found in the well-determined directions only: the 3x3 part is
  /// decomposed into eigenvectors, and along directions whose eigenvalue is below
  /// `relativeTolerance` times the largest the point stays at `origin` (typically the centroid
  /// of the collapsing vertices). On a flat patch this keeps the point on the patch near the
  /// centroid instead of sliding along it; on a crease it slides only along the crease.
  void Minimize(const double origin[3], double result[3], double relativeTolerance = 1e-6) const;
};

} // namespace meshlod

#endif

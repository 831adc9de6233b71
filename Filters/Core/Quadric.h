// MeshLOD core: quadric error of a point against a set of weighted planes (Garland-Heckbert).
//
// A quadric is the symmetric 4x4 matrix Q = sum of w p p^T over planes p = (n, d) with |n| = 1,
// stored as ten numbers. For a point v, v^T Q v (v extended with 1) is the weighted sum of
// squared distances from v to the planes. The 3x3 block A = sum of w n n^T has trace = sum of
// weights, which gives the normalisation of a mean squared distance for free.
#ifndef meshlod_Quadric_h
#define meshlod_Quadric_h

#include "vtkFiltersMeshLODModule.h"

namespace meshlod
{
struct VTKFILTERSMESHLOD_EXPORT Quadric
{
  // A00 A01 A02 A11 A12 A22, then b = (B0 B1 B2) = sum of w d n, then C = sum of w d^2.
  double Q[10] = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };

  void Clear()
  {
    for (double& q : this->Q)
    {
      q = 0.0;
    }
  }
  void Add(const Quadric& other, double scale = 1.0)
  {
    for (int i = 0; i < 10; ++i)
    {
      this->Q[i] += scale * other.Q[i];
    }
  }
  Quadric& operator+=(const Quadric& other)
  {
    for (int i = 0; i < 10; ++i)
    {
      this->Q[i] += other.Q[i];
    }
    return *this;
  }
  friend Quadric operator+(Quadric a, const Quadric& b) { return a += b; }

  /// Add the plane through `point` with unit normal `n`, weighted by `weight`.
  void AddPlane(const double n[3], const double point[3], double weight);

  /// The quadric of one plane (see AddPlane).
  static Quadric FromPlane(const double n[3], const double point[3], double weight)
  {
    Quadric q;
    q.AddPlane(n, point, weight);
    return q;
  }

  /// The sum of the plane weights (trace of the 3x3 block).
  double Weight() const { return this->Q[0] + this->Q[3] + this->Q[5]; }

  /// v^T Q v: the weighted sum of squared distances (never negative after rounding). Inline:
  /// collapse costs evaluate it in their innermost loop.
  double Evaluate(const double v[3]) const
  {
    const double* q = this->Q;
    const double ax = q[0] * v[0] + q[1] * v[1] + q[2] * v[2];
    const double ay = q[1] * v[0] + q[3] * v[1] + q[4] * v[2];
    const double az = q[2] * v[0] + q[4] * v[1] + q[5] * v[2];
    const double value = v[0] * (ax + 2.0 * q[6]) + v[1] * (ay + 2.0 * q[7]) +
      v[2] * (az + 2.0 * q[8]) + q[9];
    return value > 0.0 ? value : 0.0;
  }

  /// Root-mean-square distance to the planes, sqrt(v^T Q v / Weight()); 0 without planes.
  double RmsDistance(const double v[3]) const;

  /// The minimiser found by one regularised 3x3 L D L^T solve, (A + eps I) y = -(A o + b) with
  /// eps = relativeTolerance * trace(A) and result o + y, refined twice on the same factors
  /// (see Quadric.cxx). Along eigenvectors whose eigenvalue is well above eps this is the exact
  /// minimiser (to rounding, also between nearly parallel planes); along (nearly) null
  /// directions the point stays near `origin` (typically the centroid of the collapsing
  /// vertices), so on a flat patch it does not slide along the patch and on a crease it slides
  /// only along the crease.
  /// It behaves like MinimizeQuadric's truncated pseudo-inverse at a fraction of the cost,
  /// which matters where every candidate collapse is costed.
  void MinimizeRegularized(const double origin[3],
    double result[3],
    double relativeTolerance = 1e-6) const;
};

/// The point minimising the quadric in its well-determined directions: starting from `centre`,
/// it moves only along eigenvectors of A whose eigenvalue exceeds `relativeTolerance` times the
/// largest one, and stays at `centre` along the others (a pseudo-inverse solve). A quadric of
/// zero weight gives `centre`. Returns the number of directions left out (0: the exact
/// minimiser, 3 for a quadric of zero weight).
VTKFILTERSMESHLOD_EXPORT int MinimizeQuadric(const Quadric& q,
  const double centre[3],
  double relativeTolerance,
  double result[3]);

/// Paper 002's placement of a collapse of `count` (2 or 3) points: the quadric's minimiser when
/// its 3x3 system is solvable (every eigenvalue of A above `relativeTolerance` times the
/// largest; returns true), otherwise the cheapest of the candidates the paper lists for a
/// triangle: the centroid, the points themselves and the midpoints of each pair (for an edge:
/// its midpoint and its two ends). Ties go to the first in that order.
VTKFILTERSMESHLOD_EXPORT bool PlaceByCandidates(const Quadric& q,
  const double* const* points,
  int count,
  double relativeTolerance,
  double result[3]);

/// Plane quadric of triangle (a, b, c), weighted by its area; zero for a degenerate triangle.
/// Also returns the triangle's (unnormalised) normal, twice its area in length, and with
/// `plane` its plane (unit normal and offset: n . x + d = 0), written only when the triangle is
/// not degenerate; returns false when it is.
VTKFILTERSMESHLOD_EXPORT bool TriangleQuadric(const double a[3],
  const double b[3],
  const double c[3],
  Quadric& q,
  double normal[3],
  double plane[4] = nullptr);

/// The unit normal of the plane through the boundary edge (a, b) perpendicular to its triangle
/// (whose normal is `faceNormal`, any length); false, and `unit` untouched, when degenerate.
VTKFILTERSMESHLOD_EXPORT bool BoundaryEdgePlane(const double a[3],
  const double b[3],
  const double faceNormal[3],
  double unit[3]);

/// Quadric of the plane through the boundary edge (a, b) perpendicular to its triangle (whose
/// normal is `faceNormal`, any length), weighted by `weight` times the edge length l times
/// `lengthScale`, or times l again when `lengthScale` is 0 (weight l^2: the edge's planes
/// together weigh in proportion to the boundary's length times the input's edge length).
VTKFILTERSMESHLOD_EXPORT void BoundaryEdgeQuadric(const double a[3],
  const double b[3],
  const double faceNormal[3],
  double weight,
  Quadric& q,
  double lengthScale = 0.0);

} // namespace meshlod

#endif

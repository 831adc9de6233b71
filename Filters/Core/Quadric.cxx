#include "Quadric.h"

#include "vtk_eigen.h"
#include VTK_EIGEN(Eigenvalues)

#include <algorithm>
#include <cmath>

namespace meshlod
{
//------------------------------------------------------------------------------
void Quadric::AddPlane(const double n[3], const double point[3], double weight)
{
  const double d = -(n[0] * point[0] + n[1] * point[1] + n[2] * point[2]);
  double* q = this->Q;
  q[0] += weight * n[0] * n[0];
  q[1] += weight * n[0] * n[1];
  q[2] += weight * n[0] * n[2];
  q[3] += weight * n[1] * n[1];
  q[4] += weight * n[1] * n[2];
  q[5] += weight * n[2] * n[2];
  q[6] += weight * d * n[0];
  q[7] += weight * d * n[1];
  q[8] += weight * d * n[2];
  q[9] += weight * d * d;
}

//------------------------------------------------------------------------------
double Quadric::RmsDistance(const double v[3]) const
{
  const double weight = this->Weight();
  return weight > 0.0 ? std::sqrt(this->Evaluate(v) / weight) : 0.0;
}

//------------------------------------------------------------------------------
void Quadric::MinimizeRegularized(const double origin[3],
  double result[3],
  double relativeTolerance) const
{
  // With x = o + y the gradient A (o + y) + b = 0 gives A y = -(A o + b); A + eps I is
  // positive definite, so its L D L^T factorisation always exists.
  const double* q = this->Q;
  const double* o = origin;
  const double r0 = -(q[0] * o[0] + q[1] * o[1] + q[2] * o[2] + q[6]);
  const double r1 = -(q[1] * o[0] + q[3] * o[1] + q[4] * o[2] + q[7]);
  const double r2 = -(q[2] * o[0] + q[4] * o[1] + q[5] * o[2] + q[8]);
  const double trace = q[0] + q[3] + q[5];
  result[0] = o[0];
  result[1] = o[1];
  result[2] = o[2];
  if (!(trace > 0.0) || !std::isfinite(trace))
  {
    return;
  }
  const double eps = relativeTolerance * trace;
  // L D L^T of the regularised matrix (L unit lower triangular): the same factorisation as
  // Cholesky's without its three square roots, which sit on the critical path of every
  // candidate's solve. A pivot that rounding leaves at or below zero is taken as eps.
  const double m00 = q[0] + eps, m11 = q[3] + eps, m22 = q[5] + eps;
  const double i0 = 1.0 / m00; // q[0] >= 0, so the first pivot is at least eps
  const double l10 = q[1] * i0;
  const double l20 = q[2] * i0;
  const double d1Raw = m11 - l10 * q[1];
  const double i1 = 1.0 / (d1Raw > 0.0 ? d1Raw : eps);
  const double c21 = q[4] - l20 * q[1];
  const double l21 = c21 * i1;
  const double d2Raw = m22 - l20 * q[2] - l21 * c21;
  const double i2 = 1.0 / (d2Raw > 0.0 ? d2Raw : eps);
  // Forward substitution, scaling by D^-1, back substitution.
  auto solve = [&](double s0, double s1, double s2, double y[3]) {
    const double z0 = s0;
    const double z1 = s1 - l10 * z0;
    const double z2 = s2 - l20 * z0 - l21 * z1;
    y[2] = z2 * i2;
    y[1] = z1 * i1 - l21 * y[2];
    y[0] = z0 * i0 - l10 * y[1] - l20 * y[2];
  };
  double y[3];
  solve(r0, r1, r2, y);
  // Iterative refinement towards the unregularised minimiser: the residual of A y = r after a
  // step d is eps d, so the same factors give the next correction. Along a direction with
  // eigenvalue lambda the shortfall eps / (lambda + eps) of the first solve is raised to the
  // power RefinementSteps + 1: well-determined directions become exact (a sharp corner between
  // nearly parallel planes stays where it is instead of being pulled towards the centroid by
  // about 1e-3 of the collapse's extent, which on CAD-like meshes is most of the error), while
  // (nearly) null directions, lambda << eps, still stay at the origin.
  constexpr int RefinementSteps = 2;
  double d[3] = { y[0], y[1], y[2] };
  for (int step = 0; step < RefinementSteps; ++step)
  {
    solve(eps * d[0], eps * d[1], eps * d[2], d);
    y[0] += d[0];
    y[1] += d[1];
    y[2] += d[2];
  }
  result[0] += y[0];
  result[1] += y[1];
  result[2] += y[2];
}

//------------------------------------------------------------------------------
int MinimizeQuadric(const Quadric& quadric,
  const double centre[3],
  double relativeTolerance,
  double result[3])
{
  const double* q = quadric.Q;
  result[0] = centre[0];
  result[1] = centre[1];
  result[2] = centre[2];
  if (!(quadric.Weight() > 0.0))
  {
    return 3;
  }
  Eigen::Matrix3d a;
  a << q[0], q[1], q[2], q[1], q[3], q[4], q[2], q[4], q[5];
  // The gradient at the centre is 2 (A c + b); the step solves A s = -(A c + b).
  const Eigen::Vector3d c(centre[0], centre[1], centre[2]);
  const Eigen::Vector3d residual = -(a * c + Eigen::Vector3d(q[6], q[7], q[8]));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(a);
  const Eigen::Vector3d& values = eigen.eigenvalues(); // increasing
  const double largest = values[2];
  if (!(largest > 0.0))
  {
    return 3;
  }
  Eigen::Vector3d step = Eigen::Vector3d::Zero();
  int leftOut = 0;
  for (int i = 0; i < 3; ++i)
  {
    if (values[i] > relativeTolerance * largest)
    {
      const Eigen::Vector3d u = eigen.eigenvectors().col(i);
      step += u * (u.dot(residual) / values[i]);
    }
    else
    {
      ++leftOut;
    }
  }
  for (int i = 0; i < 3; ++i)
  {
    result[i] = centre[i] + step[i];
  }
  return leftOut;
}

//------------------------------------------------------------------------------
bool PlaceByCandidates(const Quadric& quadric,
  const double* const* points,
  int count,
  double relativeTolerance,
  double result[3])
{
  double centroid[3] = { 0.0, 0.0, 0.0 };
  for (int m = 0; m < count; ++m)
  {
    for (int i = 0; i < 3; ++i)
    {
      centroid[i] += points[m][i] / count;
    }
  }
  if (MinimizeQuadric(quadric, centroid, relativeTolerance, result) == 0)
  {
    return true; // solvable: the minimiser itself
  }
  // The candidates in order (ties: the first): the centroid, the points, the pairs' midpoints.
  std::copy_n(centroid, 3, result);
  double best = quadric.Evaluate(centroid);
  auto consider = [&](const double x[3]) {
    const double cost = quadric.Evaluate(x);
    if (cost < best)
    {
      best = cost;
      std::copy_n(x, 3, result);
    }
  };
  for (int m = 0; m < count; ++m)
  {
    consider(points[m]);
  }
  for (int m = 0; m < count; ++m)
  {
    for (int n = m + 1; n < count; ++n)
    {
      const double middle[3] = { 0.5 * (points[m][0] + points[n][0]),
        0.5 * (points[m][1] + points[n][1]), 0.5 * (points[m][2] + points[n][2]) };
      consider(middle);
    }
  }
  return false;
}

//------------------------------------------------------------------------------
bool TriangleQuadric(const double a[3],
  const double b[3],
  const double c[3],
  Quadric& q,
  double normal[3],
  double plane[4])
{
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  normal[0] = u[1] * v[2] - u[2] * v[1];
  normal[1] = u[2] * v[0] - u[0] * v[2];
  normal[2] = u[0] * v[1] - u[1] * v[0];
  q.Clear();
  const double length =
    std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  if (!(length > 0.0))
  {
    return false;
  }
  const double n[3] = { normal[0] / length, normal[1] / length, normal[2] / length };
  q.AddPlane(n, a, 0.5 * length);
  if (plane)
  {
    std::copy_n(n, 3, plane);
    plane[3] = -(n[0] * a[0] + n[1] * a[1] + n[2] * a[2]);
  }
  return true;
}

//------------------------------------------------------------------------------
bool BoundaryEdgePlane(const double a[3],
  const double b[3],
  const double faceNormal[3],
  double unit[3])
{
  const double e[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double m[3] = { e[1] * faceNormal[2] - e[2] * faceNormal[1],
    e[2] * faceNormal[0] - e[0] * faceNormal[2],
    e[0] * faceNormal[1] - e[1] * faceNormal[0] };
  const double length = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
  if (!(length > 0.0))
  {
    return false;
  }
  for (int i = 0; i < 3; ++i)
  {
    unit[i] = m[i] / length;
  }
  return true;
}

//------------------------------------------------------------------------------
void BoundaryEdgeQuadric(const double a[3],
  const double b[3],
  const double faceNormal[3],
  double weight,
  Quadric& q,
  double lengthScale)
{
  q.Clear();
  double m[3];
  if (!(weight > 0.0) || !BoundaryEdgePlane(a, b, faceNormal, m))
  {
    return;
  }
  const double e[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double length = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
  q.AddPlane(m, a, weight * length * (lengthScale > 0.0 ? lengthScale : length));
}

} // namespace meshlod

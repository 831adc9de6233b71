#include "LocalSurfaceFit.h"

#include "vtk_eigen.h"
#include VTK_EIGEN(Dense)

#include <algorithm>
#include <cmath>

namespace meshlod
{
SurfaceFitResult FitQuadraticHeightField(
  const double origin[3], const double normal[3], const double* xyz, int count, double scale)
{
  SurfaceFitResult result;
  std::copy_n(origin, 3, result.Origin);
  std::copy_n(normal, 3, result.N);
  if (count < 6 || !(scale > 0.0))
  {
    return result;
  }
  // In-plane axes: u perpendicular to n and to the coordinate axis least aligned with n.
  const Eigen::Vector3d n(normal[0], normal[1], normal[2]);
  int axis = 0;
  for (int k = 1; k < 3; ++k)
  {
    axis = std::abs(n[k]) < std::abs(n[axis]) ? k : axis;
  }
  const Eigen::Vector3d u = n.cross(Eigen::Vector3d::Unit(axis)).normalized();
  const Eigen::Vector3d v = n.cross(u);

  // The normal equations, summed by hand: the lower triangle of sum row row^T and sum row d for
  // row = (u^2, u v, v^2, u, v, 1). (Eigen's rank update, general for any size, took several
  // times as long on these 6x6 sums.) Entries that sum the same products are summed once: the
  // last row's are the sums of the row itself (times 1, exactly), and entries (3, 3), (4, 3)
  // and (4, 4), u u, v u and v v, are the row's first three (the same products in the same
  // order: the same sums, where the compiler does not fuse a product into the sum); entry
  // (5, 5), the sum of 1 * 1, is the count. mRQ is entry (R, Q), sK the sum of row[K], bK the
  // right-hand side's entry K.
  double m00 = 0, m10 = 0, m11 = 0, m20 = 0, m21 = 0, m22 = 0, m30 = 0, m31 = 0, m32 = 0,
         m40 = 0, m41 = 0, m42 = 0;
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0;
  double b0 = 0, b1 = 0, b2 = 0, b3 = 0, b4 = 0, b5 = 0;
  const double inverseScale = 1.0 / scale;
  for (int j = 0; j < count; ++j)
  {
    const double* x = xyz + 3 * j;
    const double p[3] = { (x[0] - origin[0]) * inverseScale, (x[1] - origin[1]) * inverseScale,
      (x[2] - origin[2]) * inverseScale };
    const double pu = p[0] * u[0] + p[1] * u[1] + p[2] * u[2];
    const double pv = p[0] * v[0] + p[1] * v[1] + p[2] * v[2];
    const double pd = p[0] * n[0] + p[1] * n[1] + p[2] * n[2];
    const double r0 = pu * pu, r1 = pu * pv, r2 = pv * pv; // row[3], row[4] are pu, pv
    m00 += r0 * r0;
    m10 += r1 * r0;
    m11 += r1 * r1;
    m20 += r2 * r0;
    m21 += r2 * r1;
    m22 += r2 * r2;
    m30 += pu * r0;
    m31 += pu * r1;
    m32 += pu * r2;
    m40 += pv * r0;
    m41 += pv * r1;
    m42 += pv * r2;
    s0 += r0;
    s1 += r1;
    s2 += r2;
    s3 += pu;
    s4 += pv;
    b0 += r0 * pd;
    b1 += r1 * pd;
    b2 += r2 * pd;
    b3 += pu * pd;
    b4 += pv * pd;
    b5 += pd;
  }
  const double lower[6][6] = { { m00 }, { m10, m11 }, { m20, m21, m22 }, { m30, m31, m32, s0 },
    { m40, m41, m42, s1, s2 }, { s0, s1, s2, s3, s4, static_cast<double>(count) } };
  const double sums[6] = { b0, b1, b2, b3, b4, b5 };
  Eigen::Matrix<double, 6, 6> normalMatrix;
  Eigen::Matrix<double, 6, 1> rhs;
  for (int r = 0; r < 6; ++r)
  {
    for (int q = 0; q <= r; ++q)
    {
      normalMatrix(r, q) = normalMatrix(q, r) = lower[r][q];
    }
    rhs[r] = sums[r];
  }
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> solver(normalMatrix);
  // LDLT solves a singular system quietly (zero pivots give zero components), and its rcond()
  // estimate does not always see it: test the pivots themselves. Points on one line, or too
  // few distinct ones, leave some of them (nearly) zero. The estimate (several solves, a tenth
  // of the curvature method's time when made for every fit) is asked only when the smallest
  // pivot is below RcondPivotRatio times the largest: over the tests and benchmarks it refused
  // one fit in millions, whose pivots spanned 2e9.
  constexpr double RcondPivotRatio = 1e-6;
  const Eigen::Matrix<double, 6, 1> pivots = solver.vectorD().cwiseAbs();
  if (solver.info() != Eigen::Success || !(pivots.minCoeff() > 1e-10 * pivots.maxCoeff()) ||
    (!(pivots.minCoeff() > RcondPivotRatio * pivots.maxCoeff()) && !(solver.rcond() > 1e-12)))
  {
    return result;
  }
  const Eigen::Matrix<double, 6, 1> k = solver.solve(rhs);
  if (!k.allFinite())
  {
    return result;
  }
  // Derivatives at (0, 0) in scaled coordinates; curvatures scale back by 1 / scale.
  const double fu = k[3], fv = k[4];
  const double fuu = 2.0 * k[0], fuv = k[1], fvv = 2.0 * k[2];
  const double g = 1.0 + fu * fu + fv * fv;
  const double gauss = (fuu * fvv - fuv * fuv) / (g * g);
  const double mean =
    ((1.0 + fu * fu) * fvv - 2.0 * fu * fv * fuv + (1.0 + fv * fv) * fuu) / (2.0 * std::pow(g, 1.5));
  const double root = std::sqrt(std::max(0.0, mean * mean - gauss));
  result.Kappa1 = (mean + root) * inverseScale;
  result.Kappa2 = (mean - root) * inverseScale;
  result.AbsoluteCurvature = std::abs(result.Kappa1) + std::abs(result.Kappa2);
  result.Height = k[5] * scale;
  // Back to world units: in scaled coordinates d/s = k0 (u/s)^2 + ... + k5.
  result.C[0] = k[0] * inverseScale;
  result.C[1] = k[1] * inverseScale;
  result.C[2] = k[2] * inverseScale;
  result.C[3] = k[3];
  result.C[4] = k[4];
  result.C[5] = k[5] * scale;
  for (int i = 0; i < 3; ++i)
  {
    result.U[i] = u[i];
    result.V[i] = v[i];
  }
  result.Valid = true;
  return result;
}

} // namespace meshlod

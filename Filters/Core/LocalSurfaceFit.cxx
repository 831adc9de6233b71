#include "LocalSurfaceFit.h"

#include "vtk_eigen.h"
#include VTK_EIGEN(Dense)

#include <cmath>

namespace meshlod
{
SurfaceFitResult FitQuadraticHeightField(
  const double origin[3], const double normal[3], const double* xyz, int count, double scale)
{
  SurfaceFitResult result;
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
  const Eigen::Vector3d c(origin[0], origin[1], origin[2]);

  Eigen::Matrix<double, 6, 6> normalMatrix = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
  const double inverseScale = 1.0 / scale;
  for (int j = 0; j < count; ++j)
  {
    const Eigen::Vector3d p = (Eigen::Vector3d(xyz[3 * j], xyz[3 * j + 1], xyz[3 * j + 2]) - c) *
      inverseScale;
    const double pu = p.dot(u), pv = p.dot(v), pd = p.dot(n);
    Eigen::Matrix<double, 6, 1> row;
    row << pu * pu, pu * pv, pv * pv, pu, pv, 1.0;
    normalMatrix.selfadjointView<Eigen::Lower>().rankUpdate(row);
    rhs += row * pd;
  }
  normalMatrix.triangularView<Eigen::Upper>() = normalMatrix.transpose();
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> solver(normalMatrix);
  // LDLT solves a singular system quietly (zero pivots give zero components), and its rcond()
  // estimate does not always see it: test the pivots themselves. Points on one line, or too
  // few distinct ones, leave some of them (nearly) zero.
  const Eigen::Matrix<double, 6, 1> pivots = solver.vectorD().cwiseAbs();
  if (solver.info() != Eigen::Success || !(pivots.minCoeff() > 1e-10 * pivots.maxCoeff()) ||
    !(solver.rcond() > 1e-12))
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

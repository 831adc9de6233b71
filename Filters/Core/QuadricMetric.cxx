#include "QuadricMetric.h"

#include <cmath>

namespace meshlod
{
double Quadric::RmsDistance(const double x[3]) const
{
  return this->Weight > 0.0 ? std::sqrt(this->Evaluate(x) / this->Weight) : 0.0;
}

void Quadric::Minimize(const double origin[3], double result[3], double relativeTolerance) const
{
  // Minimise around the origin: with x = o + y, the gradient A (o + y) + b = 0 gives
  // A y = -(A o + b). Solve the regularised system (A + eps I) y = -(A o + b) with
  // eps = relativeTolerance * trace(A): along eigenvectors with eigenvalues well above eps this
  // is the exact minimiser, along (nearly) null directions y stays near 0, i.e. the point stays
  // at the origin. It behaves like a truncated pseudo-inverse at the price of one 3x3
  // Cholesky factorisation (A + eps I is positive definite).
  const double* o = origin;
  const double r0 = -(this->A00 * o[0] + this->A01 * o[1] + this->A02 * o[2] + this->B0);
  const double r1 = -(this->A01 * o[0] + this->A11 * o[1] + this->A12 * o[2] + this->B1);
  const double r2 = -(this->A02 * o[0] + this->A12 * o[1] + this->A22 * o[2] + this->B2);
  const double trace = this->A00 + this->A11 + this->A22;
  result[0] = o[0];
  result[1] = o[1];
  result[2] = o[2];
  if (!(trace > 0.0) || !std::isfinite(trace))
  {
    return;
  }
  const double eps = relativeTolerance * trace;
  // Cholesky L L^T of the regularised matrix.
  const double l00 = std::sqrt(this->A00 + eps);
  const double l10 = this->A01 / l00;
  const double l20 = this->A02 / l00;
  const double d11 = this->A11 + eps - l10 * l10;
  const double l11 = std::sqrt(d11 > 0.0 ? d11 : eps);
  const double l21 = (this->A12 - l20 * l10) / l11;
  const double d22 = this->A22 + eps - l20 * l20 - l21 * l21;
  const double l22 = std::sqrt(d22 > 0.0 ? d22 : eps);
  // Forward then back substitution.
  const double i00 = 1.0 / l00, i11 = 1.0 / l11, i22 = 1.0 / l22;
  const double z0 = r0 * i00;
  const double z1 = (r1 - l10 * z0) * i11;
  const double z2 = (r2 - l20 * z0 - l21 * z1) * i22;
  const double y2 = z2 * i22;
  const double y1 = (z1 - l21 * y2) * i11;
  const double y0 = (z0 - l10 * y1 - l20 * y2) * i00;
  result[0] += y0;
  result[1] += y1;
  result[2] += y2;
}

} // namespace meshlod

#include "SymmetricEigensolver.h"

#include <cmath>

namespace pcbilateral
{

namespace
{
// The scalar operations SymmetricEigensolverSteps.h is written with.
inline double Abs(double x)
{
  return std::abs(x);
}
inline double Sqrt(double x)
{
  return std::sqrt(x);
}
inline bool Less(double a, double b)
{
  return a < b;
}
inline double Select(bool mask, double a, double b)
{
  return mask ? a : b;
}
#include "SymmetricEigensolverSteps.h"

/// A vector orthogonal to the non-zero vector u: u crossed with the axis it is least aligned
/// with. Returns its squared length.
double OrthogonalVector(const double u[3], double vector[3])
{
  int axis = 0;
  for (int other = 1; other < 3; ++other)
  {
    if (std::abs(u[other]) < std::abs(u[axis]))
    {
      axis = other;
    }
  }
  double unit[3] = { 0.0, 0.0, 0.0 };
  unit[axis] = 1.0;
  vector[0] = u[1] * unit[2] - u[2] * unit[1];
  vector[1] = u[2] * unit[0] - u[0] * unit[2];
  vector[2] = u[0] * unit[1] - u[1] * unit[0];
  return vector[0] * vector[0] + vector[1] * vector[1] + vector[2] * vector[2];
}
} // namespace

void SmallestEigenvector(const double covariance[6], double eigenvector[3])
{
  // The eigenvectors of C are those of B = (C - shift I) / scale (SymmetricEigensolverSteps.h).
  double b[6];
  const double scale = CenteredMatrix(covariance, b);
  eigenvector[0] = 0.0;
  eigenvector[1] = 0.0;
  eigenvector[2] = 1.0;
  if (!(scale > 0.0) || !std::isfinite(scale))
  {
    return; // C = shift I: every direction is an eigenvector
  }
  double p;
  const double cosine = CubicCosine(b, scale, p);
  const double e = SmallestRootOffset(cosine);

  double best[3];
  double bestNorm;
  // Below MeetingEigenvalueRoots, the two smallest eigenvalues are within 4e-6 p of each other
  // (points along a line): the smallest is then known only to about the square root of the
  // rounding error, and so is the plane of its eigenvectors, while the largest is simple and
  // well conditioned. Any unit vector orthogonal to the largest's eigenvector is the answer.
  if (e < MeetingEigenvalueRoots)
  {
    // The largest root, near 1 (f'(1) = 9: two steps from 1 suffice).
    double t = 1.0;
    for (int step = 0; step < 2; ++step)
    {
      t -= ((4.0 * t * t - 3.0) * t - cosine) / (12.0 * t * t - 3.0);
    }
    double largest[3];
    if (!(EigenvectorFromRows(b, 2.0 * p * t, largest) > 0.0))
    {
      return;
    }
    bestNorm = OrthogonalVector(largest, best);
  }
  else
  {
    bestNorm = EigenvectorFromRows(b, -p * (1.0 + 2.0 * e), best);
  }
  if (!(bestNorm > 0.0))
  {
    return;
  }
  // Divided rather than multiplied by the inverse: an axis-aligned plane then gets exactly the
  // axis as its normal.
  const double length = std::sqrt(bestNorm);
  for (int axis = 0; axis < 3; ++axis)
  {
    eigenvector[axis] = best[axis] / length;
  }
}

void TangentFrame(const double covariance[6],
  double normal[3],
  double tangentU[3],
  double tangentV[3])
{
  SmallestEigenvector(covariance, normal);
  const double length = std::sqrt(OrthogonalVector(normal, tangentU));
  for (int axis = 0; axis < 3; ++axis)
  {
    tangentU[axis] /= length;
  }
  tangentV[0] = normal[1] * tangentU[2] - normal[2] * tangentU[1];
  tangentV[1] = normal[2] * tangentU[0] - normal[0] * tangentU[2];
  tangentV[2] = normal[0] * tangentU[1] - normal[1] * tangentU[0];
}

} // namespace pcbilateral

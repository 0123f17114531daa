#include "LocalSurfaceFit.h"

#include "SymmetricEigensolver.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace pcbilateral
{
namespace
{
/// Residuals beyond this many robust deviations are left out of the fit.
constexpr double ClipInDeviations = 3.0;
/// The variance of a standard normal clipped at +-3.
constexpr double ClippedVariance = 0.97334;

/// Solves the symmetric positive system m x = b (n x n, n <= 6) by Cholesky; false if singular.
/// (n is a template parameter, as is the number of terms of the fits below: with it known, the
/// compiler unrolls the small loops, which a fit runs for every point of every ball.)
template<int n>
bool SolveCholesky(double m[QuadricTerms][QuadricTerms],
  double b[QuadricTerms],
  double x[QuadricTerms])
{
  double l[QuadricTerms][QuadricTerms] = {};
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j <= i; ++j)
    {
      double sum = m[i][j];
      for (int k = 0; k < j; ++k)
      {
        sum -= l[i][k] * l[j][k];
      }
      if (i == j)
      {
        if (!(sum > 1e-12 * std::max(1.0, m[i][i])))
        {
          return false;
        }
        l[i][i] = std::sqrt(sum);
      }
      else
      {
        l[i][j] = sum / l[j][j];
      }
    }
  }
  double y[QuadricTerms];
  for (int i = 0; i < n; ++i)
  {
    double sum = b[i];
    for (int k = 0; k < i; ++k)
    {
      sum -= l[i][k] * y[k];
    }
    y[i] = sum / l[i][i];
  }
  for (int i = n - 1; i >= 0; --i)
  {
    double sum = y[i];
    for (int k = i + 1; k < n; ++k)
    {
      sum -= l[k][i] * x[k];
    }
    x[i] = sum / l[i][i];
  }
  return true;
}

/// The height function's least-squares coefficients over the inliers (local x, y, z), with
/// `terms` terms; false when the system is singular.
template<int terms>
bool SolveHeightFunction(const std::vector<std::array<double, 3>>& local,
  const std::vector<std::uint8_t>& inlier,
  double coefficients[QuadricTerms])
{
  double normal[QuadricTerms][QuadricTerms] = {}, rhs[QuadricTerms] = {};
  for (std::size_t i = 0; i < local.size(); ++i)
  {
    if (!inlier[i])
    {
      continue;
    }
    const double x = local[i][0], y = local[i][1];
    const double basis[QuadricTerms] = { 1.0, x, y, x * x, x * y, y * y };
    // The lower triangle only: the matrix is symmetric.
    for (int r = 0; r < terms; ++r)
    {
      for (int c = 0; c <= r; ++c)
      {
        normal[r][c] += basis[r] * basis[c];
      }
      rhs[r] += basis[r] * local[i][2];
    }
  }
  for (int r = 0; r < terms; ++r)
  {
    for (int c = r + 1; c < terms; ++c)
    {
      normal[r][c] = normal[c][r];
    }
  }
  return SolveCholesky<terms>(normal, rhs, coefficients);
}

/// The robust fit of the height function: fitted, residuals to the fit, points further than
/// ClipInDeviations robust deviations left out, fitted again, twice. Fills the coefficients,
/// every point's residual and whether it is an inlier; false when it could not be fitted.
template<int terms>
bool FitHeightFunctionRobustly(const std::vector<std::array<double, 3>>& local,
  double coefficients[QuadricTerms],
  std::vector<double>& residual,
  std::vector<std::uint8_t>& inlier,
  std::size_t& inliers)
{
  const std::size_t m = local.size();
  inlier.assign(m, 1);
  residual.assign(m, 0.0);
  inliers = m;
  std::vector<double> magnitude;
  for (int pass = 0; pass < 3; ++pass)
  {
    if (!SolveHeightFunction<terms>(local, inlier, coefficients))
    {
      return false;
    }
    // A copy, which the stores to residual cannot alias.
    double c[QuadricTerms];
    std::copy_n(coefficients, QuadricTerms, c);
    magnitude.clear();
    for (std::size_t i = 0; i < m; ++i)
    {
      const double x = local[i][0], y = local[i][1];
      residual[i] =
        local[i][2] - (c[0] + c[1] * x + c[2] * y + c[3] * x * x + c[4] * x * y + c[5] * y * y);
      if (pass == 0 || inlier[i])
      {
        magnitude.push_back(std::abs(residual[i]));
      }
    }
    if (pass == 2)
    {
      break;
    }
    // The median absolute residual, as a normal's deviation (MAD x 1.4826).
    auto middle = magnitude.begin() + static_cast<std::ptrdiff_t>(magnitude.size() / 2);
    std::nth_element(magnitude.begin(), middle, magnitude.end());
    const double deviation = 1.4826 * *middle;
    inliers = 0;
    for (std::size_t i = 0; i < m; ++i)
    {
      inlier[i] = std::abs(residual[i]) <= ClipInDeviations * deviation;
      inliers += inlier[i];
    }
    if (inliers < FewestPointsToFit)
    {
      return false;
    }
  }
  return true;
}

double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

} // namespace

void LocalFit::Local(const double* p, double local[3]) const
{
  double d[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    d[axis] = (p[axis] - this->Origin[axis]) / this->Scale;
  }
  local[0] = Dot(d, this->TangentU);
  local[1] = Dot(d, this->TangentV);
  local[2] = Dot(d, this->Normal);
}

namespace
{
/// The points' mean and the upper triangle (xx, xy, xz, yy, yz, zz) of their scatter matrix
/// about it: the least-squares plane through the mean is normal to its smallest eigenvector.
void MeanAndCovariance(const std::vector<std::array<double, 3>>& points,
  double mean[3],
  double covariance[6])
{
  std::fill_n(mean, 3, 0.0);
  std::fill_n(covariance, 6, 0.0);
  for (const auto& p : points)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      mean[axis] += p[axis];
    }
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    mean[axis] /= static_cast<double>(points.size());
  }
  for (const auto& p : points)
  {
    const double d[3] = { p[0] - mean[0], p[1] - mean[1], p[2] - mean[2] };
    const double products[6] = {
      d[0] * d[0], d[0] * d[1], d[0] * d[2], d[1] * d[1], d[1] * d[2], d[2] * d[2]
    };
    for (int entry = 0; entry < 6; ++entry)
    {
      covariance[entry] += products[entry];
    }
  }
}

/// FitQuadric with the number of terms known at compile time.
template<int terms>
LocalFit FitHeightFunction(const std::vector<std::array<double, 3>>& points,
  const double centre[3],
  double radius)
{
  LocalFit fit;
  const std::size_t m = points.size();
  if (m < FewestPointsToFit)
  {
    return fit;
  }
  double mean[3], covariance[6];
  MeanAndCovariance(points, mean, covariance);
  // The frame and the coefficients in local arrays, copied into the fit once: written through
  // the fit, the per-point loops would reload them after every store (they might alias).
  double normal[3], tangentU[3], tangentV[3];
  TangentFrame(covariance, normal, tangentU, tangentV);
  std::copy_n(normal, 3, fit.Normal);
  std::copy_n(tangentU, 3, fit.TangentU);
  std::copy_n(tangentV, 3, fit.TangentV);
  fit.Scale = radius;
  for (int axis = 0; axis < 3; ++axis)
  {
    fit.Origin[axis] = centre[axis] + radius * mean[axis];
  }
  // Local coordinates: x, y along the tangents, z along the normal.
  std::vector<std::array<double, 3>> local(m);
  for (std::size_t i = 0; i < m; ++i)
  {
    const double d[3] = { points[i][0] - mean[0], points[i][1] - mean[1], points[i][2] - mean[2] };
    local[i] = { Dot(d, tangentU), Dot(d, tangentV), Dot(d, normal) };
  }
  std::vector<double> residual;
  std::vector<std::uint8_t> inlier;
  std::size_t inliers = 0;
  double coefficients[QuadricTerms] = {};
  if (!FitHeightFunctionRobustly<terms>(local, coefficients, residual, inlier, inliers))
  {
    return fit;
  }
  std::copy_n(coefficients, QuadricTerms, fit.Coefficients);
  double sum = 0.0;
  for (std::size_t i = 0; i < m; ++i)
  {
    sum += inlier[i] ? residual[i] * residual[i] : 0.0;
  }
  fit.Variance = sum / static_cast<double>(inliers - terms) / ClippedVariance * radius * radius;
  fit.Inliers = inliers;
  // The centre's foot on the fitted surface (the centre is local (0, 0, 0) shifted by -mean).
  const double c[3] = { -mean[0], -mean[1], -mean[2] };
  fit.FootX = Dot(c, fit.TangentU);
  fit.FootY = Dot(c, fit.TangentV);
  const double height = fit.Height(fit.FootX, fit.FootY);
  const double z = Dot(c, fit.Normal);
  for (int axis = 0; axis < 3; ++axis)
  {
    fit.SurfacePoint[axis] = centre[axis] + radius * (height - z) * fit.Normal[axis];
  }
  // A degenerate neighbourhood (points on a line, say) can solve to non-finite coefficients: no
  // fit, rather than a surface point nowhere.
  fit.Fitted = std::isfinite(fit.Variance) && std::isfinite(height) &&
               std::isfinite(fit.SurfacePoint[0]) && std::isfinite(fit.SurfacePoint[1]) &&
               std::isfinite(fit.SurfacePoint[2]);
  return fit;
}
} // namespace

LocalFit FitQuadric(const std::vector<std::array<double, 3>>& points,
  const double centre[3],
  double radius,
  int terms)
{
  return terms == 3 ? FitHeightFunction<3>(points, centre, radius)
                    : FitHeightFunction<QuadricTerms>(points, centre, radius);
}

namespace
{

/// The variance of the heights seen in a ball of radius rho centred on a plane whose points
/// have Gaussian offsets of deviation sigma: density g(z) (rho^2 - z^2) on [-rho, rho].
double VarianceInBall(double sigma, double rho)
{
  const int steps = 400;
  double weight = 0.0, moment = 0.0;
  for (int k = 0; k <= steps; ++k)
  {
    const double z = -rho + 2.0 * rho * k / steps;
    const double w = (k == 0 || k == steps ? 0.5 : 1.0) * std::exp(-0.5 * z * z / (sigma * sigma)) *
                     (rho * rho - z * z);
    weight += w;
    moment += w * z * z;
  }
  return moment / weight;
}

} // namespace

double SigmaFromBallVariance(double variance, double rho)
{
  double low = 0.0, high = rho;
  if (VarianceInBall(1e6 * rho, rho) <= variance)
  {
    return std::numeric_limits<double>::infinity();
  }
  while (VarianceInBall(high, rho) < variance)
  {
    high *= 2.0;
    if (high > 1e3 * rho)
    {
      return std::numeric_limits<double>::infinity();
    }
  }
  for (int k = 0; k < 60; ++k)
  {
    const double mid = 0.5 * (low + high);
    (VarianceInBall(mid, rho) < variance ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

} // namespace pcbilateral

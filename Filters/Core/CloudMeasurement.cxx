// How the scales are measured.
//
// Around each sample point, the points within a radius rho are fitted by a quadric height
// function z = q(x, y) over their principal plane, robustly (points more than 3 robust
// deviations off are left out, then the fit is redone): the quadric takes the surface's
// curvature away, the clipping takes outliers and the far side of edges away. The residuals'
// spread estimates the noise sigma.
//
// Two effects bias that estimate and are corrected:
// - the fit absorbs 6 degrees of freedom (variance x m / (m - 6) for m points) and the clipping
//   at 3 deviations removes 2.7% of the variance;
// - the ball cuts the noise's slab: a point at height z above the surface is in the ball over
//   a disc of area pi (rho^2 - z^2), so the heights seen have the density g(z) (rho^2 - z^2)
//   (g the noise's Gaussian), whose variance is less than sigma^2. It is inverted numerically.
// The radius must be a few sigmas for the slab to show, yet as small as possible to keep the
// edges out: it is found as a fixed point, rho = 5 sigma(rho) but holding at least ~50 points,
// starting from the smallest ball and growing. The per-sample deviations are read at their
// 25th percentile, not the median: at strong noise the balls are wide enough that most samples
// see an edge, which only raises their deviation.
//
// The density is counted over a small disc of each fitted surface, within 3 sigma of it, so
// that neither the noise nor (much) the borders and density changes matter. The spacing is the
// mean over the samples of 1 / (2 sqrt(density)), which is the mean nearest-neighbour distance
// of points spread at random with that density.
//
// Flatness: at 1.5 times the automatic rule's radius, the residual variance a plane fit leaves
// beyond a quadric fit of the same points (curvature and edges), in units of sigma^2. Creases:
// on the same points, the residual variance the quadric itself leaves, in units of sigma^2
// (about 1 where a smooth surface fits, well above it where an edge, corner or step does not).
//
// Large balls hold too many points: the ball is gathered from a subset of the cloud (each
// point has a fixed pseudo-random key; level l keeps a 4^-l fraction of the points), chosen so
// that it holds about a hundred points. Each level has its own hashed uniform grid.
//
// Every per-sample result is stored in its sample's slot and reduced in sample order, so the
// result does not depend on the number of threads.
#include "CloudMeasurement.h"

#include "BilateralKernel.h" // IsFinitePoint

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace pcbilateral
{
namespace
{
/// SplitMix64's finaliser.
std::uint64_t Mix(std::uint64_t x)
{
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

std::uint64_t Bits(double value)
{
  // -0 and +0 are one point.
  value = value == 0.0 ? 0.0 : value;
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

/// A fixed pseudo-random key per point, from its coordinates alone: the same point gets the same
/// key whatever its index, in whichever part of a distributed cloud it is.
std::uint64_t MeasurementKey(const double* p)
{
  return Mix(Mix(Mix(Bits(p[0])) ^ Bits(p[1])) ^ Bits(p[2]));
}

/// The key that decides whether a point is in the measured selection (SelectMeasurementPoints):
/// another hash than MeasurementKey, so that the selection and the levels inside it are
/// independent.
std::uint64_t SelectionKey(const double* p)
{
  return Mix(MeasurementKey(p) ^ 0x5bd1e995ull);
}

/// A finite point's MeasurementKey and index.
struct KeyedPoint
{
  std::uint64_t Key;
  std::size_t Index;
};

/// The indices of the count points with the smallest (key, coordinates), in that order.
std::vector<std::size_t> SmallestKeys(const PointCloudView& cloud,
  std::vector<KeyedPoint> keyed,
  std::size_t count)
{
  auto before = [&](const KeyedPoint& a, const KeyedPoint& b)
  {
    if (a.Key != b.Key)
    {
      return a.Key < b.Key;
    }
    const double* p = cloud.Positions + 3 * a.Index;
    const double* q = cloud.Positions + 3 * b.Index;
    return std::lexicographical_compare(p, p + 3, q, q + 3);
  };
  count = std::min(count, keyed.size());
  std::nth_element(keyed.begin(), keyed.begin() + count, keyed.end(), before);
  keyed.resize(count);
  std::sort(keyed.begin(), keyed.end(), before);
  std::vector<std::size_t> indices(count);
  for (std::size_t k = 0; k < count; ++k)
  {
    indices[k] = keyed[k].Index;
  }
  return indices;
}

/// Points per ball that the fits aim at, and the fewest the radius may hold at full density.
constexpr double PointsPerBall = 64.0;
constexpr double FewestPointsPerBall = 48.0;
/// The fixed point's radius in sigmas.
constexpr double RadiusInSigmas = 5.0;
/// Residuals beyond this many robust deviations are left out of the fit.
constexpr double ClipInDeviations = 3.0;
/// The variance of a standard normal clipped at +-3.
constexpr double ClippedVariance = 0.97334;
constexpr int MaximumRounds = 12;
/// The noise is read at this quantile of the per-sample deviations; its normal score.
constexpr double DeviationQuantile = 0.25;
constexpr double DeviationQuantileScore = 0.6745;
/// The flatness is measured at FlatnessRadiusInSpacings x spacing + FlatnessRadiusInSigmas x
/// sigma (1.5 times the automatic rule's radius), with about this many points per ball; a
/// sample whose plane fit leaves FeatureExcess sigma^2 more variance than its quadric fit sees
/// an edge or a strong bend.
constexpr double FlatnessRadiusInSpacings = 7.5;
constexpr double FlatnessRadiusInSigmas = 6.0;
constexpr double FlatnessPointsPerBall = 96.0;
constexpr double FeatureExcess = 0.5;
/// A sample whose quadric fit at the flatness radius leaves more than CreaseVariance sigma^2
/// of residual variance sees a crease: no smooth surface fits there. On the smooth shapes of
/// pcb_quality (spheres, terrains) no sample exceeds 2; on the shapes with edges at 0.1% noise,
/// 4% to 28% of them do (at stronger noise the quadric absorbs more of a blunt edge).
constexpr double CreaseVariance = 2.0;
/// Points in the disc that measures the density.
constexpr double DiscPoints = 40.0;
constexpr int QuadricTerms = 6;
constexpr std::size_t FewestPointsToFit = 16;

/// A uniform grid over a subset of the points, hashed into buckets (counting sort).
class HashedGrid
{
public:
  HashedGrid(const double* positions,
    const std::vector<std::size_t>& members,
    const double origin[3],
    double cellSize)
    : Positions(positions)
    , CellSize(cellSize)
  {
    std::copy(origin, origin + 3, this->Origin);
    std::size_t buckets = 1;
    while (buckets < members.size())
    {
      buckets *= 2;
    }
    this->Mask = buckets - 1;
    this->Start.assign(buckets + 1, 0);
    std::vector<std::uint32_t> bucketOf(members.size());
    for (std::size_t i = 0; i < members.size(); ++i)
    {
      std::int64_t cell[3];
      this->CellOf(positions + 3 * members[i], cell);
      bucketOf[i] = static_cast<std::uint32_t>(this->BucketOf(cell));
      ++this->Start[bucketOf[i] + 1];
    }
    for (std::size_t b = 0; b < buckets; ++b)
    {
      this->Start[b + 1] += this->Start[b];
    }
    this->Entries.resize(members.size());
    std::vector<std::size_t> next(this->Start.begin(), this->Start.end() - 1);
    for (std::size_t i = 0; i < members.size(); ++i)
    {
      this->Entries[next[bucketOf[i]]++] = members[i];
    }
  }

  /// Calls visit(index) for each member within radius of centre, in a fixed order.
  template<typename Visit>
  void ForEachInBall(const double centre[3], double radius, Visit&& visit) const
  {
    std::int64_t low[3], high[3];
    for (int axis = 0; axis < 3; ++axis)
    {
      const double lowCell =
        std::floor((centre[axis] - radius - this->Origin[axis]) / this->CellSize);
      const double highCell =
        std::floor((centre[axis] + radius - this->Origin[axis]) / this->CellSize);
      // (A ball beyond what the lattice can index holds nothing to fit.)
      if (!(std::abs(lowCell) < 1e15 && std::abs(highCell) < 1e15))
      {
        return;
      }
      low[axis] = static_cast<std::int64_t>(lowCell);
      high[axis] = static_cast<std::int64_t>(highCell);
    }
    const double radius2 = radius * radius;
    // A ball spanning more cells than there are points (a radius far above the cells' size,
    // e.g. while a degenerate cloud is probed) is cheaper to answer by looking at every point.
    double cellsInRange = 1.0;
    for (int axis = 0; axis < 3; ++axis)
    {
      cellsInRange *= static_cast<double>(high[axis] - low[axis] + 1);
    }
    if (cellsInRange > static_cast<double>(this->Entries.size()))
    {
      for (const std::size_t index : this->Entries)
      {
        const double* p = this->Positions + 3 * index;
        const double dx = p[0] - centre[0], dy = p[1] - centre[1], dz = p[2] - centre[2];
        if (dx * dx + dy * dy + dz * dz <= radius2)
        {
          visit(index);
        }
      }
      return;
    }
    std::int64_t cell[3], own[3];
    for (cell[0] = low[0]; cell[0] <= high[0]; ++cell[0])
    {
      for (cell[1] = low[1]; cell[1] <= high[1]; ++cell[1])
      {
        for (cell[2] = low[2]; cell[2] <= high[2]; ++cell[2])
        {
          const std::size_t bucket = this->BucketOf(cell);
          for (std::size_t e = this->Start[bucket]; e < this->Start[bucket + 1]; ++e)
          {
            const std::size_t index = this->Entries[e];
            const double* p = this->Positions + 3 * index;
            this->CellOf(p, own);
            // Other cells share the bucket: each point is visited from its own cell only.
            if (own[0] != cell[0] || own[1] != cell[1] || own[2] != cell[2])
            {
              continue;
            }
            const double dx = p[0] - centre[0], dy = p[1] - centre[1], dz = p[2] - centre[2];
            if (dx * dx + dy * dy + dz * dz <= radius2)
            {
              visit(index);
            }
          }
        }
      }
    }
  }

  double GetCellSize() const { return this->CellSize; }

private:
  void CellOf(const double* p, std::int64_t cell[3]) const
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      cell[axis] =
        static_cast<std::int64_t>(std::floor((p[axis] - this->Origin[axis]) / this->CellSize));
    }
  }
  std::size_t BucketOf(const std::int64_t cell[3]) const
  {
    const std::uint64_t key = static_cast<std::uint64_t>(cell[0]) * 73856093ull ^
                              static_cast<std::uint64_t>(cell[1]) * 19349663ull ^
                              static_cast<std::uint64_t>(cell[2]) * 83492791ull;
    return static_cast<std::size_t>(Mix(key) & this->Mask);
  }

  const double* Positions;
  double Origin[3];
  double CellSize;
  std::size_t Mask = 0;
  std::vector<std::size_t> Start;
  std::vector<std::size_t> Entries;
};

/// The points of the grid within rho of centre, relative to centre in units of rho, in a fixed
/// order (lexicographic by coordinates), so that the fits' sums do not depend on the order the
/// cloud lists its points in (equal points are interchangeable).
void GatherBall(const HashedGrid& grid,
  const double* positions,
  const double centre[3],
  double rho,
  std::vector<std::array<double, 3>>& points)
{
  points.clear();
  grid.ForEachInBall(centre,
    rho,
    [&](std::size_t index)
    {
      const double* p = positions + 3 * index;
      points.push_back(
        { (p[0] - centre[0]) / rho, (p[1] - centre[1]) / rho, (p[2] - centre[2]) / rho });
    });
  std::sort(points.begin(), points.end());
}

/// Eigen-decomposition of a symmetric 3x3 matrix by Jacobi rotations; the eigenvectors are the
/// columns of vectors, the eigenvalues in ascending order.
void SymmetricEigen(double a[3][3], double values[3], double vectors[3][3])
{
  double v[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  for (int sweep = 0; sweep < 50; ++sweep)
  {
    const double off = std::abs(a[0][1]) + std::abs(a[0][2]) + std::abs(a[1][2]);
    if (off <= 1e-300 || off <= 1e-15 * (std::abs(a[0][0]) + std::abs(a[1][1]) + std::abs(a[2][2])))
    {
      break;
    }
    for (int p = 0; p < 2; ++p)
    {
      for (int q = p + 1; q < 3; ++q)
      {
        if (a[p][q] == 0.0)
        {
          continue;
        }
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t =
          (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1.0 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k)
        {
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k)
        {
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k)
        {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  int order[3] = { 0, 1, 2 };
  std::sort(order, order + 3, [&](int i, int j) { return a[i][i] < a[j][j]; });
  for (int k = 0; k < 3; ++k)
  {
    values[k] = a[order[k]][order[k]];
    for (int row = 0; row < 3; ++row)
    {
      vectors[row][k] = v[row][order[k]];
    }
  }
}

/// Solves the symmetric positive system m x = b (n x n, n <= 6) by Cholesky; false if singular.
bool SolveCholesky(double m[QuadricTerms][QuadricTerms],
  double b[QuadricTerms],
  double x[QuadricTerms],
  int n)
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

/// The fit of one neighbourhood.
struct LocalFit
{
  bool Fitted = false;
  /// Residual variance of the inliers, corrected for the fit's degrees of freedom and the
  /// clipping (not yet for the ball's cut of the slab).
  double Variance = 0.0;
  /// Inliers, per unit of ball cross-section (still to be divided by the level's fraction).
  std::size_t Inliers = 0;
  /// The point of the fitted surface below the centre.
  double SurfacePoint[3] = { 0, 0, 0 };
  /// The fitted surface: z = q(x, y) in the frame (Tangent1, Tangent2, Normal) at Origin, in
  /// units of Scale.
  double Origin[3] = { 0, 0, 0 };
  double Frame[3][3] = {};
  double Coefficients[QuadricTerms] = {};
  double Scale = 1.0;
  /// The foot's local (x, y).
  double FootX = 0.0, FootY = 0.0;

  double Height(double x, double y) const
  {
    const double* c = this->Coefficients;
    return c[0] + c[1] * x + c[2] * y + c[3] * x * x + c[4] * x * y + c[5] * y * y;
  }
  /// The point's local coordinates (x, y along the tangents, z along the normal).
  void Local(const double* p, double local[3]) const
  {
    double d[3];
    for (int axis = 0; axis < 3; ++axis)
    {
      d[axis] = (p[axis] - this->Origin[axis]) / this->Scale;
    }
    for (int k = 0; k < 3; ++k)
    {
      const int column = 2 - k; // tangents are the largest axes, the normal the smallest
      local[k] = d[0] * this->Frame[0][column] + d[1] * this->Frame[1][column] +
                 d[2] * this->Frame[2][column];
    }
  }
};

/// Robust quadric fit (or plane fit, with 3 terms) of the given points (coordinates relative to
/// centre, in units of radius for conditioning).
LocalFit FitQuadric(const std::vector<std::array<double, 3>>& points,
  const double centre[3],
  double radius,
  int terms = QuadricTerms)
{
  LocalFit fit;
  const std::size_t m = points.size();
  if (m < FewestPointsToFit)
  {
    return fit;
  }
  double mean[3] = { 0, 0, 0 };
  for (const auto& p : points)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      mean[axis] += p[axis];
    }
  }
  for (double& value : mean)
  {
    value /= static_cast<double>(m);
  }
  double covariance[3][3] = {};
  for (const auto& p : points)
  {
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        covariance[i][j] += (p[i] - mean[i]) * (p[j] - mean[j]);
      }
    }
  }
  double values[3], frame[3][3];
  SymmetricEigen(covariance, values, frame);
  // Local coordinates: x, y along the two largest axes, z along the normal (smallest axis).
  std::vector<std::array<double, 3>> local(m);
  for (std::size_t i = 0; i < m; ++i)
  {
    double d[3];
    for (int axis = 0; axis < 3; ++axis)
    {
      d[axis] = points[i][axis] - mean[axis];
    }
    local[i] = { d[0] * frame[0][2] + d[1] * frame[1][2] + d[2] * frame[2][2],
      d[0] * frame[0][1] + d[1] * frame[1][1] + d[2] * frame[2][1],
      d[0] * frame[0][0] + d[1] * frame[1][0] + d[2] * frame[2][0] };
  }
  std::vector<std::uint8_t> inlier(m, 1);
  std::vector<double> residual(m), magnitude;
  double coefficients[QuadricTerms] = {};
  std::size_t inliers = m;
  for (int pass = 0; pass < 3; ++pass)
  {
    double normal[QuadricTerms][QuadricTerms] = {}, rhs[QuadricTerms] = {};
    for (std::size_t i = 0; i < m; ++i)
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
    if (!SolveCholesky(normal, rhs, coefficients, terms))
    {
      return fit;
    }
    magnitude.clear();
    for (std::size_t i = 0; i < m; ++i)
    {
      const double x = local[i][0], y = local[i][1];
      residual[i] = local[i][2] -
                    (coefficients[0] + coefficients[1] * x + coefficients[2] * y +
                      coefficients[3] * x * x + coefficients[4] * x * y + coefficients[5] * y * y);
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
      return fit;
    }
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < m; ++i)
  {
    sum += inlier[i] ? residual[i] * residual[i] : 0.0;
  }
  fit.Fitted = true;
  fit.Variance = sum / static_cast<double>(inliers - terms) / ClippedVariance * radius * radius;
  fit.Inliers = inliers;
  // The centre's foot on the fitted surface (the centre is local (0,0,0) shifted by -mean).
  double c[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    c[axis] = -mean[axis];
  }
  const double x = c[0] * frame[0][2] + c[1] * frame[1][2] + c[2] * frame[2][2];
  const double y = c[0] * frame[0][1] + c[1] * frame[1][1] + c[2] * frame[2][1];
  const double z = c[0] * frame[0][0] + c[1] * frame[1][0] + c[2] * frame[2][0];
  std::copy(coefficients, coefficients + QuadricTerms, fit.Coefficients);
  for (int axis = 0; axis < 3; ++axis)
  {
    fit.Origin[axis] = centre[axis] + radius * mean[axis];
    for (int k = 0; k < 3; ++k)
    {
      fit.Frame[axis][k] = frame[axis][k];
    }
  }
  fit.Scale = radius;
  fit.FootX = x;
  fit.FootY = y;
  const double height = fit.Height(x, y);
  for (int axis = 0; axis < 3; ++axis)
  {
    fit.SurfacePoint[axis] = centre[axis] + radius * (height - z) * frame[axis][0];
  }
  // A degenerate neighbourhood (points on a line, say) can solve to non-finite coefficients: no
  // fit, rather than a surface point nowhere.
  fit.Fitted = std::isfinite(fit.Variance) && std::isfinite(height) &&
               std::isfinite(fit.SurfacePoint[0]) && std::isfinite(fit.SurfacePoint[1]) &&
               std::isfinite(fit.SurfacePoint[2]);
  return fit;
}

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

/// The sigma whose VarianceInBall is the measured variance; +infinity when the ball is too
/// small to tell (the heights fill it as if uniformly).
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

double Median(std::vector<double> values)
{
  if (values.empty())
  {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

} // namespace

CloudScales MeasureScales(const PointCloudView& cloud, const ScaleMeasurementOptions& options)
{
  CloudScales scales;
  const CloudExtent extent = MeasureCloud(cloud);
  const std::size_t n = extent.NumberOfFinitePoints;
  if (!(options.PointFraction > 0.0 && options.PointFraction <= 1.0))
  {
    scales.Problem = "the point fraction must be in (0, 1]";
    return scales;
  }
  if (n < 2 * FewestPointsToFit || !(extent.LargestExtent() > 0.0))
  {
    scales.Measurable = false;
    scales.Problem = n < 2 * FewestPointsToFit ? "too few finite points to measure the cloud"
                                               : "the cloud has no extent";
    return scales;
  }

  // The finite points with their keys, and their level: level l holds the points with key
  // < 4^-l.
  std::vector<KeyedPoint> keyed;
  keyed.reserve(n);
  std::vector<std::vector<std::size_t>> levels(1);
  for (std::size_t i = 0; i < cloud.NumberOfPoints; ++i)
  {
    if (!IsFinitePoint(cloud.Positions + 3 * i))
    {
      continue;
    }
    const std::uint64_t key = MeasurementKey(cloud.Positions + 3 * i);
    keyed.push_back({ key, i });
    // Each level keeps the keys whose top 2l bits are zero.
    std::size_t level = 0;
    while (level < 28 && (key >> (62 - 2 * level)) == 0)
    {
      ++level;
    }
    if (levels.size() <= level)
    {
      levels.resize(level + 1);
    }
    for (std::size_t l = 0; l <= level; ++l)
    {
      levels[l].push_back(i);
    }
  }
  while (levels.size() > 1 && levels.back().size() < 256)
  {
    levels.pop_back();
  }

  // A first guess of the density: the bounding box's surface area holds the points (it
  // overstates the area of most surfaces by up to about 2, which only makes the first ball
  // larger).
  const double size[3] = {
    extent.Max[0] - extent.Min[0], extent.Max[1] - extent.Min[1], extent.Max[2] - extent.Min[2]
  };
  const double boxArea = 2.0 * (size[0] * size[1] + size[1] * size[2] + size[2] * size[0]);
  // (A flat box, e.g. points on a line, would give cells of no size.)
  const double largest = extent.LargestExtent();
  double density = static_cast<double>(n) / std::max(boxArea, 1e-4 * largest * largest);
  if (!(std::isfinite(density) && density > 0.0))
  {
    // Coordinates so far apart that areas overflow: the filter refuses such clouds anyway.
    scales.Problem = "the cloud's extent is beyond what can be measured";
    return scales;
  }

  // Grids: level l's cells are about two of its point spacings wide.
  std::vector<HashedGrid> grids;
  for (std::size_t l = 0; l < levels.size(); ++l)
  {
    const double levelDensity =
      density * static_cast<double>(levels[l].size()) / static_cast<double>(n);
    grids.emplace_back(cloud.Positions, levels[l], extent.Min, 2.0 / std::sqrt(levelDensity));
  }

  // The samples: the finite points with the smallest keys (a uniform pseudo-random choice that
  // depends on the points, not on their order), in the order of their keys.
  std::vector<std::size_t> samples = options.SampleIndices;
  if (samples.empty())
  {
    samples = SmallestKeys(cloud, std::move(keyed), std::min(options.NumberOfSamples, n));
  }
  samples.erase(std::remove_if(samples.begin(),
                  samples.end(),
                  [&](std::size_t i)
                  { return i >= cloud.NumberOfPoints || !IsFinitePoint(cloud.Positions + 3 * i); }),
    samples.end());
  scales.NumberOfSamples = samples.size();
  if (samples.empty())
  {
    scales.Problem = "no finite sample points";
    return scales;
  }

  const int threads = ResolveThreadCount(options.NumberOfThreads);
  std::vector<LocalFit> fits(samples.size());
  std::vector<double> fractions(levels.size());
  for (std::size_t l = 0; l < levels.size(); ++l)
  {
    fractions[l] = static_cast<double>(levels[l].size()) / static_cast<double>(n);
  }

  // One round: fit every sample's ball of radius rho; each ball is gathered from the coarsest
  // level that still puts about PointsPerBall points in it.
  auto fitAll = [&](double rho, std::vector<std::size_t>& levelUsed)
  {
    std::size_t level = 0;
    const double expected = density * M_PI * rho * rho;
    while (level + 1 < levels.size() && expected * fractions[level + 1] >= PointsPerBall)
    {
      ++level;
    }
    const HashedGrid& grid = grids[level];
    levelUsed.assign(samples.size(), level);
#pragma omp parallel num_threads(threads)
    {
      std::vector<std::array<double, 3>> points;
#pragma omp for schedule(dynamic, 16)
      for (std::ptrdiff_t s = 0; s < static_cast<std::ptrdiff_t>(samples.size()); ++s)
      {
        // The ball is centred on the surface the sample's previous fit found, as the ball-cut
        // correction assumes; without one yet, a first fit around the sample finds it.
        double centre[3];
        const bool refit = fits[s].Fitted;
        std::copy(refit ? fits[s].SurfacePoint : cloud.Positions + 3 * samples[s],
          (refit ? fits[s].SurfacePoint : cloud.Positions + 3 * samples[s]) + 3,
          centre);
        LocalFit fit;
        for (int pass = refit ? 1 : 0; pass < 2; ++pass)
        {
          GatherBall(grid, cloud.Positions, centre, rho, points);
          fit = FitQuadric(points, centre, rho);
          if (!fit.Fitted)
          {
            break;
          }
          std::copy(fit.SurfacePoint, fit.SurfacePoint + 3, centre);
        }
        fits[s] = fit;
      }
    }
  };

  double rho = std::sqrt(FewestPointsPerBall / (M_PI * density));
  double sigma = 0.0;
  std::vector<std::size_t> levelUsed;
  const double largestRadius = 0.5 * extent.LargestExtent();
  for (int round = 1; round <= MaximumRounds; ++round)
  {
    scales.NumberOfRounds = round;
    fitAll(rho, levelUsed);
    std::vector<double> deviations, densities;
    std::vector<double> inlierCounts;
    for (std::size_t s = 0; s < samples.size(); ++s)
    {
      if (fits[s].Fitted)
      {
        deviations.push_back(std::sqrt(fits[s].Variance));
        inlierCounts.push_back(static_cast<double>(fits[s].Inliers));
      }
    }
    if (deviations.size() < std::max<std::size_t>(8, samples.size() / 10))
    {
      // Balls too sparse to fit: the density guess was too high. Grow and retry.
      rho *= 2.0;
      density *= 0.25;
      if (rho > largestRadius)
      {
        scales.Problem = "no neighbourhood of the cloud could be fitted by a surface";
        return scales;
      }
      continue;
    }
    // A low quantile rather than the median: near edges (and corners) the fit is worse, and at
    // strong noise the balls are wide enough that most samples see an edge. On a flat part the
    // per-sample estimate varies by about 1 / sqrt(2 (m - 6)) (m points), which the quantile's
    // offset from the median corrects.
    std::sort(deviations.begin(), deviations.end());
    const double quantileDeviation =
      deviations[static_cast<std::size_t>(DeviationQuantile * (deviations.size() - 1))];
    const double spread = 1.0 / std::sqrt(2.0 * std::max(Median(inlierCounts) - QuadricTerms, 1.0));
    const double deviation = quantileDeviation / (1.0 - DeviationQuantileScore * spread);
    sigma = SigmaFromBallVariance(deviation * deviation, rho);
    // The density, to size the next ball: the inliers of the well-fitted balls cover a disc of
    // area pi (rho^2 - sigma^2) on average (the slab cut by the ball).
    const double finiteSigma = std::isfinite(sigma) ? sigma : 0.0;
    for (std::size_t s = 0; s < samples.size(); ++s)
    {
      if (fits[s].Fitted && std::sqrt(fits[s].Variance) <= 2.0 * deviation)
      {
        const double area =
          M_PI * std::max(rho * rho - finiteSigma * finiteSigma, 0.25 * rho * rho);
        densities.push_back(
          static_cast<double>(fits[s].Inliers) / (fractions[levelUsed[s]] * area * (1.0 - 0.0027)));
      }
    }
    density = Median(densities);
    const double wanted = std::max(std::sqrt(FewestPointsPerBall / (M_PI * density)),
      std::isfinite(sigma) ? RadiusInSigmas * sigma : 2.0 * rho);
    scales.NeighbourhoodRadius = rho;
    scales.NumberOfFittedSamples = deviations.size();
    if (std::abs(wanted - rho) <= 0.03 * rho || round == MaximumRounds || wanted > largestRadius)
    {
      break;
    }
    rho = wanted;
  }
  if (!std::isfinite(sigma))
  {
    scales.Problem = "the noise is too strong to tell the surface from it";
    return scales;
  }
  scales.NoiseSigma = sigma;

  // The spacing: count the points over a small disc of the fitted surface (within 3 sigma of
  // it, in the slab), holding about DiscPoints points of the level it is counted on. Small, so
  // that borders and density changes blur little; counted in the slab, so that the noise does
  // not matter. The level is the finest whose cells are at least sigma wide, so that the ball
  // around the disc and slab spans a few cells only.
  std::size_t discLevel = 0;
  while (discLevel + 1 < levels.size() && grids[discLevel].GetCellSize() < sigma)
  {
    ++discLevel;
  }
  const double disc = std::sqrt(DiscPoints / (M_PI * density * fractions[discLevel]));
  const double slab = 3.0 * sigma;
  std::vector<double> discDensities(samples.size(), 0.0);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 16)
  for (std::ptrdiff_t s = 0; s < static_cast<std::ptrdiff_t>(samples.size()); ++s)
  {
    const LocalFit& fit = fits[s];
    // Only the fits that look like noise around a smooth surface: near edges the quadric
    // misses the surface at the centre, and the disc would count too few points.
    if (!fit.Fitted || fit.Variance > 4.0 * sigma * sigma)
    {
      continue;
    }
    std::size_t count = 0;
    grids[discLevel].ForEachInBall(fit.SurfacePoint,
      std::sqrt(disc * disc + slab * slab),
      [&](std::size_t index)
      {
        double local[3];
        fit.Local(cloud.Positions + 3 * index, local);
        const double dx = (local[0] - fit.FootX) * fit.Scale;
        const double dy = (local[1] - fit.FootY) * fit.Scale;
        const double height = (local[2] - fit.Height(local[0], local[1])) * fit.Scale;
        count += dx * dx + dy * dy <= disc * disc && std::abs(height) <= slab;
      });
    discDensities[s] =
      static_cast<double>(count) / (fractions[discLevel] * M_PI * disc * disc * (1.0 - 0.0027));
  }
  // The mean of the per-sample spacings (points spread unevenly have the mean of their local
  // spacings as mean nearest-neighbour distance), trimmed by 5% on each side against the few
  // samples whose disc the fit placed badly. Empty discs are outliers: left out.
  std::vector<double> densities, spacings;
  for (double value : discDensities)
  {
    if (value > 0.0)
    {
      densities.push_back(value / options.PointFraction);
      spacings.push_back(0.5 / std::sqrt(value / options.PointFraction));
    }
  }
  if (densities.empty())
  {
    scales.Problem = "no sample has neighbours on its fitted surface";
    return scales;
  }
  std::sort(spacings.begin(), spacings.end());
  const std::size_t trim = spacings.size() / 20;
  double spacingSum = 0.0;
  for (std::size_t k = trim; k < spacings.size() - trim; ++k)
  {
    spacingSum += spacings[k];
  }
  scales.PointSpacing = spacingSum / static_cast<double>(spacings.size() - 2 * trim);

  // Flatness at the scale the filter will work at (1.5 times the automatic radius): on the
  // same points, a plane leaves more residual variance than a quadric where the surface bends
  // or breaks. The excess, in units of sigma^2, is small on flat or gently curved parts,
  // noticeable on curved ones, large near edges.
  scales.FlatnessRadius =
    FlatnessRadiusInSpacings * scales.PointSpacing + FlatnessRadiusInSigmas * sigma;
  {
    const double rho = scales.FlatnessRadius;
    std::size_t level = 0;
    const double expected = density * M_PI * rho * rho;
    while (level + 1 < levels.size() && expected * fractions[level + 1] >= FlatnessPointsPerBall)
    {
      ++level;
    }
    std::vector<double> excess(samples.size(), -1.0);
    std::vector<double> quadricVariance(samples.size(), -1.0);
#pragma omp parallel num_threads(threads)
    {
      std::vector<std::array<double, 3>> points;
#pragma omp for schedule(dynamic, 16)
      for (std::ptrdiff_t s = 0; s < static_cast<std::ptrdiff_t>(samples.size()); ++s)
      {
        if (!fits[s].Fitted)
        {
          continue;
        }
        const double* centre = fits[s].SurfacePoint;
        GatherBall(grids[level], cloud.Positions, centre, rho, points);
        const LocalFit quadric = FitQuadric(points, centre, rho);
        const LocalFit plane = FitQuadric(points, centre, rho, 3);
        if (quadric.Fitted && plane.Fitted)
        {
          excess[s] = (plane.Variance - quadric.Variance) / (sigma * sigma);
          quadricVariance[s] = quadric.Variance / (sigma * sigma);
        }
      }
    }
    std::vector<double> measured;
    std::size_t featured = 0, creased = 0;
    for (std::size_t s = 0; s < excess.size(); ++s)
    {
      if (excess[s] >= -0.5)
      {
        measured.push_back(excess[s]);
        featured += excess[s] > FeatureExcess;
        creased += quadricVariance[s] > CreaseVariance;
      }
    }
    scales.CurvatureExcess = measured.empty() ? 0.0 : Median(measured);
    scales.FeatureFraction =
      measured.empty() ? 1.0 : static_cast<double>(featured) / static_cast<double>(measured.size());
    scales.CreaseFraction =
      measured.empty() ? 1.0 : static_cast<double>(creased) / static_cast<double>(measured.size());
  }
  scales.SurfaceDensity = Median(densities);
  scales.Valid = true;
  return scales;
}

double MeasuredFraction(std::size_t numberOfFinitePoints)
{
  return numberOfFinitePoints <= MaximumMeasuredPoints
           ? 1.0
           : static_cast<double>(MaximumMeasuredPoints) / static_cast<double>(numberOfFinitePoints);
}

std::vector<double> SelectMeasurementPoints(const PointCloudView& cloud, double fraction)
{
  // Selected: SelectionKey / 2^64 < fraction.
  const double threshold = std::ldexp(fraction, 64);
  std::vector<double> selection;
  for (std::size_t i = 0; i < cloud.NumberOfPoints; ++i)
  {
    const double* p = cloud.Positions + 3 * i;
    if (IsFinitePoint(p) && (fraction >= 1.0 || static_cast<double>(SelectionKey(p)) < threshold))
    {
      selection.insert(selection.end(), p, p + 3);
    }
  }
  return selection;
}

CloudScales MeasureSelection(const std::vector<double>& selection, double fraction, int threads)
{
  PointCloudView view;
  view.NumberOfPoints = selection.size() / 3;
  view.Positions = selection.data();
  ScaleMeasurementOptions options;
  options.PointFraction = fraction;
  options.NumberOfThreads = threads;
  return MeasureScales(view, options);
}

CloudScales MeasureWholeCloud(const PointCloudView& cloud, int threads)
{
  const double fraction = MeasuredFraction(MeasureCloud(cloud).NumberOfFinitePoints);
  if (fraction >= 1.0)
  {
    // The selection would be a copy of the finite points; MeasureScales skips the others and
    // does not depend on the order, so the cloud itself gives the same bits.
    ScaleMeasurementOptions options;
    options.NumberOfThreads = threads;
    return MeasureScales(cloud, options);
  }
  return MeasureSelection(SelectMeasurementPoints(cloud, fraction), fraction, threads);
}

bool IsFlat(const CloudScales& scales, const AutomaticRule& rule)
{
  return scales.Valid && scales.CurvatureExcess < rule.FlatExcess &&
         scales.FeatureFraction < rule.FlatFeatureFraction;
}

bool IsSmoothWithThinNoise(const CloudScales& scales, const AutomaticRule& rule)
{
  return scales.Valid && !IsFlat(scales, rule) &&
         scales.CreaseFraction < rule.SmoothCreaseFraction &&
         scales.NoiseSigma < rule.ThinNoiseInSpacings * scales.PointSpacing;
}

BilateralParameters ChooseParameters(const CloudScales& scales,
  const BilateralParameters& userParameters,
  const AutomaticRule& rule)
{
  BilateralParameters parameters = userParameters;
  if (!scales.Valid)
  {
    return parameters;
  }
  const bool flat = IsFlat(scales, rule);
  const bool smooth = IsSmoothWithThinNoise(scales, rule);
  if (parameters.NumberOfIterations <= 0)
  {
    parameters.NumberOfIterations = flat     ? rule.FlatIterations
                                    : smooth ? rule.SmoothIterations
                                             : rule.NumberOfIterations;
  }
  if (!(parameters.Radius > 0.0))
  {
    parameters.Radius =
      (flat      ? rule.FlatRadiusFactor
        : smooth ? rule.SmoothRadiusFactor
                 : 1.0) *
      (rule.RadiusInSpacings * scales.PointSpacing + rule.RadiusInSigmas * scales.NoiseSigma);
  }
  if (!(parameters.NormalRadius > 0.0))
  {
    // A noise-free cloud measures sigma 0 (or round-off): the floor keeps the normal radius
    // positive and computable, far below anything a real noise would give. A smooth surface
    // with thin noise has nothing for the range weight to keep: the normal radius is the
    // radius (plain averaging along the normal), the paper's own choice.
    parameters.NormalRadius =
      smooth ? parameters.Radius
             : std::max(rule.NormalRadiusInSigmas * scales.NoiseSigma, 1e-3 * parameters.Radius);
  }
  return parameters;
}

} // namespace pcbilateral

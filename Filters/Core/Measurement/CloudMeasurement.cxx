// How the scales are measured.
//
// Around each sample point, the points within a radius rho are fitted by a robust quadric
// height function (LocalSurfaceFit.h), whose residuals estimate the noise sigma, corrected for
// the fit's degrees of freedom, the clipping and the ball's cut of the noise's slab. The radius
// must be a few sigmas for the slab to show, yet as small as possible to keep the edges out: it
// is found as a fixed point, rho = 5 sigma(rho) but holding at least ~50 points, starting from
// the smallest ball and growing. The per-sample deviations are read at their 25th percentile,
// not the median: at strong noise the balls are wide enough that most samples see an edge,
// which only raises their deviation.
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
// that it holds about a hundred points. Each level has its own grid (Neighbours/PointGrid.h).
//
// Every per-sample result is stored in its sample's slot and reduced in sample order, so the
// result does not depend on the number of threads.
#include "CloudMeasurement.h"

#include "BitOperations.h"
#include "LocalSurfaceFit.h"
#include "MeasurementSelection.h"
#include "PointGrid.h"
#include "ProgressCheck.h"
#include "Threads.h"

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
/// The measurement grids' cells, in point spacings of their level: wide enough that a ball of
/// about PointsPerBall points spans a few cells along each axis, so that a search makes few
/// hash probes. (Any width gives the same results: the searches return every point in the ball.)
constexpr double GridCellSpacings = 4.0;
/// A sample whose quadric fit at the flatness radius leaves more than CreaseVariance sigma^2
/// of residual variance sees a crease: no smooth surface fits there. On the smooth shapes of
/// pcb_quality (spheres, terrains) no sample exceeds 2; on the shapes with edges at 0.1% noise,
/// 4% to 28% of them do (at stronger noise the quadric absorbs more of a blunt edge).
constexpr double CreaseVariance = 2.0;
/// Points whose nearest-neighbour distance is measured for its percentiles: enough for the 5th
/// percentile to be read on some 400 points, a small cost next to the fits.
constexpr std::size_t NearestNeighbourSamples = 8192;
/// The structured-noise check (CheckStructuredNoise): the ball's radius in units of the noise
/// fits' radius, and how much more noise it must read there to count as structured.
constexpr double StructureScale = 4.0;
constexpr double StructuredNoiseRatio = 3.0;
/// ... and the fraction of the small balls it needs that fit their points exactly: with a
/// residual below ExactFit times the noise the small balls read.
constexpr double ExactFit = 0.1;
constexpr double ExactFitFraction = 0.1;
/// Points in the disc that measures the density.
constexpr double DiscPoints = 40.0;

/// The points of the grid within rho of centre, relative to centre in units of rho, in a fixed
/// order (lexicographic by coordinates), so that the fits' sums do not depend on the order the
/// cloud lists its points in (equal points are interchangeable).
void GatherBall(const PointGrid& grid,
  const double centre[3],
  double rho,
  std::vector<std::array<double, 3>>& points)
{
  const double* x = grid.GetX();
  const double* y = grid.GetY();
  const double* z = grid.GetZ();
  const double rhoSquared = rho * rho;
  std::size_t count = 0;
  grid.ForEachRunAroundBall(centre,
    rho,
    [&](std::size_t begin, std::size_t end)
    {
      // Every point written to the next slot and counted only when in the ball (ForEachInBall's
      // test): a branch on it would be mispredicted for many of the points near the sphere.
      points.resize(count + (end - begin));
      for (std::size_t i = begin; i < end; ++i)
      {
        const double dx = x[i] - centre[0], dy = y[i] - centre[1], dz = z[i] - centre[2];
        points[count] = { dx / rho, dy / rho, dz / rho };
        count += dx * dx + dy * dy + dz * dz <= rhoSquared;
      }
    });
  points.resize(count);
  std::sort(points.begin(), points.end());
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

/// The steps of MeasureScales, on one cloud: each fills part of Scales, or sets its Problem and
/// returns false.
class ScaleMeasurement
{
public:
  /// pointKeys: the MeasurementKey of each point of the cloud, when the caller has them, or
  /// null.
  ScaleMeasurement(const PointCloudView& cloud,
    const ScaleMeasurementOptions& options,
    const std::uint64_t* pointKeys = nullptr)
    : Cloud(cloud)
    , Options(options)
    , PointKeys(pointKeys)
    , Extent(MeasureCloud(cloud))
    , N(Extent.NumberOfFinitePoints)
    , Threads(ResolveThreadCount(options.NumberOfThreads))
  {
  }

  CloudScales Measure()
  {
    // Progress and abort between the steps (ProgressPoint): the whole cloud's selection was the
    // first half of the measurement when there was one, these steps are the rest.
    const std::uint64_t total = this->PointKeys != nullptr ? 20 : 10;
    const std::uint64_t done = total - 10;
    const auto stopped = [&](std::uint64_t step)
    {
      if (ProgressPoint(done + step, total))
      {
        this->Scales.Problem = AbortedMessage;
        return true;
      }
      return false;
    };
    if (!(this->CheckCloud() && !stopped(0) && this->SortIntoLevels() && !stopped(1) &&
          this->GuessDensity() && !stopped(2) && this->BuildGrids() && !stopped(3) &&
          this->ChooseSamples() && !stopped(4)))
    {
      return this->Scales;
    }
    this->MeasureNeighbourDistances();
    if (!stopped(5) && this->FindNoise() && !stopped(7) && this->MeasureSpacing() && !stopped(8))
    {
      this->MeasureFlatness();
      this->CheckStructuredNoise();
      this->Scales.Valid = !stopped(10);
    }
    return this->Scales;
  }

private:
  bool Fail(const char* problem)
  {
    this->Scales.Problem = problem;
    return false;
  }

  bool CheckCloud()
  {
    if (!(this->Options.PointFraction > 0.0 && this->Options.PointFraction <= 1.0))
    {
      return this->Fail("the point fraction must be in (0, 1]");
    }
    if (this->Cloud.NumberOfPoints > std::numeric_limits<std::uint32_t>::max())
    {
      // (The grids number points in 32 bits; the filter measures at most a selection of
      // MaximumMeasuredPoints.)
      return this->Fail("more than 2^32 points to measure");
    }
    if (this->N < 2 * FewestPointsToFit || !(this->Extent.LargestExtent() > 0.0))
    {
      this->Scales.Measurable = false;
      return this->Fail(this->N < 2 * FewestPointsToFit
                          ? "too few finite points to measure the cloud"
                          : "the cloud has no extent");
    }
    return true;
  }

  /// The finite points with their keys, and their level: level l holds the points with key
  /// < 4^-l.
  bool SortIntoLevels()
  {
    this->Keyed.reserve(this->N);
    this->Levels.assign(1, {});
    this->Levels[0].reserve(this->N);
    // The deepest level of each point: level l keeps the keys whose top 2l bits are zero.
    std::vector<std::uint8_t> deepest(this->Cloud.NumberOfPoints, 0);
    for (std::size_t i = 0; i < this->Cloud.NumberOfPoints; ++i)
    {
      if (!IsFinitePoint(this->Cloud.Positions + 3 * i))
      {
        continue;
      }
      const std::uint64_t key = this->PointKeys != nullptr
                                  ? this->PointKeys[i]
                                  : MeasurementKey(this->Cloud.Positions + 3 * i);
      this->Keyed.push_back({ key, i });
      this->Levels[0].push_back(static_cast<std::uint32_t>(i));
      deepest[i] = static_cast<std::uint8_t>(std::min(28, CountLeadingZeros(key) / 2));
    }
    // Each level from the one above it, every point written to the next slot and counted only
    // when it belongs (a branch on the keys' bits would be mispredicted a quarter of the time).
    while (this->Levels.back().size() >= 256)
    {
      const std::vector<std::uint32_t>& above = this->Levels.back();
      const auto level = static_cast<std::uint8_t>(this->Levels.size());
      std::vector<std::uint32_t> points(above.size() + 1);
      std::size_t count = 0;
      for (std::uint32_t i : above)
      {
        points[count] = i;
        count += deepest[i] >= level;
      }
      if (count == 0)
      {
        break;
      }
      points.resize(count);
      this->Levels.push_back(std::move(points));
    }
    while (this->Levels.size() > 1 && this->Levels.back().size() < 256)
    {
      this->Levels.pop_back();
    }
    for (const auto& level : this->Levels)
    {
      this->Fractions.push_back(static_cast<double>(level.size()) / static_cast<double>(this->N));
    }
    return true;
  }

  /// A first guess of the density: the bounding box's surface area holds the points (it
  /// overstates the area of most surfaces by up to about 2, which only makes the first ball
  /// larger).
  bool GuessDensity()
  {
    const CloudExtent& extent = this->Extent;
    const double size[3] = {
      extent.Max[0] - extent.Min[0], extent.Max[1] - extent.Min[1], extent.Max[2] - extent.Min[2]
    };
    const double boxArea = 2.0 * (size[0] * size[1] + size[1] * size[2] + size[2] * size[0]);
    // (A flat box, e.g. points on a line, would give cells of no size.)
    const double largest = extent.LargestExtent();
    this->Density = static_cast<double>(this->N) / std::max(boxArea, 1e-4 * largest * largest);
    this->FirstDensity = this->Density;
    // (Above 1e300 points per unit area, the balls' expected counts, density x pi rho^2,
    // would overflow: LevelFor compares them.)
    if (!(std::isfinite(this->Density) && this->Density > 0.0 && this->Density < 1e300))
    {
      // Coordinates so far apart that areas overflow: the filter refuses such clouds anyway.
      return this->Fail("the cloud's extent is beyond what can be measured");
    }
    return true;
  }

  /// Grids: level l's cells are about GridCellSpacings of its point spacings wide. Level 0 (the
  /// nearest-neighbour distances' grid) now; the others when a step first needs them (GridAt):
  /// most clouds use two or three of them.
  bool BuildGrids()
  {
    this->Grids.resize(this->Levels.size());
    this->GridBuilt.assign(this->Levels.size(), false);
    if (!this->BuildGrid(0))
    {
      // (A cloud so spread out that its cells cannot be numbered, e.g. a few points far
      // from a dense part: the filter refuses such clouds too. Coarser levels have wider
      // cells, so they can be numbered when level 0 can.)
      return this->Fail("the cloud's extent is beyond what can be measured");
    }
    return true;
  }

  bool BuildGrid(std::size_t level)
  {
    this->GridBuilt[level] = true;
    // (Any order: GatherBall sorts what it gathers, and the disc only counts.)
    return this->Grids[level].Build(this->Cloud.Positions,
      this->Levels[level],
      this->Extent.Min,
      0.5 * GridCellSpacings * this->TwoSpacings(level),
      PointGrid::PointOrder::Any);
  }

  /// Level `level`'s grid, built on first use (outside the parallel loops that read it).
  const PointGrid& GridAt(std::size_t level)
  {
    if (!this->GridBuilt[level])
    {
      this->BuildGrid(level);
    }
    return this->Grids[level];
  }

  /// Two point spacings of level l at the first guess of the density (the width of the grids'
  /// cells when the choice of levels below was tuned).
  double TwoSpacings(std::size_t l) const
  {
    return 2.0 / std::sqrt(this->FirstDensity * this->Fractions[l]);
  }

  /// The samples: the finite points with the smallest keys (a uniform pseudo-random choice that
  /// depends on the points, not on their order), in the order of their keys.
  bool ChooseSamples()
  {
    const PointCloudView& cloud = this->Cloud;
    // The fits' samples are the first of the nearest-neighbour distances' samples (the keys in
    // order), so that measuring the distances leaves the fits as they were.
    const std::size_t count =
      std::min(std::max(this->Options.NumberOfSamples, NearestNeighbourSamples), this->N);
    // The smallest keys are those of the deepest level that holds enough of them (level l:
    // keys below 2^(64 - 2l)): only its points need to be ordered.
    std::size_t level = 0;
    while (level + 1 < this->Levels.size() && this->Levels[level + 1].size() >= count)
    {
      ++level;
    }
    if (level > 0)
    {
      const std::uint64_t bound = std::uint64_t(1) << (64 - 2 * level);
      this->Keyed.erase(std::remove_if(this->Keyed.begin(),
                          this->Keyed.end(),
                          [&](const KeyedPoint& point) { return point.Key >= bound; }),
        this->Keyed.end());
    }
    this->DistanceSamples = SmallestKeys(cloud, std::move(this->Keyed), count);
    this->Samples = this->Options.SampleIndices;
    if (this->Samples.empty())
    {
      this->Samples.assign(this->DistanceSamples.begin(),
        this->DistanceSamples.begin() +
          static_cast<std::ptrdiff_t>(
            std::min(this->Options.NumberOfSamples, this->DistanceSamples.size())));
    }
    auto unusable = [&](std::size_t i)
    { return i >= cloud.NumberOfPoints || !IsFinitePoint(cloud.Positions + 3 * i); };
    this->Samples.erase(
      std::remove_if(this->Samples.begin(), this->Samples.end(), unusable), this->Samples.end());
    this->Scales.NumberOfSamples = this->Samples.size();
    if (this->Samples.empty())
    {
      return this->Fail("no finite sample points");
    }
    this->Fits.resize(this->Samples.size());
    return true;
  }

  /// The distance from sample point `index` to its nearest other point of the finest grid (the
  /// whole selection): balls of growing radius, from one spacing, until one holds another point;
  /// the nearest in that ball is the nearest of all. 0 for a point that has a duplicate.
  double NearestNeighbourDistance(std::size_t index) const
  {
    const PointGrid& grid = this->Grids[0];
    const double* p = this->Cloud.Positions + 3 * index;
    const double* x = grid.GetX();
    const double* y = grid.GetY();
    const double* z = grid.GetZ();
    const std::uint32_t* ids = grid.GetIds();
    // (A ball twice the cloud's extent holds every point.)
    const double wholeCloud = 2.0 * this->Extent.LargestExtent();
    // (From one point spacing, within which 96% of the points of an even surface have a
    // neighbour: a ball that spans a few cells.)
    for (double radius = 0.5 * this->TwoSpacings(0); radius <= 2.0 * wholeCloud; radius *= 2.0)
    {
      // The nearest of every point around the ball: when it lies in the ball, no point outside
      // the cells looked at is nearer.
      double nearest = std::numeric_limits<double>::infinity();
      grid.ForEachRunAroundBall(p,
        radius,
        [&](std::size_t begin, std::size_t end)
        {
          for (std::size_t i = begin; i < end; ++i)
          {
            const double dx = x[i] - p[0], dy = y[i] - p[1], dz = z[i] - p[2];
            const double distanceSquared = dx * dx + dy * dy + dz * dz;
            nearest = ids[i] != index ? std::min(nearest, distanceSquared) : nearest;
          }
        });
      if (nearest <= radius * radius)
      {
        return std::sqrt(nearest);
      }
    }
    return std::numeric_limits<double>::quiet_NaN(); // (a single point: cannot happen here)
  }

  /// The positions in `points` (indices of cloud points) in the order of their cells of a coarse
  /// grid (32 cells along the largest extent): searches done in that order find the grid's
  /// memory warm. (Each result goes to its own slot: the order changes no result.)
  std::vector<std::size_t> SpatialOrder(const std::vector<std::size_t>& points) const
  {
    const double cell = this->Extent.LargestExtent() / 32.0;
    std::vector<std::pair<std::uint32_t, std::size_t>> keyed(points.size());
    for (std::size_t k = 0; k < points.size(); ++k)
    {
      const double* p = this->Cloud.Positions + 3 * points[k];
      std::uint32_t key = 0;
      for (int axis = 0; axis < 3; ++axis)
      {
        const double at = std::floor((p[axis] - this->Extent.Min[axis]) / cell);
        key = 33 * key + static_cast<std::uint32_t>(std::min(std::max(at, 0.0), 32.0));
      }
      keyed[k] = { key, k };
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<std::size_t> order(points.size());
    for (std::size_t k = 0; k < points.size(); ++k)
    {
      order[k] = keyed[k].second;
    }
    return order;
  }

  /// The 5th, 50th and 95th percentiles of the distance from a point to its nearest neighbour,
  /// over up to NearestNeighbourSamples points; for a selection, scaled by the square root of
  /// its fraction of the cloud (the distances of a random thinning of a surface grow as one
  /// over the square root of its density).
  void MeasureNeighbourDistances()
  {
    const std::size_t count = this->DistanceSamples.size();
    std::vector<double> distances(count);
    const std::vector<std::size_t> order = this->SpatialOrder(this->DistanceSamples);
#pragma omp parallel for num_threads(this->Threads) schedule(dynamic, 64)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(count); ++k)
    {
      const std::size_t s = order[static_cast<std::size_t>(k)];
      distances[s] = this->NearestNeighbourDistance(this->DistanceSamples[s]);
    }
    const double thinning = std::sqrt(this->Options.PointFraction);
    std::vector<double> positions(3 * count), scaled(count);
    for (std::size_t s = 0; s < count; ++s)
    {
      std::copy_n(this->Cloud.Positions + 3 * this->DistanceSamples[s], 3, &positions[3 * s]);
      scaled[s] = thinning * distances[s];
    }
    auto field = std::make_shared<SpacingField>(positions, scaled, this->Threads);
    if (field->IsValid())
    {
      this->Scales.LocalSpacing = std::move(field);
    }
    distances.erase(
      std::remove_if(
        distances.begin(), distances.end(), [](double d) { return !std::isfinite(d); }),
      distances.end());
    if (distances.empty())
    {
      return;
    }
    std::sort(distances.begin(), distances.end());
    const double quantiles[3] = { 0.05, 0.5, 0.95 };
    for (int k = 0; k < 3; ++k)
    {
      const auto at =
        static_cast<std::size_t>(quantiles[k] * static_cast<double>(distances.size() - 1));
      this->Scales.NearestNeighbourDistance[k] = thinning * distances[at];
    }
    this->Scales.NumberOfDistanceSamples = distances.size();
  }

  /// The coarsest level whose grid still puts about `points` points in a ball of radius rho.
  std::size_t LevelFor(double rho, double points) const
  {
    std::size_t level = 0;
    const double expected = this->Density * M_PI * rho * rho;
    while (level + 1 < this->Levels.size() && expected * this->Fractions[level + 1] >= points)
    {
      ++level;
    }
    return level;
  }

  /// One round: fits every sample's ball of radius rho, gathered from the coarsest level that
  /// still puts about PointsPerBall points in it.
  void FitAll(double rho)
  {
    const std::size_t level = this->LevelFor(rho, PointsPerBall);
    const PointGrid& grid = this->GridAt(level);
    this->LevelUsed.assign(this->Samples.size(), level);
#pragma omp parallel num_threads(this->Threads)
    {
      std::vector<std::array<double, 3>> points;
#pragma omp for schedule(dynamic, 16)
      for (std::ptrdiff_t s = 0; s < static_cast<std::ptrdiff_t>(this->Samples.size()); ++s)
      {
        // The ball is centred on the surface the sample's previous fit found, as the ball-cut
        // correction assumes; without one yet, a first fit around the sample finds it.
        LocalFit& previous = this->Fits[s];
        const bool refit = previous.Fitted;
        const double* start =
          refit ? previous.SurfacePoint : this->Cloud.Positions + 3 * this->Samples[s];
        double centre[3] = { start[0], start[1], start[2] };
        LocalFit fit;
        for (int pass = refit ? 1 : 0; pass < 2; ++pass)
        {
          GatherBall(grid, centre, rho, points);
          fit = FitQuadric(points, centre, rho);
          if (!fit.Fitted)
          {
            break;
          }
          std::copy(fit.SurfacePoint, fit.SurfacePoint + 3, centre);
        }
        previous = fit;
      }
    }
  }

  /// The noise seen by the fits of radius rho, and the density their inliers give. False when
  /// too few balls could be fitted.
  bool ReadRound(double rho, double& deviation, double& sigma)
  {
    std::vector<double> deviations, inlierCounts;
    for (const LocalFit& fit : this->Fits)
    {
      if (fit.Fitted)
      {
        deviations.push_back(std::sqrt(fit.Variance));
        inlierCounts.push_back(static_cast<double>(fit.Inliers));
      }
    }
    if (deviations.size() < std::max<std::size_t>(8, this->Samples.size() / 10))
    {
      return false;
    }
    this->Scales.NumberOfFittedSamples = deviations.size();
    // A low quantile rather than the median: near edges (and corners) the fit is worse, and at
    // strong noise the balls are wide enough that most samples see an edge. On a flat part the
    // per-sample estimate varies by about 1 / sqrt(2 (m - 6)) (m points), which the quantile's
    // offset from the median corrects.
    std::sort(deviations.begin(), deviations.end());
    const double quantileDeviation =
      deviations[static_cast<std::size_t>(DeviationQuantile * (deviations.size() - 1))];
    const double spread = 1.0 / std::sqrt(2.0 * std::max(Median(inlierCounts) - QuadricTerms, 1.0));
    deviation = quantileDeviation / (1.0 - DeviationQuantileScore * spread);
    sigma = SigmaFromBallVariance(deviation * deviation, rho);
    // The density, to size the next ball: the inliers of the well-fitted balls cover a disc of
    // area pi (rho^2 - sigma^2) on average (the slab cut by the ball).
    const double finiteSigma = std::isfinite(sigma) ? sigma : 0.0;
    const double area = M_PI * std::max(rho * rho - finiteSigma * finiteSigma, 0.25 * rho * rho);
    std::vector<double> densities;
    for (std::size_t s = 0; s < this->Samples.size(); ++s)
    {
      const LocalFit& fit = this->Fits[s];
      if (fit.Fitted && std::sqrt(fit.Variance) <= 2.0 * deviation)
      {
        densities.push_back(static_cast<double>(fit.Inliers) /
                            (this->Fractions[this->LevelUsed[s]] * area * (1.0 - 0.0027)));
      }
    }
    this->Density = Median(densities);
    return true;
  }

  /// The noise: the radius of the fits is a fixed point, rho = RadiusInSigmas sigma(rho) but
  /// holding at least FewestPointsPerBall points, from the smallest ball, growing.
  bool FindNoise()
  {
    double rho = std::sqrt(FewestPointsPerBall / (M_PI * this->Density));
    double sigma = 0.0;
    const double largestRadius = 0.5 * this->Extent.LargestExtent();
    for (int round = 1; round <= MaximumRounds; ++round)
    {
      this->Scales.NumberOfRounds = round;
      this->FitAll(rho);
      double deviation = 0.0;
      if (!this->ReadRound(rho, deviation, sigma))
      {
        // Balls too sparse to fit: the density guess was too high. Grow and retry.
        rho *= 2.0;
        this->Density *= 0.25;
        if (rho > largestRadius)
        {
          return this->Fail("no neighbourhood of the cloud could be fitted by a surface");
        }
        continue;
      }
      const double wanted = std::max(std::sqrt(FewestPointsPerBall / (M_PI * this->Density)),
        std::isfinite(sigma) ? RadiusInSigmas * sigma : 2.0 * rho);
      this->Scales.NeighbourhoodRadius = rho;
      if (std::abs(wanted - rho) <= 0.03 * rho || round == MaximumRounds || wanted > largestRadius)
      {
        break;
      }
      rho = wanted;
    }
    if (!std::isfinite(sigma))
    {
      return this->Fail("the noise is too strong to tell the surface from it");
    }
    this->Scales.NoiseSigma = sigma;
    return true;
  }

  /// The points of the level-`level` grid over a disc of `disc` around the fit's foot on its
  /// surface, within `slab` of it, per unit area.
  double DiscDensity(const LocalFit& fit, std::size_t level, double disc, double slab) const
  {
    const PointGrid& grid = this->Grids[level];
    std::size_t count = 0;
    grid.ForEachInBall(fit.SurfacePoint,
      std::sqrt(disc * disc + slab * slab),
      [&](std::size_t i, double)
      {
        const double q[3] = { grid.GetX()[i], grid.GetY()[i], grid.GetZ()[i] };
        double local[3];
        fit.Local(q, local);
        const double dx = (local[0] - fit.FootX) * fit.Scale;
        const double dy = (local[1] - fit.FootY) * fit.Scale;
        const double height = (local[2] - fit.Height(local[0], local[1])) * fit.Scale;
        count += dx * dx + dy * dy <= disc * disc && std::abs(height) <= slab;
      });
    return static_cast<double>(count) /
           (this->Fractions[level] * M_PI * disc * disc * (1.0 - 0.0027));
  }

  /// The spacing: the points counted over a small disc of each fitted surface (within 3 sigma
  /// of it, in the slab), holding about DiscPoints points of the level it is counted on. Small,
  /// so that borders and density changes blur little; counted in the slab, so that the noise
  /// does not matter. The level is the finest whose two point spacings are at least sigma, so
  /// that the ball around the disc and slab spans a few cells only.
  bool MeasureSpacing()
  {
    const double sigma = this->Scales.NoiseSigma;
    std::size_t level = 0;
    while (level + 1 < this->Levels.size() && this->TwoSpacings(level) < sigma)
    {
      ++level;
    }
    const double disc = std::sqrt(DiscPoints / (M_PI * this->Density * this->Fractions[level]));
    this->GridAt(level);
    std::vector<double> discDensities(this->Samples.size(), 0.0);
#pragma omp parallel for num_threads(this->Threads) schedule(dynamic, 16)
    for (std::ptrdiff_t s = 0; s < static_cast<std::ptrdiff_t>(this->Samples.size()); ++s)
    {
      // Only the fits that look like noise around a smooth surface: near edges the quadric
      // misses the surface at the centre, and the disc would count too few points.
      const LocalFit& fit = this->Fits[s];
      if (fit.Fitted && fit.Variance <= 4.0 * sigma * sigma)
      {
        discDensities[s] = this->DiscDensity(fit, level, disc, 3.0 * sigma);
      }
    }
    // The mean of the per-sample spacings weighted by the area each sample's point covers (its
    // spacing squared): on a cloud sampled a hundred times more densely in one corner, the
    // spacing of most of the surface, not of most of the points. Trimmed by 5% on each side
    // against the few samples whose disc the fit placed badly. Empty discs are outliers: left
    // out.
    std::vector<double> densities, spacings;
    std::vector<std::size_t> spacingSamples;
    for (std::size_t s = 0; s < discDensities.size(); ++s)
    {
      if (discDensities[s] > 0.0)
      {
        const double density = discDensities[s] / this->Options.PointFraction;
        densities.push_back(density);
        spacings.push_back(0.5 / std::sqrt(density));
        spacingSamples.push_back(s);
      }
    }
    if (densities.empty())
    {
      return this->Fail("no sample has neighbours on its fitted surface");
    }
    this->RelateToField(spacings, spacingSamples);
    std::sort(spacings.begin(), spacings.end());
    const std::size_t trim = spacings.size() / 20;
    double areaSum = 0.0, weightedSum = 0.0;
    for (std::size_t k = trim; k < spacings.size() - trim; ++k)
    {
      areaSum += spacings[k] * spacings[k];
      weightedSum += spacings[k] * spacings[k] * spacings[k];
    }
    this->Scales.PointSpacing = weightedSum / areaSum;
    this->Scales.SurfaceDensity = Median(densities);
    return true;
  }

  /// SpacingPerNeighbourDistance: the samples' spacings (of samples spacingSamples) over the
  /// spacing field's value at them, their median.
  void RelateToField(const std::vector<double>& spacings,
    const std::vector<std::size_t>& spacingSamples)
  {
    if (!this->Scales.LocalSpacing)
    {
      return;
    }
    std::vector<double> ratios;
    for (std::size_t k = 0; k < spacings.size(); ++k)
    {
      const double field =
        this->Scales.LocalSpacing->At(this->Cloud.Positions + 3 * this->Samples[spacingSamples[k]]);
      if (field > 0.0)
      {
        ratios.push_back(spacings[k] / field);
      }
    }
    this->Scales.SpacingPerNeighbourDistance = Median(ratios);
  }

  /// Flatness at the scale the filter will work at (1.5 times the automatic radius): on the
  /// same points, a plane leaves more residual variance than a quadric where the surface bends
  /// or breaks. The excess, in units of sigma^2, is small on flat or gently curved parts,
  /// noticeable on curved ones, large near edges.
  void MeasureFlatness()
  {
    const double sigma = this->Scales.NoiseSigma;
    const double rho =
      FlatnessRadiusInSpacings * this->Scales.PointSpacing + FlatnessRadiusInSigmas * sigma;
    this->Scales.FlatnessRadius = rho;
    const PointGrid& grid = this->GridAt(this->LevelFor(rho, FlatnessPointsPerBall));
    std::vector<double> excess(this->Samples.size(), -1.0);
    std::vector<double> quadricVariance(this->Samples.size(), -1.0);
#pragma omp parallel num_threads(this->Threads)
    {
      std::vector<std::array<double, 3>> points;
#pragma omp for schedule(dynamic, 16)
      for (std::ptrdiff_t s = 0; s < static_cast<std::ptrdiff_t>(this->Samples.size()); ++s)
      {
        if (!this->Fits[s].Fitted)
        {
          continue;
        }
        const double* centre = this->Fits[s].SurfacePoint;
        GatherBall(grid, centre, rho, points);
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
    const double count = static_cast<double>(measured.size());
    this->Scales.CurvatureExcess = measured.empty() ? 0.0 : Median(measured);
    this->Scales.FeatureFraction = measured.empty() ? 1.0 : static_cast<double>(featured) / count;
    this->Scales.CreaseFraction = measured.empty() ? 1.0 : static_cast<double>(creased) / count;
  }

  /// Noise with structure at a larger scale than the fits' balls: a depth camera's quantised
  /// depths put the points of a wall on flat terraces a few millimetres apart, so a small ball,
  /// on one terrace, sees no noise at all, while the filter must smooth the steps. Gaussian noise
  /// reads the same in a ball StructureScale times wider (the quadric takes the curvature, and
  /// the quantile keeps the edges out); where it reads StructuredNoiseRatio times more, that is
  /// the noise the filter has to remove.
  void CheckStructuredNoise()
  {
    const double rho = StructureScale * this->Scales.NeighbourhoodRadius;
    if (!(rho < 0.5 * this->Extent.LargestExtent()))
    {
      return;
    }
    // Terraces first (free): the small balls of many samples fit their points exactly, far
    // below the noise they read. No Gaussian noise does that; vegetation on a terrain reads
    // more at a larger scale too, but no small ball of it is exact.
    std::size_t exact = 0, count = 0;
    for (const LocalFit& fit : this->Fits)
    {
      count += fit.Fitted;
      exact += fit.Fitted && std::sqrt(fit.Variance) < ExactFit * this->Scales.NoiseSigma;
    }
    if (exact < ExactFitFraction * static_cast<double>(count))
    {
      return;
    }
    // The fits, the density and the levels stay those of the measurement.
    const std::vector<LocalFit> fits = this->Fits;
    const std::vector<std::size_t> levels = this->LevelUsed;
    const double density = this->Density;
    const std::size_t fitted = this->Scales.NumberOfFittedSamples;
    this->FitAll(rho);
    double deviation = 0.0, sigma = 0.0;
    const bool read = this->ReadRound(rho, deviation, sigma);
    this->Fits = fits;
    this->LevelUsed = levels;
    this->Density = density;
    this->Scales.NumberOfFittedSamples = fitted;
    if (read && std::isfinite(sigma) && sigma > StructuredNoiseRatio * this->Scales.NoiseSigma)
    {
      this->Scales.NoiseSigma = sigma;
      this->Scales.StructuredNoise = true;
    }
  }

  const PointCloudView& Cloud;
  const ScaleMeasurementOptions& Options;
  const std::uint64_t* PointKeys;
  const CloudExtent Extent;
  const std::size_t N;
  const int Threads;
  CloudScales Scales;
  std::vector<KeyedPoint> Keyed;
  std::vector<std::vector<std::uint32_t>> Levels;
  /// The fraction of the finite points each level holds.
  std::vector<double> Fractions;
  std::vector<PointGrid> Grids;
  std::vector<bool> GridBuilt;
  /// The current estimate of the number of points per unit area of surface.
  double Density = 0.0;
  double FirstDensity = 0.0;
  std::vector<std::size_t> Samples;
  /// The points whose nearest-neighbour distance is measured; the first of them are Samples
  /// unless the options name these.
  std::vector<std::size_t> DistanceSamples;
  std::vector<LocalFit> Fits;
  /// The level each sample's last fit was gathered from.
  std::vector<std::size_t> LevelUsed;
};

} // namespace

CloudScales MeasureScales(const PointCloudView& cloud, const ScaleMeasurementOptions& options)
{
  return ScaleMeasurement(cloud, options).Measure();
}

namespace
{
/// MeasureSelection, with the selected points' MeasurementKey at hand (null: computed).
CloudScales MeasureSelected(const std::vector<double>& selection,
  double fraction,
  int threads,
  const std::uint64_t* keys)
{
  PointCloudView view;
  view.NumberOfPoints = selection.size() / 3;
  view.Positions = selection.data();
  ScaleMeasurementOptions options;
  options.PointFraction = fraction;
  options.NumberOfThreads = threads;
  return ScaleMeasurement(view, options, keys).Measure();
}
} // namespace

CloudScales MeasureSelection(const std::vector<double>& selection, double fraction, int threads)
{
  return MeasureSelected(selection, fraction, threads, nullptr);
}

CloudScales MeasureWholeCloud(const PointCloudView& cloud, int threads)
{
  return MeasureWholeCloud(cloud, MeasureCloud(cloud).NumberOfFinitePoints, threads);
}

CloudScales MeasureWholeCloud(const PointCloudView& cloud,
  std::size_t numberOfFinitePoints,
  int threads)
{
  const double fraction = MeasuredFraction(numberOfFinitePoints);
  if (fraction >= 1.0)
  {
    // The selection would be a copy of the finite points; MeasureScales skips the others and
    // does not depend on the order, so the cloud itself gives the same bits.
    ScaleMeasurementOptions options;
    options.NumberOfThreads = threads;
    return MeasureScales(cloud, options);
  }
  // (The selection's keys are computed on the way: the levels need them again.)
  std::vector<std::uint64_t> keys;
  const std::vector<double> selection = SelectWithKeys(cloud, fraction, &keys);
  return MeasureSelected(selection, fraction, threads, keys.data());
}

} // namespace pcbilateral

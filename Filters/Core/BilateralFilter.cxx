#include "BilateralFilter.h"

#include "BilateralKernel.h"
#include "CellColoringScheduler.h"
#include "HugePages.h"
#include "ProcessingOctree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcbilateral
{

namespace
{
std::string Describe(const char* what, double value)
{
  std::ostringstream message;
  message << what << " must be a finite number >= 0 (0 means automatic), got " << value;
  return message.str();
}

int ResolveThreadCount(int requested)
{
#ifdef _OPENMP
  return requested > 0 ? requested : omp_get_max_threads();
#else
  (void)requested;
  return 1;
#endif
}

/// The largest extent of a cloud, in radii, whose octree lattice coordinates stay far inside
/// 64-bit integers.
constexpr double MaximumExtentInRadii = 1e15;
/// Positions stay below this magnitude, far from overflow.
constexpr double MaximumMagnitude = 1e300;
/// More iterations than this are refused: the paper uses a few, and each one may move the points
/// by up to the radius, so that thousands would only collapse the cloud, slowly.
constexpr int MaximumIterations = 1000;
/// Above this mean number of neighbours per point, the run is warned about: it will be slow,
/// and the radius was probably meant smaller (the paper's clouds have tens to hundreds).
constexpr double ManyNeighbours = 10000.0;

bool IsFiniteExtent(const CloudExtent& extent)
{
  return IsFinitePoint(extent.Min) && IsFinitePoint(extent.Max);
}
} // namespace

double AutomaticRadius(std::size_t numberOfPoints, double largestExtent)
{
  if (numberOfPoints == 0)
  {
    return 0.0;
  }
  return std::sqrt(20.0 / static_cast<double>(numberOfPoints)) * largestExtent;
}

double CloudExtent::LargestExtent() const
{
  return std::max(
    { this->Max[0] - this->Min[0], this->Max[1] - this->Min[1], this->Max[2] - this->Min[2] });
}

double CloudExtent::LargestMagnitude() const
{
  double largest = 0.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    largest = std::max({ largest, std::abs(this->Min[axis]), std::abs(this->Max[axis]) });
  }
  return largest;
}

CloudExtent MeasureCloud(const PointCloudView& cloud)
{
  CloudExtent extent;
  for (std::size_t i = 0; i < cloud.NumberOfPoints; ++i)
  {
    const double* p = cloud.Positions + 3 * i;
    if (!IsFinitePoint(p))
    {
      continue;
    }
    const bool first = extent.NumberOfFinitePoints == 0;
    for (int axis = 0; axis < 3; ++axis)
    {
      extent.Min[axis] = first ? p[axis] : std::min(extent.Min[axis], p[axis]);
      extent.Max[axis] = first ? p[axis] : std::max(extent.Max[axis], p[axis]);
    }
    ++extent.NumberOfFinitePoints;
  }
  return extent;
}

RadiiUsed ResolveRadii(const BilateralParameters& parameters, const CloudExtent& extent)
{
  RadiiUsed radii;
  radii.Radius = parameters.Radius > 0.0
                   ? parameters.Radius
                   : AutomaticRadius(extent.NumberOfFinitePoints, extent.LargestExtent());
  radii.NormalRadius = parameters.NormalRadius > 0.0 ? parameters.NormalRadius : radii.Radius;
  return radii;
}

std::string CheckPrecisionLimits(const BilateralParameters& parameters, const CloudExtent& extent)
{
  // Every position a run can reach must stay far from overflow, lattice coordinates (extent
  // over radius) must fit in 64-bit integers with room to spare, and the Gaussians' scales
  // must be finite.
  const RadiiUsed radii = ResolveRadii(parameters, extent);
  const KernelConstants constants(radii.Radius, radii.NormalRadius);
  std::ostringstream problem;
  const double reach =
    extent.LargestMagnitude() + 4.2 * (parameters.NumberOfIterations + 1.0) * radii.Radius;
  if (!(reach < MaximumMagnitude))
  {
    problem << "coordinates up to " << extent.LargestMagnitude() << " with a radius of "
            << radii.Radius << " come too close to the limits of double precision (keep "
            << "coordinates and N x radius below " << MaximumMagnitude << ")";
  }
  else if (!std::isfinite(4.2 * radii.Radius) || !std::isfinite(constants.DistanceScale) ||
           !std::isfinite(constants.NormalScale))
  {
    problem << "the radius " << radii.Radius << " or the normal radius " << radii.NormalRadius
            << " is outside what double precision can compute with (about 1e-150 to 1e300)";
  }
  else if (extent.LargestExtent() / radii.Radius > MaximumExtentInRadii)
  {
    problem << "the radius " << radii.Radius << " is too small for a cloud "
            << extent.LargestExtent() << " wide (it may be at most " << MaximumExtentInRadii
            << " times smaller): give a larger radius";
  }
  return problem.str();
}

BilateralResult RunBilateralFilter(const PointCloudView& cloud,
  const BilateralParameters& parameters,
  const BilateralObserver& observer)
{
  BilateralResult result;
  if (!(std::isfinite(parameters.Radius) && parameters.Radius >= 0.0))
  {
    result.Error = Describe("the radius", parameters.Radius);
    return result;
  }
  if (!(std::isfinite(parameters.NormalRadius) && parameters.NormalRadius >= 0.0))
  {
    result.Error = Describe("the normal radius", parameters.NormalRadius);
    return result;
  }
  if (parameters.NumberOfIterations < 0)
  {
    result.Error =
      "the number of iterations must be >= 0, got " + std::to_string(parameters.NumberOfIterations);
    return result;
  }
  if (parameters.NumberOfIterations > MaximumIterations)
  {
    result.Error = "the number of iterations must be at most " + std::to_string(MaximumIterations) +
                   ", got " + std::to_string(parameters.NumberOfIterations) +
                   " (each iteration moves the points by up to the radius: a few are enough)";
    return result;
  }
  if (parameters.NumberOfThreads < 0)
  {
    result.Error = "the number of threads must be >= 0 (0 means all cores), got " +
                   std::to_string(parameters.NumberOfThreads);
    return result;
  }
  if (cloud.NumberOfPoints > 0 && cloud.Positions == nullptr)
  {
    result.Error = "the point cloud has no coordinates";
    return result;
  }
  if (cloud.NumberOfGhostPoints > cloud.NumberOfPoints)
  {
    result.Error = "the point cloud has more ghost points than points";
    return result;
  }
  if (parameters.GlobalExtent && !IsFiniteExtent(*parameters.GlobalExtent))
  {
    result.Error = "the global extent of the cloud is not finite";
    return result;
  }
  if (cloud.NumberOfPoints > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
  {
    result.Error = "the point cloud has more than 2^31 - 1 points";
    return result;
  }

  const std::size_t n = cloud.NumberOfPoints;
  ReserveWithHugePages(3 * n, result.Positions);
  result.Positions.assign(cloud.Positions, cloud.Positions + 3 * n);
  result.Removed.assign(n, 0);
  if (parameters.ComputeNormals)
  {
    result.Normals.assign(3 * n, 0.0);
  }

  auto warn = [&](const std::string& warning)
  {
    result.Warnings.push_back(warning);
    if (observer.Warning)
    {
      observer.Warning(warning);
    }
  };

  // Non-finite points are passed through and never become neighbours.
  const CloudExtent localExtent = MeasureCloud(cloud);
  const std::size_t finiteCount = localExtent.NumberOfFinitePoints;
  const CloudExtent& extent = parameters.GlobalExtent ? *parameters.GlobalExtent : localExtent;
  result.NumberOfNonFinitePoints = n - finiteCount;
  if (result.NumberOfNonFinitePoints > 0)
  {
    warn(std::to_string(result.NumberOfNonFinitePoints) +
         " point(s) have NaN or infinite coordinates: they are passed through unchanged and are "
         "never used as neighbours");
  }
  const RadiiUsed radii = ResolveRadii(parameters, extent);
  result.RadiusUsed = radii.Radius;
  result.NormalRadiusUsed = radii.NormalRadius;
  result.Status = BilateralStatus::Completed;
  if (finiteCount == 0 || parameters.NumberOfIterations == 0)
  {
    return result;
  }
  if (!(result.RadiusUsed > 0.0))
  {
    warn("all points coincide, so no radius can be chosen automatically: the points are left "
         "where they are");
    return result;
  }

  const std::string problem = CheckPrecisionLimits(parameters, extent);
  if (!problem.empty())
  {
    result.Status = BilateralStatus::Failed;
    result.Error = problem;
    return result;
  }
  const KernelConstants constants(result.RadiusUsed, result.NormalRadiusUsed);

  const int threads = ResolveThreadCount(parameters.NumberOfThreads);
  ProcessingOctree octree(extent.Min, extent.Max, result.RadiusUsed);
  result.ProcessingDepth = octree.GetProcessingDepth();
  octree.Load(cloud.Positions, n);

  PointState state;
  state.Positions = std::move(result.Positions); // given back when the run ends
  state.Normals = std::move(result.Normals);
  state.Removed = std::move(result.Removed);
  state.OrientationNormals = cloud.OrientationNormals;
  state.FirstGhost = n - cloud.NumberOfGhostPoints;

  CellColoringScheduler scheduler(
    octree, constants, result.RadiusUsed, parameters.RemoveIsolatedPoints, threads);
  const int iterations = parameters.NumberOfIterations;
  int iteration = 0;
  double lastReported = -1.0;
  auto report = [&](double fraction)
  {
    if (observer.Progress && fraction - lastReported >= 0.01)
    {
      observer.Progress(fraction);
      lastReported = fraction;
    }
  };
  scheduler.ShouldAbort = observer.ShouldAbort;
  scheduler.ReportPoints = [&](std::size_t pointsDone)
  {
    const std::size_t total = std::max<std::size_t>(1, scheduler.GetNumberOfPointsProcessed());
    report((iteration + static_cast<double>(pointsDone) / static_cast<double>(total)) / iterations);
  };

  bool completed = true;
  for (; iteration < iterations; ++iteration)
  {
    octree.Compact(threads);
    if (iteration == 0)
    {
      const double neighbours = scheduler.EstimateNeighboursPerPoint(32);
      if (neighbours > ManyNeighbours)
      {
        std::ostringstream warning;
        warning << "the radius " << result.RadiusUsed << " gives about "
                << static_cast<long long>(neighbours)
                << " neighbours per point, so the run will be slow (its time grows with that "
                   "number): lower the radius, a few times the point spacing is usually enough";
        warn(warning.str());
      }
    }
    if (!scheduler.RunIteration(state))
    {
      completed = false;
      break;
    }
    result.NumberOfNeighbourEvaluations += scheduler.GetNumberOfNeighbourEvaluations();
    report(static_cast<double>(iteration + 1) / iterations);
  }

  // The points' last moves, from the octree's layout back to their ids.
  if (completed)
  {
    const std::uint32_t* ids = octree.GetIds();
    const double* moved[3] = { octree.GetMovedX(), octree.GetMovedY(), octree.GetMovedZ() };
    const auto count = static_cast<std::int64_t>(octree.GetNumberOfPoints());
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t i = 0; i < count; ++i)
    {
      if (!state.Removed[ids[i]])
      {
        for (int axis = 0; axis < 3; ++axis)
        {
          state.Positions[3 * static_cast<std::size_t>(ids[i]) + axis] = moved[axis][i];
        }
      }
    }
  }
  result.Positions = std::move(state.Positions);
  result.Normals = std::move(state.Normals);
  result.Removed = std::move(state.Removed);
  result.NumberOfRemovedPoints = static_cast<std::size_t>(
    std::count(result.Removed.begin(), result.Removed.end(), std::uint8_t{ 1 }));
  if (!completed)
  {
    result.Status = BilateralStatus::Aborted;
  }
  return result;
}

} // namespace pcbilateral

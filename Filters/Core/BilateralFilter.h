// Public entry point of the bilateral filter core: plain C++17, no VTK types. Every front end
// (the VTK filter, the command-line program, the tests) drives this one function.
#ifndef pcbilateral_BilateralFilter_h
#define pcbilateral_BilateralFilter_h

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace pcbilateral
{

/// The finite points of a cloud and their bounding box (NaN and infinite points are left out).
struct CloudExtent
{
  std::size_t NumberOfFinitePoints = 0;
  double Min[3] = { 0.0, 0.0, 0.0 };
  double Max[3] = { 0.0, 0.0, 0.0 };
  double LargestExtent() const;
  /// The largest absolute value of a coordinate.
  double LargestMagnitude() const;
};

/// Parameters in the paper's terms (section 5).
struct BilateralParameters
{
  /// Neighbourhood radius r; sd = r / 3. Zero means automatic: sqrt(20 / number of points)
  /// times the largest extent of the bounding box.
  double Radius = 0.0;
  /// Normal radius rn, the thickness of the slab around the tangent plane; sn = rn / 3. Zero
  /// means "same as Radius".
  double NormalRadius = 0.0;
  /// Number of iterations N; each reads the positions written by the previous one.
  int NumberOfIterations = 1;
  /// Points with fewer than 5 neighbours (or a zero weight sum) stay where they are; with this
  /// on they are removed for the rest of the run instead, as the authors' program does.
  bool RemoveIsolatedPoints = false;
  /// Threads for the parallel loops; 0 uses all cores. Results do not depend on it.
  int NumberOfThreads = 0;
  /// Also return the estimated normals of the last iteration.
  bool ComputeNormals = false;
  /// Distributed runs: the extent of the whole cloud, all processes together. It fixes the
  /// automatic radius and the octree's geometry, hence the order of every sum, so that each
  /// process computes the bits a single process would. Empty: the extent of the given points.
  std::optional<CloudExtent> GlobalExtent;
};

/// The points to filter. Arrays are interleaved x y z, NumberOfPoints triples.
struct PointCloudView
{
  std::size_t NumberOfPoints = 0;
  const double* Positions = nullptr;
  /// Optional: each estimated normal is flipped to agree with this one.
  const double* OrientationNormals = nullptr;
  /// The last NumberOfGhostPoints points are neighbours only: they are not filtered and keep
  /// their positions. A distributed run passes here the points of other processes that lie
  /// within reach of its own.
  std::size_t NumberOfGhostPoints = 0;
};

/// Hooks called from the calling thread while the filter runs.
struct BilateralObserver
{
  /// Fraction done, from 0 to 1, at least every percent.
  std::function<void(double)> Progress;
  /// Polled often; returning true stops the run, which then reports Aborted.
  std::function<bool()> ShouldAbort;
  /// Called with each warning as soon as it arises (they are also in BilateralResult::Warnings).
  std::function<void(const std::string&)> Warning;
};

enum class BilateralStatus
{
  Completed,
  Aborted,
  Failed
};

struct BilateralResult
{
  BilateralStatus Status = BilateralStatus::Failed;
  /// Why the run failed (empty unless Status is Failed).
  std::string Error;
  /// Things the user should know about a run that still completed.
  std::vector<std::string> Warnings;

  /// Filtered positions, one triple per input point; removed and non-finite points keep the
  /// last position they had.
  std::vector<double> Positions;
  /// Estimated unit normals (if asked for); zero where no normal was estimated.
  std::vector<double> Normals;
  /// 1 for each point removed by RemoveIsolatedPoints.
  std::vector<std::uint8_t> Removed;

  double RadiusUsed = 0.0;
  double NormalRadiusUsed = 0.0;
  int ProcessingDepth = 0;
  std::size_t NumberOfRemovedPoints = 0;
  /// Points with a NaN or infinite coordinate: passed through, never neighbours.
  std::size_t NumberOfNonFinitePoints = 0;
  /// Neighbours visited, summed over points and iterations (the kernel's unit of work).
  std::uint64_t NumberOfNeighbourEvaluations = 0;
};

/// The automatic radius of the paper: sqrt(20 / numberOfPoints) * largestExtent.
double AutomaticRadius(std::size_t numberOfPoints, double largestExtent);

CloudExtent MeasureCloud(const PointCloudView& cloud);

/// The radius and normal radius a run uses on a cloud of this extent, the automatic choices
/// resolved (both 0 when the cloud has no extent and the radius is automatic).
struct RadiiUsed
{
  double Radius = 0.0;
  double NormalRadius = 0.0;
};
RadiiUsed ResolveRadii(const BilateralParameters& parameters, const CloudExtent& extent);

/// Why a run with these parameters on a cloud of this extent (radius > 0 once resolved) cannot
/// be computed in double precision, or empty: coordinates and N x radius near overflow, radii
/// whose Gaussians cannot be computed, a cloud too many radii wide. RunBilateralFilter checks
/// it; a distributed run, which runs the core one iteration at a time, checks it for the whole
/// run first.
std::string CheckPrecisionLimits(const BilateralParameters& parameters, const CloudExtent& extent);

/// Runs NumberOfIterations iterations of the bilateral filter on the cloud.
BilateralResult RunBilateralFilter(const PointCloudView& cloud,
  const BilateralParameters& parameters,
  const BilateralObserver& observer = BilateralObserver());

} // namespace pcbilateral

#endif

// Public entry point of the bilateral filter core: plain C++17, no VTK types. Every front end
// (the VTK filters, the command-line program, the tests) drives a BilateralRun, directly or
// through RunBilateralFilter: one validation, one iteration loop, one place for progress,
// warnings and counts.
#ifndef pcbilateral_BilateralFilter_h
#define pcbilateral_BilateralFilter_h

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pcbilateral
{
struct CloudScales;

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

/// Limits every front end enforces (the VTK class, the ParaView XML and the command line read
/// them from here, so that they cannot disagree).
namespace limits
{
/// More iterations than this are refused: the paper uses a few, and each one may move the points
/// by up to the radius, so that thousands would only collapse the cloud, slowly.
constexpr int MaximumIterations = 1000;
} // namespace limits

/// How the parameters left at 0 (automatic) are chosen.
enum class AutomaticParameters
{
  /// From the cloud's measured point spacing and noise (CloudMeasurement.h, README.md
  /// "Automatic parameters"): r = 5 spacings + 4 sigma, rn = 5 sigma, N = 2 (flat clouds:
  /// 1.5 r, N = 3; smooth clouds with noise below half a spacing: 1.25 r, rn = r, N = 1).
  Measured = 0,
  /// The paper's heuristic: r = sqrt(20 / number of points) x the bounding box's largest
  /// extent, rn = r, N = 1 (the authors' program).
  Paper = 1
};

/// Parameters in the paper's terms (section 5). The member initialisers are the defaults of
/// every front end: all automatic.
struct BilateralParameters
{
  /// Neighbourhood radius r; sd = r / 3. Zero means automatic (see Automatic).
  double Radius = 0.0;
  /// Normal radius rn, the thickness of the slab around the tangent plane; sn = rn / 3. Zero
  /// means automatic (see Automatic).
  double NormalRadius = 0.0;
  /// Number of iterations N; each reads the positions written by the previous one. Zero means
  /// automatic (see Automatic).
  int NumberOfIterations = 0;
  /// How the parameters left at 0 are chosen; each given parameter overrides only itself.
  AutomaticParameters Automatic = AutomaticParameters::Measured;
  /// Points with fewer than 5 neighbours (or a zero weight sum) stay where they are; with this
  /// on they are removed for the rest of the run instead, as the authors' program does.
  bool RemoveIsolatedPoints = false;
  /// Threads for the parallel loops; 0 uses all cores. Results do not depend on it.
  int NumberOfThreads = 0;
  /// Also return the estimated normals of the last iteration.
  bool ComputeNormals = false;
  /// Edge-aware mode, beyond the paper (EdgeAwareNormals.h): the normals are filtered
  /// bilaterally before the displacement, which keeps sharp edges under strong noise. Off: the
  /// paper's filter, bit for bit.
  bool EdgeAware = false;
};

/// Why these parameters cannot run, in words for the user, or empty. The one check of every
/// front end (a BilateralRun makes it first).
std::string CheckParameters(const BilateralParameters& parameters);

/// The points to filter. Arrays are interleaved x y z, NumberOfPoints triples.
struct PointCloudView
{
  std::size_t NumberOfPoints = 0;
  const double* Positions = nullptr;
  /// Optional: each estimated normal is flipped to agree with this one.
  const double* OrientationNormals = nullptr;
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
  int NumberOfIterationsUsed = 0;
  /// The cloud's measured point spacing and noise sigma when the automatic mode measured it
  /// (Measured true), else 0.
  bool Measured = false;
  double PointSpacing = 0.0;
  double NoiseSigma = 0.0;
  int ProcessingDepth = 0;
  std::size_t NumberOfRemovedPoints = 0;
  /// Points with a NaN or infinite coordinate: passed through, never neighbours.
  std::size_t NumberOfNonFinitePoints = 0;
  /// Neighbours visited, summed over points and iterations (the kernel's unit of work).
  std::uint64_t NumberOfNeighbourEvaluations = 0;
};

/// The automatic radius of the paper: sqrt(20 / numberOfPoints) * largestExtent.
double AutomaticRadius(std::size_t numberOfPoints, double largestExtent);

/// The extent of the finite points among a cloud's points.
CloudExtent MeasureCloud(const PointCloudView& cloud);
/// The extent of two parts of one cloud together.
CloudExtent MergeExtents(const CloudExtent& a, const CloudExtent& b);

/// Whether p lies in box (xmin, xmax, ymin, ymax, zmin, zmax), bounds included.
inline bool InsideBox(const double box[6], const double p[3])
{
  return p[0] >= box[0] && p[0] <= box[1] && p[1] >= box[2] && p[1] <= box[3] && p[2] >= box[4] &&
         p[2] <= box[5];
}

/**
 * One run of the filter, one iteration at a time. RunBilateralFilter is the loop over it for a
 * whole cloud; a distributed run (several parts of one cloud, in several processes) drives the
 * same object on each part:
 *
 *   BilateralRun run(part, parameters, observer);    // checks the parameters and the part
 *   run.Start(extent of the whole cloud,             // every part uses the same parameters
 *     scales of the whole cloud if run.NeedsScales()); // and octree
 *   while (run.HasNextIteration())
 *     run.Step(ghosts);   // ghosts: the other parts' points within GetGhostReach() of this one
 *   BilateralResult result = run.Finish();
 *
 * With ghosts, each step rebuilds the octree from the part's points and the ghosts, which are
 * neighbours only (never filtered, never moved). Because the octree's geometry comes from the
 * whole cloud's extent and every sum runs in an order fixed by geometry, each part gets exactly
 * the bits one run over the whole cloud gives its points. A run that is given no ghosts keeps
 * its octree from one iteration to the next.
 */
class BilateralRun
{
public:
  /// Checks the parameters and the cloud; a failure shows in GetStatus() and GetError(), and
  /// the run then does nothing. The cloud's arrays are read until Finish, which copies them:
  /// they must stay valid and unchanged until then.
  BilateralRun(const PointCloudView& cloud,
    const BilateralParameters& parameters,
    const BilateralObserver& observer = BilateralObserver());
  ~BilateralRun();
  BilateralRun(const BilateralRun&) = delete;
  BilateralRun& operator=(const BilateralRun&) = delete;

  /// Failed (with GetError()) or Aborted once the run ended that way, else Completed.
  BilateralStatus GetStatus() const;
  const std::string& GetError() const;

  /// The extent of this run's own finite points.
  const CloudExtent& GetLocalExtent() const;

  /// Whether Start needs the whole cloud's scales: some parameter is automatic and chosen from
  /// the measured spacing and noise.
  bool NeedsScales() const;

  /**
   * Resolves the parameters from the extent of the whole cloud (for a run on a whole cloud, its
   * own GetLocalExtent()) and, when NeedsScales(), from the whole cloud's scales
   * (MeasureWholeCloud, or MeasureSelection of the parts' gathered selections; when not given,
   * this run measures its own points), warns about non-finite points, and checks the limits of
   * double precision for the whole run. Returns whether there are iterations to run.
   */
  bool Start(const CloudExtent& wholeCloud, const CloudScales* wholeCloudScales = nullptr);

  /// Whether Step has an iteration left to run (false once the run failed or was aborted).
  bool HasNextIteration() const;
  /// The radius, normal radius and number of iterations used (valid after Start).
  double GetRadius() const;
  double GetNormalRadius() const;
  int GetNumberOfIterations() const;

  /**
   * The current positions, interleaved, of this run's points that other parts may need as
   * neighbours (finite, not removed), and the box within reach of them: the other parts' points
   * in it are this run's ghosts for the next step (more than needed is harmless, the kernel
   * ignores candidates beyond the radius). The box is empty (min > max) when there are none.
   */
  std::vector<double> GetPositionsForOthers() const;
  void GetGhostReach(double box[6]) const;

  /// Runs the next iteration on this run's points alone. Returns the status after it.
  BilateralStatus Step();
  /// Runs the next iteration with ghost points (interleaved xyz) as extra neighbours.
  BilateralStatus Step(const std::vector<double>& ghosts);

  /// Ends the run early with this status, e.g. when another part failed or was aborted.
  void Stop(BilateralStatus status, const std::string& error = std::string());

  /// The result: positions by point id (each point's last position), normals, removed points,
  /// counts. Call once, when no iteration is left or after Stop.
  BilateralResult Finish();

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

/// Runs NumberOfIterations iterations of the bilateral filter on the cloud: a loop over a
/// BilateralRun.
BilateralResult RunBilateralFilter(const PointCloudView& cloud,
  const BilateralParameters& parameters,
  const BilateralObserver& observer = BilateralObserver());

} // namespace pcbilateral

#endif

// Public entry point of the bilateral filter core: plain C++17, no VTK types. Every front end
// (the VTK filters, the command-line program, the tests) drives a BilateralRun, directly or
// through RunBilateralFilter: one validation, one iteration loop, one place for progress,
// warnings and counts.
#ifndef pcbilateral_BilateralFilter_h
#define pcbilateral_BilateralFilter_h

#include "BilateralParameters.h"
#include "PointCloudView.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pcbilateral
{
struct CloudScales;

/// Hooks called from the calling thread while the filter runs.
struct BilateralResult;

struct BilateralObserver
{
  /// Fraction done, from 0 to 1, at least every percent.
  std::function<void(double)> Progress;
  /// The phase running ("measuring", "iteration K of N") and the fraction of it done, called
  /// just before Progress (and, while measuring, at the measurement's progress points, when
  /// Progress is called with 0).
  std::function<void(const std::string&, double)> PhaseProgress;
  /// Polled often; returning true stops the run, which then reports Aborted.
  std::function<bool()> ShouldAbort;
  /// Called with each warning as soon as it arises (they are also in BilateralResult::Warnings).
  std::function<void(const std::string&)> Warning;
  /// Called once the parameters are resolved (measured, chosen), before the first iteration,
  /// with the result so far: the parameters used and the measured scales are filled in.
  std::function<void(const BilateralResult&)> ParametersChosen;
  /// Set by a caller that discards an aborted run's result (a VTK filter's output is then
  /// empty): its Positions are then left empty rather than filled with the input's. The copy
  /// of 20 million points' positions into fresh memory took 0.05 s, up to 0.27 s when the
  /// kernel had to gather huge pages for it, after every abort.
  bool DiscardsAbortedResult = false;
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
  /// last position they had. Empty after an abort when the observer DiscardsAbortedResult.
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
  /// The 5th, 50th and 95th percentiles of the distance from a point to its nearest neighbour,
  /// measured with them (CloudScales), else 0.
  double NearestNeighbourDistance[3] = { 0.0, 0.0, 0.0 };
  /// Whether the automatic radius followed the density (RadiusFollowsDensity in
  /// AutomaticRule.h): each point's radius from its local spacing, between RadiusRange[0] and
  /// RadiusRange[1] (RadiusUsed is then the radius at the whole cloud's spacing), its normal
  /// radius in NormalRadiusRange; and how many times the local spacing varies across the cloud
  /// (the 95th over the 5th percentile of the local spacing, whenever the cloud was measured).
  bool RadiusFollowsDensity = false;
  double RadiusRange[2] = { 0.0, 0.0 };
  double NormalRadiusRange[2] = { 0.0, 0.0 };
  double SpacingSpread = 0.0;
  /// Where the radius followed the density: each point's radius (0 for points that are not
  /// finite), else empty.
  std::vector<double> PointRadius;
  int ProcessingDepth = 0;
  std::size_t NumberOfRemovedPoints = 0;
  /// Points with a NaN or infinite coordinate: passed through, never neighbours.
  std::size_t NumberOfNonFinitePoints = 0;
  /// Neighbours visited, summed over points and iterations (the kernel's unit of work).
  std::uint64_t NumberOfNeighbourEvaluations = 0;
};

/**
 * One run of the filter, one iteration at a time. RunBilateralFilter is the loop over it for a
 * whole cloud; a distributed run (several parts of one cloud, in several processes) drives the
 * same object on each part:
 *
 *   BilateralRun run(part, parameters, observer);    // checks the parameters and the part
 *   run.Start(extent of the whole cloud,             // every part uses the same parameters
 *     scales of the whole cloud if run.NeedsScales()); // and octree
 *   while (run.HasNextIteration())
 *     run.Step(ghosts);   // ghosts: the other parts' points in GetGhostReaches() of this one
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
   * neighbours (finite, not removed), and the boxes within reach of them (6 doubles each: x
   * min, x max, y min, ..., none when there are no such points): the other parts' points in any
   * of them are this run's ghosts for the next step (more than needed is harmless, the kernel
   * ignores candidates beyond the radius). One box per radius band this run has points in,
   * each that band's points grown by the band's own reach (one box when the radius is fixed):
   * where the radius follows the density, one box grown by the largest radius would reach over
   * most of a dense neighbour's part.
   */
  std::vector<double> GetPositionsForOthers() const;
  std::vector<double> GetGhostReaches() const;

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
  /// RunBilateralFilter's run of a whole cloud (`whole`): the cloud's extent, a pass over every
  /// point before the measurement, asks the observer whether to stop, and an abort there ends
  /// the run. (The parts of a distributed run must decide alike, so they ask from Start on.)
  BilateralRun(const PointCloudView& cloud,
    const BilateralParameters& parameters,
    const BilateralObserver& observer,
    bool whole);
  friend BilateralResult RunBilateralFilter(const PointCloudView& cloud,
    const BilateralParameters& parameters,
    const BilateralObserver& observer);

  struct Internals;
  std::unique_ptr<Internals> Impl;
};

/// How far one iteration reads from a point, in radii: 1 for the paper's filter (the normal and
/// the move read the neighbours within one radius), EdgeAwareReachInRadii for the edge-aware
/// mode (the move reads filtered normals, which read normals, which read positions, each within
/// one radius). A distributed run's ghosts and a streamed run's halo are taken from it.
double IterationReachInRadii(const BilateralParameters& parameters);

/// Runs NumberOfIterations iterations of the bilateral filter on the cloud: a loop over a
/// BilateralRun.
BilateralResult RunBilateralFilter(const PointCloudView& cloud,
  const BilateralParameters& parameters,
  const BilateralObserver& observer = BilateralObserver());

} // namespace pcbilateral

#endif

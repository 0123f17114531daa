#include "BilateralFilter.h"

#include "AutomaticRule.h"
#include "BilateralKernel.h"
#include "CellColoringScheduler.h"
#include "CloudMeasurement.h"
#include "EdgeAwareNormals.h"
#include "HugePages.h"
#include "IterationEngine.h"
#include "ProcessingOctree.h"
#include "ProgressCheck.h"
#include "RadiusBands.h"
#include "Threads.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace pcbilateral
{

namespace
{
/// The largest extent of a cloud, in radii, whose octree lattice coordinates stay far inside
/// 32-bit integers (ProcessingOctree.h: LatticeCoord).
constexpr double MaximumExtentInRadii = 1e8;
/// Positions stay below this magnitude, far from overflow.
constexpr double MaximumMagnitude = 1e300;
/// Above this mean number of neighbours per point, the run is warned about: it will be slow,
/// and the radius was probably meant smaller (the paper's clouds have tens to hundreds).
constexpr double ManyNeighbours = 10000.0;

/// The margin of a ghost reach box beyond one radius, for the rounding of the box's own
/// arithmetic; a larger box only brings candidates the kernel ignores.
double GhostMargin(double radius, double magnitude)
{
  return 1.01 * radius + 1e-12 * magnitude;
}

struct RadiiUsed
{
  double Radius = 0.0;
  double NormalRadius = 0.0;
};

/// The radius and normal radius a run uses on a cloud of this extent, the automatic choices
/// resolved (both 0 when the cloud has no extent and the radius is automatic).
RadiiUsed ResolveRadii(const BilateralParameters& parameters, const CloudExtent& extent)
{
  RadiiUsed radii;
  radii.Radius = parameters.Radius > 0.0
                   ? parameters.Radius
                   : PaperRadius(extent.NumberOfFinitePoints, extent.LargestExtent());
  radii.NormalRadius = parameters.NormalRadius > 0.0 ? parameters.NormalRadius : radii.Radius;
  return radii;
}

/// Why a run with these parameters on a cloud of this extent (radius > 0 once resolved) cannot
/// be computed in double precision, or empty: coordinates and N x radius near overflow, radii
/// whose Gaussians cannot be computed, a cloud too many radii wide.
std::string CheckPrecisionLimits(const BilateralParameters& parameters,
  const CloudExtent& extent,
  const RadiiUsed& radii)
{
  // Every position a run can reach must stay far from overflow, lattice coordinates (extent
  // over radius) must fit in 32-bit integers with room to spare, and the Gaussians' scales
  // must be finite.
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

} // namespace

struct BilateralRun::Internals
{
  PointCloudView Cloud;
  BilateralParameters Parameters;
  BilateralObserver Observer;
  int Threads = 1;
  CloudExtent LocalExtent;
  CloudExtent WholeExtent;
  RadiiUsed Radii;
  int Iteration = 0;
  bool Started = false;
  bool Finished = false;
  /// RunBilateralFilter's run of a whole cloud: asks from its construction to its Finish.
  bool Whole = false;
  bool PositionsCopied = false;
  /// Whether the constructor accepted the parameters and the cloud (the result then has
  /// positions, even when no iteration ran).
  bool Accepted = false;
  double LastReported = -1.0;
  std::chrono::steady_clock::time_point LastReportTime;
  BilateralResult Result;
  /// The engine of a run without ghosts, kept from one iteration to the next.
  std::unique_ptr<IterationEngine> Engine;
  /// Where the radius follows the density: each point's band (else empty).
  RadiusBands Bands;
  /// The share of the current iteration done before the points being filtered now, and theirs
  /// (a radius band is a share of an iteration).
  double StepDone = 0.0;
  double StepShare = 1.0;
  bool WarnedAboutNeighbours = false;

  void Warn(const std::string& warning)
  {
    this->Result.Warnings.push_back(warning);
    if (this->Observer.Warning)
    {
      this->Observer.Warning(warning);
    }
  }

  /// `fraction` of the whole run; `iterationEnd`: the end of an iteration, reported whenever it
  /// comes (it was skipped when the last report had come less than 1 % and 0.1 s before it, so
  /// that an observer missed the end of the run, or saw the next iteration's progress first).
  void Report(double fraction, bool iterationEnd = false)
  {
    // Every 1 % of the run, and at least every 0.1 s while it runs, even when 1 % takes longer:
    // a GUI that runs the filter on its own thread (ParaView) repaints and sees its Abort button
    // only in these calls.
    const auto now = std::chrono::steady_clock::now();
    if ((this->Observer.Progress || this->Observer.PhaseProgress) &&
        (fraction - this->LastReported >= 0.01 ||
          now - this->LastReportTime >= std::chrono::milliseconds(100)))
    {
      this->ReportPhase(fraction);
      if (this->Observer.Progress)
      {
        this->Observer.Progress(fraction);
      }
      this->LastReported = fraction;
      this->LastReportTime = now;
    }
    else if (iterationEnd && this->Observer.Progress)
    {
      // The run's progress only: the phases' reports (a command line's bars) keep their pace.
      this->Observer.Progress(fraction);
    }
  }

  /// The iteration that the whole run's `fraction` falls in, and the fraction of it done.
  void ReportPhase(double fraction) const
  {
    if (!this->Observer.PhaseProgress)
    {
      return;
    }
    const int iterations = std::max(1, this->Parameters.NumberOfIterations);
    const double done = fraction * iterations;
    const int iteration = std::min(iterations - 1, static_cast<int>(done));
    this->Observer.PhaseProgress(
      "iteration " + std::to_string(iteration + 1) + " of " + std::to_string(iterations),
      done - iteration);
  }

  /// Whether the run was aborted and its caller discards the result: its positions are not
  /// copied then (BilateralObserver::DiscardsAbortedResult).
  bool DiscardsResult() const
  {
    return this->Result.Status == BilateralStatus::Aborted && this->Observer.DiscardsAbortedResult;
  }

  /// What a whole cloud's run asks while it moves its result back into the points' order, when
  /// its caller discards an aborted result (a result moved in part is not handed over then).
  std::function<bool()> StopWhileFinishing() const
  {
    return this->Whole && this->Observer.DiscardsAbortedResult ? this->Observer.ShouldAbort
                                                               : nullptr;
  }

  /// The result's positions as a copy of the input's, if not made yet: made only when needed,
  /// so that a whole cloud's run does not hold its positions beside the octree's.
  void CopyInputPositions()
  {
    if (!this->PositionsCopied)
    {
      ReserveWithHugePages(3 * this->Cloud.NumberOfPoints, this->Result.Positions);
      this->Result.Positions.assign(
        this->Cloud.Positions, this->Cloud.Positions + 3 * this->Cloud.NumberOfPoints);
      this->PositionsCopied = true;
    }
  }

  std::unique_ptr<IterationEngine> MakeEngine(PointState state,
    const double* positions,
    const RadiiUsed& radii)
  {
    auto engine = std::make_unique<IterationEngine>(std::move(state),
      positions,
      this->WholeExtent,
      radii.Radius,
      radii.NormalRadius,
      this->Parameters.RemoveIsolatedPoints,
      this->Threads,
      this->AskDuringOctree());
    this->Result.ProcessingDepth = engine->Octree.GetProcessingDepth();
    CellColoringScheduler& scheduler = engine->Scheduler;
    scheduler.ShouldAbort = this->Observer.ShouldAbort;
    scheduler.ReportPoints = [this, &scheduler](std::size_t pointsDone)
    {
      const std::size_t total = std::max<std::size_t>(1, scheduler.GetNumberOfPointsProcessed());
      this->ReportWithinStep(static_cast<double>(pointsDone) / static_cast<double>(total));
    };
    return engine;
  }

  /// What the octree's construction and Compact ask whether to stop, between and within their
  /// passes; they report the progress so far there too (at most every 0.1 s: Report), so that
  /// a GUI repaints and sees its Abort button while they run.
  std::function<bool()> AskDuringOctree()
  {
    if (!this->Observer.ShouldAbort && !this->Observer.Progress && !this->Observer.PhaseProgress)
    {
      return nullptr;
    }
    return [this]()
    {
      this->ReportWithinStep(0.0);
      return this->Observer.ShouldAbort && this->Observer.ShouldAbort();
    };
  }

  /// Progress within the current iteration's share being filtered.
  void ReportWithinStep(double fraction)
  {
    this->Report((this->Iteration + this->StepDone + this->StepShare * fraction) /
                 this->Parameters.NumberOfIterations);
  }

  /// One iteration of an engine at `radius`; false if aborted.
  bool Iterate(IterationEngine& engine, double radius)
  {
    if (!engine.Loaded)
    {
      return false; // aborted while the octree was built
    }
    if (engine.PointsPlaced && !engine.Octree.Compact(this->Threads, this->AskDuringOctree()))
    {
      return false; // aborted between two iterations
    }
    if (this->Iteration == 0 && !this->WarnedAboutNeighbours)
    {
      const double neighbours = engine.Scheduler.EstimateNeighboursPerPoint(32);
      if (neighbours > ManyNeighbours)
      {
        this->WarnedAboutNeighbours = true;
        std::ostringstream warning;
        warning << "the radius " << radius << " gives about " << static_cast<long long>(neighbours)
                << " neighbours per point, so the run will be slow (its time grows with that "
                   "number): lower the radius, a few times the point spacing is usually enough";
        this->Warn(warning.str());
      }
    }
    engine.PointsPlaced = true;
    if (!engine.Scheduler.RunIteration(engine.State))
    {
      return false;
    }
    this->Result.NumberOfNeighbourEvaluations += engine.Scheduler.GetNumberOfNeighbourEvaluations();
    return true;
  }

  /// One iteration of the edge-aware mode on `state` (no octree: EdgeAwareNormals.h); false
  /// if aborted.
  bool IterateEdgeAware(PointState& state, const RadiiUsed& radii)
  {
    EdgeAwareSettings settings;
    settings.Radius = radii.Radius;
    settings.NormalRadius = radii.NormalRadius;
    std::copy(this->WholeExtent.Min, this->WholeExtent.Min + 3, settings.Origin);
    settings.CloudReach = this->WholeExtent.LargestExtent() +
                          (this->Parameters.NumberOfIterations + 1.0) * radii.Radius;
    settings.RemoveIsolatedPoints = this->Parameters.RemoveIsolatedPoints;
    settings.NumberOfThreads = this->Threads;
    settings.ShouldAbort = this->Observer.ShouldAbort;
    settings.Progress = [this](double fraction) { this->ReportWithinStep(fraction); };
    std::uint64_t evaluations = 0;
    if (!RunEdgeAwareIteration(state, settings, evaluations))
    {
      return false;
    }
    this->Result.NumberOfNeighbourEvaluations += evaluations;
    return true;
  }

  /// Measures this run's cloud (progress and abort at the measurement's points: ProgressScope)
  /// and chooses the automatic parameters from it. False if aborted.
  bool MeasureOwnCloud()
  {
    const BilateralObserver& observer = this->Observer;
    ProgressScope scope(
      [&observer](double fraction)
      {
        if (observer.PhaseProgress)
        {
          observer.PhaseProgress("measuring", fraction);
        }
        if (observer.Progress)
        {
          observer.Progress(0.0); // (a GUI repaints and sees its Abort button in these calls)
        }
      },
      observer.ShouldAbort);
    scope.Check(0.0);
    const CloudScales scales =
      MeasureWholeCloud(this->Cloud, this->LocalExtent.NumberOfFinitePoints, this->Threads);
    if (scope.StopAsked() || scope.CheckNow())
    {
      return false;
    }
    this->ChooseAutomaticParameters(scales);
    return true;
  }

  /// The automatic parameters from the whole cloud's scales, and the radius bands where the
  /// radius follows the density.
  void ChooseAutomaticParameters(const CloudScales& scales)
  {
    BilateralResult& result = this->Result;
    if (scales.Valid)
    {
      result.Measured = true;
      result.PointSpacing = scales.PointSpacing;
      result.NoiseSigma = scales.NoiseSigma;
      std::copy_n(scales.NearestNeighbourDistance, 3, result.NearestNeighbourDistance);
      result.SpacingSpread = scales.LocalSpacing ? scales.LocalSpacing->GetSpread() : 0.0;
    }
    else if (scales.Measurable)
    {
      // (A cloud too small or of no extent has nothing to measure: that needs no warning, and
      // the one of no extent comes below.)
      this->Warn("the cloud's point spacing and noise could not be measured (" + scales.Problem +
                 "): the parameters not given follow the paper's heuristic (r = sqrt(20 / "
                 "points) x largest extent, rn = r, N = 1)");
    }
    const BilateralParameters userParameters = this->Parameters;
    this->Parameters = ChooseParameters(scales, userParameters);
    if (RadiusFollowsDensity(scales, userParameters))
    {
      this->Bands =
        AssignRadiusBands(this->Cloud, scales, userParameters, this->Parameters, this->Threads);
      if (!this->Bands.Empty())
      {
        result.RadiusFollowsDensity = true;
        result.PointSpacing = SurfaceSpacing(scales);
        result.RadiusRange[0] = this->Bands.SmallestRadius();
        result.RadiusRange[1] = this->Bands.LargestRadius();
        const auto normal =
          std::minmax_element(this->Bands.NormalRadius.begin(), this->Bands.NormalRadius.end());
        result.NormalRadiusRange[0] = *normal.first;
        result.NormalRadiusRange[1] = *normal.second;
      }
    }
  }

  /// One iteration of the points `active` (ids) at `radii`: `view` holds their positions, then
  /// the ghosts' (neighbours only). Writes their moved positions and removals by id into
  /// `positions` and `removed`, and their normals into the result's in the last iteration.
  /// False if aborted.
  bool FilterPart(const std::vector<std::size_t>& active,
    std::vector<double> view,
    const RadiiUsed& radii,
    std::vector<double>& positions,
    std::vector<std::uint8_t>& removed)
  {
    if (active.empty())
    {
      return true;
    }
    // Orientation changes only the reported normals, which only the last iteration gives.
    const bool last = this->Iteration + 1 == this->Parameters.NumberOfIterations;
    const bool computeNormals = last && this->Parameters.ComputeNormals;
    std::vector<double> orientation;
    if (computeNormals && this->Cloud.OrientationNormals)
    {
      orientation.assign(view.size(), 0.0);
      for (std::size_t j = 0; j < active.size(); ++j)
      {
        const double* o = this->Cloud.OrientationNormals + 3 * active[j];
        std::copy(o, o + 3, orientation.begin() + 3 * j);
      }
    }
    PointState partState;
    partState.Positions = std::move(view);
    partState.Removed.assign(partState.Positions.size() / 3, 0);
    if (computeNormals)
    {
      partState.Normals.assign(partState.Positions.size(), 0.0);
    }
    partState.OrientationNormals = orientation.empty() ? nullptr : orientation.data();
    partState.FirstGhost = active.size();
    std::unique_ptr<IterationEngine> engine;
    if (!this->Parameters.EdgeAware)
    {
      engine = this->MakeEngine(std::move(partState), nullptr, radii);
    }
    const bool completed =
      engine ? this->Iterate(*engine, radii.Radius) : this->IterateEdgeAware(partState, radii);
    if (!completed)
    {
      return false;
    }
    if (engine)
    {
      engine->ScatterMoves();
    }
    const PointState& state = engine ? engine->State : partState;
    for (std::size_t j = 0; j < active.size(); ++j)
    {
      const std::size_t i = active[j];
      std::copy_n(state.Positions.data() + 3 * j, 3, positions.data() + 3 * i);
      removed[i] = state.Removed[j];
      if (computeNormals)
      {
        std::copy_n(state.Normals.data() + 3 * j, 3, this->Result.Normals.data() + 3 * i);
      }
    }
    return true;
  }

  /// One iteration where the radius follows the density: each band runs on the positions the
  /// last iteration wrote, with every other point within its reach (this run's, and the
  /// `ghosts` of other parts) as neighbours only. False if aborted.
  bool IterateBands(const std::vector<double>& ghosts)
  {
    this->CopyInputPositions();
    BilateralResult& result = this->Result;
    std::vector<double> nextPositions = result.Positions;
    std::vector<std::uint8_t> nextRemoved = result.Removed;
    std::vector<std::vector<std::size_t>> members(this->Bands.Radius.size());
    std::size_t total = 0;
    for (std::size_t i = 0; i < result.Removed.size(); ++i)
    {
      if (!result.Removed[i] && this->Bands.BandOfPoint[i] != RadiusBands::NoBand)
      {
        members[this->Bands.BandOfPoint[i]].push_back(i);
        ++total;
      }
    }
    std::size_t done = 0;
    for (std::size_t band = 0; band < members.size(); ++band)
    {
      const std::vector<std::size_t>& active = members[band];
      this->StepDone =
        static_cast<double>(done) / static_cast<double>(std::max<std::size_t>(total, 1));
      this->StepShare =
        static_cast<double>(active.size()) / static_cast<double>(std::max<std::size_t>(total, 1));
      done += active.size();
      const RadiiUsed radii{ this->Bands.Radius[band], this->Bands.NormalRadius[band] };
      if (!active.empty() &&
          !this->FilterPart(
            active, this->BandView(active, band, ghosts), radii, nextPositions, nextRemoved))
      {
        return false;
      }
    }
    this->StepDone = 0.0;
    this->StepShare = 1.0;
    result.Positions = std::move(nextPositions);
    result.Removed = std::move(nextRemoved);
    return true;
  }

  /// The positions of a band's points `active`, then of the others within its reach: this
  /// run's points of other bands that are not removed, and the other parts' `ghosts`.
  std::vector<double> BandView(const std::vector<std::size_t>& active,
    std::size_t band,
    const std::vector<double>& ghosts) const
  {
    const std::vector<double>& positions = this->Result.Positions;
    std::vector<double> view;
    view.reserve(3 * active.size());
    for (std::size_t i : active)
    {
      view.insert(view.end(), &positions[3 * i], &positions[3 * i] + 3);
    }
    const double reachInRadii = IterationReachInRadii(this->Parameters);
    const NearPoints near(view,
      GhostMargin(reachInRadii * this->Bands.Radius[band], this->WholeExtent.LargestMagnitude()),
      this->WholeExtent.Min);
    for (std::size_t i = 0; i < this->Result.Removed.size(); ++i)
    {
      const double* p = &positions[3 * i];
      if (!this->Result.Removed[i] && this->Bands.BandOfPoint[i] != band &&
          this->Bands.BandOfPoint[i] != RadiusBands::NoBand && near.Near(p))
      {
        view.insert(view.end(), p, p + 3);
      }
    }
    for (std::size_t g = 0; g + 2 < ghosts.size(); g += 3)
    {
      if (near.Near(&ghosts[g]))
      {
        view.insert(view.end(), &ghosts[g], &ghosts[g] + 3);
      }
    }
    return view;
  }

  BilateralStatus EndIteration(bool completed)
  {
    if (!completed)
    {
      this->Result.Status = BilateralStatus::Aborted;
      return this->Result.Status;
    }
    ++this->Iteration;
    this->Report(static_cast<double>(this->Iteration) / this->Parameters.NumberOfIterations, true);
    return this->Result.Status;
  }
};

BilateralRun::BilateralRun(const PointCloudView& cloud,
  const BilateralParameters& parameters,
  const BilateralObserver& observer)
  : BilateralRun(cloud, parameters, observer, false)
{
}

BilateralRun::BilateralRun(const PointCloudView& cloud,
  const BilateralParameters& parameters,
  const BilateralObserver& observer,
  bool whole)
  : Impl(std::make_unique<Internals>())
{
  Internals& run = *this->Impl;
  run.Cloud = cloud;
  run.Parameters = parameters;
  run.Observer = observer;
  BilateralResult& result = run.Result;
  result.Error = CheckParameters(parameters);
  if (result.Error.empty() && cloud.NumberOfPoints > 0 && cloud.Positions == nullptr)
  {
    result.Error = "the point cloud has no coordinates";
  }
  if (result.Error.empty() &&
      cloud.NumberOfPoints > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
  {
    result.Error = "the point cloud has more than 2^31 - 1 points";
  }
  if (!result.Error.empty())
  {
    result.Status = BilateralStatus::Failed;
    return;
  }
  result.Status = BilateralStatus::Completed;
  run.Threads = ResolveThreadCount(parameters.NumberOfThreads);
  const std::size_t n = cloud.NumberOfPoints;
  // The positions are copied when first needed (CopyInputPositions): the input stays valid
  // until Finish.
  run.Accepted = true;
  result.Removed.assign(n, 0);
  if (parameters.ComputeNormals)
  {
    result.Normals.assign(3 * n, 0.0);
  }
  run.Whole = whole;
  if (whole && observer.ShouldAbort)
  {
    bool stopped = false;
    {
      ProgressScope scope(
        [&observer](double)
        {
          if (observer.Progress)
          {
            observer.Progress(0.0); // (a GUI repaints and sees its Abort button in these calls)
          }
        },
        observer.ShouldAbort);
      run.LocalExtent = MeasureCloudUnlessStopped(cloud, stopped);
    }
    if (stopped)
    {
      result.Status = BilateralStatus::Aborted;
      return;
    }
  }
  else
  {
    run.LocalExtent = MeasureCloud(cloud);
  }
  result.NumberOfNonFinitePoints = n - run.LocalExtent.NumberOfFinitePoints;
}

BilateralRun::~BilateralRun() = default;

BilateralStatus BilateralRun::GetStatus() const
{
  return this->Impl->Result.Status;
}

const std::string& BilateralRun::GetError() const
{
  return this->Impl->Result.Error;
}

const CloudExtent& BilateralRun::GetLocalExtent() const
{
  return this->Impl->LocalExtent;
}

double BilateralRun::GetRadius() const
{
  return this->Impl->Radii.Radius;
}

double BilateralRun::GetNormalRadius() const
{
  return this->Impl->Radii.NormalRadius;
}

int BilateralRun::GetNumberOfIterations() const
{
  return this->Impl->Parameters.NumberOfIterations;
}

bool BilateralRun::NeedsScales() const
{
  const BilateralParameters& parameters = this->Impl->Parameters;
  return this->Impl->Result.Status == BilateralStatus::Completed &&
         parameters.Automatic == AutomaticParameters::Measured &&
         (parameters.Radius == 0.0 || parameters.NormalRadius == 0.0 ||
           parameters.NumberOfIterations == 0);
}

bool BilateralRun::Start(const CloudExtent& wholeCloud, const CloudScales* wholeCloudScales)
{
  Internals& run = *this->Impl;
  BilateralResult& result = run.Result;
  if (result.Status != BilateralStatus::Completed || run.Started)
  {
    return false;
  }
  run.Started = true;
  if (!wholeCloud.IsFinite())
  {
    this->Stop(BilateralStatus::Failed, "the extent of the whole cloud is not finite");
    return false;
  }
  run.WholeExtent = wholeCloud;
  if (result.NumberOfNonFinitePoints > 0)
  {
    run.Warn(std::to_string(result.NumberOfNonFinitePoints) +
             " point(s) have NaN or infinite coordinates: they are passed through unchanged and "
             "are never used as neighbours");
  }
  if (this->NeedsScales() && wholeCloud.NumberOfFinitePoints > 0)
  {
    if (wholeCloudScales != nullptr)
    {
      run.ChooseAutomaticParameters(*wholeCloudScales);
    }
    else if (!run.MeasureOwnCloud())
    {
      // Asked during the run's own measurement (a distributed run is given the scales, and
      // every part must decide alike here: its parts see an abort in Step, together).
      this->Stop(BilateralStatus::Aborted);
      return false;
    }
  }
  if (run.Parameters.NumberOfIterations == 0)
  {
    // The paper's mode, or a cloud that could not be measured: the authors' single iteration.
    run.Parameters.NumberOfIterations = 1;
  }
  run.Radii = ResolveRadii(run.Parameters, wholeCloud);
  result.RadiusUsed = run.Radii.Radius;
  result.NormalRadiusUsed = run.Radii.NormalRadius;
  result.NumberOfIterationsUsed = run.Parameters.NumberOfIterations;
  if (wholeCloud.NumberOfFinitePoints == 0)
  {
    return false;
  }
  if (!(run.Radii.Radius > 0.0))
  {
    run.Warn(wholeCloud.NumberOfFinitePoints == 1
               ? "the cloud has a single point, so no radius can be chosen automatically (there "
                 "is no spacing to measure): it is left where it is"
               : "all points coincide, so no radius can be chosen automatically: the points are "
                 "left where they are");
    return false;
  }
  // Where the radius follows the density, the smallest radius sets the octree's finest
  // lattice and the largest how far points reach.
  std::string problem = CheckPrecisionLimits(run.Parameters, wholeCloud, run.Radii);
  for (std::size_t band = 0; band < run.Bands.Radius.size() && problem.empty(); ++band)
  {
    problem = CheckPrecisionLimits(run.Parameters,
      wholeCloud,
      RadiiUsed{ run.Bands.Radius[band], run.Bands.NormalRadius[band] });
  }
  if (!problem.empty())
  {
    this->Stop(BilateralStatus::Failed, problem);
    return false;
  }
  if (run.Observer.ParametersChosen)
  {
    run.Observer.ParametersChosen(result);
  }
  return true;
}

bool BilateralRun::HasNextIteration() const
{
  const Internals& run = *this->Impl;
  return run.Started && !run.Finished && run.Result.Status == BilateralStatus::Completed &&
         run.Radii.Radius > 0.0 && run.WholeExtent.NumberOfFinitePoints > 0 &&
         run.Iteration < run.Parameters.NumberOfIterations;
}

std::vector<double> BilateralRun::GetPositionsForOthers() const
{
  const BilateralResult& result = this->Impl->Result;
  // Before the first step, the input's positions are the current ones.
  const double* current =
    this->Impl->PositionsCopied ? result.Positions.data() : this->Impl->Cloud.Positions;
  std::vector<double> positions;
  for (std::size_t i = 0; i < result.Removed.size(); ++i)
  {
    const double* p = current + 3 * i;
    if (!result.Removed[i] && IsFinitePoint(p))
    {
      positions.insert(positions.end(), p, p + 3);
    }
  }
  return positions;
}

double IterationReachInRadii(const BilateralParameters& parameters)
{
  return parameters.EdgeAware ? EdgeAwareReachInRadii : 1.0;
}

std::vector<double> BilateralRun::GetGhostReaches() const
{
  const Internals& run = *this->Impl;
  const BilateralResult& result = run.Result;
  const double* current = run.PositionsCopied ? result.Positions.data() : run.Cloud.Positions;
  // One group per band (one for all points when the radius is fixed): a band's points read
  // neighbours within its own radius only (IterateBands views each band with its own reach), so
  // the sparse bands' long reach does not spread over the dense bands' points.
  const bool banded = !run.Bands.Empty();
  const std::size_t groups = banded ? run.Bands.Radius.size() : 1;
  std::vector<double> bounds(6 * groups);
  std::vector<std::uint8_t> used(groups, 0);
  for (std::size_t g = 0; g < groups; ++g)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      bounds[6 * g + 2 * axis] = std::numeric_limits<double>::max();
      bounds[6 * g + 2 * axis + 1] = -std::numeric_limits<double>::max();
    }
  }
  double magnitude = 0.0;
  for (std::size_t i = 0; i < result.Removed.size(); ++i)
  {
    const double* p = current + 3 * i;
    const std::size_t g = banded ? run.Bands.BandOfPoint[i] : 0;
    if (result.Removed[i] || !IsFinitePoint(p) || g >= groups)
    {
      continue;
    }
    used[g] = 1;
    for (int axis = 0; axis < 3; ++axis)
    {
      bounds[6 * g + 2 * axis] = std::min(bounds[6 * g + 2 * axis], p[axis]);
      bounds[6 * g + 2 * axis + 1] = std::max(bounds[6 * g + 2 * axis + 1], p[axis]);
      magnitude = std::max(magnitude, std::abs(p[axis]));
    }
  }
  // Points move by less than a radius per iteration, but the boxes are taken from the current
  // positions, so one radius of reach is enough. The edge-aware mode reads its neighbours'
  // normals, which read theirs (with the same band's radii): it reaches further.
  const double reach = IterationReachInRadii(run.Parameters);
  std::vector<double> boxes;
  for (std::size_t g = 0; g < groups; ++g)
  {
    if (!used[g])
    {
      continue;
    }
    const double radius = banded ? run.Bands.Radius[g] : run.Radii.Radius;
    const double margin = GhostMargin(reach * radius, magnitude);
    for (int axis = 0; axis < 3; ++axis)
    {
      boxes.push_back(bounds[6 * g + 2 * axis] - margin);
      boxes.push_back(bounds[6 * g + 2 * axis + 1] + margin);
    }
  }
  return boxes;
}

BilateralStatus BilateralRun::Step()
{
  Internals& run = *this->Impl;
  if (!this->HasNextIteration())
  {
    return run.Result.Status;
  }
  if (!run.Bands.Empty())
  {
    return run.EndIteration(run.IterateBands(std::vector<double>()));
  }
  if (run.Parameters.EdgeAware)
  {
    // Every point by id, in place, for each iteration.
    run.CopyInputPositions();
    BilateralResult& result = run.Result;
    PointState state;
    state.Positions = std::move(result.Positions);
    state.Normals = std::move(result.Normals);
    state.Removed = std::move(result.Removed);
    state.OrientationNormals = run.Cloud.OrientationNormals;
    state.FirstGhost = run.Cloud.NumberOfPoints;
    const bool completed = run.IterateEdgeAware(state, run.Radii);
    result.Positions = std::move(state.Positions);
    result.Normals = std::move(state.Normals);
    result.Removed = std::move(state.Removed);
    return run.EndIteration(completed);
  }
  if (!run.Engine)
  {
    // All points, their ids kept, for every iteration; the result's arrays become the engine's
    // state and come back in Finish. The positions are read from the input: the octree holds
    // them from then on, and Finish writes them back by id.
    PointState state;
    state.Normals = std::move(run.Result.Normals);
    state.Removed = std::move(run.Result.Removed);
    state.OrientationNormals = run.Cloud.OrientationNormals;
    state.FirstGhost = run.Cloud.NumberOfPoints;
    run.Engine = run.MakeEngine(std::move(state), run.Cloud.Positions, run.Radii);
  }
  return run.EndIteration(run.Iterate(*run.Engine, run.Radii.Radius));
}

BilateralStatus BilateralRun::Step(const std::vector<double>& ghosts)
{
  Internals& run = *this->Impl;
  if (!this->HasNextIteration())
  {
    return run.Result.Status;
  }
  if (!run.Bands.Empty())
  {
    return run.EndIteration(run.IterateBands(ghosts));
  }
  run.CopyInputPositions();
  BilateralResult& result = run.Result;
  // This part's points that are not removed, then the ghosts; rebuilt for every iteration,
  // since the ghosts change.
  std::vector<std::size_t> active;
  std::vector<double> view;
  for (std::size_t i = 0; i < result.Removed.size(); ++i)
  {
    if (!result.Removed[i])
    {
      active.push_back(i);
      view.insert(view.end(), &result.Positions[3 * i], &result.Positions[3 * i] + 3);
    }
  }
  view.insert(view.end(), ghosts.begin(), ghosts.end());
  return run.EndIteration(
    run.FilterPart(active, std::move(view), run.Radii, result.Positions, result.Removed));
}

void BilateralRun::Stop(BilateralStatus status, const std::string& error)
{
  BilateralResult& result = this->Impl->Result;
  if (status == BilateralStatus::Completed || result.Status == BilateralStatus::Failed)
  {
    return;
  }
  result.Status = status;
  if (status == BilateralStatus::Failed)
  {
    result.Error = error;
  }
}

BilateralResult BilateralRun::Finish()
{
  Internals& run = *this->Impl;
  BilateralResult& result = run.Result;
  run.Finished = true;
  if (run.Engine)
  {
    // The output's positions take the place of the octree's layout, freed first, so that the
    // peak memory is that of the iterations: the input's positions, then the moves by id, then
    // where removed points stopped.
    PointState& state = run.Engine->State;
    run.Engine->Octree.ReleaseAllButMoves();
    // An abort asked once the last iteration is done still ends a whole cloud's run (its result
    // is then an aborted one's: the input's positions). Its parts must decide alike: asked in
    // Step only.
    if (result.Status == BilateralStatus::Completed && run.Whole && run.Observer.ShouldAbort &&
        run.Observer.ShouldAbort())
    {
      result.Status = BilateralStatus::Aborted;
    }
    if (!run.DiscardsResult())
    {
      run.CopyInputPositions();
      state.Positions = std::move(result.Positions);
      if (result.Status == BilateralStatus::Completed &&
          !run.Engine->ScatterMoves(run.StopWhileFinishing()))
      {
        result.Status = BilateralStatus::Aborted; // (moved in part: discarded)
      }
      for (const StoppedPoint& stopped : state.Stopped)
      {
        std::copy(stopped.Position,
          stopped.Position + 3,
          state.Positions.data() + 3 * static_cast<std::size_t>(stopped.Id));
      }
    }
    result.Positions = std::move(state.Positions);
    result.Removed = std::move(state.Removed);
    result.Normals = std::move(state.Normals);
    run.Engine.reset();
  }
  else if (run.Accepted && !run.DiscardsResult())
  {
    run.CopyInputPositions();
  }
  if (run.DiscardsResult())
  {
    std::vector<double>().swap(result.Positions); // (copied already by the bands' iterations)
  }
  if (!run.Bands.Empty())
  {
    result.PointRadius.assign(run.Bands.BandOfPoint.size(), 0.0);
    for (std::size_t i = 0; i < result.PointRadius.size(); ++i)
    {
      const std::uint16_t band = run.Bands.BandOfPoint[i];
      result.PointRadius[i] = band == RadiusBands::NoBand ? 0.0 : run.Bands.Radius[band];
    }
  }
  result.NumberOfRemovedPoints = static_cast<std::size_t>(
    std::count(result.Removed.begin(), result.Removed.end(), std::uint8_t{ 1 }));
  return std::move(result);
}

BilateralResult RunBilateralFilter(const PointCloudView& cloud,
  const BilateralParameters& parameters,
  const BilateralObserver& observer)
{
  BilateralRun run(cloud, parameters, observer, true);
  if (run.Start(run.GetLocalExtent()))
  {
    while (run.HasNextIteration())
    {
      run.Step();
    }
  }
  return run.Finish();
}

} // namespace pcbilateral

// Abort in the phases before the kernel (issue 28): the octree's construction asks ShouldAbort
// between its passes over the points, and a run that measured its own cloud asks it once the
// measurement is done, so an abort asked there ends the run before the octree and the kernel
// (pcb_abort_latency measured 4 to 7 s on 20 million points when only the kernel asked).
#include "BilateralFilter.h"
#include "BilateralKernel.h"
#include "CellColoringScheduler.h"
#include "CloudView.h"
#include "CoreTesting.h"
#include "ProcessingOctree.h"
#include "ProgressCheck.h"
#include "TestClouds.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace
{
using pcbilateral::BilateralObserver;
using pcbilateral::BilateralParameters;
using pcbilateral::BilateralResult;
using pcbilateral::BilateralStatus;

/// The octree's construction stops at whichever of its checks says stop, and is then empty (one
/// thread: the same checks in every run).
void Octree()
{
  const std::vector<double> cloud = pcbilateral_testing::NoisyPlane(0.002, 7);
  const std::size_t count = cloud.size() / 3;
  const double low[3] = { -0.1, -0.1, -0.1 }, high[3] = { 1.1, 1.1, 0.1 };
  int checks = 0;
  {
    pcbilateral::ProcessingOctree octree(low, high, 0.05);
    const bool loaded = octree.Load(cloud.data(), count, 1, [&checks] { return ++checks < 0; });
    PCB_CHECK(loaded && octree.GetNumberOfPoints() == count, "a load never stopped loads");
  }
  // Between the passes (6) and within them: per block of points, chunk and bucket.
  PCB_CHECK(checks > 50, "the load asked %d time(s) whether to stop", checks);
  std::printf("the load asked %d times whether to stop\n", checks);
  for (int stopAt = 1; stopAt <= checks; ++stopAt)
  {
    pcbilateral::ProcessingOctree octree(low, high, 0.05);
    int asked = 0;
    const bool loaded =
      octree.Load(cloud.data(), count, 1, [&asked, stopAt] { return ++asked == stopAt; });
    PCB_CHECK(!loaded && asked == stopAt && octree.GetNumberOfPoints() == 0,
      "stopped at check %d: loaded %d, asked %d, %zu points",
      stopAt,
      loaded,
      asked,
      octree.GetNumberOfPoints());
  }
}

/// A run stopped during its own measurement, or during the octree's construction, ends
/// aborted, before the parameters are reported chosen (measurement) or before any progress
/// within the first iteration (octree).
void Run()
{
  const std::vector<double> cloud = pcbilateral_testing::NoisyPlane(0.002, 11);
  BilateralParameters automatic; // every parameter chosen from the measured scales
  bool chosen = false;
  BilateralObserver observer;
  observer.ShouldAbort = [] { return true; };
  observer.ParametersChosen = [&chosen](const BilateralResult&) { chosen = true; };
  BilateralResult result =
    pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(cloud), automatic, observer);
  PCB_CHECK(result.Status == BilateralStatus::Aborted && !chosen,
    "aborted during the measurement: status %d, parameters chosen %d",
    int(result.Status),
    chosen);

  BilateralParameters given;
  given.Radius = 0.05;
  given.NormalRadius = 0.01;
  given.NumberOfIterations = 1;
  int asked = 0;
  double progress = 0.0;
  observer.ShouldAbort = [&asked] { return ++asked == 1; };
  observer.ParametersChosen = nullptr;
  observer.Progress = [&progress](double fraction) { progress = std::max(progress, fraction); };
  result = pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(cloud), given, observer);
  PCB_CHECK(result.Status == BilateralStatus::Aborted && asked == 1 && progress == 0.0,
    "aborted while the octree was built: status %d, asked %d, progress %g",
    int(result.Status),
    asked,
    progress);
  PCB_CHECK(result.Positions.size() == cloud.size(), "the result keeps every point");
}
/**
 * The run's own measurement asks whether to stop at its points (between its steps, and every
 * block of points while it selects the points of a large cloud), not only once it is done
 * (issue 28: 1.4 s on 20 million points): an abort at any of them ends the run there, before
 * the parameters are chosen. Every point is seen (ProgressScope's interval set to 0).
 */
void Measurement()
{
  pcbilateral::ProgressScope::SetReportInterval(std::chrono::microseconds(0));
  const std::vector<double> cloud = pcbilateral_testing::NoisyPlane(0.002, 11);
  const BilateralParameters automatic;
  int asked = 0, askedWhenChosen = -1;
  std::vector<double> measuring;
  BilateralObserver observer;
  observer.ShouldAbort = [&asked] { return ++asked < 0; };
  observer.PhaseProgress = [&measuring](const std::string& phase, double fraction)
  {
    if (phase == "measuring")
    {
      measuring.push_back(fraction);
    }
  };
  observer.ParametersChosen = [&](const BilateralResult&) { askedWhenChosen = asked; };
  pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(cloud), automatic, observer);
  PCB_CHECK(askedWhenChosen >= 8 && measuring.size() >= 8 && measuring.front() == 0.0 &&
              std::is_sorted(measuring.begin(), measuring.end()),
    "the measurement asked %d time(s) and reported %zu fractions",
    askedWhenChosen,
    measuring.size());
  for (int stopAt = 1; stopAt <= askedWhenChosen; ++stopAt)
  {
    bool chosen = false;
    int polls = 0;
    observer.ShouldAbort = [&polls, stopAt] { return ++polls == stopAt; };
    observer.ParametersChosen = [&chosen](const BilateralResult&) { chosen = true; };
    const BilateralResult result =
      pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(cloud), automatic, observer);
    PCB_CHECK(result.Status == BilateralStatus::Aborted && !chosen && polls == stopAt,
      "stopped at the measurement's check %d: status %d, chosen %d, asked %d",
      stopAt,
      int(result.Status),
      chosen,
      polls);
  }
  // A cloud larger than the measured selection: the selection (a pass over every point) asks
  // per block of points.
  // (Counted from the measurement's start: the cloud's extent, before it, asks too.)
  const std::vector<double> large = pcbilateral_testing::NoisyCube(600000, 0.001, 3);
  int polls = 0;
  double reached = 0.0;
  bool chosen = false, started = false;
  observer.ShouldAbort = [&] { return started && ++polls == 3; };
  observer.ParametersChosen = [&chosen](const BilateralResult&) { chosen = true; };
  observer.PhaseProgress = [&](const std::string&, double fraction)
  {
    started = true;
    reached = fraction;
  };
  const BilateralResult result =
    pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(large), automatic, observer);
  PCB_CHECK(result.Status == BilateralStatus::Aborted && polls == 3 && !chosen && reached > 0.0 &&
              reached < 0.5,
    "stopped within the selection: status %d, asked %d, chosen %d, at %g of the measurement",
    int(result.Status),
    polls,
    chosen,
    reached);
  pcbilateral::ProgressScope::SetReportInterval(std::chrono::milliseconds(50));
}

/// A whole cloud's run asks while it measures the cloud's extent, before the measurement: an
/// abort at its first question ends it there, before the measurement reports anything (the
/// extent of 20 million points took a tenth of a second or more, unasked).
void BeforeMeasuring()
{
  const std::vector<double> large = pcbilateral_testing::NoisyCube(600000, 0.001, 3);
  int asked = 0;
  bool measured = false, chosen = false;
  BilateralObserver observer;
  observer.ShouldAbort = [&asked] { return ++asked == 1; };
  observer.PhaseProgress = [&measured](const std::string&, double) { measured = true; };
  observer.ParametersChosen = [&chosen](const BilateralResult&) { chosen = true; };
  const BilateralResult result =
    pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(large), {}, observer);
  PCB_CHECK(result.Status == BilateralStatus::Aborted && asked == 1 && !measured && !chosen &&
              result.Positions == large,
    "aborted at the first question: status %d, asked %d, measuring reported %d, chosen %d",
    int(result.Status),
    asked,
    measured,
    chosen);
}

/// An octree whose points one iteration has placed (the state Compact starts from between two
/// iterations), on one thread.
struct PlacedOctree
{
  std::vector<double> Cloud = pcbilateral_testing::NoisyPlane(0.002, 11);
  double Low[3] = { -0.1, -0.1, -0.1 }, High[3] = { 1.1, 1.1, 0.1 };
  pcbilateral::ProcessingOctree Octree{ Low, High, 0.02 };
  pcbilateral::PointState State;

  PlacedOctree()
  {
    const std::size_t count = this->Cloud.size() / 3;
    this->Octree.Load(this->Cloud.data(), count, 1);
    this->State.Removed.assign(count, 0);
    this->State.FirstGhost = count;
    pcbilateral::CellColoringScheduler scheduler(
      this->Octree, pcbilateral::KernelConstants(0.02, 0.01), 0.02, false, 1);
    scheduler.RunIteration(this->State);
  }
};

/**
 * Between two iterations the octree's Compact asks whether to stop (between its steps and every
 * 4,096 cells within its passes), not only the next iteration's kernel once Compact is done (a
 * whole cloud's Compact went unasked); a stop at any of its questions leaves the octree empty.
 */
void BetweenIterations()
{
  int checks = 0;
  {
    PlacedOctree placed;
    const bool compacted = placed.Octree.Compact(1, [&checks] { return ++checks < 0; });
    PCB_CHECK(compacted && placed.Octree.GetNumberOfPoints() == placed.Cloud.size() / 3,
      "a Compact never stopped lays out every point");
  }
  PCB_CHECK(checks >= 6, "Compact asked %d time(s) whether to stop", checks);
  std::printf("Compact asked %d times whether to stop\n", checks);
  for (int stopAt = 1; stopAt <= checks; ++stopAt)
  {
    PlacedOctree placed;
    int asked = 0;
    const bool compacted = placed.Octree.Compact(1, [&asked, stopAt] { return ++asked == stopAt; });
    PCB_CHECK(!compacted && asked == stopAt && placed.Octree.GetNumberOfPoints() == 0,
      "stopped at check %d: compacted %d, asked %d, %zu points",
      stopAt,
      compacted,
      asked,
      placed.Octree.GetNumberOfPoints());
  }
  // A run stopped there ends aborted, before the second iteration's kernel reports progress.
  const std::vector<double> cloud = pcbilateral_testing::NoisyPlane(0.002, 11);
  BilateralParameters given;
  given.Radius = 0.05;
  given.NormalRadius = 0.02;
  given.NumberOfIterations = 2;
  double progress = 0.0;
  BilateralObserver observer;
  observer.Progress = [&progress](double fraction) { progress = std::max(progress, fraction); };
  observer.ShouldAbort = [&progress] { return progress >= 0.5; };
  const BilateralResult result =
    pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(cloud), given, observer);
  PCB_CHECK(result.Status == BilateralStatus::Aborted && progress == 0.5,
    "aborted between the iterations: status %d, progress %g",
    int(result.Status),
    progress);
}

/// An abort asked once the last iteration is done, before the result is handed over, still
/// ends a whole cloud's run: aborted, the input's positions.
void AfterLastIteration()
{
  const std::vector<double> cloud = pcbilateral_testing::NoisyPlane(0.002, 11);
  BilateralParameters given;
  given.Radius = 0.05;
  given.NormalRadius = 0.02;
  given.NumberOfIterations = 1;
  bool done = false;
  BilateralObserver observer;
  observer.Progress = [&done](double fraction) { done = done || fraction >= 1.0; };
  observer.ShouldAbort = [&done] { return done; };
  const BilateralResult result =
    pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(cloud), given, observer);
  PCB_CHECK(result.Status == BilateralStatus::Aborted && result.Positions == cloud,
    "aborted after the last iteration: status %d",
    int(result.Status));
}

/**
 * A caller that discards an aborted run's result (the VTK filter) is not handed the input's
 * positions: an aborted run of 20 million points spent 0.05 to 0.27 s copying them into fresh
 * memory. Aborted at the first question (no octree yet), between two iterations, after the
 * last, while the moves are put back in the points' order (0.09 to 0.17 s for 20 million
 * points), and in the edge-aware mode (positions copied in its first iteration); a completed
 * run is the same with or without the flag.
 */
void DiscardedResult()
{
  const std::vector<double> cloud = pcbilateral_testing::NoisyPlane(0.002, 11);
  auto run = [&cloud](bool edgeAware, const std::function<bool(double)>& stopAt)
  {
    BilateralParameters given;
    given.Radius = 0.05;
    given.NormalRadius = 0.02;
    given.NumberOfIterations = 2;
    given.EdgeAware = edgeAware;
    double progress = 0.0;
    BilateralObserver observer;
    observer.DiscardsAbortedResult = true;
    observer.Progress = [&progress](double fraction) { progress = std::max(progress, fraction); };
    observer.ShouldAbort = [&progress, &stopAt] { return stopAt(progress); };
    return pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(cloud), given, observer);
  };
  // The last: at the question after the one that follows the last iteration, asked while the
  // moves are put back into the points' order (asked only when the result is discarded).
  const std::function<bool(double)> moments[] = { [](double) { return true; },
    [](double progress) { return progress >= 0.5; },
    [](double progress) { return progress >= 1.0; },
    [after = 0](double progress) mutable { return progress >= 1.0 && ++after == 2; } };
  for (bool edgeAware : { false, true })
  {
    // (The edge-aware mode asks nothing once its last iteration is done.)
    for (std::size_t m = 0; m < (edgeAware ? 2u : 4u); ++m)
    {
      const BilateralResult aborted = run(edgeAware, moments[m]);
      PCB_CHECK(aborted.Status == BilateralStatus::Aborted && aborted.Positions.empty(),
        "edge-aware %d, abort %zu: status %d, %zu position values handed back",
        edgeAware,
        m,
        int(aborted.Status),
        aborted.Positions.size());
    }
    const BilateralResult completed = run(edgeAware, [](double) { return false; });
    BilateralParameters given;
    given.Radius = 0.05;
    given.NormalRadius = 0.02;
    given.NumberOfIterations = 2;
    given.EdgeAware = edgeAware;
    const BilateralResult plain =
      pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(cloud), given);
    PCB_CHECK(completed.Status == BilateralStatus::Completed &&
                completed.Positions == plain.Positions && completed.Removed == plain.Removed,
      "edge-aware %d: a completed run differs with DiscardsAbortedResult",
      edgeAware);
  }
}
} // namespace

int main(int argc, char* argv[])
{
  return RunNamedCase(argc,
    argv,
    { { "Octree", Octree },
      { "Run", Run },
      { "Measurement", Measurement },
      { "BeforeMeasuring", BeforeMeasuring },
      { "BetweenIterations", BetweenIterations },
      { "AfterLastIteration", AfterLastIteration },
      { "DiscardedResult", DiscardedResult } });
}

// Distributed runs: each process holds a part of the cloud and drives a pcbilateral::BilateralRun
// on it, with the points of the other parts within reach as ghosts, so that the union of the
// parts' results is, bit for bit, what one process filtering the whole cloud computes. This file
// only communicates: the checks, the loop, progress, warnings and counts are the core's.
//
// The part a process filters is not its input part but one slab of space (SpatialRedistribution):
// a reader's share of a file in random spatial order spans the whole cloud, and its ghosts would
// be every other point. Redistributing always, rather than when the parts overlap, keeps one
// path: on parts that are compact already it costs one exchange of the points each way (0.1 to
// 0.3 s for 5M points on 2 processes), small next to filtering them.
//
// Ghosts are exchanged again before every iteration rather than fetched once in a halo wide
// enough for all of them. The core never moves ghost points, so a one-time halo would have to
// be filtered along with the own points (its outer layers growing stale by one radius per
// iteration): a halo about 2 N radii wide, filtered redundantly on every process that holds it,
// and a special case for points removed as isolated inside it. Exchanging every iteration sends
// only a layer one radius wide, filters every point exactly once, and is the recipe the core's
// exactness test (Testing/Core/TestPartitionedRun.cxx) runs in one process; its cost is one
// collective exchange per iteration, small next to filtering (N is 1 to a few).
//
// Every function here that communicates is collective: all processes call it in the same order.
// Decisions that end a run early are taken either from values every process shares (the
// parameters, the whole cloud's extent) or after a reduction of each process's status, so a
// failure on one process never leaves the others waiting.
#include "vtkPPointCloudBilateralFilter.h"

#include "BilateralFilter.h"
#include "CloudMeasurement.h"
#include "SpatialRedistribution.h"

#include "vtkCommunicator.h"
#include "vtkMPIController.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <vector>

vtkStandardNewMacro(vtkPPointCloudBilateralFilter);
vtkCxxSetObjectMacro(vtkPPointCloudBilateralFilter, Controller, vtkMultiProcessController);

namespace
{
using pcbilateral::BilateralResult;
using pcbilateral::BilateralStatus;
using pcbilateral::CloudExtent;

/// The whole cloud's extent (finite points only), and whether any process failed to prepare.
CloudExtent ShareExtent(vtkMultiProcessController* controller,
  const CloudExtent& local,
  bool failedHere,
  bool& anyFailed)
{
  const long long counts[2] = { failedHere ? 1 : 0,
    static_cast<long long>(local.NumberOfFinitePoints) };
  long long totals[2] = { 0, 0 };
  controller->AllReduce(counts, totals, 2, vtkCommunicator::SUM_OP);
  // A process without finite points must not widen the bounds.
  const bool empty = local.NumberOfFinitePoints == 0;
  double lower[3], upper[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    lower[axis] = empty ? std::numeric_limits<double>::max() : local.Min[axis];
    upper[axis] = empty ? -std::numeric_limits<double>::max() : local.Max[axis];
  }
  CloudExtent whole;
  controller->AllReduce(lower, whole.Min, 3, vtkCommunicator::MIN_OP);
  controller->AllReduce(upper, whole.Max, 3, vtkCommunicator::MAX_OP);
  anyFailed = totals[0] > 0;
  whole.NumberOfFinitePoints = static_cast<std::size_t>(totals[1]);
  return whole.NumberOfFinitePoints == 0 ? CloudExtent() : whole;
}

/// Every process learns the worst status of this step; Failed outranks Aborted.
BilateralStatus ShareStatus(vtkMultiProcessController* controller, BilateralStatus status)
{
  const int local = status == BilateralStatus::Failed    ? 2
                    : status == BilateralStatus::Aborted ? 1
                                                         : 0;
  int worst = 0;
  controller->AllReduce(&local, &worst, 1, vtkCommunicator::MAX_OP);
  return worst == 2   ? BilateralStatus::Failed
         : worst == 1 ? BilateralStatus::Aborted
                      : BilateralStatus::Completed;
}

/// The totals a single process would report, on every process.
void ShareTotals(vtkMultiProcessController* controller, BilateralResult& result)
{
  const long long counts[2] = { static_cast<long long>(result.NumberOfRemovedPoints),
    static_cast<long long>(result.NumberOfNonFinitePoints) };
  long long totals[2] = { 0, 0 };
  controller->AllReduce(counts, totals, 2, vtkCommunicator::SUM_OP);
  result.NumberOfRemovedPoints = static_cast<std::size_t>(totals[0]);
  result.NumberOfNonFinitePoints = static_cast<std::size_t>(totals[1]);
  // Processes without points of their own build no octree; the others agree on its depth.
  int depth = result.ProcessingDepth;
  controller->AllReduce(&depth, &result.ProcessingDepth, 1, vtkCommunicator::MAX_OP);
}

/// Collective: every process's `own` values, concatenated in process order; `offsets` (when
/// given) gets where each process's values begin, one more entry than processes.
std::vector<double> GatherFromAll(vtkMultiProcessController* controller,
  const std::vector<double>& own,
  std::vector<vtkIdType>* offsets = nullptr)
{
  const int processes = controller->GetNumberOfProcesses();
  const vtkIdType ownLength = static_cast<vtkIdType>(own.size());
  std::vector<vtkIdType> lengths(processes), starts(processes + 1, 0);
  controller->AllGather(&ownLength, lengths.data(), 1);
  for (int p = 0; p < processes; ++p)
  {
    starts[p + 1] = starts[p] + lengths[p];
  }
  std::vector<double> all(static_cast<std::size_t>(starts.back()));
  controller->AllGatherV(own.data(), all.data(), ownLength, lengths.data(), starts.data());
  if (offsets != nullptr)
  {
    *offsets = std::move(starts);
  }
  return all;
}

/**
 * The current positions of the other processes' points within this process's reach boxes
 * (BilateralRun::GetGhostReaches: one per radius band, 6 doubles each). `own` holds this
 * process's points that others may need. Every process learns every process's boxes and sends
 * each the points of `own` inside any of its boxes. One box per process (VTK's
 * vtkDistributedPointCloudFilter::GetPointsInsideBounds) would be grown by the largest band's
 * reach and, on a cloud whose density varies, bring a sparse part most of a dense part's
 * points. Positions travel as doubles: ghosts rounded to float would change the sums.
 */
std::vector<double> FetchGhosts(vtkMPIController* controller,
  const std::vector<double>& own,
  const std::vector<double>& reach)
{
  const int processes = controller->GetNumberOfProcesses();
  const int self = controller->GetLocalProcessId();
  std::vector<vtkIdType> offsets;
  const std::vector<double> boxes = GatherFromAll(controller, reach, &offsets);

  pcbilateral::ExchangedBuffers outgoing(processes);
  for (int other = 0; other < processes; ++other)
  {
    const double* first = boxes.data() + offsets[other];
    const double* last = boxes.data() + offsets[other + 1];
    for (std::size_t i = 0; other != self && i < own.size(); i += 3)
    {
      const double* p = own.data() + i;
      for (const double* box = first; box != last; box += 6)
      {
        if (pcbilateral::InsideBox(box, p))
        {
          outgoing[other].insert(outgoing[other].end(), p, p + 3);
          break;
        }
      }
    }
  }
  pcbilateral::ExchangedBuffers incoming =
    pcbilateral::ExchangeBuffers(controller, std::move(outgoing));
  std::vector<double> ghosts;
  for (std::vector<double>& from : incoming)
  {
    ghosts.insert(ghosts.end(), from.begin(), from.end());
    std::vector<double>().swap(from);
  }
  return ghosts;
}
/**
 * The whole cloud's scales for the automatic mode, the same bits on every process and as a run
 * on the whole cloud in one process: each process selects its points of the whole cloud's
 * measured selection (chosen by coordinates, so the parts together select what the whole cloud
 * would), every process gathers all of them and measures them (MeasureScales does not depend on
 * their order).
 */
pcbilateral::CloudScales ShareScales(vtkMultiProcessController* controller,
  const pcbilateral::PointCloudView& cloud,
  const CloudExtent& whole,
  int threads)
{
  const double fraction = pcbilateral::MeasuredFraction(whole.NumberOfFinitePoints);
  const std::vector<double> selection =
    GatherFromAll(controller, pcbilateral::SelectMeasurementPoints(cloud, fraction));
  return pcbilateral::MeasureSelection(selection, fraction, threads);
}
} // namespace

vtkPPointCloudBilateralFilter::vtkPPointCloudBilateralFilter()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPPointCloudBilateralFilter::~vtkPPointCloudBilateralFilter()
{
  this->SetController(nullptr);
}

BilateralResult vtkPPointCloudBilateralFilter::RunCore(const pcbilateral::PointCloudView& cloud,
  const pcbilateral::BilateralParameters& parameters,
  const pcbilateral::BilateralObserver& observer,
  bool preparedHere)
{
  this->NumberOfPointsHeld = static_cast<vtkIdType>(cloud.NumberOfPoints);
  this->LargestNumberOfPointsHeld = this->NumberOfPointsHeld;
  if (!this->Controller || this->Controller->GetNumberOfProcesses() <= 1)
  {
    return this->Superclass::RunCore(cloud, parameters, observer, preparedHere);
  }
  // The parameters are the same on every process: a run they make fail fails everywhere
  // before any communication. This run on the share as it is only checks and measures.
  auto shareRun = std::make_unique<pcbilateral::BilateralRun>(cloud, parameters, observer);
  if (shareRun->GetStatus() == BilateralStatus::Failed)
  {
    return shareRun->Finish();
  }
  auto* controller = vtkMPIController::SafeDownCast(this->Controller);
  if (!controller)
  {
    shareRun->Stop(BilateralStatus::Failed,
      std::string("a distributed run needs a vtkMPIController, not a ") +
        this->Controller->GetClassName());
    return shareRun->Finish();
  }

  bool anyFailed = false;
  const CloudExtent whole =
    ShareExtent(controller, shareRun->GetLocalExtent(), !preparedHere, anyFailed);
  if (anyFailed)
  {
    shareRun->Stop(BilateralStatus::Failed,
      preparedHere ? "another process could not start the distributed run (see its error); "
                     "nothing was filtered"
                   : "");
    return shareRun->Finish();
  }
  // Start decides from the whole cloud's extent, its scales and the parameters only: the same
  // everywhere, whoever holds which points.
  pcbilateral::CloudScales scales;
  if (shareRun->NeedsScales() && whole.NumberOfFinitePoints > 0)
  {
    scales = ShareScales(controller, cloud, whole, parameters.NumberOfThreads);
  }
  shareRun.reset();
  return this->RunRedistributed(controller, cloud, parameters, observer, whole, scales);
}

BilateralResult vtkPPointCloudBilateralFilter::RunRedistributed(vtkMPIController* controller,
  const pcbilateral::PointCloudView& cloud,
  const pcbilateral::BilateralParameters& parameters,
  const pcbilateral::BilateralObserver& observer,
  const CloudExtent& whole,
  const pcbilateral::CloudScales& scales)
{
  const pcbilateral::SpatialRedistribution region(controller, cloud, whole);
  pcbilateral::BilateralRun run(region.View(), parameters, observer);
  // Only the region's size can fail here, and on some processes only.
  if (ShareStatus(controller, run.GetStatus()) != BilateralStatus::Completed &&
      run.GetStatus() == BilateralStatus::Completed)
  {
    run.Stop(
      BilateralStatus::Failed, "another process failed (see its error); nothing was filtered");
  }
  std::size_t mostGhosts = 0;
  if (run.GetStatus() == BilateralStatus::Completed && run.Start(whole, &scales))
  {
    while (run.HasNextIteration())
    {
      const std::vector<double> ghosts =
        FetchGhosts(controller, run.GetPositionsForOthers(), run.GetGhostReaches());
      mostGhosts = std::max(mostGhosts, ghosts.size() / 3);
      const BilateralStatus status = ShareStatus(controller, run.Step(ghosts));
      if (status != BilateralStatus::Completed)
      {
        run.Stop(status, "another process failed (see its error); nothing was filtered");
      }
    }
  }
  BilateralResult result = region.ReturnResult(run.Finish());
  ShareTotals(controller, result);
  this->NumberOfPointsHeld = static_cast<vtkIdType>(region.View().NumberOfPoints + mostGhosts);
  controller->AllReduce(
    &this->NumberOfPointsHeld, &this->LargestNumberOfPointsHeld, 1, vtkCommunicator::MAX_OP);
  return result;
}

void vtkPPointCloudBilateralFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "NumberOfPointsHeld: " << this->NumberOfPointsHeld << "\n";
  os << indent << "LargestNumberOfPointsHeld: " << this->LargestNumberOfPointsHeld << "\n";
}

// Distributed runs of vtkPointCloudBilateralFilter: each process holds a part of the cloud and
// filters it with the points of the other parts within reach as ghosts, so that the union of
// the parts' results is, bit for bit, what one process filtering the whole cloud computes.
//
// Ghosts are exchanged again before every iteration rather than fetched once in a halo wide
// enough for all of them. The core never moves ghost points, so a one-time halo would have to
// be filtered along with the own points (its outer layers growing stale by one radius per
// iteration): a halo about 2 N radii wide, filtered redundantly on every process that holds it,
// and a special case for points removed as isolated inside it. Exchanging every iteration sends
// only a layer one radius wide, filters every point exactly once, and is the recipe the core's
// exactness test (Testing/Core/TestPartitionedRun.cxx) verifies; its cost is one collective
// exchange per iteration, small next to filtering (N is 1 to a few).
//
// Every function here that communicates is collective: all processes call it in the same order.
// Decisions that end a run early are taken either from values every process shares (the
// parameters, the whole cloud's extent) or after a reduction of each process's status, so a
// failure on one process never leaves the others waiting.
#include "vtkPointCloudBilateralFilter.h"

#include "BilateralFilter.h"
#include "BilateralKernel.h"

#include "vtkCommunicator.h"
#include "vtkDistributedPointCloudFilter.h"
#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkMPIController.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace
{
using pcbilateral::BilateralObserver;
using pcbilateral::BilateralParameters;
using pcbilateral::BilateralResult;
using pcbilateral::BilateralStatus;
using pcbilateral::CloudExtent;
using pcbilateral::PointCloudView;

/// Names of the arrays the ghost exchange carries; vtkPoints travel as float.
constexpr const char* PositionArrayName = "vtkPointCloudBilateralPosition";
constexpr const char* ProcessArrayName = "vtkPointCloudBilateralProcess";

struct SharedExtent
{
  bool AnyFailed = false;
  CloudExtent Extent;
};

/// The whole cloud's extent (finite points only), and whether any process failed to prepare.
SharedExtent ShareExtent(vtkMultiProcessController* controller,
  const CloudExtent& local,
  bool failed)
{
  const long long counts[2] = { failed ? 1 : 0,
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
  SharedExtent shared;
  controller->AllReduce(lower, shared.Extent.Min, 3, vtkCommunicator::MIN_OP);
  controller->AllReduce(upper, shared.Extent.Max, 3, vtkCommunicator::MAX_OP);
  shared.AnyFailed = totals[0] > 0;
  shared.Extent.NumberOfFinitePoints = static_cast<std::size_t>(totals[1]);
  if (shared.Extent.NumberOfFinitePoints == 0)
  {
    shared.Extent = CloudExtent(); // what MeasureCloud gives for a cloud without finite points
  }
  return shared;
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

/**
 * The box within `radius` of `xyz` (interleaved finite positions), with a margin for the
 * rounding of the box's own arithmetic; more ghosts than needed are harmless, since the kernel
 * ignores candidates beyond the radius. An inverted box when there are no points: it reaches
 * nothing.
 */
void ReachBox(const std::vector<double>& xyz, double radius, double box[6])
{
  for (int axis = 0; axis < 3; ++axis)
  {
    box[2 * axis] = std::numeric_limits<double>::max();
    box[2 * axis + 1] = -std::numeric_limits<double>::max();
  }
  if (xyz.empty())
  {
    return;
  }
  double magnitude = 0.0;
  for (std::size_t i = 0; i < xyz.size(); i += 3)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      box[2 * axis] = std::min(box[2 * axis], xyz[i + axis]);
      box[2 * axis + 1] = std::max(box[2 * axis + 1], xyz[i + axis]);
      magnitude = std::max(magnitude, std::abs(xyz[i + axis]));
    }
  }
  const double margin = 1.01 * radius + 1e-12 * magnitude;
  for (int axis = 0; axis < 3; ++axis)
  {
    box[2 * axis] -= margin;
    box[2 * axis + 1] += margin;
  }
}

bool InBox(const double* p, const double* box)
{
  return p[0] >= box[0] && p[0] <= box[1] && p[1] >= box[2] && p[1] <= box[3] && p[2] >= box[4] &&
         p[2] <= box[5];
}

/**
 * The current positions of the other processes' points within this process's reach box,
 * fetched with VTK's vtkDistributedPointCloudFilter::GetPointsInsideBounds. `xyz` holds this
 * process's finite, not removed points. The positions travel in a double array: the exchanged
 * vtkPoints are float, and ghosts rounded to float would change the sums.
 */
std::vector<double> FetchGhosts(vtkMPIController* controller,
  const std::vector<double>& xyz,
  const double box[6])
{
  const int processes = controller->GetNumberOfProcesses();
  const int self = controller->GetLocalProcessId();
  std::vector<double> boxes(6 * static_cast<std::size_t>(processes));
  controller->AllGather(box, boxes.data(), 6);

  // Only the points some other process reaches are offered: GetPointsInsideBounds also sends a
  // process its own points within its box, and most of those would be all of them.
  vtkNew<vtkPoints> points;
  points->SetDataType(VTK_DOUBLE);
  vtkNew<vtkDoubleArray> positions;
  positions->SetName(PositionArrayName);
  positions->SetNumberOfComponents(3);
  vtkNew<vtkIntArray> owner;
  owner->SetName(ProcessArrayName);
  for (std::size_t i = 0; i < xyz.size(); i += 3)
  {
    const double* p = xyz.data() + i;
    for (int other = 0; other < processes; ++other)
    {
      if (other != self && InBox(p, boxes.data() + 6 * other))
      {
        points->InsertNextPoint(p);
        positions->InsertNextTuple(p);
        owner->InsertNextValue(self);
        break;
      }
    }
  }
  vtkNew<vtkPolyData> offered;
  offered->SetPoints(points);
  offered->GetPointData()->AddArray(positions);
  offered->GetPointData()->AddArray(owner);

  vtkNew<vtkPolyData> received;
  vtkDistributedPointCloudFilter::GetPointsInsideBounds(controller, offered, received, box);

  std::vector<double> ghosts;
  auto* receivedPositions =
    vtkDoubleArray::SafeDownCast(received->GetPointData()->GetAbstractArray(PositionArrayName));
  auto* receivedOwners =
    vtkIntArray::SafeDownCast(received->GetPointData()->GetAbstractArray(ProcessArrayName));
  if (!receivedPositions || !receivedOwners)
  {
    return ghosts; // nothing was received
  }
  const vtkIdType count = receivedPositions->GetNumberOfTuples();
  ghosts.reserve(3 * static_cast<std::size_t>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    if (receivedOwners->GetValue(i) != self) // this process's own points come back too
    {
      const double* p = receivedPositions->GetPointer(3 * i);
      ghosts.insert(ghosts.end(), p, p + 3);
    }
  }
  return ghosts;
}
} // namespace

bool vtkPointCloudBilateralFilter::IsDistributed() const
{
  return this->Controller && this->Controller->GetNumberOfProcesses() > 1;
}

pcbilateral::BilateralResult vtkPointCloudBilateralFilter::RunDistributed(
  const PointCloudView& cloud,
  const BilateralParameters& parameters,
  const BilateralObserver& observer,
  bool failedHere)
{
  // Checks whose outcome is the same on every process come first and end the run without any
  // communication: every process sees the same parameters and controller.
  BilateralResult validation = pcbilateral::RunBilateralFilter(PointCloudView(), parameters);
  if (validation.Status == BilateralStatus::Failed)
  {
    return validation;
  }
  BilateralResult result;
  auto* controller = vtkMPIController::SafeDownCast(this->Controller);
  if (!controller)
  {
    result.Error = std::string("a distributed run needs a vtkMPIController, not a ") +
                   this->Controller->GetClassName();
    return result;
  }

  const CloudExtent local = pcbilateral::MeasureCloud(cloud);
  const SharedExtent shared = ShareExtent(controller, local, failedHere);
  if (shared.AnyFailed)
  {
    result.Error = failedHere ? "this process could not start the distributed run"
                              : "another process could not start the distributed run (see its "
                                "error); nothing was filtered";
    return result;
  }

  BilateralParameters step = parameters;
  step.GlobalExtent = shared.Extent;
  const pcbilateral::RadiiUsed radii = pcbilateral::ResolveRadii(parameters, shared.Extent);
  const int iterations = parameters.NumberOfIterations;
  if (shared.Extent.NumberOfFinitePoints == 0 || iterations == 0 || !(radii.Radius > 0.0))
  {
    // Nothing moves anywhere. The core returns before its first iteration here, with the
    // warnings a single process would give; it sees the whole cloud's extent.
    result = pcbilateral::RunBilateralFilter(cloud, step, observer);
    ShareTotals(controller, result);
    return result;
  }

  // The limits of double precision for the whole run (the core sees one iteration at a time).
  const std::string problem = pcbilateral::CheckPrecisionLimits(parameters, shared.Extent);
  if (!problem.empty())
  {
    result.Error = problem;
    return result;
  }

  // Radii fixed from the whole cloud, so that every process uses the same, and one iteration
  // per run of the core, the ghosts refreshed in between.
  step.Radius = radii.Radius;
  step.NormalRadius = radii.NormalRadius;
  step.NumberOfIterations = 1;

  const std::size_t n = cloud.NumberOfPoints;
  result.Status = BilateralStatus::Completed;
  result.RadiusUsed = radii.Radius;
  result.NormalRadiusUsed = radii.NormalRadius;
  result.Positions.assign(cloud.Positions, cloud.Positions + 3 * n);
  result.Removed.assign(n, 0);
  if (parameters.ComputeNormals)
  {
    result.Normals.assign(3 * n, 0.0);
  }
  result.NumberOfNonFinitePoints = n - local.NumberOfFinitePoints;

  std::vector<std::size_t> active; // own points not removed: the first points of the view
  std::vector<double> finite;      // their finite positions: what others may need as ghosts
  std::vector<double> view;
  std::vector<double> orientation;
  for (int iteration = 0; iteration < iterations; ++iteration)
  {
    active.clear();
    finite.clear();
    view.clear();
    for (std::size_t i = 0; i < n; ++i)
    {
      if (!result.Removed[i])
      {
        const double* p = result.Positions.data() + 3 * i;
        active.push_back(i);
        view.insert(view.end(), p, p + 3);
        if (pcbilateral::IsFinitePoint(p))
        {
          finite.insert(finite.end(), p, p + 3);
        }
      }
    }
    // Points move by less than a radius per iteration, but the box is taken from the current
    // positions, so one radius of reach is enough.
    double box[6];
    ReachBox(finite, radii.Radius, box);
    const std::vector<double> ghosts = FetchGhosts(controller, finite, box);
    view.insert(view.end(), ghosts.begin(), ghosts.end());

    PointCloudView part;
    part.NumberOfPoints = view.size() / 3;
    part.Positions = view.data();
    part.NumberOfGhostPoints = ghosts.size() / 3;
    const bool last = iteration + 1 == iterations;
    step.ComputeNormals = last && parameters.ComputeNormals;
    part.OrientationNormals = nullptr;
    if (step.ComputeNormals && cloud.OrientationNormals)
    {
      // Orientation changes only the reported normals, which only the last iteration gives.
      orientation.assign(view.size(), 0.0);
      for (std::size_t j = 0; j < active.size(); ++j)
      {
        const double* o = cloud.OrientationNormals + 3 * active[j];
        std::copy(o, o + 3, orientation.begin() + 3 * j);
      }
      part.OrientationNormals = orientation.data();
    }
    BilateralObserver stepObserver;
    stepObserver.ShouldAbort = observer.ShouldAbort;
    if (iteration == 0)
    {
      stepObserver.Warning = observer.Warning; // each step would repeat them
    }
    if (observer.Progress)
    {
      stepObserver.Progress = [&](double fraction)
      { observer.Progress((iteration + fraction) / iterations); };
    }

    const BilateralResult partResult = pcbilateral::RunBilateralFilter(part, step, stepObserver);
    const BilateralStatus status = ShareStatus(controller, partResult.Status);
    if (status != BilateralStatus::Completed)
    {
      result.Status = status;
      if (status == BilateralStatus::Failed)
      {
        result.Error = partResult.Status == BilateralStatus::Failed
                         ? partResult.Error
                         : "another process failed (see its error); nothing was filtered";
      }
      return result;
    }
    if (iteration == 0)
    {
      result.Warnings = partResult.Warnings; // the same in every step
    }
    result.ProcessingDepth = std::max(result.ProcessingDepth, partResult.ProcessingDepth);
    result.NumberOfNeighbourEvaluations += partResult.NumberOfNeighbourEvaluations;
    for (std::size_t j = 0; j < active.size(); ++j)
    {
      const std::size_t i = active[j];
      std::copy_n(partResult.Positions.data() + 3 * j, 3, result.Positions.data() + 3 * i);
      result.Removed[i] = partResult.Removed[j];
      if (step.ComputeNormals)
      {
        std::copy_n(partResult.Normals.data() + 3 * j, 3, result.Normals.data() + 3 * i);
      }
    }
  }
  result.NumberOfRemovedPoints = static_cast<std::size_t>(
    std::count(result.Removed.begin(), result.Removed.end(), std::uint8_t{ 1 }));
  ShareTotals(controller, result);
  return result;
}

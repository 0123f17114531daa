// Moving a cloud's points between the processes of a distributed run so that each holds one
// region of space: the shares a reader gives (contiguous ranges of a file's records) can each
// span the whole cloud, and then every process would need every other point as a neighbour.
// Internal to Filters/Parallel; every function that communicates is collective.
#ifndef pcbilateral_SpatialRedistribution_h
#define pcbilateral_SpatialRedistribution_h

#include "BilateralFilter.h"
#include "PointCloudView.h"

#include <cstddef>
#include <vector>

class vtkMPIController;

namespace pcbilateral
{

/// One buffer of doubles per process.
using ExchangedBuffers = std::vector<std::vector<double>>;

/// Collective: outgoing[p] goes to process p (outgoing[self] stays); returns what each process
/// sent here, by process. Each outgoing buffer is freed once sent.
ExchangedBuffers ExchangeBuffers(vtkMPIController* controller, ExchangedBuffers outgoing);

/**
 * The points of this process's region, moved there from the processes that hold them in the
 * input, and the way back for the run's result.
 *
 * The regions are slabs along the whole cloud's longest axis, cut where the cumulative count of
 * a global histogram (2^18 bins, reduced over the processes) reaches k/N of the finite points:
 * balanced to a bin's count, and the same on every process since it depends only on the whole
 * cloud's extent and the reduced counts. Coordinates (and orientation normals) travel as
 * doubles, bit for bit. Non-finite points stay where they are (they are never neighbours, and
 * the process that holds them warns about them as before). The region's points are ordered by
 * the process they came from, then by their index there; the core's results do not depend on
 * the split or the order (its sums run in an order fixed by geometry), so the result brought
 * back is, bit for bit, what a run on the shares as they were gives.
 */
class SpatialRedistribution
{
public:
  /// Collective: moves every finite point of `share` to the process whose slab of `whole`
  /// holds it.
  SpatialRedistribution(vtkMPIController* controller,
    const PointCloudView& share,
    const CloudExtent& whole);

  /// The points this process holds now (its region), valid while this object lives.
  PointCloudView View() const;

  /**
   * Collective: the result of the run on View() brought back to the processes the points came
   * from, each point at its index in `share`. The counts and parameters are the region
   * result's (ShareTotals makes the totals the same everywhere).
   */
  BilateralResult ReturnResult(BilateralResult regionResult) const;

private:
  vtkMPIController* Controller;
  int NumberOfProcesses;
  bool HasOrientation = false;
  /// For each point of the share, the process that filters it.
  std::vector<int> Destination;
  /// How many points came from each process, in the order they are held.
  std::vector<std::size_t> ReceivedCounts;
  std::vector<double> Positions;
  std::vector<double> Orientation;
};

} // namespace pcbilateral

#endif

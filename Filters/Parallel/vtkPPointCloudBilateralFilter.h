/**
 * @class   vtkPPointCloudBilateralFilter
 * @brief   the bilateral filter on a point cloud split across the processes of an MPI run
 *
 * vtkPPointCloudBilateralFilter runs vtkPointCloudBilateralFilter on a cloud whose points are
 * split across processes: under `mpirun pvbatch` or pvserver (ParaView's proxy uses this
 * class), or in any program with a vtkMPIController of several processes as the Controller.
 * Each process's input is its part of the cloud, split in any way (a reader's pieces,
 * ParaView's Distribute Points, or empty on some processes). Each process filters its own
 * points and outputs only them, in their order and with all their arrays; the union of the
 * outputs is bit for bit the output of vtkPointCloudBilateralFilter on the whole cloud.
 *
 * How: the automatic radius and the octree's geometry come from the whole cloud's point count
 * and bounds (a reduction); the points are then moved, as doubles, into one slab of space per
 * process with equal counts (so that a process whose input part spans the whole cloud, as a
 * reader's share of a file in random order does, never needs the whole cloud as neighbours);
 * before each iteration, the processes exchange the current positions of their points within
 * reach of each other's slabs (one box per radius band: a band reaches as far as its own radius),
 * which the core uses as neighbours only; the filtered positions go back to the processes that
 * hold the points in the input. Every process must update the filter together, as with VTK's other
 * parallel filters; a failure on one process (bad input, bad parameters) ends the update on all of
 * them with an error. The numbers read after an update (GetRadiusUsed(),
 * GetNumberOfRemovedPoints()...) are the same on every process: totals over the whole cloud.
 *
 * With no controller or a single process, it is vtkPointCloudBilateralFilter.
 *
 * @sa
 * vtkPointCloudBilateralFilter
 */
#ifndef vtkPPointCloudBilateralFilter_h
#define vtkPPointCloudBilateralFilter_h

#include "vtkFiltersParallelPointCloudBilateralModule.h" // For export macro
#include "vtkPointCloudBilateralFilter.h"

class vtkMPIController;
class vtkMultiProcessController;
namespace pcbilateral
{
struct CloudExtent;
struct CloudScales;
}

class VTKFILTERSPARALLELPOINTCLOUDBILATERAL_EXPORT vtkPPointCloudBilateralFilter
  : public vtkPointCloudBilateralFilter
{
public:
  static vtkPPointCloudBilateralFilter* New();
  vtkTypeMacro(vtkPPointCloudBilateralFilter, vtkPointCloudBilateralFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The processes sharing the cloud; by default the global controller. With several
   * processes, it must be a vtkMPIController, and every process must update the filter.
   */
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /**
   * After an update, the most points this process held at once for filtering: those it
   * filtered (its region, after the redistribution) plus the most ghost points it received for
   * one iteration (its input part, which it keeps for its output, is not counted); and the most
   * any process held (the same on every process). With one process, its input's (chosen)
   * points. They show that no process holds the whole cloud: each holds about 1/N of
   * it plus a layer one radius wide (three in the edge-aware mode) at its region's borders.
   */
  vtkGetMacro(NumberOfPointsHeld, vtkIdType);
  vtkGetMacro(LargestNumberOfPointsHeld, vtkIdType);
  ///@}

protected:
  vtkPPointCloudBilateralFilter();
  ~vtkPPointCloudBilateralFilter() override;

  pcbilateral::BilateralResult RunCore(const pcbilateral::PointCloudView& cloud,
    const pcbilateral::BilateralParameters& parameters,
    const pcbilateral::BilateralObserver& observer,
    bool preparedHere) override;

  vtkMultiProcessController* Controller = nullptr;
  vtkIdType NumberOfPointsHeld = 0;
  vtkIdType LargestNumberOfPointsHeld = 0;

private:
  /// The run on the points of this process's region of space (SpatialRedistribution.h), its
  /// result brought back to the processes that hold the points in the input.
  pcbilateral::BilateralResult RunRedistributed(vtkMPIController* controller,
    const pcbilateral::PointCloudView& cloud,
    const pcbilateral::BilateralParameters& parameters,
    const pcbilateral::BilateralObserver& observer,
    const pcbilateral::CloudExtent& whole,
    const pcbilateral::CloudScales& scales);

  vtkPPointCloudBilateralFilter(const vtkPPointCloudBilateralFilter&) = delete;
  void operator=(const vtkPPointCloudBilateralFilter&) = delete;
};

#endif

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
 * and bounds (a reduction); before each iteration, the processes exchange the current
 * positions of their points within one radius of each other's (with
 * vtkDistributedPointCloudFilter::GetPointsInsideBounds), which the core uses as neighbours
 * only. Every process must update the filter together, as with VTK's other parallel filters;
 * a failure on one process (bad input, bad parameters) ends the update on all of them with an
 * error. The numbers read after an update (GetRadiusUsed(), GetNumberOfRemovedPoints()...) are
 * the same on every process: totals over the whole cloud.
 *
 * With no controller or a single process, it is vtkPointCloudBilateralFilter.
 *
 * @sa
 * vtkPointCloudBilateralFilter vtkDistributedPointCloudFilter
 */
#ifndef vtkPPointCloudBilateralFilter_h
#define vtkPPointCloudBilateralFilter_h

#include "vtkFiltersParallelPointCloudBilateralModule.h" // For export macro
#include "vtkPointCloudBilateralFilter.h"

class vtkMultiProcessController;

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

protected:
  vtkPPointCloudBilateralFilter();
  ~vtkPPointCloudBilateralFilter() override;

  pcbilateral::BilateralResult RunCore(const pcbilateral::PointCloudView& cloud,
    const pcbilateral::BilateralParameters& parameters,
    const pcbilateral::BilateralObserver& observer,
    bool preparedHere) override;

  vtkMultiProcessController* Controller = nullptr;

private:
  vtkPPointCloudBilateralFilter(const vtkPPointCloudBilateralFilter&) = delete;
  void operator=(const vtkPPointCloudBilateralFilter&) = delete;
};

#endif

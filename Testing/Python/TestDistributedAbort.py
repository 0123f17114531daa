"""An abort on one rank stops the distributed filter on every rank: under
mpirun pvbatch --symmetric (every rank runs this script), rank 1 sets AbortExecute at the
filter's first progress event; every rank's update then ends early with no output, none waits
for another, and a later update without the abort completes on all of them.

    mpirun -np P pvbatch --symmetric TestDistributedAbort.py

Each rank prints its own checks; a failed one exits with 1, which mpirun reports.
"""
import os
import sys

import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkParallelCore import vtkMultiProcessController

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pcb_testing import check, failures, finish  # noqa: E402
from pointcloudbilateral import vtkPPointCloudBilateralFilter  # noqa: E402

controller = vtkMultiProcessController.GetGlobalController()
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
check(ranks >= 2, f"rank {rank}: {ranks} MPI processes")
# Each rank's slab of a noisy plane.
rng = np.random.default_rng(3)
xyz = np.column_stack([rng.random(20000), rng.random(20000), rng.normal(0, 0.005, 20000)])
mine = (xyz[:, 0] * ranks).astype(int) == rank
cloud = dsa.WrapDataObject(vtkPolyData())
cloud.Points = xyz[mine]

bilateral = vtkPPointCloudBilateralFilter()
bilateral.SetInputData(cloud.VTKObject)
bilateral.SetRadius(0.05)
bilateral.SetNumberOfIterations(4)
bilateral.SetNumberOfThreads(1)


def abort_at_first_progress(caller, event):
    if rank == 1:
        caller.SetAbortExecute(1)


tag = bilateral.AddObserver("ProgressEvent", abort_at_first_progress)
bilateral.Update()
count = bilateral.GetOutput().GetNumberOfPoints()
check(count == 0, f"rank {rank}: rank 1 aborted, {count} points out here")

bilateral.RemoveObserver(tag)
bilateral.Modified()
bilateral.Update()
count = bilateral.GetOutput().GetNumberOfPoints()
check(count == int(mine.sum()), f"rank {rank}: without the abort, {count} points out of "
      f"{int(mine.sum())}")
if failures:
    finish()
print(f"rank {rank}: all checks passed")

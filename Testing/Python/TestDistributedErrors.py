"""Errors in distributed runs end the update on every rank with a message, never in a hang.

    mpirun -np P pvbatch TestDistributedErrors.py PLUGIN

- a negative radius: every rank refuses it before any communication;
- an orientation array of 2 components on rank 1 only: rank 1 cannot start, and the others,
  told so by the first reduction, stop too;
- then a valid update of the same pipeline completes: no rank was left mid-exchange.
The test's timeout catches a hang.
"""
import os
import sys

from paraview import servermanager, simple
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pcb_testing import check, failures, finish  # noqa: E402

plugin = sys.argv[1]
simple.LoadPlugin(plugin, remote=True, ns=vars(simple))

# Rank 0 is a server too, and the programmable source runs its script in this interpreter's
# __main__: names here must not clash with the ones ParaView defines there (such as "source").
# Each rank makes its own slab of a noisy plane; "Orient" has 3 components on rank 0 only.
cloud_source = simple.ProgrammableSource(OutputDataSetType="vtkPolyData")
cloud_source.Script = """
import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkParallelCore import vtkMultiProcessController

controller = vtkMultiProcessController.GetGlobalController()
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
rng = np.random.default_rng(3)
xyz = np.column_stack([rng.random(4000), rng.random(4000), rng.normal(0, 0.005, 4000)])
mine = (xyz[:, 0] * ranks).astype(int) == rank
output = dsa.WrapDataObject(self.GetPolyDataOutput())
output.Points = xyz[mine]
components = 2 if rank == 1 else 3
output.PointData.append(np.tile([0.0, 0.0, 1.0], (int(mine.sum()), 1))[:, :components].copy(),
                        "Orient")
"""
cloud_source.UpdatePipeline()
total = servermanager.Fetch(cloud_source).GetNumberOfPoints()
check(total == 4000, f"{total} points over the ranks")


def run(**properties):
    """Updates the filter; returns the gathered output's point count and rank 0's messages."""
    console = vtkOutputWindow.GetInstance()
    messages = vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(messages)
    try:
        bilateral = simple.PointCloudBilateralFilter(Input=cloud_source, NumberOfThreads=1,
                                                     **properties)
        bilateral.UpdatePipeline()
        count = servermanager.Fetch(bilateral).GetNumberOfPoints()
        simple.Delete(bilateral)
    finally:
        vtkOutputWindow.SetInstance(console)
    return count, messages.GetOutput()


count, text = run(Radius=-0.1)
check(count == 0 and "the radius must be a finite number >= 0" in text,
      f"negative radius: {count} points out, and the message says why")

count, text = run(Radius=0.05, OrientEstimatedNormals=1, OrientNormalsBy="Orient",
                  OutputEstimatedNormals=1)
check(count == 0 and "another process could not start the distributed run" in text,
      f"a 2-component orientation array on rank 1: {count} points out, and rank 0 says why")

count, text = run(Radius=0.05, NumberOfIterations=2)
check(count == total and "ERR" not in text,
      f"a valid update afterwards: {count} points out of {total}")

if failures:
    finish()
# sys.exit would skip MPI_Finalize, which mpirun reports as a failure: end the script instead.
print("all checks passed")

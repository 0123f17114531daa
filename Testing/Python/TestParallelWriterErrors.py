"""A rank that cannot write its part fails the parallel LAS/LAZ writer on every rank, promptly,
and leaves no file:

    mpirun -np P pvbatch TestParallelWriterErrors.py PLUGIN SCRATCH_FOLDER

- a point whose coordinates are not finite on rank 1 only (the LAS records cannot hold it):
  SaveData to .las and to .laz fails on every rank, rank 0 says another process could not write
  its part, no file and no temporary file are left;
- an unwritable destination (a folder that does not exist): every rank fails with one line;
- then a sound cloud is written: no rank was left waiting in a collective.
The test's timeout catches a hang.
"""
import os
import sys

from paraview import simple
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pcb_testing import check, failures, finish  # noqa: E402

plugin, scratch = sys.argv[1:3]
os.makedirs(scratch, exist_ok=True)
simple.LoadPlugin(plugin, remote=True, ns=vars(simple))

# Rank 0 is a server too, and the programmable source runs its script in this interpreter's
# __main__ (with numpy's names): the names here must not clash with them. Each rank's slab of a
# plane; rank 1 has a point at NaN when BAD is set.
SCRIPT = """
import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkParallelCore import vtkMultiProcessController

controller = vtkMultiProcessController.GetGlobalController()
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
rng = np.random.default_rng(5)
xyz = np.column_stack([rng.random(3000), rng.random(3000), rng.normal(0, 0.005, 3000)])
mine = xyz[(xyz[:, 0] * ranks).astype(int) == rank]
if BAD and rank == 1:
    mine[0, 2] = np.nan
output = dsa.WrapDataObject(self.GetPolyDataOutput())
output.Points = mine
"""


def save_slabs(bad, path):
    """SaveData of the slabs to `path`; returns rank 0's messages."""
    cloud = simple.ProgrammableSource(OutputDataSetType="vtkPolyData",
                                      Script=SCRIPT.replace("BAD", str(bad)))
    console = vtkOutputWindow.GetInstance()
    messages = vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(messages)
    try:
        simple.SaveData(path, proxy=cloud)
    except Exception as error:
        print(f"SaveData: {error}")
    finally:
        vtkOutputWindow.SetInstance(console)
        simple.Delete(cloud)
    return messages.GetOutput()


for extension in ("las", "laz"):
    path = os.path.join(scratch, f"not-finite.{extension}")
    for old in (path, path + ".partial"):
        if os.path.exists(old):
            os.remove(old)
    text = save_slabs(True, path)
    check("another process could not write its part" in text,
          f".{extension}: a non-finite point on rank 1: rank 0 says another process could not "
          f"write its part")
    check(not os.path.exists(path) and not os.path.exists(path + ".partial"),
          f".{extension}: no file and no temporary file left")

missing = os.path.join(scratch, "no-such-folder", "cloud.las")
text = save_slabs(False, missing)
check("cannot be written" in text and not os.path.exists(missing),
      f"an unwritable destination: one line on rank 0: {text.strip().splitlines()[-1:]}")

sound = os.path.join(scratch, "sound.las")
text = save_slabs(False, sound)
check(os.path.isfile(sound) and "ERR" not in text, "a sound cloud afterwards is written")
if os.path.isfile(sound):
    with open(sound, "rb") as stream:
        count = int.from_bytes(stream.read(111)[107:111], "little")
    check(count == 3000, f"with its {count} points from every rank")
if failures:
    finish()
# sys.exit would skip MPI_Finalize, which mpirun reports as a failure: end the script instead.
print("all checks passed")

"""A piece that cannot be read stops every rank, promptly: under mpirun pvbatch, a file whose
damage lies in the last rank's share (its last line cut short) fails the read on every rank
(the damaged rank says what is wrong, the others that another process could not read its
piece), the distributed filter outputs no point, SaveData with the parallel LAS writer
completes on every rank, and a later update on a sound file completes (no rank was left
waiting in a collective).

    mpirun -np P pvbatch TestPieceFailure.py PLUGIN SCRATCH_FOLDER FILE
    mpirun -np P pvbatch TestPieceFailure.py PLUGIN SCRATCH_FOLDER --laz

FILE is a text (.xyz, .txt) or PCD ascii file; the damaged copy is written to SCRATCH_FOLDER.
With --laz, a LAZ file of 120,000 points (point format 0, three chunks) is written there and its
last chunk's last 20,000 bytes overwritten: only the last ranks' pieces decode that chunk (the
LAS reader, which reported the damage and went on with no points on that rank, fails too).
Before the collective check the other ranks waited for the damaged one in the filter for ever:
the test's timeout catches that. Exits with 77 (skipped) when FILE does not exist.
"""
import os
import sys

from paraview import servermanager, simple
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkParallelCore import vtkMultiProcessController

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pcb_testing import check, failures, finish  # noqa: E402

plugin, scratch, source = sys.argv[1:4]
laz = source == "--laz"
if not laz and not os.path.isfile(source):
    print(f"skipped: no file '{source}' (set the shared data folders)")
    sys.exit(77)
ranks = vtkMultiProcessController.GetGlobalController().GetNumberOfProcesses()
check(ranks >= 2, f"{ranks} MPI processes")
os.makedirs(scratch, exist_ok=True)
simple.LoadPlugin(plugin, remote=True, ns=vars(simple))

if laz:
    import numpy as np
    from vtkmodules.numpy_interface import dataset_adapter as dsa
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    from pointcloudbilateral import vtkLASPointCloudWriter

    rng = np.random.default_rng(27)
    cloud = dsa.WrapDataObject(vtkPolyData())
    cloud.Points = np.column_stack([rng.random(120000), rng.random(120000),
                                    rng.normal(0, 0.005, 120000)])
    source = os.path.join(scratch, f"sound-{ranks}.laz")
    writer = vtkLASPointCloudWriter()
    writer.SetInputData(cloud.VTKObject)
    writer.SetFileName(source)
    check(writer.Write() == 1, f"{source} written")
extension = os.path.splitext(source)[1].lower()
Reader = {".pcd": simple.PCDPointCloudReader, ".laz": simple.LASPointCloudReader}.get(
    extension, simple.PointCloudTextReader)
damaged = os.path.join(scratch, f"cut-short-{ranks}-" + os.path.basename(source))


def damage_last_chunk():
    """The LAZ file with the last 20,000 bytes before its chunk table overwritten."""
    with open(source, "rb") as stream:
        data = bytearray(stream.read())
    point_data = int.from_bytes(data[96:100], "little")
    table = int.from_bytes(data[point_data:point_data + 8], "little")
    data[table - 20000:table] = b"\xff" * 20000
    with open(damaged, "wb") as stream:
        stream.write(data)


def cut_last_line():
    """The last line cut after its first value, so that only the last share is bad."""
    with open(source, "rb") as stream:
        data = stream.read().rstrip(b"\r\n")
    last_line = data.rfind(b"\n") + 1
    first_value_end = data.find(b" ", last_line + 1)
    tab = data.find(b"\t", last_line + 1)
    if tab != -1 and (first_value_end == -1 or tab < first_value_end):
        first_value_end = tab
    with open(damaged, "wb") as stream:
        stream.write(data[:first_value_end] + b"\n")


if laz:
    damage_last_chunk()
else:
    cut_last_line()


def update(proxy, fetch=True):
    """Updates `proxy` (or writes with it); returns the gathered point count and rank 0's
    messages."""
    console = vtkOutputWindow.GetInstance()
    messages = vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(messages)
    try:
        proxy.UpdatePipeline()
        count = servermanager.Fetch(proxy).GetNumberOfPoints() if fetch else None
    finally:
        vtkOutputWindow.SetInstance(console)
    return count, messages.GetOutput()


reader = Reader(FileName=damaged)
bilateral = simple.PointCloudBilateralFilter(Input=reader, NumberOfThreads=1)
count, text = update(bilateral)
check(count == 0 and "another process could not read its piece" in text,
      f"the last rank's piece cut short: {count} points out on {ranks} ranks, and rank 0 says "
      f"why: {text.strip().splitlines()[:1]}")

# A new pipeline (a failed reader keeps its empty output until modified, as in one process).
reader = Reader(FileName=damaged)
bilateral = simple.PointCloudBilateralFilter(Input=reader, NumberOfThreads=1)
written = os.path.join(scratch, f"cut-short-{ranks}.las")
if os.path.exists(written):
    os.remove(written)
console = vtkOutputWindow.GetInstance()
messages = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(messages)
try:
    simple.SaveData(written, proxy=bilateral)
except Exception as error:
    print(f"SaveData: {error}")
finally:
    vtkOutputWindow.SetInstance(console)
# SaveData updates the filter, then the writer: the failed reader's empty output is up to date
# by then, so, as in one process, a file of no points may be written (ParaView's behaviour).
points_written = 0
if os.path.exists(written):
    with open(written, "rb") as stream:
        points_written = int.from_bytes(stream.read(111)[107:111], "little")
check(points_written == 0 and not os.path.exists(written + ".partial"),
      f"SaveData after the failed read completes on every rank and writes no point "
      f"({'a file of 0 points' if os.path.exists(written) else 'no file'})")
check("another process could not read its piece" in messages.GetOutput(),
      "and says why on rank 0")

sound = Reader(FileName=source)
bilateral = simple.PointCloudBilateralFilter(Input=sound, NumberOfThreads=1)
count, text = update(bilateral)
check(count > 0 and "ERR" not in text, f"a sound file afterwards: {count} points out")
if failures:
    finish()
# sys.exit would skip MPI_Finalize, which mpirun reports as a failure: end the script instead.
print("all checks passed")

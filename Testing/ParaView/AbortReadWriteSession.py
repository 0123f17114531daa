"""Run inside the ParaView GUI (paraview --script=... --exit) by TestAbort.sh read-write: Abort
stops the plugin's LAS/LAZ reader and writer too, logged as the GUI sees it. A LAZ file of
PCB_ABORT_POINTS points (12 million by default: read in about 1.5 s and written in about 3, so
that the click at 5 % lands well before the end; 3 million points were read in 0.35 s, and a
read or a write under load could end before the click) is written first by the VTK class
itself, then:
  1. opened (the LAS reader) and shown: TestAbort.sh clicks Abort during the read;
  2. reloaded (File > Reload Files: a new VTK object for the reader): Abort again;
  3. reloaded once more, to the end;
  4. saved to a .laz file (a writer made by the writer factory, as by File > Save Data, which
     registers no pipeline source): Abort during the write;
  5. saved again, to the end, and read back.
Logged (AbortLog.py):
  start NAME         an abortable phase starts (TestAbort.sh clicks Abort in each, at 5 %)
  progress P T       the progress bar showed P percent and the text T
  returned NAME      the reader or writer returned (aborted or not)
  aborted-message K  the plugin's message after an aborted run (K: Reader or Writer)
  end NAME N [F]     the phase ended with N points read (a write: N 1 if the file exists, and F
                     the files left in the output folder)
  again NAME N       a run after the aborts ended with N points (read back, for the write)
  points N           the generated file's number of points
  camera X Y         the view's focal point after the reload (the cloud spans 0-1000 in x and y)
  radius R           the display's Point Gaussian radius then (set from empty bounds, -0.01, when
                     the display was first shown on the aborted read's empty output)"""
import os
import sys

import numpy
from paraview import simple
from pointcloudbilateral import vtkLASPointCloudReader, vtkLASPointCloudWriter
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData

sys.path.insert(0, os.path.join(os.environ["PCB_SOURCE_DIR"], "Testing", "ParaView"))
from AbortLog import log, note, follow_progress_and_warnings  # noqa: E402

scratch = os.path.dirname(os.path.abspath(os.environ["PCB_LOG"]))
follow_progress_and_warnings(lambda text: "aborted-message " + (
    "Writer" if "Writer" in text else "Reader") if "aborted" in text else None)


def write_cloud(path, count):
    """A terrain-like cloud (a smooth surface with noise), written by the VTK class."""
    generator = numpy.random.default_rng(28)
    xy = generator.random((count, 2)) * 1000.0
    z = 20.0 * numpy.sin(xy[:, 0] / 90.0) * numpy.cos(xy[:, 1] / 70.0) + generator.random(count)
    points = vtkPoints()
    points.SetData(numpy_to_vtk(numpy.column_stack((xy, z)), deep=True))
    cloud = vtkPolyData()
    cloud.SetPoints(points)
    writer = vtkLASPointCloudWriter()
    writer.SetFileName(path)
    writer.SetInputData(cloud)
    writer.Write()


def read_back(path):
    reader = vtkLASPointCloudReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput().GetNumberOfPoints()


def observe_return(proxy, name):
    proxy.GetClientSideObject().AddObserver("EndEvent", lambda caller, event: note(
        f"returned {name}"))


source = os.path.join(scratch, "cloud.laz")
saved_folder = os.path.join(scratch, "saved")
os.makedirs(saved_folder, exist_ok=True)
for name in os.listdir(saved_folder):
    os.remove(os.path.join(saved_folder, name))
saved = os.path.join(saved_folder, "saved.laz")
note("generating")
write_cloud(source, int(os.environ.get("PCB_ABORT_POINTS", "12000000")))
note(f"points {read_back(source)}")

reader = simple.OpenDataFile(source)
observe_return(reader, "read")
note("start read")
display = simple.Show(reader)  # (reads the file)
simple.Render()
# Only the reads are timed: drawing millions of points would take longer than reading them.
display.SetRepresentationType("Outline")
note(f"end read {reader.GetDataInformation().GetNumberOfPoints()}")

# File > Reload Files: the reader's VTK object is made anew, and Abort must reach the new one.
simple.ReloadFiles(reader)
observe_return(reader, "reload")
note("start reload")
simple.Render()
note(f"end reload {reader.GetDataInformation().GetNumberOfPoints()}")
simple.ReloadFiles(reader)
simple.Render()
note(f"again read {reader.GetDataInformation().GetNumberOfPoints()}")

# What File > Save Data does (pqSaveDataReaction): a writer proxy from the writer factory, then
# its UpdatePipeline.
writer = simple.CreateWriter(saved, reader)
observe_return(writer, "write")
note("start write")
writer.UpdatePipeline()
left = ",".join(sorted(os.listdir(saved_folder))) or "-"
note(f"end write {int(os.path.exists(saved))} {left}")
# The display, first shown on the aborted read's empty output, had the camera fitted to nothing;
# once the reload had points, the plugin fitted it to them (as the reload's data was updated).
note("camera {:.0f} {:.0f}".format(*simple.GetActiveCamera().GetFocalPoint()[:2]))
note(f"radius {simple.GetDisplayProperties(reader).GaussianRadius}")
del writer
simple.SaveData(saved, proxy=reader)
note(f"again write {read_back(saved) if os.path.exists(saved) else 0}")
log.close()

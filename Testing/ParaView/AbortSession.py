"""Run inside the ParaView GUI (paraview --script=... --exit) by TestAbort.sh: one long Apply
(radius 1.5 on the 40,000-point cube: every point is a neighbour of every other), logged as the
GUI sees it. Each line of PCB_LOG is "<absolute time> <what> [value]", flushed at once so that
the driving script can follow the run and click Abort:
  progress P T the session's progress handler (what the progress bar shows) reported P percent
               and the text T
  warning      a warning reached the output window (the Output Messages window)
  returned     the filter returned (aborted or not)
  aborted-message   the plugin's message after an aborted run reached the output window
  end N        the run ended with N output points (0 after an abort)
  again N      a later Apply, with radius 0.06 then 0.07, ended with N output points"""
import os
import time

from paraview import servermanager, simple
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkOutputWindow

log = open(os.environ["PCB_LOG"], "w")


def note(what):
    log.write(f"{time.time():.3f} {what}\n")
    log.flush()


handler = servermanager.ActiveConnection.Session.GetProgressHandler()
handler.AddObserver("ProgressEvent", lambda caller, event: note(
    f"progress {caller.GetLastProgress()} {caller.GetLastProgressText()}"))


@calldata_type(VTK_STRING)
def on_warning(caller, event, text):
    note("aborted-message" if "aborted" in text else "warning")


vtkOutputWindow.GetInstance().AddObserver("WarningEvent", on_warning)

data = os.path.join(os.environ["PCB_SOURCE_DIR"], "Data", "cube_noise0.5.ply")
reader = simple.PLYReader(FileNames=[data])
reader.UpdatePipeline()
bilateral = simple.PointCloudBilateralFilter(Input=reader, Radius=1.5, NumberOfIterations=4)
# When the filter itself returns (the end of the Apply adds a render of its empty output).
bilateral.GetClientSideObject().AddObserver("EndEvent", lambda caller, event: note("returned"))
note("start")
simple.Show(bilateral)
simple.Render()
note(f"end {bilateral.GetDataInformation().GetNumberOfPoints()}")
# Two Applies after the abort, with an ordinary radius: each must run to the end (the abort once
# stuck, and every later Apply of the filter aborted within a second).
for radius in (0.06, 0.07):
    bilateral.Radius = radius
    simple.Render()
    note(f"again {bilateral.GetDataInformation().GetNumberOfPoints()}")
log.close()

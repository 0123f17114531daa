"""Run inside the ParaView GUI (paraview --script=... --exit) by TestAbort.sh: one long Apply
(radius 1.5 on the 40,000-point cube: every point is a neighbour of every other), logged as the
GUI sees it (AbortLog.py):
  progress P T the progress bar showed P percent and the text T
  warning      a warning reached the output window (the Output Messages window)
  returned     the filter returned (aborted or not)
  aborted-message   the plugin's message after an aborted run reached the output window
  end N        the run ended with N output points (0 after an abort)
  again N      a later Apply, with radius 0.06 then 0.07, ended with N output points"""
import os
import sys

from paraview import simple

sys.path.insert(0, os.path.join(os.environ["PCB_SOURCE_DIR"], "Testing", "ParaView"))
from AbortLog import log, note, follow_progress_and_warnings  # noqa: E402

follow_progress_and_warnings(lambda text: "aborted-message" if "aborted" in text else "warning")

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

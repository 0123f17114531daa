"""Bad parameters in ParaView give a clear message and an empty or unchanged output, no crash.

    pvpython TestParaViewBadParameters.py PLUGIN SCRATCH_FOLDER
"""
import os
import sys

import numpy as np
from paraview import servermanager, simple
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pcb_testing import check, finish, write_noisy_plane  # noqa: E402

plugin, scratch = sys.argv[1], sys.argv[2]
os.makedirs(scratch, exist_ok=True)
points, _, _ = write_noisy_plane(os.path.join(scratch, "plane.vtp"))
simple.LoadPlugin(plugin, remote=True, ns=vars(simple))


def run(source, **properties):
    """Runs the filter; returns its output and what the output window showed meanwhile (as in
    ParaView's Output Messages). pvpython prints through that window too, so it is swapped in
    only while the filter runs."""
    console = vtkOutputWindow.GetInstance()
    messages = vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(messages)
    try:
        bilateral = simple.PointCloudBilateralFilter(Input=source, **properties)
        bilateral.UpdatePipeline()
        bilateral.UpdatePropertyInformation()
        global last_run  # what the Properties panel's Last Run shows
        last_run = bilateral.LastRun
        output = dsa.WrapDataObject(servermanager.Fetch(bilateral))
        simple.Delete(bilateral)
    finally:
        vtkOutputWindow.SetInstance(console)
    return output, messages.GetOutput()


reader = simple.XMLPolyDataReader(FileName=[os.path.join(scratch, "plane.vtp")])
reader.UpdatePipeline()

output, text = run(reader, Radius=-0.1)
check(output.GetNumberOfPoints() == 0, f"negative radius: {output.GetNumberOfPoints()} points out")
check("the radius must be a finite number >= 0 (0 means automatic), got -0.1" in text,
      "negative radius: the message says what is wrong")
check(last_run == "failed: the radius must be a finite number >= 0 (0 means automatic), got -0.1",
      f"negative radius: the last run says '{last_run}'")

output, text = run(reader, Radius=0.05, NormalRadius=-1)
check(output.GetNumberOfPoints() == 0 and "the normal radius must be" in text,
      "negative normal radius: empty output and a message")

output, text = run(reader, Radius=0.05, NumberOfIterations=0)
check(output.GetNumberOfPoints() == len(points) and not np.array_equal(np.asarray(output.Points), points),
      "0 iterations (automatic): the points are filtered")

# A polydata with no points at all.
empty_path = os.path.join(scratch, "empty.vtp")
writer = vtkXMLPolyDataWriter()
writer.SetInputData(vtkPolyData())
writer.SetFileName(empty_path)
writer.Write()
empty = simple.XMLPolyDataReader(FileName=[empty_path])
empty.UpdatePipeline()
output, text = run(empty, Radius=0.05)
check(output.GetNumberOfPoints() == 0, "empty input: an empty output")
check("error" not in text.lower(), f"empty input: no error ({text.strip()[:80]!r})")
output, text = run(empty, Radius=0)
check(output.GetNumberOfPoints() == 0 and "error" not in text.lower(),
      "empty input, automatic radius: an empty output, no error")
finish()

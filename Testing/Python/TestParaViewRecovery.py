"""A view follows the filter through good, bad and good parameters: after a failed run (one
message, an empty output) the next valid run is what the view shows and what the Information
panel's data information says.

    pvpython TestParaViewRecovery.py PLUGIN SCRATCH_FOLDER

Before the fix the filter's RequestData returned 0 on bad parameters; ParaView then marked the
representation up to date without running it, and every later render showed the data from
before the error.
"""
import os
import sys

import numpy as np
from paraview import simple
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pcb_testing import check, finish, write_noisy_plane  # noqa: E402

plugin, scratch = sys.argv[1], sys.argv[2]
os.makedirs(scratch, exist_ok=True)
write_noisy_plane(os.path.join(scratch, "plane.vtp"))
simple.LoadPlugin(plugin, remote=True, ns=vars(simple))

reader = simple.XMLPolyDataReader(FileName=[os.path.join(scratch, "plane.vtp")])
bilateral = simple.PointCloudBilateralFilter(Input=reader)
view = simple.CreateRenderView()
view.ViewSize = [200, 150]
display = simple.Show(bilateral, view)


def points_of(data):
    """The points of a data set or of every block of a multiblock, as one array."""
    if data is None or data.GetNumberOfPoints() == 0:
        return np.zeros((0, 3))
    points = dsa.WrapDataObject(data).Points
    arrays = points.Arrays if hasattr(points, "Arrays") else [points]
    return np.concatenate([np.asarray(a) for a in arrays])


def render(radius):
    """Sets the radius, renders as the GUI does after Apply; returns the filter's own output
    points, the points the view's representation drew, the data information's point count and
    the messages printed meanwhile."""
    console = vtkOutputWindow.GetInstance()
    messages = vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(messages)
    try:
        bilateral.Radius = radius
        simple.Render(view)
    finally:
        vtkOutputWindow.SetInstance(console)
    produced = points_of(bilateral.GetClientSideObject().GetOutputDataObject(0))
    drawn = points_of(display.GetClientSideObject().GetRenderedDataObject(0))
    return produced, drawn, bilateral.GetDataInformation().GetNumberOfPoints(), messages.GetOutput()


def same(a, b):
    return a.shape == b.shape and np.array_equal(np.sort(a, axis=0), np.sort(b, axis=0))


results = {}
for step, radius in enumerate([0.06, -1.0, 0.1, -0.5, 0.3]):
    produced, drawn, counted, text = render(radius)
    label = f"step {step}, radius {radius}"
    if radius < 0:
        errors = text.count("ERR|") + text.count("ERROR")
        check(produced.shape[0] == 0 and drawn.shape[0] == 0 and counted == 0,
              f"{label}: empty output, nothing drawn, 0 points in the information "
              f"({produced.shape[0]}, {drawn.shape[0]}, {counted})")
        check("the radius must be a finite number >= 0" in text and "returned failure" not in text,
              f"{label}: one clear message, no pipeline dump ({errors} error line(s))")
    else:
        check(produced.shape[0] > 0 and same(produced, drawn),
              f"{label}: the view draws the filter's output ({drawn.shape[0]} points)")
        check(counted == produced.shape[0], f"{label}: the data information counts {counted}")
        check("ERR" not in text and "ERROR" not in text, f"{label}: no error")
        for earlier, points in results.items():
            check(not same(points, drawn), f"{label}: not the render of radius {earlier}")
        results[radius] = drawn
# Closing the view before exit: tearing it down at interpreter exit may fail with GLXBadContext.
simple.Hide(bilateral, view)
simple.Delete(view)
del view, display
finish()

"""Run inside the ParaView GUI (paraview --script=...): a PLY scan without faces opened and shown
as a new user would, with no representation chosen. ParaView 5.11 gives it no cells, which its
default Surface representation draws as nothing; the plugin's GUI part shows such data as Point
Gaussian spheres, so the compared image has the cloud (and is empty without the plugin)."""
import os

from paraview import simple

data = os.path.join(os.environ["PCB_SOURCE_DIR"], "Data", "sharp_edge_noise0.5.ply")
reader = simple.OpenDataFile(data)
view = simple.GetActiveViewOrCreate("RenderView")
view.ViewSize = [600, 400]
view.OrientationAxesVisibility = 0
simple.Show(reader, view)
view.CameraPosition = [0.0, -3.0, 1.5]
view.CameraFocalPoint = [0.0, 0.0, -0.3]
view.CameraViewUp = [0.0, 0.0, 1.0]
simple.Render(view)

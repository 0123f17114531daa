"""Run inside the ParaView GUI (paraview --script=...) by TakeScreenshots.sh: sets up, from
Python, the state one screenshot shows, so that the script that takes it has only a few clicks
to make, on places that do not move when the Properties panel grows (the menu bar, a dialog, the
panel's header). PCB_SHOT says which:
  menu        the bundled sample opened (Filters > Point Cloud then lists the filter);
  panel       the filter applied with its automatic parameters to a real scan (PCB_SCAN), so
              that the panel shows the values it chose and measured;
  beforeafter the real scan and the filter's output side by side, the same camera in both;
  dialog      nothing: File > Open is then opened on a folder of LAS, LAZ and PCD files;
  colour      the filter on the bundled sample, coloured by how far each point moved;
  error       the filter with a radius far too small: its error in the Output Messages window;
  running     a long run (every point a neighbour of every other) that Abort then stops.
Once set up (for running: once the run has started), it writes the file PCB_READY."""
import os

from paraview import servermanager, simple

shot = os.environ["PCB_SHOT"]
scan = os.environ.get("PCB_SCAN", "")

sample = os.path.join(os.environ["PCB_SOURCE_DIR"], "Data", "sharp_edge_noise0.5.ply")


def ready():
    open(os.environ["PCB_READY"], "w").close()


if shot == "menu":
    simple.Show(simple.PLYReader(registrationName="sharp_edge_noise0.5.ply", FileNames=[sample]))
    simple.Render()
elif shot in ("colour", "error"):
    reader = simple.PLYReader(registrationName="sharp_edge_noise0.5.ply", FileNames=[sample])
    bilateral = simple.PointCloudBilateralFilter(Input=reader, OutputDisplacementLength=1,
                                                 Radius=1e-9 if shot == "error" else 0.0)
    display = simple.Show(bilateral)
    if shot == "colour":
        simple.ColorBy(display, ("POINTS", "DisplacementLength"))
        display.SetScalarBarVisibility(simple.GetActiveView(), True)
    simple.Render()
elif shot == "running":
    cube = os.path.join(os.environ["PCB_SOURCE_DIR"], "Data", "cube_noise0.5.ply")
    reader = simple.PLYReader(registrationName="cube_noise0.5.ply", FileNames=[cube])
    reader.UpdatePipeline()
    bilateral = simple.PointCloudBilateralFilter(Input=reader, Radius=1.5, NumberOfIterations=4)
    started = []
    handler = servermanager.ActiveConnection.Session.GetProgressHandler()
    handler.AddObserver("ProgressEvent", lambda caller, event: started or started.append(ready()))
    simple.Show(bilateral)
    simple.Render()
elif shot in ("panel", "beforeafter"):
    reader = simple.PLYReader(registrationName=os.path.basename(scan), FileNames=[scan])
    bilateral = simple.PointCloudBilateralFilter(registrationName="PointCloudBilateralFilter1",
                                                 Input=reader)
    view = simple.GetActiveViewOrCreate("RenderView")
    view.OrientationAxesVisibility = 0
    if shot == "panel":
        simple.Show(bilateral, view)
        simple.Render(view)
    else:
        # Input on the left, output on the right, one camera; both shown as the GUI shows a
        # point cloud (Point Gaussian), small flat discs (shaded spheres would speckle the
        # picture with their highlights) so that the rows of points show.
        layout = simple.GetLayout(view)
        before = simple.Show(reader, view)
        layout.SplitHorizontal(0, 0.5)
        after_view = simple.CreateView("RenderView")
        after_view.OrientationAxesVisibility = 0
        simple.AssignViewToLayout(view=after_view, layout=layout, hint=2)
        after = simple.Show(bilateral, after_view)
        for display in (before, after):
            display.SetRepresentationType("Point Gaussian")
            display.GaussianRadius = float(os.environ.get("PCB_POINT_RADIUS", "0.002"))
            display.ShaderPreset = "Plain circle"
        simple.Render(after_view)
        simple.AddCameraLink(view, after_view, "before and after")
        camera = [float(v) for v in os.environ.get("PCB_CAMERA", "").split()]
        if len(camera) == 9:
            view.CameraPosition = camera[0:3]
            view.CameraFocalPoint = camera[3:6]
            view.CameraViewUp = camera[6:9]
        else:
            simple.ResetCamera(view)
        simple.Render(view)
        simple.Render(after_view)
    simple.SetActiveSource(bilateral)
ready()

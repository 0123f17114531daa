"""The CAD-like sample after filtering, its points coloured by how far each one moved: about the
noise level everywhere, the edges and the step included."""
from vtkmodules.test import Testing
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
from vtkmodules.vtkRenderingCore import vtkCamera, vtkColorTransferFunction

import pcb_rendering as scene


class TestDisplacementColours(Testing.vtkTest):
    def testDisplacementColours(self):
        noisy = scene.read_sample(Testing.VTK_DATA_ROOT, "cad_part_noise0.3.ply")
        filtered = scene.bilateral(noisy, 0.03, 0.019, 2, displacement=True)
        filtered.GetPointData().SetActiveScalars("DisplacementLength")

        colours = vtkColorTransferFunction()
        # Dark to bright, so that a change of the displacements changes pixels a lot.
        colours.AddRGBPoint(0.0, 0.05, 0.05, 0.45)
        colours.AddRGBPoint(0.004, 0.85, 0.25, 0.30)
        colours.AddRGBPoint(0.008, 1.0, 0.95, 0.40)
        actor = scene.points_actor(filtered)
        actor.GetMapper().ScalarVisibilityOn()
        actor.GetMapper().SetLookupTable(colours)
        actor.GetMapper().SetScalarRange(0.0, 0.008)
        bar = vtkScalarBarActor()
        bar.SetLookupTable(colours)
        bar.SetTitle("moved by")
        bar.SetNumberOfLabels(3)
        bar.SetPosition(0.86, 0.1)
        bar.SetWidth(0.1)
        bar.SetHeight(0.8)

        camera = vtkCamera()
        camera.SetFocalPoint(0.0, 0.0, 0.2)
        camera.SetPosition(1.6, -2.2, 1.6)
        camera.SetViewUp(0.0, 0.0, 1.0)
        window = scene.show([([actor, bar], "cad part, r 0.03, rn 0.019, N 2")], camera, 520, 400)
        window.GetRenderers().GetFirstRenderer().ResetCamera()
        camera.Zoom(1.35)
        window.Render()
        # Correct runs differ from the baseline by 0 here; points are sparse on a dark
        # background, so a visible change scores little: keep the threshold low.
        Testing.compareImage(window, self.pathToValidatedOutput("TestDisplacementColours.png"), threshold=0.01)


if __name__ == "__main__":
    Testing.main([(TestDisplacementColours, "test")])

"""What the Python image tests share: reading a sample, filtering it, and drawing clouds side by
side with one camera, points as lit spheres."""
import os

from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderWindow,
                                         vtkRenderer, vtkTextActor)
import vtkmodules.vtkRenderingFreeType  # noqa: F401
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

from pointcloudbilateral import vtkPointCloudBilateralFilter


def read_sample(data_dir, name):
    reader = vtkPLYReader()
    reader.SetFileName(os.path.join(data_dir, name))
    reader.Update()
    return reader.GetOutput()


def bilateral(cloud, radius, normal_radius, iterations, displacement=False):
    filter_ = vtkPointCloudBilateralFilter()
    filter_.SetInputData(cloud)
    filter_.SetRadius(radius)
    filter_.SetNormalRadius(normal_radius)
    filter_.SetNumberOfIterations(iterations)
    filter_.SetGenerateDisplacementLength(displacement)
    filter_.Update()
    return filter_.GetOutput()


def slab(cloud, low, high):
    """The points with low <= z <= high: a cross-section that shows the profile."""
    points, vertices = vtkPoints(), vtkCellArray()
    for i in range(cloud.GetNumberOfPoints()):
        p = cloud.GetPoint(i)
        if low <= p[2] <= high:
            vertices.InsertNextCell(1, [points.InsertNextPoint(p)])
    result = vtkPolyData()
    result.SetPoints(points)
    result.SetVerts(vertices)
    return result


def points_actor(cloud, colour=(0.93, 0.80, 0.55), size=2.0):
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(cloud)
    mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetPointSize(size)
    actor.GetProperty().SetRenderPointsAsSpheres(True)
    actor.GetProperty().SetColor(*colour)
    return actor


def caption(text):
    actor = vtkTextActor()
    actor.SetInput(text)
    actor.GetTextProperty().SetFontSize(14)
    actor.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
    actor.GetPositionCoordinate().SetValue(0.03, 0.04)
    return actor


def show(panels, camera, width, height):
    """panels: (props, caption) pairs, drawn left to right. Returns the render window."""
    window = vtkRenderWindow()
    window.SetSize(width * len(panels), height)
    window.SetMultiSamples(0)
    for i, (props, text) in enumerate(panels):
        renderer = vtkRenderer()
        renderer.SetViewport(i / len(panels), 0.0, (i + 1) / len(panels), 1.0)
        renderer.SetBackground(0.16, 0.18, 0.22)
        for prop in props:
            renderer.AddViewProp(prop)
        renderer.AddViewProp(caption(text))
        renderer.SetActiveCamera(camera)
        window.AddRenderer(renderer)
    window.Render()
    return window

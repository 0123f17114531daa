"""Helpers shared by the Python tests: a deterministic noisy plane, and checks that report."""
import sys

import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

PLANE_POINTS = 20000
PLANE_NOISE = 0.005

failures = []


def check(condition, message):
    """Records a failed check and goes on, so one run reports every problem."""
    print(("ok:     " if condition else "FAILED: ") + message)
    if not condition:
        failures.append(message)


def finish():
    print(f"{len(failures)} check(s) failed" if failures else "all checks passed")
    sys.exit(1 if failures else 0)


def shared_file_or_skip(folder, name, variable):
    """The path of a shared sample file, or exit 77 (ctest: skipped) when it is not there."""
    import os
    path = os.path.join(folder, name)
    if not folder or not os.path.isfile(path):
        print(f"skipped: no {name} in '{folder}' (set {variable})")
        sys.exit(77)
    return path


def noisy_plane():
    """A unit patch of the plane z = 0 with Gaussian noise, colours and an intensity."""
    rng = np.random.default_rng(2017)
    points = np.column_stack([rng.random(PLANE_POINTS), rng.random(PLANE_POINTS),
                              rng.normal(0.0, PLANE_NOISE, PLANE_POINTS)])
    colours = rng.integers(0, 256, size=(PLANE_POINTS, 3), dtype=np.uint8)
    intensity = rng.random(PLANE_POINTS).astype(np.float32)
    return points, colours, intensity


def write_noisy_plane(path):
    points, colours, intensity = noisy_plane()
    cloud = dsa.WrapDataObject(vtkPolyData())
    cloud.Points = points
    cloud.PointData.append(colours, "RGB")
    cloud.PointData.append(intensity, "Intensity")
    writer = vtkXMLPolyDataWriter()
    writer.SetInputData(cloud.VTKObject)
    writer.SetFileName(path)
    writer.Write()
    return points, colours, intensity


def interior(points, margin=0.1):
    """Points away from the patch border, where an open surface bends."""
    return np.all((points[:, :2] > margin) & (points[:, :2] < 1 - margin), axis=1)

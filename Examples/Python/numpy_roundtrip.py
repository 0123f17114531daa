"""From NumPy to the bilateral filter and back, with vtkmodules.numpy_interface.

    PYTHONPATH=<build>/lib/python3/dist-packages /usr/bin/python3 Examples/Python/numpy_roundtrip.py

Makes a noisy plane with a colour per point in NumPy, filters it, and reads the result back as
NumPy arrays: the heights shrink, the colours come back unchanged and in order.
"""
import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonDataModel import vtkPolyData

from pointcloudbilateral import vtkPointCloudBilateralFilter

rng = np.random.default_rng(2017)
count = 20000
noise = 0.005
points = np.column_stack([rng.random(count), rng.random(count), rng.normal(0.0, noise, count)])
colours = rng.integers(0, 256, size=(count, 3), dtype=np.uint8)

cloud = dsa.WrapDataObject(vtkPolyData())
cloud.Points = points
cloud.PointData.append(colours, "RGB")

bilateral = vtkPointCloudBilateralFilter()
bilateral.SetInputData(cloud.VTKObject)
bilateral.SetRadius(0.05)
bilateral.SetNumberOfIterations(2)
bilateral.Update()
result = dsa.WrapDataObject(bilateral.GetOutput())

inner = np.all((points[:, :2] > 0.1) & (points[:, :2] < 0.9), axis=1)  # away from the border
before = np.sqrt(np.mean(points[inner, 2] ** 2))
after = np.sqrt(np.mean(np.asarray(result.Points)[inner, 2] ** 2))
print(f"rms height {before:.5f} -> {after:.5f} (x{before / after:.1f} flatter)")
assert after < before / 5, "the plane did not get flatter"
assert np.array_equal(np.asarray(result.PointData["RGB"]), colours), "colours changed"
print("colours passed through unchanged")

"""The plugin in pvpython and pvbatch: PointCloudBilateralFilter on a noisy plane.

    pvpython TestParaViewFilter.py PLUGIN SCRATCH_FOLDER
"""
import os
import sys

import numpy as np
from paraview import servermanager, simple
from vtkmodules.numpy_interface import dataset_adapter as dsa

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pcb_testing import PLANE_NOISE, PLANE_POINTS, check, finish, interior, write_noisy_plane  # noqa: E402

plugin, scratch = sys.argv[1], sys.argv[2]
os.makedirs(scratch, exist_ok=True)
points, colours, intensity = write_noisy_plane(os.path.join(scratch, "plane.vtp"))

simple.LoadPlugin(plugin, remote=True, ns=vars(simple))
check(hasattr(simple, "PointCloudBilateralFilter"), "the plugin adds PointCloudBilateralFilter")
reader = simple.XMLPolyDataReader(FileName=[os.path.join(scratch, "plane.vtp")])
reader.UpdatePipeline()
bilateral = simple.PointCloudBilateralFilter(Input=reader)
largest_extent = np.max(np.ptp(points, axis=0))
# The proxy's defaults are the core's (configured into the XML from Filters/Core/BilateralFilter.h):
# every parameter automatic, from the measured scales.
check(bilateral.Radius == 0 and bilateral.NormalRadius == 0 and bilateral.NumberOfIterations == 0
      and bilateral.AutomaticParameters == "Measured",
      f"the defaults are the core's: radius {bilateral.Radius}, normal radius "
      f"{bilateral.NormalRadius}, iterations {bilateral.NumberOfIterations}, "
      f"automatic {bilateral.AutomaticParameters}")
# RequestInformation reports metadata only: nothing is "used" before the filter has run.
bilateral.UpdatePipelineInformation()
bilateral.UpdatePropertyInformation()
check(bilateral.RadiusUsed == 0 and bilateral.NormalRadiusUsed == 0
      and bilateral.NumberOfIterationsUsed == 0 and bilateral.PointSpacing == 0
      and bilateral.LastRun == "not run yet",
      f"nothing used before a run: radius used {bilateral.RadiusUsed}, last run "
      f"'{bilateral.LastRun}'")
bilateral.Radius = 0.05
bilateral.NumberOfIterations = 2
bilateral.OutputDisplacementLength = 1
bilateral.UpdatePipeline()
bilateral.UpdatePropertyInformation()
# A given radius and N override only themselves: rn = 5 sigma from the measured noise.
check(bilateral.RadiusUsed == 0.05 and bilateral.NumberOfIterationsUsed == 2
      and abs(bilateral.NoiseSigma / PLANE_NOISE - 1) < 0.25
      and abs(bilateral.NormalRadiusUsed - 5 * bilateral.NoiseSigma) < 1e-12,
      f"information properties: radius used {bilateral.RadiusUsed}, normal radius used "
      f"{bilateral.NormalRadiusUsed}, iterations used {bilateral.NumberOfIterationsUsed}, "
      f"noise sigma {bilateral.NoiseSigma} (true {PLANE_NOISE}), spacing {bilateral.PointSpacing}")
# Each parameter says where it came from when some were given (it once said "(measured)" only).
check(bilateral.LastRun.startswith("r 0.05 (given), rn ") and
      bilateral.LastRun.endswith(" (measured), N 2 (given)"), f"last run: '{bilateral.LastRun}'")
# The spread of the sampling, measured with the spacing: on a jittered grid (each point anywhere
# in its cell) the 95th percentile is some 4.4 times the 5th, where a scan spans hundreds.
distances = list(bilateral.NearestNeighbourDistances)
check(0 < distances[0] <= distances[1] <= distances[2] < 6 * distances[0],
      f"nearest-neighbour distances (5%, median, 95%): {distances}")

result = dsa.WrapDataObject(servermanager.Fetch(bilateral))
filtered = np.asarray(result.Points)
check(filtered.shape == points.shape, f"{filtered.shape[0]} points out of {PLANE_POINTS}")
check(np.array_equal(np.asarray(result.PointData["RGB"]), colours), "colours pass through")
check(np.array_equal(np.asarray(result.PointData["Intensity"]), intensity),
      "intensities pass through")
inner = interior(points)
before = np.sqrt(np.mean(points[inner, 2] ** 2))
after = np.sqrt(np.mean(filtered[inner, 2] ** 2))
check(after < before / 5, f"rms height {before:.5f} -> {after:.5f}")
# Interior points move onto the plane: by about their noise, |z|, on average.
moved = np.asarray(result.PointData["DisplacementLength"])[inner]
expected = np.mean(np.abs(points[inner, 2]))
check(0.8 < np.mean(moved) / expected < 1.05,
      f"mean displacement {np.mean(moved):.5f}, mean |noise| {expected:.5f}")
check(np.max(moved) < 2 * 0.05, f"no point moved by more than N r: {np.max(moved):.4f}")

# All automatic on a flat cloud: 1.5 x (5 spacings + 4 sigma), rn = 5 sigma, N = 3.
bilateral.Radius = 0
bilateral.NumberOfIterations = 0
bilateral.UpdatePipeline()
bilateral.UpdatePropertyInformation()
rule = 1.5 * (5 * bilateral.PointSpacing + 4 * bilateral.NoiseSigma)
check(abs(bilateral.RadiusUsed / rule - 1) < 1e-12 and bilateral.NumberOfIterationsUsed == 3,
      f"automatic radius {bilateral.RadiusUsed:.6g} (rule {rule:.6g}), "
      f"N {bilateral.NumberOfIterationsUsed}")
# The paper's heuristic by name: sqrt(20 / points) times the largest extent, rn = r, N = 1.
bilateral.AutomaticParameters = "Paper"
bilateral.UpdatePipeline()
bilateral.UpdatePropertyInformation()
automatic = np.sqrt(20.0 / PLANE_POINTS) * largest_extent
check(abs(bilateral.RadiusUsed - automatic) < 1e-12
      and bilateral.NormalRadiusUsed == bilateral.RadiusUsed
      and bilateral.NumberOfIterationsUsed == 1 and bilateral.PointSpacing == 0,
      f"paper's radius {bilateral.RadiusUsed:.6g}, expected {automatic:.6g}")
check(bilateral.LastRun.endswith("N 1 (paper's rule)"), f"last run: '{bilateral.LastRun}'")
bilateral.AutomaticParameters = "Measured"

# The authors' text format opens through the plugin's reader, by extension; columns become arrays.
text_path = os.path.join(scratch, "small.xyz")
with open(text_path, "w") as text:
    text.write("x y z nx ny nz intensity\n")
    for i in range(200):
        text.write(f"{i % 20 * 0.05} {i // 20 * 0.05} 0 0 0 1 {i}\n")
# ParaView's PLOT3D reader claims .xyz too: the GUI asks which reader to use, so the plugin's
# must be among the possible ones.
factory = servermanager.vtkSMProxyManager.GetProxyManager().GetReaderFactory()
possible = factory.GetPossibleReaders(text_path, servermanager.ActiveConnection.Session)
names = [possible.GetString(i) for i in range(possible.GetNumberOfStrings())]
check("ASCIIPointCloudTextReader" in names,
      f".xyz files can be opened with the Point Cloud Text Reader ({len(names) // 3} offered)")
# Asked for no reader by name, as OpenDataFile is, the factory chooses the plugin's (it chose
# PLOT3D's, which read 0 points, while the proxy's name sorted after P3DReader's).
opened = simple.OpenDataFile(text_path)
check(opened is not None and opened.GetXMLName() == "ASCIIPointCloudTextReader",
      f"OpenDataFile opens .xyz with the Point Cloud Text Reader "
      f"({opened.GetXMLName() if opened else None})")
opened.UpdatePipeline()
check(opened.GetDataInformation().GetNumberOfPoints() == 200,
      f"... and reads its 200 points ({opened.GetDataInformation().GetNumberOfPoints()})")
simple.Delete(opened)
text_reader = simple.PointCloudTextReader(FileName=text_path, HasNormals=1)
text_reader.UpdatePipeline()
text_cloud = servermanager.Fetch(text_reader)
check(text_cloud.GetNumberOfPoints() == 200 and text_cloud.GetPointData().GetNormals() is not None
      and text_cloud.GetPointData().GetArray("intensity") is not None,
      "the reader gives 200 points, point normals and the named extra column")

# A multiblock of clouds is filtered block by block.
group = simple.GroupDatasets(Input=[reader, text_reader])
blocks = simple.PointCloudBilateralFilter(Input=group, Radius=0.12)
blocks.UpdatePipeline()
output = servermanager.Fetch(blocks)
sizes = [output.GetBlock(i).GetNumberOfPoints() for i in range(output.GetNumberOfBlocks())]
check(output.IsA("vtkMultiBlockDataSet") and sizes == [PLANE_POINTS, 200],
      f"a multiblock input gives a multiblock output, block by block: {sizes}")
finish()

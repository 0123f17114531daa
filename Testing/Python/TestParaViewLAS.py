"""The LAS reader and writer in ParaView: OpenDataFile picks the plugin's reader for .las and
.laz (no reader choice) without GDAL's "ERROR 4" line, the points are there with one vertex
each, a damaged file gives one error and no points, and SaveData writes .las with the plugin's writer. A COPC file's level of detail
and box (the reader's advanced properties) give the points IO.TestCOPC and CommandLine.copc
count.

    pvpython TestParaViewLAS.py PLUGIN LAS_FOLDER SCRATCH_FOLDER

Exits with 77 (skipped) when LAS_FOLDER has no autzen_trim.las.
"""
import os
import sys

from paraview import simple

# The wrapped classes, so that the reader's own methods are reachable from Python.
import pointcloudbilateral  # noqa: F401
from pcb_testing import check, finish, shared_file_or_skip

plugin, folder, scratch = sys.argv[1], sys.argv[2], sys.argv[3]
autzen = shared_file_or_skip(folder, "autzen_trim.las", "PCB_LAS_DATA_DIR")
os.makedirs(scratch, exist_ok=True)

simple.LoadPlugin(plugin, remote=False, ns=vars(simple))
# What the reader factory prints while it picks the reader (GDAL writes to the process's
# standard error, below Python): GDAL's raster reader, which also claims .las, was asked first
# and printed "ERROR 4: ... not recognized as a supported file format".
printed_path = os.path.join(scratch, "open-data-file.stderr")
saved_stderr = os.dup(2)
with open(printed_path, "w") as printed_file:
    os.dup2(printed_file.fileno(), 2)
    try:
        reader = simple.OpenDataFile(autzen)
    finally:
        os.dup2(saved_stderr, 2)
        os.close(saved_stderr)
printed = open(printed_path).read()
check("ERROR 4" not in printed, f"OpenDataFile asked no GDAL reader (printed: {printed!r})")
check(reader is not None and reader.GetXMLName() == "ASPRSLASPointCloudReader",
      f"OpenDataFile picks the LAS reader: {reader.GetXMLName() if reader else None}")
reader.UpdatePipeline()
info = reader.GetDataInformation()
check(info.GetNumberOfPoints() == 110000, f"{info.GetNumberOfPoints()} points")
check(info.GetNumberOfCells() == 110000, f"{info.GetNumberOfCells()} vertex cells")
arrays = [reader.PointData[k].GetName() for k in range(len(reader.PointData))]
for name in ("Intensity", "Classification", "GpsTime", "RGB", "Colors"):
    check(name in arrays, f"point array {name}")
display = simple.Show(reader)
# As ParaView's GUI shows a PLY point cloud (the plugin's RepresentationType hint).
check(display.Representation == "Point Gaussian", f"shown as {display.Representation}")

# Written with the plugin's writer and read again.
out = os.path.join(scratch, "autzen_copy.las")
simple.SaveData(out, proxy=reader)
again = simple.OpenDataFile(out)
again.UpdatePipeline()
check(again.GetDataInformation().GetNumberOfPoints() == 110000, "SaveData wrote the LAS file")
a = open(autzen, "rb").read()
b = open(out, "rb").read()
check(a[2038:2038 + 110000 * 34] == b[2038:2038 + 110000 * 34] and b[104] == 3,
      "the same point records and point format")

# Filtered and written: the same header fields (point format, record length, scales,
# offsets), the same VLRs (the coordinate system), every field but the coordinates unchanged.
bilateral = simple.PointCloudBilateralFilter(Input=reader, Radius=10.0)
filtered = os.path.join(scratch, "autzen_filtered.las")
simple.SaveData(filtered, proxy=bilateral)
c = open(filtered, "rb").read()
check(len(c) == len(a) and c[94:107] == a[94:107] and c[131:179] == a[131:179],
      "the filtered file keeps the header's offsets, counts, format, scales and offsets")
check(c[227:2038] == a[227:2038], "and the VLRs (coordinate system)")
moved = sum(1 for k in range(0, 110000, 97) if c[2038 + 34 * k: 2038 + 34 * k + 12] !=
            a[2038 + 34 * k: 2038 + 34 * k + 12])
unchanged = all(c[2038 + 34 * k + 12: 2038 + 34 * k + 34] == a[2038 + 34 * k + 12: 2038 + 34 * k + 34]
                for k in range(0, 110000, 97))
check(moved > 0 and unchanged, f"the coordinates moved ({moved} of 1134 sampled), nothing else")

# A damaged file: one error, no points.
damaged = os.path.join(folder, "permutations", "1.2-no-points.las")
bad = simple.OpenDataFile(damaged)
bad.UpdatePipeline()
check(bad.GetDataInformation().GetNumberOfPoints() == 0, "a truncated file gives no points")
message = bad.GetClientSideObject().GetErrorMessage()
check("truncated" in message and "\n" not in message, f"and one error: {message}")

# LAZ (beside the LAS samples, when there): opened by the same reader, saved compressed.
laz = os.path.join(folder, "..", "laz", "autzen_trim.laz")
if os.path.isfile(laz):
    compressed = simple.OpenDataFile(laz)
    check(compressed is not None and compressed.GetXMLName() == "ASPRSLASPointCloudReader",
          f"OpenDataFile picks the LAS reader for .laz: "
          f"{compressed.GetXMLName() if compressed else None}")
    compressed.UpdatePipeline()
    check(compressed.GetDataInformation().GetNumberOfPoints() == 110000, "110000 LAZ points")
    saved = os.path.join(scratch, "autzen_copy.laz")
    simple.SaveData(saved, proxy=compressed)
    again = simple.OpenDataFile(saved)
    again.UpdatePipeline()
    d = open(saved, "rb").read()
    check(d[104] == 0x83 and again.GetDataInformation().GetNumberOfPoints() == 110000,
          f"SaveData wrote LAZ ({len(d)} bytes) that reads back")
else:
    print(f"skipped the LAZ checks: no {laz}")

# COPC: the reader's advanced properties read a level of detail or a box from the octree; the
# filter passes every point array of what was read.
copc = os.path.join(folder, "..", "laz", "1.2-with-color.copc.laz")
if os.path.isfile(copc):
    octree = simple.OpenDataFile(copc)
    octree.UpdatePipeline()
    check(octree.GetDataInformation().GetNumberOfPoints() == 1065, "COPC: every point by default")
    octree.COPCMaxLevel = 1
    octree.UpdatePipeline()
    check(octree.GetDataInformation().GetNumberOfPoints() == 90, "COPC Max Level 1: 90 points")
    octree.COPCMaxLevel = -1
    octree.COPCUseBounds = 1
    octree.COPCBounds = [637000, 638200.5, 850000, 852500, 420, 560]
    octree.UpdatePipeline()
    check(octree.GetDataInformation().GetNumberOfPoints() == 207,
          "COPC Bounds: the 207 points inside the box (CommandLine.copc)")
    filtered = simple.PointCloudBilateralFilter(Input=octree)
    filtered.UpdatePipeline()
    names = lambda proxy: sorted(proxy.PointData.keys())
    check(filtered.GetDataInformation().GetNumberOfPoints() == 207
          and set(names(octree)) <= set(names(filtered)),
          f"the filter keeps the points and arrays read: {names(filtered)}")
    # Pieces (MPI) decode whole nodes of their own: level 1 (the root's 24 points and four
    # nodes below it) in two pieces is the 90 points, in order, neither piece holding them all.
    from vtkmodules.util.numpy_support import vtk_to_numpy

    def level_one_piece(piece, pieces):
        vtk_reader = pointcloudbilateral.vtkLASPointCloudReader()
        vtk_reader.SetFileName(copc)
        vtk_reader.SetCOPCMaxLevel(1)
        vtk_reader.UpdatePiece(piece, pieces, 0)
        return vtk_to_numpy(vtk_reader.GetOutput().GetPoints().GetData()).tolist()

    first, second = level_one_piece(0, 2), level_one_piece(1, 2)
    check(0 < len(first) < 90 and first + second == level_one_piece(0, 1),
          f"COPC Max Level 1 in two pieces: {len(first)} + {len(second)} points, those of one "
          "piece in order")
    plain = simple.OpenDataFile(autzen)
    plain.COPCMaxLevel = 0
    plain.UpdatePipeline()
    check(plain.GetDataInformation().GetNumberOfPoints() == 110000,
          "COPC Max Level on a LAS file: a warning, and every point")
else:
    print(f"skipped the COPC checks: no {copc}")

finish()
print("all checks passed")

"""vtkPointCloudFileIO from Python: the reader and writer of each extension, a write-then-read
round trip through every format, and damaged or unsupported files as one line.

    python3 TestFileIO.py SCRATCH_FOLDER
"""
import os
import sys

from pointcloudbilateral import vtkPointCloudFileIO
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData

scratch = sys.argv[1]
os.makedirs(scratch, exist_ok=True)
failures = []


def check(condition, message):
    print(("ok: " if condition else "FAILED: ") + message)
    if not condition:
        failures.append(message)


expected = {".txt": ("vtkPointCloudTextReader", "vtkPointCloudTextWriter"),
            ".XYZ": ("vtkPointCloudTextReader", "vtkPointCloudTextWriter"),
            ".las": ("vtkLASPointCloudReader", "vtkLASPointCloudWriter"),
            ".pcd": ("vtkPCDPointCloudReader", "vtkPCDPointCloudWriter"),
            ".ply": ("vtkPLYReader", "vtkPLYWriter"),
            ".vtp": ("vtkXMLPolyDataReader", "vtkXMLPolyDataWriter")}
for extension, (reader, writer) in expected.items():
    r = vtkPointCloudFileIO.NewReader("cloud" + extension)
    w = vtkPointCloudFileIO.NewWriter("cloud" + extension)
    check(r is not None and r.GetClassName() == reader and r.GetFileName() == "cloud" + extension,
          f"{extension}: {r.GetClassName() if r else None}")
    check(w is not None and w.GetClassName() == writer, f"{extension}: {w.GetClassName() if w else None}")
check(vtkPointCloudFileIO.NewReader("cloud.obj") is None, "no reader for .obj")
check(vtkPointCloudFileIO.NewWriter("cloud.laz").GetClassName() == "vtkLASPointCloudWriter",
      ".laz is written by the LAS writer (compressed)")
check(vtkPointCloudFileIO.NewReader("cloud.laz").GetClassName() == "vtkLASPointCloudReader",
      ".laz is read by the LAS reader (decompressed)")

cloud = vtkPolyData()
points = vtkPoints()
points.SetDataTypeToDouble()
intensity = vtkDoubleArray()
intensity.SetName("Intensity")
for i in range(100):
    points.InsertNextPoint(0.25 * (i % 10), 0.5 * (i // 10), 0.125 * (i % 7))
    intensity.InsertNextValue(i)
cloud.SetPoints(points)
cloud.GetPointData().AddArray(intensity)
io = vtkPointCloudFileIO()
for extension in (".xyz", ".las", ".pcd", ".ply", ".vtp"):
    path = os.path.join(scratch, "cloud" + extension)
    check(io.Write(cloud, path), f"write {extension}: {io.GetErrorMessage()}")
    back = vtkPolyData()
    check(io.Read(path, back) and back.GetNumberOfPoints() == 100,
          f"read {extension}: {back.GetNumberOfPoints()} points {io.GetErrorMessage()}")
    check(back.GetPoint(57) == cloud.GetPoint(57), f"{extension}: point 57 {back.GetPoint(57)}")
    array = back.GetPointData().GetArray("Intensity")
    if extension != ".ply":  # PLY keeps positions, normals and colours only
        check(array is not None and array.GetTuple1(57) == 57, f"{extension}: Intensity kept")

damaged = os.path.join(scratch, "cut.ply")
with open(os.path.join(scratch, "cloud.ply"), "rb") as whole:
    data = whole.read()
with open(damaged, "wb") as cut:
    cut.write(data[: len(data) - 500])
back = vtkPolyData()
check(not io.Read(damaged, back) and back.GetNumberOfPoints() == 0, "a cut PLY file is not read")
message = io.GetErrorMessage()
check(message.startswith(damaged + ": truncated") and "\n" not in message, message)
# PCL's PCD from Python: the package's classes, a cut binary block refused in one line, and an
# organised frame's NaN points dropped and counted, or kept.
from pointcloudbilateral import vtkPCDPointCloudReader, vtkPCDPointCloudWriter  # noqa: E402
with open(os.path.join(scratch, "cloud.pcd"), "rb") as whole:
    data = whole.read()
damaged = os.path.join(scratch, "cut.pcd")
with open(damaged, "wb") as cut:
    cut.write(data[: len(data) - 7])
check(not io.Read(damaged, back) and back.GetNumberOfPoints() == 0 and
      io.GetErrorMessage() == damaged + ": the binary data holds 99 points, the header announces 100",
      io.GetErrorMessage())
frame = os.path.join(scratch, "frame.pcd")
with open(frame, "w") as text:
    text.write("VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\n"
               "HEIGHT 2\nPOINTS 4\nDATA ascii\n0 0 1\nnan nan nan\n0 1 1\n1 1 1\n")
reader = vtkPCDPointCloudReader()
reader.SetFileName(frame)
reader.Update()
check(reader.GetOutput().GetNumberOfPoints() == 3 and reader.GetNumberOfDroppedPoints() == 1,
      "the NaN point dropped and counted")
reader.KeepNaNPointsOn()
reader.Update()
writer = vtkPCDPointCloudWriter()
writer.SetInputConnection(reader.GetOutputPort())
writer.SetFileName(os.path.join(scratch, "frame-back.pcd"))
check(reader.GetOutput().GetNumberOfPoints() == 4 and writer.Write() == 1, "the NaN point kept")
with open(os.path.join(scratch, "frame-back.pcd")) as text:
    check("WIDTH 2\nHEIGHT 2\n" in text.read(), "the frame written back as a frame")
problem = vtkPointCloudFileIO.CheckInputFile(os.path.join(scratch, "missing.vtp"))
check(problem.endswith("missing.vtp: No such file or directory"), problem)
check(not io.Write(cloud, os.path.join(scratch, "cloud.obj")) and
      "unsupported file type '.obj'" in io.GetErrorMessage(), io.GetErrorMessage())
check(not os.path.exists(os.path.join(scratch, "no", "out.las")) and
      not io.Write(cloud, os.path.join(scratch, "no", "out.las")) and
      io.GetErrorMessage().startswith(os.path.join(scratch, "no", "out.las")), io.GetErrorMessage())

# Pieces of a text file: each parses only its share of the point lines (comments, blank lines
# and the header are not points), and a malformed line is reported, with the file's own line
# number, by the piece that holds it only.
from pointcloudbilateral import vtkPointCloudTextReader  # noqa: E402

pieces_path = os.path.join(scratch, "pieces.xyz")
with open(pieces_path, "w") as text:
    text.write("# comment\nx y z\n\n1 2 3\n# c2\n4 5 6\n\n7 8 9\n10 11 12 13\n")
for piece, pieces, first, error in [(0, 1, None, True), (0, 3, 1.0, False), (1, 3, 4.0, False),
                                    (2, 3, None, True), (2, 4, 7.0, False), (3, 4, None, True),
                                    (0, 5, None, False)]:
    reader = vtkPointCloudTextReader()
    reader.SetFileName(pieces_path)
    reader.GlobalWarningDisplayOff()
    reader.UpdatePiece(piece, pieces, 0)
    output = reader.GetOutput()
    got = output.GetPoint(0)[0] if output.GetNumberOfPoints() == 1 else None
    message = reader.GetErrorMessage()
    check(got == first and (message.endswith("pieces.xyz:9: expected 3 columns like the first "
                                             "point, found 4") if error else message == ""),
          f"text piece {piece} of {pieces}: first x {got} (expected {first}), error {message!r}")

if failures:
    sys.exit(f"{len(failures)} check(s) failed")
print("all checks passed")

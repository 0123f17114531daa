"""LAZ files through the VTK reader, the LAS writer and pcbilateral (shared/data/laz).

Each LAZ file with an uncompressed twin in the LAS folder reads, with vtkLASPointCloudReader,
to the twin's points and arrays, bit for bit; written back with vtkLASPointCloudWriter it gives
the twin's point records byte for byte. pcbilateral filters a LAZ file (read by extension) to
the same points as its twin, and writes .laz that reads back to the points it writes as .las.
A LAZ file cut short gives one error line and no points.

    python3 TestLAZFiles.py PCBILATERAL LAS_FOLDER SCRATCH_FOLDER

The LAZ files are in LAS_FOLDER/../laz. Exits with 77 (skipped) when they are not there.
"""
import os
import struct
import subprocess
import sys

from pointcloudbilateral import vtkLASPointCloudReader, vtkLASPointCloudWriter
from vtkmodules.util.numpy_support import vtk_to_numpy

from pcb_testing import check, failures

TWINS = [
    ("autzen_trim.laz", "autzen_trim.las"),
    ("simple.laz", "simple.las"),
    ("laszip-generated.laz", "simple.las"),
    ("liblas-generated.laz", "simple.las"),
    ("laszip-generated_with2bytespadding.laz", "simple.las"),
    ("simple-laszip-compressor-version-1.2r0.laz", "simple.las"),
]


def read(path):
    reader = vtkLASPointCloudReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput(), reader.GetErrorMessage()


def point_records(path):
    data = open(path, "rb").read()
    offset = struct.unpack_from("<I", data, 96)[0]
    length, count = struct.unpack_from("<HI", data, 105)
    return data[offset: offset + length * count]


def main():
    pcbilateral, las_folder, scratch = sys.argv[1:4]
    laz_folder = os.path.join(las_folder, "..", "laz")
    if not os.path.isfile(os.path.join(laz_folder, "autzen_trim.laz")):
        print(f"skipped: no LAZ samples in '{laz_folder}'")
        return 77
    os.makedirs(scratch, exist_ok=True)
    for laz_name, las_name in TWINS:
        laz, error = read(os.path.join(laz_folder, laz_name))
        las, _ = read(os.path.join(las_folder, las_name))
        check(not error and laz.GetNumberOfPoints() == las.GetNumberOfPoints(),
              f"{laz_name}: {laz.GetNumberOfPoints()} points {error}")
        same_points = (vtk_to_numpy(laz.GetPoints().GetData()).tobytes()
                       == vtk_to_numpy(las.GetPoints().GetData()).tobytes())
        arrays = [las.GetPointData().GetArrayName(k)
                  for k in range(las.GetPointData().GetNumberOfArrays())]
        different = [name for name in arrays
                     if laz.GetPointData().GetArray(name) is None
                     or vtk_to_numpy(laz.GetPointData().GetArray(name)).tobytes()
                     != vtk_to_numpy(las.GetPointData().GetArray(name)).tobytes()]
        check(same_points and not different,
              f"{laz_name}: the points and the {len(arrays)} arrays of {las_name} "
              f"(different: {different})")
        out = os.path.join(scratch, laz_name + ".las")
        writer = vtkLASPointCloudWriter()
        writer.SetInputData(laz)
        writer.SetFileName(out)
        check(writer.Write() == 1 and point_records(out)
              == point_records(os.path.join(las_folder, las_name)),
              f"{laz_name} written as LAS: the point records of {las_name}")

    # The command line reads .laz by its extension.
    outputs = []
    for name, folder in (("autzen_trim.laz", laz_folder), ("autzen_trim.las", las_folder)):
        out = os.path.join(scratch, "filtered-" + name + ".las")
        run = subprocess.run([pcbilateral, os.path.join(folder, name), out, "-r", "6", "-n",
                              "2", "-N", "1"], capture_output=True, text=True)
        check(run.returncode == 0, f"pcbilateral {name}: exit {run.returncode} {run.stderr}")
        outputs.append(point_records(out) if run.returncode == 0 else b"")
    check(outputs[0] and outputs[0] == outputs[1],
          "pcbilateral filters autzen_trim.laz to the same point records as autzen_trim.las")
    # Written as LAZ: it reads back to the points written as LAS.
    out = os.path.join(scratch, "filtered.laz")
    run = subprocess.run([pcbilateral, os.path.join(laz_folder, "autzen_trim.laz"), out, "-r",
                          "6", "-n", "2", "-N", "1"], capture_output=True, text=True)
    written, error = read(out)
    las, _ = read(os.path.join(scratch, "filtered-autzen_trim.las.las"))
    check(run.returncode == 0 and not error and open(out, "rb").read(4) == b"LASF"
          and open(out, "rb").read()[104] == 0x83
          and vtk_to_numpy(written.GetPoints().GetData()).tobytes()
          == vtk_to_numpy(las.GetPoints().GetData()).tobytes(),
          f"pcbilateral writes .laz (format 3, compressed) with the points of the .las output "
          f"({os.path.getsize(out) if os.path.exists(out) else 0} bytes) {error}")

    # Damaged: cut in its last chunk, and its chunk table gone.
    data = open(os.path.join(laz_folder, "autzen_trim.laz"), "rb").read()
    for name, damaged in (("cut.laz", data[:400000]), ("no-table.laz", data[:-20] + b"\0" * 20)):
        path = os.path.join(scratch, name)
        open(path, "wb").write(damaged)
        cloud, error = read(path)
        check(error and "\n" not in error and cloud.GetNumberOfPoints() == 0,
              f"{name}: one error and no points: '{error}'")
        out = os.path.join(scratch, name + ".las")
        run = subprocess.run([pcbilateral, path, out], capture_output=True, text=True)
        check(run.returncode == 1 and run.stderr.count("\n") == 1 and not os.path.exists(out),
              f"pcbilateral {name}: exit {run.returncode}, '{run.stderr.strip()}'")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

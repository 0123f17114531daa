"""One LAS or LAZ file written by every rank: under mpirun pvbatch, SaveData of the distributed
filter's output writes, from the ranks' pieces, the file one process writes from the whole cloud.

    mpirun -np P pvbatch TestParallelWriters.py PLUGIN SCRATCH_FOLDER FILE las|laz [--shuffled]

FILE is a LAS, LAZ or text file, read in pieces by the plugin's reader proxy (each rank its
share, in file order), filtered by the distributed filter and saved with SaveData to a .las or
.laz file. With --shuffled, FILE's points are first written in a random order (by the project's
LAS writer), so that each rank's share spans the whole cloud and the filter exchanges points
across all of them. Exits with 77 (skipped) when FILE does not exist.

Checks, against vtkLASPointCloudWriter run in this process on the serial filter's output of the
whole file:
- .las: the two files are the same, byte for byte (header, VLRs, records, EVLRs);
- .laz: both decode (with the project's reader) to the same points and arrays, bit for bit and
  in order, and the same header fields; the file written under MPI has each rank's points in
  chunks of its own (the LASzip record says the chunks' sizes vary), so more chunks than one
  process's when a share does not end at a multiple of 50,000 points; with --lazperf and
  --laz-records (and Node.js), laz-perf decodes it to the records our decoder gives.
"""
import argparse
import os
import shutil
import struct
import subprocess
import sys

import numpy as np
from paraview import simple
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkParallelCore import vtkMultiProcessController

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pcb_testing import check, failures, finish  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("plugin")
parser.add_argument("scratch")
parser.add_argument("file")
parser.add_argument("output", choices=["las", "laz"])
parser.add_argument("--shuffled", action="store_true")
parser.add_argument("--iterations", type=int, default=1)
parser.add_argument("--lazperf", help="the laz-perf npm package (LAZ.laz-perf's), if installed")
parser.add_argument("--laz-records", help="the LAZRecords program of Testing/IO")
args = parser.parse_args()

if not os.path.isfile(args.file):
    print(f"skipped: no file '{args.file}' (set the shared data folders)")
    sys.exit(77)
ranks = vtkMultiProcessController.GetGlobalController().GetNumberOfProcesses()
check(ranks >= 2, f"{ranks} MPI processes")
os.makedirs(args.scratch, exist_ok=True)
simple.LoadPlugin(args.plugin, remote=True, ns=vars(simple))
# Before any filter object reaches Python, or VTK wraps it as its base class for good.
from pointcloudbilateral import (  # noqa: E402
    vtkLASPointCloudReader, vtkLASPointCloudWriter, vtkPointCloudBilateralFilter,
    vtkPointCloudTextReader)

extension = os.path.splitext(args.file)[1].lower()
is_las = extension in (".las", ".laz")
stem = os.path.splitext(os.path.basename(args.file))[0] + ("-shuffled" if args.shuffled else "")
stem += f"-{ranks}"


def read(path):
    reader = (vtkLASPointCloudReader if path.lower().endswith((".las", ".laz"))
              else vtkPointCloudTextReader)()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def write(cloud, path):
    writer = vtkLASPointCloudWriter()
    writer.SetInputData(cloud)
    writer.SetFileName(path)
    return writer.Write() == 1


path = args.file
if args.shuffled:
    whole = dsa.WrapDataObject(read(args.file))
    order = np.random.default_rng(27).permutation(whole.GetNumberOfPoints())
    shuffled = dsa.WrapDataObject(type(whole.VTKObject)())
    shuffled.Points = np.asarray(whole.Points)[order]
    for name in set(whole.PointData.keys()) - {"Colors"}:
        shuffled.PointData.append(np.array(whole.PointData[name])[order], name)
    shuffled.VTKObject.GetFieldData().ShallowCopy(whole.VTKObject.GetFieldData())
    path = os.path.join(args.scratch, stem + extension)
    check(write(shuffled.VTKObject, path), f"the shuffled cloud written to {path}")

# Under MPI: each rank reads its share, filters it with the others, and writes it.
reader = (simple.LASPointCloudReader if is_las else simple.PointCloudTextReader)(FileName=path)
bilateral = simple.PointCloudBilateralFilter(Input=reader, NumberOfIterations=args.iterations,
                                             NumberOfThreads=1)
written = os.path.join(args.scratch, f"{stem}-mpi.{args.output}")
if os.path.exists(written):
    os.remove(written)
try:
    simple.SaveData(written, proxy=bilateral)
except Exception as error:  # ParaView offers no writer for the extension under MPI
    check(False, f"SaveData({written}) under MPI: {error}")
check(os.path.isfile(written), f"{written} written on {ranks} ranks")
check(not os.path.exists(written + ".partial"), "no temporary file left")

# One process: the serial filter on the whole file, written by the serial writer.
serial = vtkPointCloudBilateralFilter()
serial.SetInputData(read(path))
serial.SetNumberOfIterations(args.iterations)
serial.SetNumberOfThreads(1)
serial.Update()
reference = os.path.join(args.scratch, f"{stem}-one-process.{args.output}")
check(write(serial.GetOutput(), reference), f"{reference} written by one process")


def same_bits(a, b):
    a, b = np.ascontiguousarray(a), np.ascontiguousarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def field_data(data):
    fields = data.GetFieldData()
    return {fields.GetAbstractArray(i).GetName():
            [fields.GetAbstractArray(i).GetVariantValue(k).ToString()
             for k in range(fields.GetAbstractArray(i).GetNumberOfValues())]
            for i in range(fields.GetNumberOfArrays())}


def chunk_count(laz):
    """The number of chunks in a LAZ file's chunk table."""
    with open(laz, "rb") as stream:
        data = stream.read()
    point_data = struct.unpack_from("<I", data, 96)[0]
    table = struct.unpack_from("<Q", data, point_data)[0]
    return struct.unpack_from("<I", data, table + 4)[0]


if os.path.isfile(written) and os.path.isfile(reference):
    if args.output == "las":
        with open(written, "rb") as a, open(reference, "rb") as b:
            mine, theirs = a.read(), b.read()
        first = next((i for i in range(min(len(mine), len(theirs))) if mine[i] != theirs[i]),
                     None)
        check(mine == theirs, f"the file written on {ranks} ranks is one process's, byte for "
              f"byte ({len(mine)} and {len(theirs)} bytes; first difference at {first})")
    else:
        ours, one = dsa.WrapDataObject(read(written)), dsa.WrapDataObject(read(reference))
        total = one.GetNumberOfPoints()
        check(ours.GetNumberOfPoints() == total > 0,
              f"{ours.GetNumberOfPoints()} points decoded, one process's file {total}")
        names = sorted(one.PointData.keys())
        differ = [name for name in names if name not in ours.PointData.keys() or not same_bits(
            ours.PointData[name], one.PointData[name])]
        if not same_bits(ours.Points, one.Points):
            differ.append("Points")
        check(not differ, f"the same records, bit for bit and in order: points and {names}"
              + (f"; differ: {differ}" if differ else ""))
        mine, theirs = field_data(ours.VTKObject), field_data(one.VTKObject)
        header_differs = [k for k in theirs if mine.get(k) != theirs[k]]
        check(not header_differs, f"the same header and VLRs in the field data"
              + (f"; differ: {header_differs}" if header_differs else ""))
        shares = [(r + 1) * total // ranks - r * total // ranks for r in range(ranks)]
        expected = sum(-(-share // 50000) for share in shares)
        check(chunk_count(written) == expected,
              f"{chunk_count(written)} chunks: each rank's own ({expected} for shares {shares}; "
              f"one process: {chunk_count(reference)})")


def check_with_lazperf(laz):
    """laz-perf (an independent LASzip implementation) decodes `laz` to our records."""
    node = shutil.which("node")
    if not (node and args.lazperf and args.laz_records
            and os.path.isfile(os.path.join(args.lazperf, "package.json"))):
        print("laz-perf not installed (.ci/install-lazperf) or no Node.js: its check is skipped")
        return
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "IO",
                          "lazperf-records.js")
    theirs, ours = laz + ".lazperf", laz + ".ours"
    decoded = subprocess.run([node, script, args.lazperf, laz, theirs], capture_output=True,
                             text=True)
    mine = subprocess.run([args.laz_records, laz, ours], capture_output=True, text=True)
    same = (decoded.returncode == 0 and mine.returncode == 0
            and open(theirs, "rb").read() == open(ours, "rb").read())
    check(same, f"laz-perf decodes {os.path.basename(laz)} to our records "
          f"({(decoded.stderr or decoded.stdout).strip().splitlines()[-1:]})")


if args.output == "laz" and os.path.isfile(written):
    check_with_lazperf(written)
if failures:
    finish()  # exits with status 1; mpirun then ends the other ranks
# sys.exit would skip MPI_Finalize, which mpirun reports as a failure: end the script instead.
print("all checks passed")

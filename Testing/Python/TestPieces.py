"""Readers that honour pieces: under mpirun pvbatch each rank's reader reads only its share of
the file's points, and the distributed filter on those shares gives, gathered, the bits of one
process on the whole file.

    mpirun -np P pvbatch TestPieces.py PLUGIN SCRATCH_FOLDER FILE [--shuffled] [--dark-first-third]
        [--iterations N] [--copc-level L] [--held-at-most F]

FILE is a LAS, LAZ, PCD or text file (.xyz or .txt), read with the plugin's reader. With
--shuffled, the script first writes FILE's points in a random order to a LAS or LAZ file (as
FILE is) with the project's writer and reads that instead: each rank's share then spans the
whole cloud. With --dark-first-third, the RGB values (8-bit in FILE) of all but the first third
of the points are made 16-bit (times 257) first: the display colours ("Colors") must still
follow the whole file (16-bit) on the pieces that hold only 8-bit values. With --copc-level, FILE
is a COPC file read to octree level L: each piece then decodes whole nodes of its own (so the
shares are those of the one-process reader's pieces, whole nodes, rather than floor(r N / P)).
--held-at-most: the largest share of the cloud a rank may hold during the filter (default
1/P + 0.2). Exits with 77 (skipped) when FILE does not exist.

Checks:
- each rank holds exactly points [floor(r N / P), floor((r + 1) N / P)) of the file: the
  gathered output of the reader (rank after rank) is, array by array and bit for bit, what the
  reader gives in one piece, in the file's order;
- each piece read in this process (UpdatePiece) has the same field data as the whole file, and
  its arrays are the whole file's rows of its share;
- the distributed filter's gathered output equals, bit for bit and in order, the plain VTK
  filter run in this process on the whole file.

The script runs on rank 0 (the client); the other ranks are servers, as in TestDistributed.py.
"""
import argparse
import os
import sys

import numpy as np
from paraview import servermanager, simple
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkParallelCore import vtkMultiProcessController

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pcb_testing import check, failures, finish  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("plugin")
parser.add_argument("scratch")
parser.add_argument("file")
parser.add_argument("--shuffled", action="store_true")
parser.add_argument("--dark-first-third", action="store_true")
parser.add_argument("--iterations", type=int, default=1)
parser.add_argument("--copc-level", type=int, default=-1)
parser.add_argument("--held-at-most", type=float)
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
    vtkLASPointCloudReader, vtkLASPointCloudWriter, vtkPCDPointCloudReader,
    vtkPointCloudBilateralFilter, vtkPointCloudTextReader)

extension = os.path.splitext(args.file)[1].lower()
READERS = {".las": vtkLASPointCloudReader, ".laz": vtkLASPointCloudReader,
           ".pcd": vtkPCDPointCloudReader, ".xyz": vtkPointCloudTextReader,
           ".txt": vtkPointCloudTextReader}


def read_piece(path, piece, pieces):
    reader = READERS[os.path.splitext(path)[1].lower()]()
    reader.SetFileName(path)
    if args.copc_level >= 0:
        reader.SetCOPCMaxLevel(args.copc_level)
    reader.UpdatePiece(piece, pieces, 0)
    return reader.GetOutput()


path = args.file
if args.shuffled or args.dark_first_third:
    # The file's points in a random order, or with dark colours first, written by the project's
    # LAS writer: each rank's contiguous share is then spread over the whole cloud.
    whole = dsa.WrapDataObject(read_piece(args.file, 0, 1))
    count = whole.GetNumberOfPoints()
    order = np.random.default_rng(27).permutation(count) if args.shuffled else np.arange(count)
    rewritten = dsa.WrapDataObject(type(whole.VTKObject)())
    rewritten.Points = np.asarray(whole.Points)[order]
    for name in set(whole.PointData.keys()) - {"Colors"}:
        values = np.array(whole.PointData[name])[order]
        if name == "RGB" and args.dark_first_third:  # 8-bit values first, 16-bit ones after
            check(values.max() <= 255, "the file's RGB holds 8-bit values")
            values[count // 3:] *= 257
            check(values[count // 3:].max() > 255, "the other points' RGB is 16-bit")
        rewritten.PointData.append(values, name)
    rewritten.VTKObject.GetFieldData().ShallowCopy(whole.VTKObject.GetFieldData())
    kind = "shuffled" if args.shuffled else "dark"
    path = os.path.join(args.scratch, f"{kind}-{ranks}-" + os.path.basename(args.file))
    writer = vtkLASPointCloudWriter()
    writer.SetInputData(rewritten.VTKObject)
    writer.SetFileName(path)
    check(writer.Write() == 1, f"the {kind} cloud written to {path}")

whole = read_piece(path, 0, 1)
total = whole.GetNumberOfPoints()
check(total > 0, f"{path}: {total} points in one piece")


def piece_starts(pieces):
    """Where each piece's rows start in the whole file (and the end): floor(r N / P), or with
    --copc-level the pieces' own counts, whole nodes each, checked to split the file."""
    if args.copc_level < 0:
        return [r * total // pieces for r in range(pieces + 1)]
    counts = [read_piece(path, r, pieces).GetNumberOfPoints() for r in range(pieces)]
    check(0 < max(counts) < total, f"{pieces} pieces of a COPC file hold {counts} points")
    return list(np.cumsum([0] + counts))


starts = piece_starts(ranks)


def same_bits(a, b):
    a, b = np.ascontiguousarray(a), np.ascontiguousarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def same_arrays(data, reference, rows, what):
    """Points and every point array of `data` are `reference`'s `rows`, bit for bit."""
    data, reference = dsa.WrapDataObject(data), dsa.WrapDataObject(reference)
    problems = []
    if not same_bits(np.asarray(data.Points), np.asarray(reference.Points)[rows]):
        problems.append("Points")
    names = [n for n in reference.PointData.keys()]
    for name in names:
        if name not in data.PointData.keys() or not same_bits(
                np.asarray(data.PointData[name]), np.asarray(reference.PointData[name])[rows]):
            problems.append(name)
    differ = f"; differ: {problems}" if problems else ""
    check(not problems, f"{what}: the points and arrays {names} are the whole file's rows "
          f"{rows.start} to {rows.stop}, bit for bit{differ}")


def field_data(data):
    fields = data.GetFieldData()
    values = {}
    for i in range(fields.GetNumberOfArrays()):
        array = fields.GetAbstractArray(i)
        values[array.GetName()] = [array.GetVariantValue(k).ToString()
                                   for k in range(array.GetNumberOfValues())]
    return values


# Every piece, read in this process: its share, the whole file's field data.
for pieces in sorted({2, 3, ranks}):
    bounds = piece_starts(pieces)
    for piece in range(pieces):
        part = read_piece(path, piece, pieces)
        rows = slice(bounds[piece], bounds[piece + 1])
        same_arrays(part, whole, rows, f"piece {piece} of {pieces}")
        check(field_data(part) == field_data(whole),
              f"piece {piece} of {pieces}: the field data is the whole file's")

# Under MPI: each rank reads its share, with the plugin's reader proxy.
PROXIES = {".las": "LASPointCloudReader", ".laz": "LASPointCloudReader",
           ".pcd": "PCDPointCloudReader", ".xyz": "PointCloudTextReader",
           ".txt": "PointCloudTextReader"}
reader = getattr(simple, PROXIES[extension])(FileName=path)
if args.copc_level >= 0:
    reader.COPCMaxLevel = args.copc_level
tagged = simple.ProcessIdScalars(Input=reader)
gathered = servermanager.Fetch(tagged)
holders = np.asarray(dsa.WrapDataObject(gathered).PointData["ProcessId"])
per_rank = [int(np.count_nonzero(holders == r)) for r in range(ranks)]
expected = [starts[r + 1] - starts[r] for r in range(ranks)]
print(f"points per rank: {per_rank}")
check(per_rank == expected, f"each rank reads its share: {per_rank}, expected {expected}")
check(np.array_equal(holders, np.repeat(np.arange(ranks), expected)),
      "the gathered points come rank after rank")
same_arrays(gathered, whole, slice(0, total), f"{ranks} ranks gathered")

# The distributed filter on the ranks' shares against one process on the whole file.
bilateral = simple.PointCloudBilateralFilter(Input=reader, NumberOfIterations=args.iterations,
                                             NumberOfThreads=1)
bilateral.UpdatePipeline()
# No rank holds the whole cloud, even when its share spans it (--shuffled): the filter moves the
# points into one slab of space per rank first. Before, each rank held the whole cloud (its share
# and every other point as ghosts).
held = bilateral.GetClientSideObject().GetLargestNumberOfPointsHeld()
print(f"the most points a rank held: {held} of {total} ({held / total:.2f})")
# 1/N and its border layers: up to 0.51 at 2 ranks and 0.46 at 3 on these small files.
bound = args.held_at_most if args.held_at_most else 1.0 / ranks + 0.2
check(0 < held <= bound * total,
      f"the most points a rank held ({held}) is at most {bound:.2f} of the cloud ({total})")
output = servermanager.Fetch(bilateral)
serial = vtkPointCloudBilateralFilter()
serial.SetInputData(whole)
serial.SetNumberOfIterations(args.iterations)
serial.Update()
reference = serial.GetOutput()
check(output.GetNumberOfPoints() == reference.GetNumberOfPoints() == total,
      f"the filter outputs {output.GetNumberOfPoints()} points, one process "
      f"{reference.GetNumberOfPoints()}")
moved = np.any(np.asarray(dsa.WrapDataObject(reference).Points) !=
               np.asarray(dsa.WrapDataObject(whole).Points), axis=1)
check(np.count_nonzero(moved) > total // 2, f"the filter moved {np.count_nonzero(moved)} points")
if output.GetNumberOfPoints() == reference.GetNumberOfPoints():
    same_arrays(output, reference, slice(0, total), f"the filter on {ranks} ranks, gathered")
if failures:
    finish()  # exits with status 1; mpirun then ends the other ranks
# sys.exit would skip MPI_Finalize, which mpirun reports as a failure: end the script instead.
print("all checks passed")

"""Distributed runs: under mpirun pvbatch, the ranks' outputs put together are, bit for bit, the
output of one process filtering the whole cloud.

    mpirun -np P pvbatch TestDistributed.py PLUGIN SCRATCH_FOLDER --split SPLIT [--iterations N]
        [--radius R] [--normal-radius RN] [--remove-isolated] [--edge-aware]

SPLIT says how the cloud is shared among the ranks:
- distribute: read on one rank, then ParaView's Distribute Points (a kd-tree split into equal
  counts; it writes float points, so the serial run is on those float points too);
- slabs: uneven slabs along x, 70/25/5% of the points for 3 ranks (80/20 for 2);
- random: every point to a random rank (60/30/10%), each rank's points in shuffled order: parts
  that overlap everywhere;
- empty: rank 1 holds no points; the others share the cloud in slabs along y.
Each point carries its global number in the array PointId; the script gathers the output to
rank 0, matches points by PointId and compares positions and every array bitwise with the
plain VTK filter run in this process on the gathered input.

Rank 0 is a server too: the programmable source runs its script in this interpreter's
__main__, which leaves ParaView's parallel numpy_interface.algorithms (sum, min, max, all,
any, abs) in place of Python's builtins; they would wait for the other ranks: use NumPy's.
"""
import argparse
import os
import sys

import numpy as np
from paraview import servermanager, simple
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
from vtkmodules.vtkParallelCore import vtkMultiProcessController

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pcb_testing import check, failures, finish  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("plugin")
parser.add_argument("scratch")
parser.add_argument("--split", required=True, choices=["distribute", "slabs", "random", "empty"])
parser.add_argument("--iterations", type=int, default=2)
parser.add_argument("--radius", type=float, default=0.0)
parser.add_argument("--normal-radius", type=float, default=0.0)
parser.add_argument("--remove-isolated", action="store_true")
parser.add_argument("--edge-aware", action="store_true")
# A density that falls this many times along u (as a scan's falls with the distance from the
# scanner): the automatic radius then follows the density.
parser.add_argument("--density-ratio", type=float, default=1.0)
# Filter only class 2 of a "Classification" array that gives 30% of the points class 5.
parser.add_argument("--classes", action="store_true")
args = parser.parse_args()

ranks = vtkMultiProcessController.GetGlobalController().GetNumberOfProcesses()
check(ranks >= 2, f"{ranks} MPI processes")
os.makedirs(args.scratch, exist_ok=True)
path = os.path.join(args.scratch, f"cloud-{args.split}-{ranks}-{args.density_ratio:g}"
                    f"{'-classes' if args.classes else ''}.vtp")


def make_cloud():
    """A noisy sheet folded into a sharp ridge, with exact duplicates (ties in the octree's
    leaves), isolated outliers (removed with --remove-isolated) and, unless Distribute Points
    splits it (its kd-tree has no place for it), a NaN point that must pass through."""
    rng = np.random.default_rng(179)
    count = 12000
    u, v = rng.random(count), rng.random(count)
    if args.density_ratio > 1.0:  # the inverse of the distribution of a density ratio^-u
        ratio = args.density_ratio
        u = -np.log(1.0 - u * (1.0 - 1.0 / ratio)) / np.log(ratio)
    points = np.column_stack([u, v, 0.3 * np.abs(u - 0.5)]) + rng.normal(0, 0.004, (count, 3))
    points[1::97] = points[0:-1:97]  # exact duplicates
    outliers = np.column_stack([rng.random(6), rng.random(6), np.full(6, 0.6)])
    points = np.vstack([points, outliers])
    if args.split != "distribute":
        points = np.vstack([points, [[np.nan, 0.5, 0.5]]])
    n = len(points)
    normals = np.tile(np.array([0.0, 0.0, 1.0], dtype=np.float32), (n, 1))
    cloud = dsa.WrapDataObject(vtkPolyData())
    cloud.Points = points
    cloud.PointData.append(np.arange(n, dtype=np.int64), "PointId")
    cloud.PointData.append(rng.integers(0, 256, (n, 3), dtype=np.uint8), "RGB")
    cloud.PointData.append(rng.random(n).astype(np.float32), "Intensity")
    cloud.PointData.append(normals, "Normals")
    if args.classes:
        classes = np.where(rng.random(n) < 0.3, 5, 2).astype(np.uint8)
        classes[-1] = 2  # the NaN point, if any: filtered, and warned about
        cloud.PointData.append(classes, "Classification")
    writer = vtkXMLPolyDataWriter()
    writer.SetInputData(cloud.VTKObject)
    writer.SetFileName(path)
    writer.Write()
    return n


total = make_cloud()
# The most a rank may hold, as a fraction of the cloud: its 1/N and two border layers (0.56 at
# 2 ranks, 0.44 at 3, 0.69 with the edge-aware mode's layers of 3 radii). Where the radius
# follows the density, each band's points reach as far as their own radius only
# (BilateralRun::GetGhostReaches): 0.58 at 3 ranks (0.98 when the whole part reached as far as
# its largest radius, 10 times the dense end's here). Not checked in the edge-aware mode there:
# the sparse bands' points read 3 of their radii, the whole sheet.
if args.density_ratio > 1.0:
    HELD_BOUND = 1.0 if args.edge_aware else 0.7
else:
    HELD_BOUND = 0.75
simple.LoadPlugin(args.plugin, remote=True, ns=vars(simple))
# Before any filter object reaches Python, or VTK wraps it as its base class for good.
from pointcloudbilateral import vtkPointCloudBilateralFilter  # noqa: E402

# The split, run on every rank by a programmable source (or by Distribute Points).
SPLIT_SCRIPT = """
import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkParallelCore import vtkMultiProcessController

controller = vtkMultiProcessController.GetGlobalController()
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
reader = vtkXMLPolyDataReader()
reader.SetFileName({path!r})
reader.Update()
cloud = dsa.WrapDataObject(reader.GetOutput())
xyz = np.asarray(cloud.Points)
n = len(xyz)
split = {split!r}
if split == "slabs":
    shares = [0.7, 0.25, 0.05] if ranks == 3 else [0.8, 0.2]
    order = np.argsort(np.nan_to_num(xyz[:, 0]), kind="stable")
    owner = np.empty(n, dtype=int)
    cuts = np.round(np.cumsum([0.0] + shares) * n).astype(int)
    for r in range(ranks):
        owner[order[cuts[r]:cuts[r + 1]]] = r
    mine = np.flatnonzero(owner == rank)
elif split == "random":
    shares = [0.6, 0.3, 0.1] if ranks == 3 else [0.7, 0.3]
    owner = np.random.default_rng(5).choice(ranks, size=n, p=shares)
    mine = np.random.default_rng(6 + rank).permutation(np.flatnonzero(owner == rank))
else:  # empty: rank 1 has nothing, the others share slabs along y
    holders = [r for r in range(ranks) if r != 1]
    order = np.argsort(np.nan_to_num(xyz[:, 1]), kind="stable")
    owner = np.empty(n, dtype=int)
    for k, part in enumerate(np.array_split(order, len(holders))):
        owner[part] = holders[k]
    mine = np.flatnonzero(owner == rank)
output = dsa.WrapDataObject(self.GetPolyDataOutput())
output.Points = xyz[mine]
for name in cloud.PointData.keys():
    output.PointData.append(np.asarray(cloud.PointData[name])[mine], name)
"""

if args.split == "distribute":
    reader = simple.XMLPolyDataReader(FileName=[path])
    source = simple.DistributePoints(Input=reader)
else:
    source = simple.ProgrammableSource(OutputDataSetType="vtkPolyData")
    source.Script = SPLIT_SCRIPT.format(path=path, split=args.split)
# Each point records the rank that holds it.
tagged = simple.ProcessIdScalars(Input=source)
tagged.UpdatePipeline()
properties = dict(Radius=args.radius, NormalRadius=args.normal_radius,
                  NumberOfIterations=args.iterations, RemoveIsolatedPoints=args.remove_isolated,
                  EdgeAware=int(args.edge_aware),
                  OrientNormalsBy="Normals", OutputEstimatedNormals=1,
                  OutputDisplacementLength=1, OutputPointRadius=1, NumberOfThreads=1,
                  Classes=[2] if args.classes else [])
bilateral = simple.PointCloudBilateralFilter(Input=tagged, **properties)
# Warnings reach the user during a distributed run too, once: rank 0's filter is this process's.
warnings = []
bilateral.GetClientSideObject().AddObserver("WarningEvent", lambda obj, event: warnings.append(1))
bilateral.UpdatePipeline()
bilateral.UpdatePropertyInformation()

gathered_input = servermanager.Fetch(tagged)
gathered_output = servermanager.Fetch(bilateral)
cloud_in = dsa.WrapDataObject(gathered_input)
cloud_out = dsa.WrapDataObject(gathered_output)

# The split is what the case says.
holders = np.asarray(cloud_in.PointData["ProcessId"])
if args.split == "slabs":  # the NaN point sorts first, to rank 0
    check(len(warnings) == 1, f"rank 0 holds the NaN point: 1 warning, got {len(warnings)}")
per_rank = [int(np.count_nonzero(holders == r)) for r in range(ranks)]
print(f"points per rank: {per_rank}")
check(np.sum(per_rank) == total, f"the ranks hold the {total} points between them")
if args.split == "empty":
    check(per_rank[1] == 0 and np.all([per_rank[r] > 0 for r in range(ranks) if r != 1]),
          "rank 1 holds no points, the others do")
elif args.split in ("slabs", "random"):
    check(per_rank[0] > 2 * per_rank[-1] > 0, "the split is uneven")
else:
    check(np.min(per_rank) > 0.9 * np.max(per_rank), "Distribute Points split the cloud evenly")

# No rank holds the whole cloud: the filter moves the points into one slab of space per rank,
# with equal counts, so that each holds about 1/N of them plus a layer at its slab's borders
# (one radius wide, three in the edge-aware mode). Before, a rank held its share as it was and
# every other point within reach as ghosts: on the random split, rank 0 its 60% and all the
# others' points (the whole cloud).
held = bilateral.GetClientSideObject().GetLargestNumberOfPointsHeld()
print(f"the most points a rank held: {held} of {total} ({held / total:.2f})")
check(0 < held <= HELD_BOUND * total,
      f"the most points a rank held ({held}) is at most {HELD_BOUND} of the cloud ({total})")

# The same filter, serially, on the gathered input: points of the same type, the same arrays.

# The serial class never communicates: made in a script under mpirun, it runs on this rank alone
# (before the parallel module existed it waited for the other ranks unless given no controller).
serial = vtkPointCloudBilateralFilter()
serial.SetInputData(gathered_input)
serial.SetRadius(args.radius)
serial.SetNormalRadius(args.normal_radius)
serial.SetNumberOfIterations(args.iterations)
serial.SetRemoveIsolatedPoints(args.remove_isolated)
serial.SetEdgeAware(args.edge_aware)
serial.SetOrientationArrayName("Normals")
serial.GenerateEstimatedNormalsOn()
serial.GenerateDisplacementLengthOn()
serial.GeneratePointRadiusOn()  # where the radius follows the density: BilateralPointRadius
if args.classes:
    serial.AddClass(2)
serial.Update()
reference = dsa.WrapDataObject(serial.GetOutput())

check(bilateral.RadiusUsed == serial.GetRadiusUsed() and
      bilateral.NormalRadiusUsed == serial.GetNormalRadiusUsed() and
      bilateral.NumberOfIterationsUsed == serial.GetNumberOfIterationsUsed(),
      f"radius used {bilateral.RadiusUsed!r} (serial {serial.GetRadiusUsed()!r}), normal radius "
      f"used {bilateral.NormalRadiusUsed!r} (serial {serial.GetNormalRadiusUsed()!r}), "
      f"iterations {bilateral.NumberOfIterationsUsed} (serial {serial.GetNumberOfIterationsUsed()})")
# The automatic mode measures the whole cloud, not each process's part: the same bits.
if args.radius == 0 or args.normal_radius == 0 or args.iterations == 0:
    check(serial.GetPointSpacing() > 0 and bilateral.PointSpacing == serial.GetPointSpacing()
          and bilateral.NoiseSigma == serial.GetNoiseSigma(),
          f"measured spacing {bilateral.PointSpacing!r} (serial {serial.GetPointSpacing()!r}), "
          f"noise {bilateral.NoiseSigma!r} (serial {serial.GetNoiseSigma()!r})")
    distances = list(bilateral.NearestNeighbourDistances)
    check(distances == list(serial.GetNearestNeighbourDistances()) and 0 < distances[0],
          f"nearest-neighbour distances {distances} "
          f"(serial {list(serial.GetNearestNeighbourDistances())})")
# A radius that follows the density: the same bands on every rank as serially.
check(bool(bilateral.RadiusFollowsDensity) == bool(serial.GetRadiusFollowsDensity()) and
      list(bilateral.RadiusRange) == list(serial.GetRadiusRange()) and
      bool(serial.GetRadiusFollowsDensity()) == (args.density_ratio > 1.0 and args.radius == 0),
      f"radius follows the density: {bilateral.RadiusFollowsDensity} "
      f"{list(bilateral.RadiusRange)} (serial {serial.GetRadiusFollowsDensity()} "
      f"{list(serial.GetRadiusRange())})")
removed = total - reference.GetNumberOfPoints()
print(f"{removed} point(s) removed as isolated")
if args.remove_isolated:
    check(removed > 0, "the serial run removes the outliers")

ids_in = np.asarray(cloud_in.PointData["PointId"])
ids_out = np.asarray(cloud_out.PointData["PointId"])
ids_ref = np.asarray(reference.PointData["PointId"])
check(gathered_output.GetNumberOfPoints() == reference.GetNumberOfPoints(),
      f"{gathered_output.GetNumberOfPoints()} points out, serially {reference.GetNumberOfPoints()}")
check(len(np.unique(ids_out)) == len(ids_out) and set(ids_out) == set(ids_ref),
      "the ranks output each kept point once, and only those")
# Each rank outputs its own points, in their order: the gathered output is the gathered input
# (rank after rank) less the removed points.
kept = np.isin(ids_in, ids_ref)
check(np.array_equal(ids_out, ids_in[kept]), "each rank keeps its points' order")
# vtkOriginalPointIds numbers points within their rank's input.
if args.remove_isolated:
    local_index = np.zeros(total, dtype=np.int64)
    for r in range(ranks):
        local_index[holders == r] = np.arange(per_rank[r])
    check(np.array_equal(np.asarray(cloud_out.PointData["vtkOriginalPointIds"]),
                         local_index[kept]), "vtkOriginalPointIds are ids within each rank's input")

# Bit for bit, point by point.
if len(ids_out) == len(ids_ref) and set(ids_out) == set(ids_ref):
    where = np.argsort(ids_ref)[np.searchsorted(ids_ref, ids_out, sorter=np.argsort(ids_ref))]
    out_xyz = np.asarray(cloud_out.Points)
    ref_xyz = np.asarray(reference.Points)[where]
    check(out_xyz.dtype == ref_xyz.dtype, f"points of type {out_xyz.dtype}, as serially")
    differ = np.any(out_xyz.view(np.uint8).reshape(len(out_xyz), -1) !=
                    ref_xyz.view(np.uint8).reshape(len(ref_xyz), -1), axis=1)
    check(not differ.any(), f"positions: {np.count_nonzero(differ)} of {len(differ)} points "
          "differ from the serial run in some bit")
    moved = np.any(np.asarray(cloud_in.Points)[kept] != out_xyz, axis=1)
    if args.classes:  # the class-5 points kept their exact coordinates
        other = np.asarray(cloud_in.PointData["Classification"])[kept] != 2
        check(not np.any(moved & other) and np.count_nonzero(moved) > np.count_nonzero(~other) // 2,
              f"{np.count_nonzero(moved & other)} points of class 5 moved, "
              f"{np.count_nonzero(moved & ~other)} of class 2")
    check(np.count_nonzero(moved) > len(out_xyz) // 2,
          f"{np.count_nonzero(moved)} of {len(out_xyz)} points moved")
    names = set(reference.PointData.keys()) - {"vtkOriginalPointIds"}
    check(names == set(cloud_out.PointData.keys()) - {"vtkOriginalPointIds"},
          f"the same point arrays as serially: {sorted(names)}")
    if args.density_ratio > 1.0:  # each point's radius, brought back from the rank that filtered it
        check("BilateralPointRadius" in names, "the output has each point's radius")
    for name in sorted(names & set(cloud_out.PointData.keys())):
        mine = np.ascontiguousarray(np.asarray(cloud_out.PointData[name]))
        theirs = np.ascontiguousarray(np.asarray(reference.PointData[name])[where])
        check(mine.dtype == theirs.dtype and mine.tobytes() == theirs.tobytes(),
              f"array {name} ({mine.dtype}) is bitwise the serial one")
field = gathered_output.GetFieldData().GetArray("BilateralRadius")
check(field is not None and field.GetValue(0) == serial.GetRadiusUsed(),
      "the output's field data records the radius used")
if failures:
    finish()  # exits with status 1; mpirun then ends the other ranks
# sys.exit would skip MPI_Finalize, which mpirun reports as a failure: end the script instead.
print("all checks passed")

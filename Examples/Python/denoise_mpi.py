"""Denoise a point cloud on several processes (or machines) with ParaView's MPI engine.

    mpirun -np 2 pvbatch Examples/Python/denoise_mpi.py IN OUT.pvtp --radius R [--threads 1]

The cloud is read (by one process, for files that are not split in pieces), spread over the
processes with ParaView's Distribute Points (equal point counts in compact regions), filtered by
every process on its part, and written. Every process takes the points of its neighbours within
one radius from them before each iteration, so the result is, bit for bit, what one process
filtering the whole cloud gives (Distribute Points stores points as float: compare with a
single-process run on float points).

IN: .ply, .vtp, .pvtp, or the authors' text format (.xyz, .txt). OUT: .pvtp (every process
writes its own piece, OUT names the file that lists them) or .ply (gathered to the first
process). Under pvbatch alone (one process) the same script filters the whole cloud. With
several processes per machine, give each one thread (--threads 1) or start mpirun with
--bind-to none: OpenMPI pins each process to one core. The script loads the PointCloudBilateral
plugin itself: from --plugin, from PV_PLUGIN_PATH (auto-loaded), or from the build or install
tree that holds this script.
"""
import argparse
import glob
import os
import sys
import time

from paraview import simple
from vtkmodules.vtkParallelCore import vtkMultiProcessController

PLUGIN = "PointCloudBilateral"
HERE = os.path.dirname(os.path.abspath(__file__))
# Where the plugin is relative to this script: the source tree next to a build/ folder, and the
# install tree (<prefix>/share/pointcloudbilateral/examples/).
CANDIDATES = [
    os.path.join(HERE, "..", "..", "build", "lib", "paraview-5.11", "plugins", PLUGIN),
    os.path.join(HERE, "..", "..", "..", "lib", "paraview-5.11", "plugins", PLUGIN),
    os.path.join(HERE, "..", "..", "..", "lib", "*", "paraview-5.11", "plugins", PLUGIN),
]


def load_plugin(explicit):
    if hasattr(simple, "PointCloudBilateralFilter"):
        return "already loaded (PV_PLUGIN_PATH)"
    paths = [explicit] if explicit else []
    for pattern in CANDIDATES:
        paths += glob.glob(os.path.join(pattern, PLUGIN + ".so"))
    for path in paths:
        if os.path.isfile(path):
            # remote=True: every process of the run loads it, not only this one.
            simple.LoadPlugin(path, remote=True, ns=vars(simple))
            return os.path.normpath(path)
    sys.exit(f"error: the {PLUGIN} plugin was not found: give --plugin PATH or set PV_PLUGIN_PATH")


def open_cloud(path, oriented_normals):
    if not os.path.isfile(path):
        sys.exit(f"error: {path}: no such file")
    if path.endswith((".xyz", ".txt")):
        return simple.PointCloudTextReader(FileName=path, HasNormals=int(oriented_normals))
    reader = simple.OpenDataFile(path)
    if reader is None:
        sys.exit(f"error: {path}: no reader for this file type")
    return reader


def main():
    parser = argparse.ArgumentParser(
        description="Denoise a point cloud with the bilateral filter on several MPI processes.")
    parser.add_argument("input")
    parser.add_argument("output", help=".pvtp (one piece per process) or .ply")
    parser.add_argument("--radius", type=float, default=0.0, help="0 (default): automatic")
    parser.add_argument("--normal-radius", type=float, default=0.0, help="0 (default): the radius")
    parser.add_argument("--iterations", type=int, default=1)
    parser.add_argument("--oriented-normals", action="store_true",
                        help="text files carry normals in columns 4-6")
    parser.add_argument("--remove-isolated", action="store_true")
    parser.add_argument("--threads", type=int, default=0,
                        help="threads per process; 0 (default): all the cores it may use")
    parser.add_argument("--plugin", help="path of PointCloudBilateral.so")
    args = parser.parse_args()
    if not args.output.endswith((".pvtp", ".ply")):
        sys.exit("error: the output must be a .pvtp file (one piece per process) or a .ply file")

    processes = vtkMultiProcessController.GetGlobalController().GetNumberOfProcesses()
    where = load_plugin(args.plugin)
    reader = open_cloud(args.input, args.oriented_normals)
    parts = simple.DistributePoints(Input=reader)
    start = time.perf_counter()
    parts.UpdatePipeline()
    read = time.perf_counter()
    bilateral = simple.PointCloudBilateralFilter(
        Input=parts,
        Radius=args.radius,
        NormalRadius=args.normal_radius,
        NumberOfIterations=args.iterations,
        RemoveIsolatedPoints=int(args.remove_isolated),
        NumberOfThreads=args.threads,
    )
    bilateral.UpdatePipeline()
    filtered = time.perf_counter()
    bilateral.UpdatePropertyInformation()
    points = bilateral.GetDataInformation().GetNumberOfPoints()
    if points == 0:
        sys.exit("error: the filter produced no points (see the messages above)")
    simple.SaveData(args.output, proxy=bilateral)
    written = time.perf_counter()
    print(f"plugin: {where}")
    print(f"radius {bilateral.RadiusUsed:.6g}, normal radius {bilateral.NormalRadiusUsed:.6g}, "
          f"{args.iterations} iteration(s) on {processes} process(es): {points} points written "
          f"to {args.output}")
    print(f"seconds: reading and distributing {read - start:.2f}, filtering "
          f"{filtered - read:.2f}, writing {written - filtered:.2f}")


if __name__ == "__main__":
    main()

"""Denoise a point cloud on several processes (or machines) with ParaView's MPI engine.

    mpirun -np 2 pvbatch Examples/Python/denoise_mpi.py IN OUT.pvtp [--radius R] [--threads 1]
    mpirun -np 2 pvbatch Examples/Python/denoise_mpi.py IN.las OUT.las [--threads 1]
    mpirun -np 2 pvbatch --symmetric Examples/Python/denoise_mpi.py ...   (the same; one report)

The cloud is read (by one process, for files that are not split in pieces), spread over the
processes with ParaView's Distribute Points (equal point counts in compact regions), filtered by
every process on its part, and written. Every process takes the points of its neighbours within
one radius from them before each iteration, so the result is, bit for bit, what one process
filtering the whole cloud gives (Distribute Points stores points as float: compare with a
single-process run on float points).

IN: .ply, .vtp, .pvtp, or the authors' text format (.xyz, .txt), or .las/.laz: a LAS or LAZ
file is not spread but read in pieces, each process its share of the file's points in file
order, in double precision (Distribute Points would round georeferenced coordinates to float).
OUT: .pvtp (every process writes its own piece, OUT names the file that lists them), .ply
(gathered to the first process), or .las/.laz (one file written by every process, in the order
of the processes' points: a LAS or LAZ input's file order). Under pvbatch alone (one process) the same script filters the whole cloud. With
several processes per machine, give each one thread (--threads 1) or start mpirun with
--bind-to none: OpenMPI pins each process to one core. The script loads the PointCloudBilateral
plugin itself: from --plugin, from PV_PLUGIN_PATH (auto-loaded), or from the build or install
tree that holds this script.
"""
import argparse
import os
import sys
import time

from paraview import simple
from vtkmodules.vtkParallelCore import vtkMultiProcessController

# The plugin search, the reader choice and the filter's options are denoise.py's, beside this.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from denoise import (  # noqa: E402
    add_filter_arguments, check_output, describe_run, load_plugin, open_cloud, run_filter)


def whole_count(points):
    """The whole cloud's count, and whether this process reports it. Under `pvbatch --symmetric`
    every process runs this script and its proxies see its own points only: the counts are
    summed and the first process reports. Otherwise the first process alone runs it and its
    data information already covers every process."""
    from paraview.servermanager import vtkProcessModule
    if not vtkProcessModule.GetProcessModule().GetSymmetricMPIMode():
        return points, True
    from vtkmodules.vtkCommonCore import vtkIdTypeArray
    from vtkmodules.vtkParallelCore import vtkCommunicator
    controller = vtkMultiProcessController.GetGlobalController()
    mine, total = vtkIdTypeArray(), vtkIdTypeArray()
    mine.InsertNextValue(points)
    controller.AllReduce(mine, total, vtkCommunicator.SUM_OP)
    return total.GetValue(0), controller.GetLocalProcessId() == 0


def main():
    parser = argparse.ArgumentParser(
        description="Denoise a point cloud with the bilateral filter on several MPI processes.")
    parser.add_argument("input")
    parser.add_argument("output", help=".pvtp (one piece per process), .ply or .las/.laz")
    add_filter_arguments(
        parser, threads_help="threads per process; 0 (default): all the cores it may use")
    args = parser.parse_args()
    if not args.output.lower().endswith((".pvtp", ".ply", ".las", ".laz")):
        sys.exit("error: the output must be a .pvtp file (one piece per process), a .ply file or "
                 "a .las/.laz file")
    check_output(args.output, args.input)  # every process sees the same files: all stop alike

    processes = vtkMultiProcessController.GetGlobalController().GetNumberOfProcesses()
    where = load_plugin(args.plugin)
    reader = open_cloud(args.input, args.oriented_normals)
    # LAS and LAZ files are read in pieces, in double precision; others are spread.
    in_pieces = args.input.lower().endswith((".las", ".laz"))
    parts = reader if in_pieces else simple.DistributePoints(Input=reader)
    start = time.perf_counter()
    parts.UpdatePipeline()
    read = time.perf_counter()
    bilateral, points = run_filter(parts, args)
    filtered = time.perf_counter()
    simple.SaveData(args.output, proxy=bilateral)
    written = time.perf_counter()
    points, speaking = whole_count(points)
    if not speaking:
        return
    print(f"plugin: {where}")
    print(f"{describe_run(bilateral)} on {processes} process(es): {points} points written "
          f"to {args.output}")
    reading = "reading" if in_pieces else "reading and distributing"
    print(f"seconds: {reading} {read - start:.2f}, filtering "
          f"{filtered - read:.2f}, writing {written - filtered:.2f}")


if __name__ == "__main__":
    main()

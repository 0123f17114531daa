"""Denoise a point cloud with ParaView's Python, in a batch script.

    pvpython Examples/Python/denoise.py IN OUT [--radius R] [--normal-radius RN] [--iterations N]
                                        [--paper] [--edge-aware]
    pvbatch  Examples/Python/denoise.py IN OUT ...
    mpirun -np 2 pvbatch Examples/Python/denoise.py IN OUT ...

IN and OUT: .ply, .vtp, .las, .pcd, or the authors' text format (.xyz, .txt). The parameters not given
are automatic: chosen from the cloud's measured point spacing and noise, or with --paper by the
paper's heuristic (r = sqrt(20 / points) x largest extent, rn = r, N = 1). The script loads the
PointCloudBilateral plugin itself: from --plugin, from PV_PLUGIN_PATH (auto-loaded), or from the
build or install tree that holds this script.
"""
import argparse
import glob
import os
import sys

from paraview import servermanager
from paraview import simple

PLUGIN = "PointCloudBilateral"
HERE = os.path.dirname(os.path.abspath(__file__))


def plugin_candidates():
    """Where the plugin is relative to this script: the source tree next to a build/ folder, and
    the install tree (<prefix>/share/pointcloudbilateral/examples/); ParaView's plugin folder is
    named after its version (lib[/<arch>]/paraview-X.Y/plugins)."""
    version = simple.GetParaViewVersion()
    plugins = os.path.join(f"paraview-{version.major}.{version.minor}", "plugins", PLUGIN)
    return [os.path.join(HERE, "..", "..", "build", "lib", plugins),
            os.path.join(HERE, "..", "..", "..", "lib", plugins),
            os.path.join(HERE, "..", "..", "..", "lib", "*", plugins)]


def load_plugin(explicit):
    if hasattr(simple, "PointCloudBilateralFilter"):
        return "already loaded (PV_PLUGIN_PATH)"
    paths = [explicit] if explicit else []
    for pattern in plugin_candidates():
        paths += glob.glob(os.path.join(pattern, PLUGIN + ".so"))
    for path in paths:
        if os.path.isfile(path):
            # Into paraview.simple's namespace, where an auto-loaded plugin's functions are too;
            # remote=True: under mpirun, every process loads it, not only this one.
            simple.LoadPlugin(path, remote=True, ns=vars(simple))
            return os.path.normpath(path)
    sys.exit(f"error: the {PLUGIN} plugin was not found: give --plugin PATH or set PV_PLUGIN_PATH")


def check_input(path):
    """The project's checks of damaged files (vtkPointCloudFileIO), when its Python package is
    on the path: a damaged PLY, VTP or LAS file is one line here rather than VTK's messages."""
    try:
        from pointcloudbilateral import vtkPointCloudFileIO
    except ImportError:
        return
    problem = vtkPointCloudFileIO.CheckInputFile(path)
    if problem:
        sys.exit(f"error: {problem}")


def check_output(output, input_path):
    """Exits with one line, before anything is read, when `output` is the input file: the raw
    cloud would be replaced by the result."""
    both = os.path.exists(output) and os.path.exists(input_path)
    if both and os.path.samefile(output, input_path):
        sys.exit(f"error: {output}: is the input file; write the result to another file")


def open_cloud(path, oriented_normals):
    if not os.path.isfile(path):
        sys.exit(f"error: {path}: no such file")
    check_input(path)
    if path.endswith((".xyz", ".txt")):
        return simple.PointCloudTextReader(FileName=path, HasNormals=int(oriented_normals))
    reader = simple.OpenDataFile(path)
    if reader is None:
        sys.exit(f"error: {path}: no reader for this file type")
    return reader


def add_filter_arguments(parser, threads_help="0 (default): all cores"):
    """The filter's options, shared with denoise_mpi.py."""
    parser.add_argument("--radius", type=float, default=0.0, help="0 (default): automatic")
    parser.add_argument("--normal-radius", type=float, default=0.0, help="0 (default): automatic")
    parser.add_argument("--iterations", type=int, default=0, help="0 (default): automatic")
    parser.add_argument("--paper", action="store_true",
                        help="the parameters not given follow the paper's heuristic")
    parser.add_argument("--oriented-normals", action="store_true",
                        help="text files carry normals in columns 4-6")
    parser.add_argument("--remove-isolated", action="store_true")
    parser.add_argument("--edge-aware", action="store_true",
                        help="edge-aware mode (beyond the paper): sharper edges under strong noise")
    parser.add_argument("--classes", type=lambda text: [int(c) for c in text.split(",")],
                        default=[], help="filter only the points of these classes, e.g. 2,6 "
                        "(comma-separated); the others keep their exact coordinates")
    parser.add_argument("--class-array", default="Classification",
                        help="the integer point array holding the class (default: "
                        "Classification)")
    parser.add_argument("--threads", type=int, default=0, help=threads_help)
    parser.add_argument("--plugin", help="path of PointCloudBilateral.so")


def make_filter(source, args):
    """The bilateral filter on `source`, with the options of add_filter_arguments."""
    return simple.PointCloudBilateralFilter(
        Input=source,
        Radius=args.radius,
        NormalRadius=args.normal_radius,
        NumberOfIterations=args.iterations,
        AutomaticParameters="Paper" if args.paper else "Measured",
        RemoveIsolatedPoints=int(args.remove_isolated),
        EdgeAware=int(args.edge_aware),
        Classes=args.classes,
        ClassArray=args.class_array,
        NumberOfThreads=args.threads,
    )


def run_filter(source, args):
    """The bilateral filter on `source`, run; exits with a message when it gave no points.
    Returns the filter and its number of output points."""
    bilateral = make_filter(source, args)
    bilateral.UpdatePipeline()
    bilateral.UpdatePropertyInformation()
    points = bilateral.GetDataInformation().GetNumberOfPoints()
    if points == 0:
        sys.exit("error: the filter produced no points (see the messages above)")
    return bilateral, points


def describe_run(bilateral):
    """What the last run measured and used (call UpdatePropertyInformation first)."""
    measured = ""
    if bilateral.PointSpacing > 0:
        measured = (f"measured point spacing {bilateral.PointSpacing:.6g}, noise sigma "
                    f"{bilateral.NoiseSigma:.6g}; ")
    chosen = ""
    if len(bilateral.Classes) > 0:  # the last run's summary ends with the points filtered
        chosen = "; " + str(bilateral.LastRun).split("; ")[-1]
    return (f"{measured}radius {bilateral.RadiusUsed:.6g}, normal radius "
            f"{bilateral.NormalRadiusUsed:.6g}, {bilateral.NumberOfIterationsUsed} "
            f"iteration(s){chosen}")


def main():
    parser = argparse.ArgumentParser(description="Denoise a point cloud with the bilateral filter.")
    parser.add_argument("input")
    parser.add_argument("output")
    add_filter_arguments(parser)
    args = parser.parse_args()
    check_output(args.output, args.input)

    where = load_plugin(args.plugin)
    reader = open_cloud(args.input, args.oriented_normals)
    reader.UpdatePipeline()
    bilateral, points = run_filter(reader, args)
    if args.output.endswith((".xyz", ".txt")):
        simple.SaveData(args.output, proxy=bilateral, WriteNormals=int(args.oriented_normals))
    else:
        simple.SaveData(args.output, proxy=bilateral)
    print(f"plugin: {where}")
    print(f"{describe_run(bilateral)}: {points} points written to {args.output}")


if __name__ == "__main__":
    main()

"""A VTK pipeline in Python: reader, bilateral filter, writer.

    PYTHONPATH=<build>/lib/python3/dist-packages \
        /usr/bin/python3 Examples/Python/vtk_pipeline.py Data/cube_noise0.5.ply cube.vtp --radius 0.06

Reads .ply, .vtp or the authors' text format (.xyz, .txt), filters, and writes a .vtp file
with every point array of the input.
"""
import argparse
import sys

from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter

from pointcloudbilateral import vtkPointCloudBilateralFilter, vtkPointCloudTextReader


def make_reader(path):
    if path.endswith(".ply"):
        reader = vtkPLYReader()
    elif path.endswith(".vtp"):
        reader = vtkXMLPolyDataReader()
    else:
        reader = vtkPointCloudTextReader()
    reader.SetFileName(path)
    return reader


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("input")
    parser.add_argument("output", help="a .vtp file")
    parser.add_argument("--radius", type=float, default=0.0, help="0: automatic")
    parser.add_argument("--normal-radius", type=float, default=0.0, help="0: same as the radius")
    parser.add_argument("--iterations", type=int, default=1)
    args = parser.parse_args()

    reader = make_reader(args.input)
    bilateral = vtkPointCloudBilateralFilter()
    bilateral.SetInputConnection(reader.GetOutputPort())
    bilateral.SetRadius(args.radius)
    bilateral.SetNormalRadius(args.normal_radius)
    bilateral.SetNumberOfIterations(args.iterations)
    bilateral.GenerateDisplacementLengthOn()
    writer = vtkXMLPolyDataWriter()
    writer.SetInputConnection(bilateral.GetOutputPort())
    writer.SetFileName(args.output)
    if writer.Write() != 1:
        sys.exit(f"error: {args.output} was not written")
    moved = bilateral.GetOutput().GetPointData().GetArray("DisplacementLength").GetRange()
    print(f"{bilateral.GetOutput().GetNumberOfPoints()} points, radius {bilateral.GetRadiusUsed():.6g}, "
          f"normal radius {bilateral.GetNormalRadiusUsed():.6g}, largest move {moved[1]:.3g}")


if __name__ == "__main__":
    main()

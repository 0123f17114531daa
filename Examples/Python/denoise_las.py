"""Denoise a LiDAR survey (an uncompressed LAS file) with the bilateral filter, in pvpython.

    pvpython denoise_las.py IN.las OUT.las [--radius R] [--normal-radius RN] [--iterations N]
                                           [--paper]

The output keeps the input's point format, scales, offsets, coordinate system and every
per-point field (classification, GPS time, colours...): only the coordinates change, so the
tools that made the survey read the result. The filter's options are those of denoise.py.
For example, with the project's shared sample data:

    pvpython denoise_las.py ../shared/data/las/autzen_trim.las autzen_denoised.las
"""
import argparse
import os
import sys

from paraview import simple

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from denoise import (  # noqa: E402
    add_filter_arguments, check_output, describe_run, load_plugin, run_filter)


def main():
    parser = argparse.ArgumentParser(description="Denoise a LAS point cloud.")
    parser.add_argument("input", help="an uncompressed .las file")
    parser.add_argument("output", help="the .las file to write")
    add_filter_arguments(parser)
    args = parser.parse_args()
    if not args.output.lower().endswith(".las"):
        sys.exit(f"error: {args.output}: the output must be a .las file")
    check_output(args.output, args.input)

    where = load_plugin(args.plugin)
    if not os.path.isfile(args.input):
        sys.exit(f"error: {args.input}: no such file")
    reader = simple.LASPointCloudReader(FileName=args.input)
    reader.UpdatePipeline()
    count = reader.GetDataInformation().GetNumberOfPoints()
    if count == 0:
        sys.exit(f"error: {args.input}: no points read (see the message above)")
    bilateral, points = run_filter(reader, args)
    # The LAS writer takes the point format, scales, offsets and records of the file read from
    # the field data the reader left, which the filter passes on.
    simple.SaveData(args.output, proxy=bilateral)
    print(f"plugin: {where}")
    print(f"{describe_run(bilateral)}: {points} points written to {args.output}")


if __name__ == "__main__":
    main()

"""pcbilateral --memory-limit with --edge-aware, --remove-isolated and -R, and LAS into text and
PCD (issue 27, item 3):
the file filtered in slabs gives the same output file, byte for byte, as the run in memory.

Cases: a generated survey whose density varies, with outliers, shuffled, as LAS and as text;
--edge-aware with explicit parameters (one iteration, where the halo of N^2 radii that the
paper's filter takes would be too narrow, and two) and automatic ones (a long strip, so that the
automatic radius leaves room for several slabs); --remove-isolated (the LAS header's count, LAZ
output, text), with both; -R (normals in columns 4-6, with and without a header line, and the
in-memory error for a line without them); LAS into text and into PCD (the columns or fields,
16-bit and 8-bit RGB, the warning; F4 coordinates). PCB_STREAMING_SLAB_POINTS forces several slabs.

    CheckStreamingOptions.py PCBILATERAL SCRATCH
"""
import os
import re
import struct
import sys

import numpy as np

from CheckStreaming import Checks, survey, write_las, write_text

EXPLICIT = ["-r", "1.2", "-n", "0.1"]


def same_lines(c, name, source, parameters, slab_points, extension, pattern):
    """Beyond the bytes: the lines `pattern` matches are said as in memory."""
    in_memory = c.run([source, os.path.join(c.scratch, "lines-memory" + extension)] + parameters)
    streamed = c.run([source, os.path.join(c.scratch, "lines-streamed" + extension),
                      "--memory-limit", "1G"] + parameters, slab_points)
    said = [re.findall(pattern, run.stdout, re.MULTILINE) for run in (in_memory, streamed)]
    c.check(said[0] and said[0] == said[1], f"{name}: says {said[1]} as in memory ({said[0]})")
    c.check(in_memory.stderr == streamed.stderr,
            f"{name}: warns {streamed.stderr!r} as in memory ({in_memory.stderr!r})")


def check_edge_aware(c, las, text):
    for name, source, parameters, slabs in (
            ("edge-aware-1", las, EXPLICIT + ["-N", "1"], [0, 8000, 5000]),
            ("edge-aware-2", las, EXPLICIT + ["-N", "2"], [14000, 11000]),
            ("edge-aware-text", text, EXPLICIT + ["-N", "2"], [12000])):
        out = c.same_as_in_memory(name, source, parameters + ["--edge-aware"], slabs)
        c.check("mode:          edge-aware" in out, f"{name}: the edge-aware mode said")
    # Automatic parameters on a long strip (uniform density: one radius), shuffled.
    rng = np.random.default_rng(11)
    count = 30000
    x, y = rng.random(count) * 300.0, rng.random(count)
    z = 0.5 * np.sin(x / 7.0) + np.where(x % 40 < 20, 0.3, 0.0) + rng.normal(0, 0.01, count)
    strip = os.path.join(c.scratch, "strip.las")
    write_las(strip, np.column_stack([x, y, z]))
    c.same_as_in_memory("edge-aware-automatic", strip, ["--edge-aware"], [16000, 12000],
                        expect="automatic")


def check_remove_isolated(c, las, text):
    for name, source, parameters, slabs, extension, range_points in (
            ("isolated-explicit", las, EXPLICIT + ["-N", "2"], [0, 8000], None, None),
            ("isolated-automatic", las, [], [8000], None, None),
            ("isolated-laz", las, EXPLICIT + ["-N", "2"], [8000], ".laz", 7000),
            ("isolated-text", text, EXPLICIT + ["-N", "2"], [8000], None, None),
            ("isolated-edge-aware", las, EXPLICIT + ["-N", "1", "--edge-aware"], [8000], None,
             None)):
        c.same_as_in_memory(name, source, parameters + ["--remove-isolated"], slabs,
                            extension=extension, range_points=range_points)
    same_lines(c, "isolated", las, EXPLICIT + ["-N", "2", "--remove-isolated"], 8000, ".las",
               r"^(?:removed|output): .*?(\d+) (?:isolated )?points$")


def write_normals(path, points, header):
    """x y z nx ny nz and a class, the normals' signs alternating (oriented)."""
    with open(path, "w") as stream:
        if header:
            stream.write("x y z nx ny nz class\n")
        for i, p in enumerate(points):
            sign = 1 if i % 2 else -1
            stream.write(f"{p[0]:.6f} {p[1]:.6f} {p[2]:.6f} {0.012345679 * sign:.9f} 0.000 "
                         f"{0.99992 * sign:.5f} {i % 7}\n")


def check_oriented_normals(c, points):
    order = np.random.default_rng(13).permutation(len(points))
    for header in (False, True):
        path = os.path.join(c.scratch, f"normals-{header}.xyz")
        write_normals(path, points[order], header)
        c.same_as_in_memory(f"normals-header-{header}", path, EXPLICIT + ["-N", "2", "-R"],
                            [0, 8000])
    short = os.path.join(c.scratch, "no-normals.xyz")
    write_text(short, points[:100], False, " ")
    output = os.path.join(c.scratch, "no-normals-out.xyz")
    in_memory = c.run([short, output, "-R"])
    streamed = c.run([short, output, "-R", "--memory-limit", "1G"])
    c.check(streamed.returncode != 0 and streamed.stderr == in_memory.stderr and
            "nx ny nz" in streamed.stderr and not os.path.exists(output) and
            not c.temporary_left(),
            f"-R on a file without normals: the in-memory error ({streamed.stderr.strip()})")


def write_las_rgb(path, points, colours):
    """A LAS 1.2 file of point format 2 (format 0 and RGB), records in the order given."""
    write_las(path, points)
    with open(path, "rb") as stream:
        data = bytearray(stream.read())
    header, records = data[:227], np.frombuffer(bytes(data[227:]), dtype=np.uint8)
    records = records.reshape(len(points), 20)
    rgb = np.ascontiguousarray(colours.astype("<u2")).view(np.uint8).reshape(len(points), 6)
    header[104] = 2  # point format
    header[105:107] = (26).to_bytes(2, "little")  # record length
    with open(path, "wb") as stream:
        stream.write(bytes(header) + np.hstack([records, rgb]).tobytes())


def check_las_into(c, las, points, extension):
    """LAS into text or PCD: the columns or fields, header and warning of the run in memory; RGB
    as 16-bit and as 8-bit values (the display colours are the high bytes or the values)."""
    kind = extension[1:]
    for name, parameters, slabs in (("explicit", EXPLICIT + ["-N", "2"], [0, 8000]),
                                    ("automatic", [], [8000]),
                                    ("isolated", EXPLICIT + ["--remove-isolated"], [8000])):
        c.same_as_in_memory(f"into-{kind}-{name}", las, parameters, slabs, extension=extension,
                            range_points=7777)
    rng = np.random.default_rng(19)
    order = rng.permutation(len(points))
    for bits, top in ((16, 65536), (8, 256)):
        path = os.path.join(c.scratch, f"rgb{bits}.las")
        write_las_rgb(path, points[order], rng.integers(0, top, (len(points), 3)))
        c.same_as_in_memory(f"rgb{bits}-into-{kind}", path, EXPLICIT + ["-N", "2"], [8000],
                            extension=extension)
    runs = [c.run([las, os.path.join(c.scratch, f"warned-{k}{extension}"), "-r", "1.2"] +
                  (["--memory-limit", "1G"] if k == "streamed" else []))
            for k in ("memory", "streamed")]
    c.check(runs[1].returncode == 0 and "cannot hold the LAS file's scale" in runs[1].stderr and
            runs[1].stderr.replace("streamed", "memory") == runs[0].stderr,
            f"LAS into {kind}: the warning of the run in memory ({runs[1].stderr.strip()})")


def check_las_into_pcd(c, las, points):
    """LAS into PCD, and x y z as F4 when every position written is a float (coordinates on a
    grid of 0.5, a radius with no neighbours: nothing moves); --classes into PCD."""
    check_las_into(c, las, points, ".pcd")
    on_grid = os.path.join(c.scratch, "half-grid.las")
    write_las(on_grid, points)
    with open(on_grid, "r+b") as stream:
        stream.seek(131)
        stream.write(struct.pack("<3d", 0.5, 0.5, 0.5))
    c.same_as_in_memory("floats-into-pcd", on_grid, ["-r", "0.1", "-N", "1"], [8000],
                        extension=".pcd")
    with open(os.path.join(c.scratch, "floats-into-pcd-memory.pcd"), "rb") as stream:
        head = stream.read(400)
    c.check(b"SIZE 4 4 4 " in head, "positions that are floats: x y z written as F4")
    # (--classes into PCD is streamed: CheckStreamingClasses.py.)
    c.same_as_in_memory("classes-into-pcd", las, ["--classes", "2", "-r", "1.2", "-N", "2"],
                        [8000], extension=".pcd")


def check_damaged(c, las):
    """A LAS file cut short, into each output streamed: one line, non-zero exit, no output, no
    temporary file."""
    cut = os.path.join(c.scratch, "cut.las")
    with open(las, "rb") as stream:
        data = stream.read()
    with open(cut, "wb") as stream:
        stream.write(data[:len(data) * 2 // 3])
    for extension in (".las", ".laz", ".xyz", ".pcd"):
        output = os.path.join(c.scratch, "cut-out" + extension)
        result = c.run([cut, output, "-r", "1.2", "--edge-aware", "--remove-isolated",
                        "--memory-limit", "1G"], 8000)
        c.check(result.returncode != 0 and len(result.stderr.strip().splitlines()) == 1 and
                not os.path.exists(output) and not c.temporary_left(),
                f"a LAS file cut short into {extension}: one line, no output, no temporary file "
                f"({result.stderr.strip()})")


def main(program, scratch):
    os.makedirs(scratch, exist_ok=True)
    c = Checks(program, scratch)
    points = survey(20000, 9)
    rng = np.random.default_rng(17)
    outliers = np.column_stack([rng.random(40) * 240.0, rng.random(40) * 12.0,
                                5.0 + rng.random(40) * 20.0])
    cloud = np.vstack([points, outliers])
    las = os.path.join(scratch, "outliers-shuffled.las")
    write_las(las, cloud[rng.permutation(len(cloud))])
    text = os.path.join(scratch, "outliers-shuffled.xyz")
    write_text(text, cloud[rng.permutation(len(cloud))], True, " ")
    check_edge_aware(c, las, text)
    check_remove_isolated(c, las, text)
    check_oriented_normals(c, points)
    check_las_into(c, las, points, ".xyz")
    check_las_into_pcd(c, las, points)
    check_damaged(c, las)
    return 1 if c.failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))

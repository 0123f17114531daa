"""pcbilateral --copc-level and --copc-bounds on PDAL's COPC sample
(shared/data/laz/1.2-with-color.copc.laz, 1,065 points of format 7 in an octree of 4 levels;
its twin shared/data/las/1.2-with-color.las holds the same points, format 3, another order).
The filter moves only the coordinates: the points written are known by their other fields.
- --copc-level 1: the 90 points of levels 0 and 1 (24 + 66, IO.TestCOPC.levels), every field
  of the records kept (format 7, the twin's intensity, GPS time and colour);
- --copc-bounds: exactly the twin's points inside the box (found by testing every point);
- on a file that is not COPC: one warning, and every point is read;
- a box that is not six numbers, a level below -1: one-line errors, exit status 1, no output.

    CheckCOPC.py PCBILATERAL LAS_FOLDER SCRATCH
"""
import collections
import os
import struct
import subprocess
import sys


def points(path):
    """The points of an uncompressed LAS file as (x, y, z, intensity, gps time, r, g, b)."""
    data = open(path, "rb").read()
    offset, = struct.unpack_from("<I", data, 96)
    point_format = data[104] & 0x3F
    length, = struct.unpack_from("<H", data, 105)
    count, = struct.unpack_from("<I", data, 107)
    if data[25] >= 4 and count == 0:
        count, = struct.unpack_from("<Q", data, 247)
    scale = struct.unpack_from("<3d", data, 131)
    shift = struct.unpack_from("<3d", data, 155)
    time_at, rgb_at = (22, 30) if point_format >= 6 else (20, 28)
    result = []
    for i in range(count):
        at = offset + i * length
        xyz = struct.unpack_from("<3i", data, at)
        real = tuple(round(xyz[a] * scale[a] + shift[a], 2) for a in range(3))
        intensity, = struct.unpack_from("<H", data, at + 12)
        time, = struct.unpack_from("<d", data, at + time_at)
        rgb = struct.unpack_from("<3H", data, at + rgb_at)
        result.append(real + (intensity, time) + rgb)
    return point_format, result


def run(program, arguments):
    return subprocess.run([program] + arguments + ["-N", "1"], capture_output=True, text=True)


def fields(cloud):
    """What the filter does not change: intensity, GPS time and colour."""
    return collections.Counter(p[3:] for p in cloud)


def main(program, folder, scratch):
    os.makedirs(scratch, exist_ok=True)
    copc = os.path.join(folder, "..", "laz", "1.2-with-color.copc.laz")
    twin_path = os.path.join(folder, "1.2-with-color.las")
    _, twin = points(twin_path)
    failures = []

    output = os.path.join(scratch, "level1.las")
    done = run(program, [copc, output, "--copc-level", "1"])
    if done.returncode != 0:
        failures.append("--copc-level 1: " + done.stderr.strip())
    else:
        point_format, read = points(output)
        extra = fields(read) - fields(twin)
        if point_format != 7 or len(read) != 90 or extra:
            failures.append("--copc-level 1: format %d, %d points (90 expected), %d not the "
                            "twin's" % (point_format, len(read), sum(extra.values())))

    box = (637000.0, 638200.5, 850000.0, 852500.0, 420.0, 560.0)
    output = os.path.join(scratch, "box.las")
    done = run(program, [copc, output, "--copc-bounds", ",".join(str(v) for v in box)])
    inside = [p for p in twin
              if all(box[2 * a] <= p[a] <= box[2 * a + 1] for a in range(3))]
    if done.returncode != 0:
        failures.append("--copc-bounds: " + done.stderr.strip())
    else:
        _, read = points(output)
        if fields(read) != fields(inside) or not inside:
            failures.append("--copc-bounds: %d points, the twin has %d inside the box"
                            % (len(read), len(inside)))
    print("box %s: %d points" % (box, len(inside)))

    output = os.path.join(scratch, "not_copc.las")
    done = run(program, [twin_path, output, "--copc-level", "0"])
    warning = "warning: %s: not a COPC file: the COPC level and bounds apply to COPC files only" \
        % twin_path
    if done.returncode != 0 or warning not in done.stderr or len(points(output)[1]) != 1065:
        failures.append("not COPC: exit %d, %s" % (done.returncode, done.stderr.strip()))

    for arguments, said in (
            (["--copc-bounds", "1,2,3"], "--copc-bounds: '1,2,3' is not six numbers"),
            (["--copc-bounds", "1,0,0,1,0,1"], "with each min <= max"),
            (["--copc-level", "-2"], "--copc-level: '-2' is not a level")):
        output = os.path.join(scratch, "refused.las")
        done = run(program, [copc, output] + arguments)
        lines = done.stderr.splitlines()
        if (done.returncode != 1 or len(lines) != 1 or said not in lines[0]
                or os.path.exists(output)):
            failures.append("%s: exit %d, %r" % (arguments, done.returncode, done.stderr))

    for failure in failures:
        print("FAILED: " + failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))

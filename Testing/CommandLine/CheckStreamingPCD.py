"""pcbilateral --memory-limit with PCD input (issue 27, item 3): a PCD file (ascii or binary)
filtered in slabs into PCD gives the same file, byte for byte, as the run in memory (its fields,
WIDTH, HEIGHT and VIEWPOINT, packed rgb unpacked and packed again, normals gathered and
scattered, padding as zeros, the points without coordinates of an organised frame dropped);
binary_compressed input is decompressed whole; a damaged file gives the run in memory's
one-line error, no output and no temporary file.

Cases: a generated survey as an organised frame with NaN pixels (F4 and F8 coordinates, normals,
rgb, padding, a U2 and an I8 x 2 field), ascii and binary, in spatial and random order, explicit
and automatic parameters, several slab sizes, --remove-isolated; given the shared PCD folder,
instead: face_model.pcd (binary), lamppost.pcd and object_template_0.pcd (ascii, padding), and
binary_compressed files (decompressed whole): milk.pcd (rgba), region_growing_tutorial.pcd (rgb),
capture0001.pcd (an organised frame with NaN pixels, with --remove-isolated),
samp21_utm_ground.pcd, and milk.pcd cut short or damaged (the run in memory's error).

    CheckStreamingPCD.py PCBILATERAL SCRATCH [PCD_DATA_DIR]
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from CheckStreaming import Checks, survey  # noqa: E402

FIELDS = [("x", "F", 4, 1), ("y", "F", 4, 1), ("z", "F", 4, 1), ("normal_x", "F", 4, 1),
          ("normal_y", "F", 4, 1), ("normal_z", "F", 4, 1), ("rgb", "F", 4, 1),
          ("_", "U", 1, 4), ("intensity", "U", 2, 1), ("pair", "I", 8, 2)]
NUMPY = {("F", 4): "<f4", ("F", 8): "<f8", ("U", 1): "u1", ("U", 2): "<u2", ("I", 8): "<i8"}


def write_pcd(path, points, encoding, width, height, fields=FIELDS):
    """An organised frame of width x height points (NaN coordinates where a point has none)."""
    count = len(points)
    dtype = [(name, NUMPY[(kind, size)], (n,)) for name, kind, size, n in fields]
    records = np.zeros(count, dtype=dtype)
    for axis, name in enumerate("xyz"):
        records[name][:, 0] = points[:, axis]
    rng = np.random.default_rng(5)
    names = [f[0] for f in fields]
    if "normal_x" in names:
        normals = rng.normal(size=(count, 3))
        normals /= np.linalg.norm(normals, axis=1)[:, None]
        for axis, name in enumerate(("normal_x", "normal_y", "normal_z")):
            records[name][:, 0] = normals[:, axis]
        # Alpha bytes other than 255: the run in memory writes rgb's alpha as 255.
        packed = rng.integers(0, 2**32, count, dtype=np.uint64).astype(np.uint32) & 0x7F7FFFFF
        records["rgb"][:, 0] = packed.view("<f4")
        records["_"] = 7
        records["intensity"][:, 0] = np.arange(count) % 65536
        records["pair"][:, 0] = np.arange(count) * 3
        records["pair"][:, 1] = -np.arange(count)
    header = ("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"
              f"FIELDS {' '.join(names)}\nSIZE {' '.join(str(f[2]) for f in fields)}\n"
              f"TYPE {' '.join(f[1] for f in fields)}\nCOUNT {' '.join(str(f[3]) for f in fields)}\n"
              f"WIDTH {width}\nHEIGHT {height}\nVIEWPOINT 1 2 3 1 0 0 0\nPOINTS {count}\n"
              f"DATA {encoding}\n")
    with open(path, "wb") as stream:
        stream.write(header.encode())
        if encoding == "binary":
            stream.write(records.tobytes())
            return
        for record in records:
            values = []
            for name, kind, size, n in fields:
                for value in np.atleast_1d(record[name]):
                    if name == "rgb":
                        values.append(str(int(np.float32(value).view(np.uint32))))
                    elif kind == "F":
                        values.append(repr(float(value)))
                    else:
                        values.append(str(int(value)))
            stream.write((" ".join(values) + "\n").encode())


def frame(seed, shuffled):
    """The survey of 20,000 points as a 200 x 100 frame, 5% of its pixels without a point."""
    points = survey(20000, seed)
    rng = np.random.default_rng(seed)
    if shuffled:
        points = points[rng.permutation(len(points))]
    points[rng.random(len(points)) < 0.05] = np.nan
    return points


def check_refused_and_damaged(c, binary, ascii_file):
    output = os.path.join(c.scratch, "refused.pcd")
    # (--keep-nan and PCD into LAS or text are streamed: CheckStreamingFormats.py.)
    # (--classes and the --copc options are streamed: CheckStreamingClasses.py,
    # CheckStreamingCOPC.py.)
    for arguments, words in (([binary, os.path.join(c.scratch, "o.ply")], "not yet PLY"),):
        result = c.run(arguments + ["--memory-limit", "1G", "-r", "1"])
        c.check(result.returncode == 1 and words in result.stderr and
                len(result.stderr.strip().splitlines()) == 1 and not os.path.exists(output),
                f"refused: {' '.join(arguments[2:])}: {result.stderr.strip()}")
    with open(binary, "rb") as stream:
        whole = stream.read()
    with open(ascii_file, "rb") as stream:
        text = stream.read()
    lines = text.split(b"\n")
    bad_value = lines[:3000] + [lines[3000].replace(b" ", b" x", 1)] + lines[3001:]
    for name, data in (("binary-cut", whole[:-1000]), ("ascii-cut", b"\n".join(lines[:-500])),
                       ("ascii-bad-value", b"\n".join(bad_value)),
                       ("ascii-more-lines", text + lines[20] + b"\n")):
        damaged = os.path.join(c.scratch, name + ".pcd")
        with open(damaged, "wb") as stream:
            stream.write(data)
        memory = c.run([damaged, output, "-r", "1"])
        streamed = c.run([damaged, output, "-r", "1", "--memory-limit", "1G"], 5000)
        c.check(memory.returncode == 1 and streamed.returncode == 1 and
                streamed.stderr == memory.stderr and len(streamed.stderr.splitlines()) == 1 and
                not os.path.exists(output) and not c.temporary_left(),
                f"{name}: the run in memory's error, no output, no temporary file "
                f"({streamed.stderr.strip()} / {memory.stderr.strip()})")


def main(program, scratch, pcd_dir=None):
    os.makedirs(scratch, exist_ok=True)
    c = Checks(program, scratch)
    if pcd_dir:
        c.same_as_in_memory("face-model", os.path.join(pcd_dir, "face_model.pcd"), [],
                            [0, 40000])
        c.same_as_in_memory("lamppost", os.path.join(pcd_dir, "lamppost.pcd"), [], [0, 1000])
        c.same_as_in_memory("object-template", os.path.join(pcd_dir, "object_template_0.pcd"),
                            [], [0])
        # binary_compressed: rgba (milk), rgb in a float's bits (region growing), an organised
        # frame with NaN pixels (capture0001), UTM coordinates as floats (samp21).
        c.same_as_in_memory("milk", os.path.join(pcd_dir, "milk.pcd"), [], [0, 8000],
                            range_points=3000)
        c.same_as_in_memory("region-growing", os.path.join(pcd_dir,
                                                           "region_growing_tutorial.pcd"),
                            ["-r", "0.05", "-N", "2"], [0, 40000], range_points=30000)
        stdout = c.same_as_in_memory("capture", os.path.join(pcd_dir, "capture0001.pcd"),
                                     ["-r", "0.02", "-N", "2", "--remove-isolated"], [0, 80000])
        c.check("dropped" in stdout, "capture: the points without coordinates said dropped")
        c.same_as_in_memory("samp21", os.path.join(pcd_dir, "samp21_utm_ground.pcd"), [],
                            [0, 5000])
        with open(os.path.join(pcd_dir, "milk.pcd"), "rb") as stream:
            milk = stream.read()
        output = os.path.join(scratch, "damaged-out.pcd")
        if os.path.exists(output):
            os.remove(output)  # (an earlier run's)
        sizes = milk.index(b"DATA binary_compressed\n") + len("DATA binary_compressed\n")
        for name, data in (("milk-cut", milk[:len(milk) // 2]),
                           ("milk-wrong-size", milk[:sizes + 4] + b"\x10\0\0\0" + milk[sizes + 8:])):
            damaged = os.path.join(scratch, name + ".pcd")
            with open(damaged, "wb") as stream:
                stream.write(data)
            memory = c.run([damaged, output, "-r", "0.01"])
            streamed = c.run([damaged, output, "-r", "0.01", "--memory-limit", "1G"])
            c.check(memory.returncode == 1 and streamed.returncode == 1 and
                    streamed.stderr == memory.stderr and not os.path.exists(output) and
                    not c.temporary_left(),
                    f"{name}: the run in memory's error, no output, no temporary file "
                    f"({streamed.stderr.strip()} / {memory.stderr.strip()})")
        return 1 if c.failures else 0
    files = {}
    for order in ("ordered", "shuffled"):
        points = frame(11, order == "shuffled")
        for encoding in ("binary", "ascii"):
            path = os.path.join(scratch, f"{order}-{encoding}.pcd")
            write_pcd(path, points, encoding, 200, 100)
            files[(order, encoding)] = path
    for (order, encoding), path in files.items():
        name = f"{order}-{encoding}"
        stdout = c.same_as_in_memory(name + "-explicit", path,
                                     ["-r", "1.2", "-n", "0.1", "-N", "2"], [0, 9000, 6000],
                                     range_points=7000)
        c.check("dropped" in stdout, f"{name}: the points without coordinates said dropped")
        c.same_as_in_memory(name + "-automatic", path, [], [0, 12000], range_points=5000)
    c.same_as_in_memory("remove-isolated", files[("shuffled", "binary")],
                        ["-r", "0.3", "-N", "2", "--remove-isolated"], [6000])
    doubles = os.path.join(scratch, "doubles.pcd")
    # No point without coordinates: the frame's WIDTH and HEIGHT are kept.
    write_pcd(doubles, survey(20000, 3)[np.random.default_rng(3).permutation(20000)] + 1e5,
              "ascii", 200, 100,
              [("x", "F", 8, 1), ("y", "F", 8, 1), ("z", "F", 8, 1)])
    c.same_as_in_memory("doubles", doubles, ["-r", "1.2", "-N", "2"], [7000])
    check_refused_and_damaged(c, files[("shuffled", "binary")], files[("shuffled", "ascii")])
    return 1 if c.failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))

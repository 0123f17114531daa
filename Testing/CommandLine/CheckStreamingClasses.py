"""pcbilateral --memory-limit with --classes for every input and output the run in memory takes:
LAS into PCD, and PCD input (an integer field as the class array; ascii, binary and
binary_compressed) into PCD, LAS, LAZ and text, each filtered in slabs, give the same file, byte
for byte, the same warnings and the same `classes:` line as the run in memory, or its error and
no output.

Cases: a shuffled survey of two classes (2 on the terrain's ridges, 6 elsewhere) with outliers of
class 6 beyond the chosen points' extent (so that the points left alone decide a LAS output's
bounds, its scale and offset), several slab sizes and ranges that cut the files' checkpoints;
explicit and automatic parameters; --remove-isolated, --keep-nan; a LAS file whose chosen points
are floats and whose other points are not (the PCD output's x y z are F8 only because of the
points left alone); the errors (no such array, a float array, several components, the packed
colours and the normals the reader makes), and the warning when no point is chosen.

    CheckStreamingClasses.py PCBILATERAL SCRATCH
"""
import os
import re
import struct
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from CheckStreaming import Checks, survey, write_las  # noqa: E402

# x y z, normals, packed rgb, a U1 class, a float, two 64-bit integers, a signed class.
PCD_FIELDS = [("x", "F", 8, 1), ("y", "F", 8, 1), ("z", "F", 8, 1), ("normal_x", "F", 4, 1),
              ("normal_y", "F", 4, 1), ("normal_z", "F", 4, 1), ("rgb", "F", 4, 1),
              ("label", "U", 1, 1), ("weight", "F", 4, 1), ("pair", "I", 8, 2),
              ("code", "I", 4, 1)]
NUMPY = {("F", 4): "<f4", ("F", 8): "<f8", ("U", 1): "u1", ("I", 4): "<i4", ("I", 8): "<i8"}


def lzf_literals(data):
    """An LZF stream of literal runs only (valid LZF, a little larger than its data)."""
    out = bytearray()
    for start in range(0, len(data), 32):
        chunk = data[start:start + 32]
        out.append(len(chunk) - 1)
        out += chunk
    return bytes(out)


def write_pcd(path, points, labels, encoding):
    count = len(points)
    records = np.zeros(count, dtype=[(n, NUMPY[(t, s)], (k,)) for n, t, s, k in PCD_FIELDS])
    rng = np.random.default_rng(3)
    for axis, name in enumerate("xyz"):
        records[name][:, 0] = points[:, axis]
    normals = rng.normal(size=(count, 3))
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    for axis, name in enumerate(("normal_x", "normal_y", "normal_z")):
        records[name][:, 0] = normals[:, axis]
    records["rgb"][:, 0] = (rng.integers(0, 2**24, count).astype(np.uint32) |
                            np.uint32(0xFF000000)).view("<f4")
    records["label"][:, 0] = labels
    records["weight"][:, 0] = rng.random(count)
    records["pair"][:, 0] = np.arange(count)
    records["pair"][:, 1] = -np.arange(count)
    records["code"][:, 0] = np.where(labels == 2, -3, 5)
    header = ("VERSION 0.7\n"
              f"FIELDS {' '.join(f[0] for f in PCD_FIELDS)}\n"
              f"SIZE {' '.join(str(f[2]) for f in PCD_FIELDS)}\n"
              f"TYPE {' '.join(f[1] for f in PCD_FIELDS)}\n"
              f"COUNT {' '.join(str(f[3]) for f in PCD_FIELDS)}\n"
              f"WIDTH {count}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {count}\n"
              f"DATA {encoding}\n")
    with open(path, "wb") as stream:
        stream.write(header.encode())
        if encoding == "binary":
            stream.write(records.tobytes())
        elif encoding == "binary_compressed":
            fields = b"".join(np.ascontiguousarray(records[f[0]]).tobytes() for f in PCD_FIELDS)
            compressed = lzf_literals(fields)
            stream.write(struct.pack("<II", len(compressed), len(fields)) + compressed)
        else:
            for record in records:
                values = []
                for name, kind, _, _ in PCD_FIELDS:
                    for value in np.atleast_1d(record[name]):
                        if name == "rgb":
                            values.append(str(int(np.float32(value).view(np.uint32))))
                        else:
                            values.append(repr(float(value)) if kind == "F" else str(int(value)))
                stream.write((" ".join(values) + "\n").encode())


def classified_survey(seed, nan_fraction=0.0):
    """The survey, shuffled, with 40 outliers of class 6 beyond its extent in x and z; class 2
    where the terrain is above 0.3 (its ridges), 6 elsewhere."""
    rng = np.random.default_rng(seed)
    points = survey(20000, seed)
    outliers = np.column_stack([-30.0 - rng.random(40) * 20.0, rng.random(40) * 12.0,
                                8.0 + rng.random(40) * 5.0])
    cloud = np.vstack([points, outliers])
    labels = np.where(cloud[:, 2] > 0.3, 2, 6).astype(np.uint8)
    labels[len(points):] = 6
    order = rng.permutation(len(cloud))
    cloud, labels = cloud[order], labels[order]
    cloud[rng.random(len(cloud)) < nan_fraction] = np.nan
    return cloud, labels


def classes_line(stdout):
    return re.findall(r"^classes: .*$", stdout, re.MULTILINE)


def same_as_in_memory(c, name, source, extension, parameters, slab_sizes, range_points=7777,
                      classes=True):
    """The streamed outputs against the run in memory's: the same bytes (or the same one-line
    error and no output), the same standard error and (`classes`) the same `classes:` line."""
    in_memory, memory, streamed_runs = c.memory_and_streamed(name, source, extension, parameters,
                                                             slab_sizes, range_points)
    for slab_points, streamed, result in streamed_runs:
        slabs = [line for line in result.stdout.splitlines() if "along" in line]
        same_stderr = result.stderr.replace(streamed, in_memory) == memory.stderr
        if memory.returncode != 0:
            ok = (result.returncode == memory.returncode and same_stderr and
                  result.stderr.count("error:") == 1 and not os.path.exists(streamed))
            what = "the run in memory's error, no output"
        else:
            ok = (result.returncode == 0 and os.path.exists(streamed) and
                  c.read(streamed) == c.read(in_memory) and same_stderr and
                  classes_line(result.stdout) == classes_line(memory.stdout) and
                  len(classes_line(memory.stdout)) == (1 if classes else 0))
            what = f"the same bytes, warnings and classes line as in memory {slabs}"
        c.check(ok and not c.temporary_left(),
                f"{name}, slabs of at most {slab_points} points: {what} "
                f"({classes_line(result.stdout)} {result.stderr.strip()} / "
                f"{memory.stderr.strip()})")
    return memory


def check_las_into_pcd(c):
    cloud, labels = classified_survey(21)
    las = os.path.join(c.scratch, "classes.las")
    write_las(las, cloud, labels)
    explicit = ["--classes", "2", "-r", "1.2", "-n", "0.1", "-N", "2"]
    same_as_in_memory(c, "las-pcd", las, ".pcd", explicit, [0, 8000, 3000])
    same_as_in_memory(c, "las-pcd-automatic", las, ".pcd", ["--classes", "6"], [0, 9000])
    same_as_in_memory(c, "las-pcd-isolated", las, ".pcd", explicit + ["--remove-isolated"],
                      [5000])
    same_as_in_memory(c, "las-pcd-intensity", las, ".pcd",
                      ["--classes", ",".join(map(str, range(0, 20000, 3))), "--class-array",
                       "Intensity", "-r", "1.2", "-N", "1"], [6000])
    same_as_in_memory(c, "las-pcd-none", las, ".pcd", ["--classes", "17", "-r", "1"], [8000])
    # The chosen points on a grid of whole units, floats, the others not: with a radius that
    # reaches no neighbour nothing moves, and only the points left alone make x y z F8.
    grid = np.round(cloud, 2)
    floats_las = os.path.join(c.scratch, "classes-floats.las")
    chosen = labels == 2
    write_las(floats_las, np.where(chosen[:, None], grid, cloud), labels)
    with open(floats_las, "r+b") as stream:
        stream.seek(131)
        stream.write(struct.pack("<3d", 0.1, 0.1, 0.1))
    same_as_in_memory(c, "las-pcd-floats", floats_las, ".pcd",
                      ["--classes", "2", "-r", "0.1", "-N", "1"], [0, 8000])
    with open(os.path.join(c.scratch, "las-pcd-floats-memory.pcd"), "rb") as stream:
        head = stream.read(400)
    c.check(b"SIZE 8 8 8 " in head, "the points left alone are not floats: x y z as F8")
    only = ["--classes", "2", "-r", "0.1", "-N", "1"]
    chosen_only = os.path.join(c.scratch, "classes-floats-only.las")
    write_las(chosen_only, grid[chosen], labels[chosen])
    with open(chosen_only, "r+b") as stream:
        stream.seek(131)
        stream.write(struct.pack("<3d", 0.1, 0.1, 0.1))
    result = c.run([chosen_only, os.path.join(c.scratch, "floats-only.pcd")] + only)
    with open(os.path.join(c.scratch, "floats-only.pcd"), "rb") as stream:
        head = stream.read(400)
    c.check(result.returncode == 0 and b"SIZE 4 4 4 " in head,
            "the chosen points alone are floats (x y z as F4): the case above tests the others")


def check_pcd_input(c):
    cloud, labels = classified_survey(23)
    label = ["--class-array", "label"]
    explicit = ["--classes", "2", "-r", "1.2", "-n", "0.1", "-N", "2"] + label
    files = {}
    for encoding in ("binary", "ascii", "binary_compressed"):
        files[encoding] = os.path.join(c.scratch, f"classes-{encoding}.pcd")
        write_pcd(files[encoding], cloud, labels, encoding)
    for extension in (".pcd", ".las", ".laz", ".txt"):
        same_as_in_memory(c, "pcd-binary" + extension, files["binary"], extension, explicit,
                          [0, 8000, 3000])
    for encoding in ("ascii", "binary_compressed"):
        for extension in (".pcd", ".las"):
            same_as_in_memory(c, f"pcd-{encoding}{extension}", files[encoding], extension,
                              explicit, [8000], range_points=5000)
    binary = files["binary"]
    same_as_in_memory(c, "pcd-automatic", binary, ".pcd", ["--classes", "6"] + label, [0, 9000])
    same_as_in_memory(c, "pcd-automatic.las", binary, ".las", ["--classes", "2"] + label,
                      [7000])
    same_as_in_memory(c, "pcd-code", binary, ".pcd",
                      ["--classes", "-3", "--class-array", "code", "-r", "1.2", "-N", "2"],
                      [6000])
    same_as_in_memory(c, "pcd-isolated", binary, ".las", explicit + ["--remove-isolated"],
                      [5000])
    same_as_in_memory(c, "pcd-none", binary, ".pcd", ["--classes", "17", "-r", "1"] + label,
                      [8000])
    for array in ("weight", "pair", "rgb", "RGB", "Normals", "normal_x", "nope"):
        same_as_in_memory(c, "pcd-error-" + array, binary, ".pcd",
                          ["--classes", "2", "--class-array", array, "-r", "1"], [8000])
    # NaN points: left out, or with --keep-nan kept in place (passed through).
    with_nan, nan_labels = classified_survey(25, nan_fraction=0.05)
    nan_file = os.path.join(c.scratch, "classes-nan.pcd")
    write_pcd(nan_file, with_nan, nan_labels, "binary")
    for extension in (".pcd", ".txt"):
        same_as_in_memory(c, "pcd-nan" + extension, nan_file, extension, explicit, [6000])
        same_as_in_memory(c, "pcd-keep-nan" + extension, nan_file, extension,
                          explicit + ["--keep-nan"], [6000])
    same_as_in_memory(c, "pcd-keep-nan.las", nan_file, ".las", explicit + ["--keep-nan"], [6000])


def main(program, scratch):
    os.makedirs(scratch, exist_ok=True)
    c = Checks(program, scratch)
    check_las_into_pcd(c)
    check_pcd_input(c)
    return 1 if c.failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))

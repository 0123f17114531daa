"""pcbilateral --memory-limit across formats (issue 27, item 3): PCD input into LAS, LAZ and
text, text input into LAS, LAZ and PCD, and --keep-nan, each filtered in slabs, give the same
file, byte for byte, and the same warnings as the run in memory.

Cases: the generated 200 x 100 frame of CheckStreamingPCD.py (NaN pixels, normals, rgb, padding,
a U2 and an I8 x 2 field), binary and ascii, in spatial and random order, into .las, .laz and
.txt (also with -R: the normals as columns 4-6), with --remove-isolated; a text survey with a
header (intensity), shuffled, into .las, .laz and .pcd; a text file whose columns are LAS
dimensions (Intensity, Classification, GpsTime, RGB:0-2: point format 3) into .las and .pcd;
with -R into .pcd; a text file with NaN lines into .pcd and .las; --keep-nan for binary, ascii
and binary_compressed PCD into .pcd, .txt and .las. Several slab sizes and ranges.

    CheckStreamingFormats.py PCBILATERAL SCRATCH
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from CheckStreaming import Checks, survey, write_text  # noqa: E402
from CheckStreamingPCD import frame, write_pcd  # noqa: E402


def warnings(stderr):
    return [line for line in stderr.splitlines() if "warning" in line]


def same_as_in_memory(c, name, source, extension, parameters, slab_sizes, range_points=None):
    """The streamed outputs into `extension` against the run in memory's: the same bytes (or the
    same one-line error, and no output) and the same warnings."""
    in_memory, memory, streamed_runs = c.memory_and_streamed(name, source, extension, parameters,
                                                             slab_sizes, range_points)
    for slab_points, streamed, result in streamed_runs:
        slabs = [line for line in result.stdout.splitlines() if "along" in line]
        if memory.returncode != 0:
            c.check(result.returncode == memory.returncode and
                    result.stderr.replace(streamed, in_memory) == memory.stderr and
                    not os.path.exists(streamed),
                    f"{name}, slabs of {slab_points}: the run in memory's error "
                    f"({result.stderr.strip()} / {memory.stderr.strip()})")
        else:
            c.check(result.returncode == 0 and os.path.exists(streamed) and
                    c.read(streamed) == c.read(in_memory),
                    f"{name}, slabs of at most {slab_points} points ({slabs}): the same bytes "
                    f"as in memory {result.stderr.strip()}")
            said = [w.replace(streamed, in_memory) for w in warnings(result.stderr)]
            c.check(said == warnings(memory.stderr),
                    f"{name}: the same warnings as in memory ({said} / "
                    f"{warnings(memory.stderr)})")
        c.check(not c.temporary_left(), f"{name}: no temporary file left")
    return memory


def write_las_columns(path, points, seed):
    """Text whose columns the LAS writer takes: Intensity (halves), Classification, GpsTime,
    RGB (beyond 65535: clamped)."""
    rng = np.random.default_rng(seed)
    with open(path, "w") as stream:
        stream.write("x y z Intensity Classification GpsTime RGB:0 RGB:1 RGB:2 other\n")
        for i, p in enumerate(points):
            rgb = rng.integers(0, 70000, 3)
            # (Halves: the LAS writer rounds them away from zero.)
            stream.write(f"{p[0]:.6f} {p[1]:.6f} {p[2]:.6f} {i % 300 + 0.5} {i % 7} "
                         f"{1000 + i * 0.5} {rgb[0]} {rgb[1]} {rgb[2]} {rng.normal():.4f}\n")


def write_normals(path, points, seed):
    """x y z nx ny nz and a column, tabs, no header."""
    rng = np.random.default_rng(seed)
    normals = rng.normal(size=points.shape)
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    with open(path, "w") as stream:
        for p, n in zip(points, normals):
            stream.write("\t".join(f"{v:.6f}" for v in list(p) + list(n)) + "\t1.5\n")


def check_pcd_input(c):
    for order in ("ordered", "shuffled"):
        points = frame(11, order == "shuffled")
        for encoding in ("binary", "ascii"):
            path = os.path.join(c.scratch, f"{order}-{encoding}.pcd")
            write_pcd(path, points, encoding, 200, 100)
            explicit = ["-r", "1.2", "-n", "0.1", "-N", "2"]
            for extension in (".las", ".txt") if encoding == "binary" else (".las",):
                same_as_in_memory(c, f"pcd-{order}-{encoding}{extension}", path, extension,
                                  explicit, [0, 9000, 6000], range_points=7000)
    shuffled = os.path.join(c.scratch, "shuffled-binary.pcd")
    same_as_in_memory(c, "pcd-laz", shuffled, ".laz", ["-r", "1.2", "-N", "2"], [6000],
                      range_points=7000)
    same_as_in_memory(c, "pcd-automatic", shuffled, ".las", [], [0, 12000])
    same_as_in_memory(c, "pcd-normals-as-columns", shuffled, ".txt", ["-r", "1.2", "-R"],
                      [8000])
    same_as_in_memory(c, "pcd-remove-isolated", shuffled, ".las",
                      ["-r", "0.3", "-N", "2", "--remove-isolated"], [6000])
    return shuffled


def check_text_input(c):
    points = survey(20000, 7)
    shuffled = points[np.random.default_rng(7).permutation(len(points))]
    text = os.path.join(c.scratch, "survey-shuffled.txt")
    write_text(text, shuffled, True, " ")
    explicit = ["-r", "1.2", "-n", "0.1", "-N", "2"]
    for extension in (".las", ".laz", ".pcd"):
        same_as_in_memory(c, "text" + extension, text, extension, explicit, [0, 9000, 6000],
                          range_points=7000)
    same_as_in_memory(c, "text-automatic", text, ".las", [], [0, 12000])
    same_as_in_memory(c, "text-remove-isolated", text, ".pcd",
                      ["-r", "0.3", "-N", "2", "--remove-isolated"], [6000])
    columns = os.path.join(c.scratch, "las-columns.txt")
    write_las_columns(columns, shuffled, 8)
    for extension in (".las", ".pcd"):
        same_as_in_memory(c, "text-columns" + extension, columns, extension, explicit, [7000])
    normals = os.path.join(c.scratch, "normals.xyz")
    write_normals(normals, shuffled * 1.0001, 9)
    same_as_in_memory(c, "text-normals", normals, ".pcd", explicit + ["-R"], [7000])
    with_nan = os.path.join(c.scratch, "with-nan.txt")
    nan_points = shuffled.copy()
    nan_points[::50] = np.nan
    write_text(with_nan, nan_points, True, "\t")
    for extension in (".pcd", ".las"):
        same_as_in_memory(c, "text-nan" + extension, with_nan, extension, explicit, [7000])


def check_samples(c, pcd_dir):
    """PCL's files: binary_compressed rgba (milk) and binary (face_model) into LAS and text, an
    organised frame with NaN pixels (capture0001) with --keep-nan into PCD and LAS."""
    milk = os.path.join(pcd_dir, "milk.pcd")
    for extension in (".las", ".txt"):
        same_as_in_memory(c, "milk" + extension, milk, extension, [], [0, 8000],
                          range_points=3000)
        same_as_in_memory(c, "face-model" + extension, os.path.join(pcd_dir, "face_model.pcd"),
                          extension, [], [0, 40000])
    capture = os.path.join(pcd_dir, "capture0001.pcd")
    for extension in (".pcd", ".las"):
        same_as_in_memory(c, "capture-keep-nan" + extension, capture, extension,
                          ["-r", "0.02", "-N", "2", "--keep-nan"], [0, 80000])


def check_keep_nan(c, shuffled):
    explicit = ["-r", "1.2", "-n", "0.1", "-N", "2", "--keep-nan"]
    ascii_file = os.path.join(c.scratch, "shuffled-ascii.pcd")
    for source, label in ((shuffled, "binary"), (ascii_file, "ascii")):
        for extension in (".pcd", ".txt", ".las"):
            same_as_in_memory(c, f"keep-nan-{label}{extension}", source, extension, explicit,
                              [0, 9000], range_points=7000)
    same_as_in_memory(c, "keep-nan-remove-isolated", shuffled, ".pcd",
                      ["-r", "0.3", "-N", "2", "--remove-isolated", "--keep-nan"], [6000])


def main(program, scratch, pcd_dir=None):
    os.makedirs(scratch, exist_ok=True)
    c = Checks(program, scratch)
    if pcd_dir:
        check_samples(c, pcd_dir)
        return 1 if c.failures else 0
    shuffled = check_pcd_input(c)
    check_text_input(c)
    check_keep_nan(c, shuffled)
    return 1 if c.failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))

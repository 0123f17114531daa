"""pcbilateral --memory-limit (issue 27, item 3): the file filtered in slabs gives the same output
file, byte for byte, as the run in memory; a slab that cannot fit is refused; the temporary files
are removed on every exit.

Cases: a generated survey whose sampling density varies (so that the automatic radius follows
the density), as LAS and as text (a header and an extra column; no header, tabs), in spatial
order and shuffled, with explicit and automatic parameters, each with
several slab sizes (PCB_STREAMING_SLAB_POINTS caps the points of a slab and its halo, so that a
small file makes many slabs); the refusals (a slab that cannot fit, formats not streamed, a bad
size) and the clean-up (after an error, after Ctrl-C). Given the shared LAS folder, instead: the
Autzen survey as LAS, LAZ and LAS 1.4, and a file with extra bytes.

    CheckStreaming.py PCBILATERAL SCRATCH [LAS_DATA_DIR]
"""
import os
import re
import shutil
import signal
import struct
import subprocess
import sys
import time

import numpy as np


def write_las(path, points, classes=2):
    """A LAS 1.2 file of point format 0 (scale 0.001), records in the order given."""
    scale = 0.001
    low, high = points.min(axis=0), points.max(axis=0)
    offset = np.floor(low)
    header = struct.pack("<4sHH16sBB32s32sHHHIIBHI5I3d3d6d", b"LASF", 0, 0, b"\0" * 16, 1, 2,
                         b"pcbilateral test", b"CheckStreaming.py", 1, 2026, 227, 227, 0, 0, 20,
                         len(points), len(points), 0, 0, 0, 0, scale, scale, scale, *offset,
                         high[0], low[0], high[1], low[1], high[2], low[2])
    records = np.zeros(len(points), dtype=[("xyz", "<i4", 3), ("intensity", "<u2"),
                                           ("flags", "u1"), ("class", "u1"), ("angle", "i1"),
                                           ("user", "u1"), ("source", "<u2")])
    records["xyz"] = np.round((points - offset) / scale).astype(np.int32)
    records["intensity"] = np.arange(len(points)) % 65536
    records["flags"] = 9
    records["class"] = classes
    with open(path, "wb") as stream:
        stream.write(header)
        stream.write(records.tobytes())


def write_text(path, points, header, delimiter):
    """The authors' text format: x y z and an integer column, with or without a header line."""
    with open(path, "w") as stream:
        if header:
            stream.write(delimiter.join(["X", "Y", "Z", "intensity"]) + "\n")
        for i, p in enumerate(points):
            stream.write(delimiter.join([f"{p[0]:.6f}", f"{p[1]:.6f}", f"{p[2]:.6f}",
                                         str(i % 255)]) + "\n")


def survey(count, seed):
    """A rolling terrain sampled 6 times more densely at one end (a scan's falloff), with
    noise, sorted along x as a survey's flight lines are."""
    rng = np.random.default_rng(seed)
    # Density falling as 1 / (1 + x / 40)^2 over x in [0, 240]: spacing varying about 7 times.
    u = rng.random(count)
    x = 40.0 * (1.0 / (1.0 - u * (1.0 - 1.0 / 7.0)) - 1.0)
    y = rng.random(count) * 12.0
    z = 2.0 * np.sin(x / 9.0) * np.cos(y / 5.0) + rng.normal(0.0, 0.03, count)
    points = np.column_stack([x, y, z])
    return points[np.argsort(x, kind="stable")]


class Checks:
    def __init__(self, program, scratch):
        self.program, self.scratch, self.failures = program, scratch, []
        self.tmp = os.path.join(scratch, "tmp")
        shutil.rmtree(self.tmp, ignore_errors=True)  # (what a crashed earlier run left)
        os.makedirs(self.tmp, exist_ok=True)

    def check(self, condition, message):
        print(("ok:     " if condition else "FAILED: ") + message, flush=True)
        if not condition:
            self.failures.append(message)

    def run(self, arguments, slab_points=None, range_points=None):
        env = dict(os.environ, TMPDIR=self.tmp)
        if slab_points is not None:
            env["PCB_STREAMING_SLAB_POINTS"] = str(slab_points)
        if range_points is not None:
            env["PCB_STREAMING_RANGE_POINTS"] = str(range_points)
        return subprocess.run([self.program] + arguments, capture_output=True, text=True, env=env)

    def read(self, path):
        with open(path, "rb") as stream:
            return stream.read()

    def temporary_left(self):
        return os.listdir(self.tmp)

    def memory_and_streamed(self, name, source, extension, parameters, slab_sizes,
                            range_points=None):
        """The run in memory into NAME-memory.EXT, then one streamed run (--memory-limit 1G) per
        slab size into NAME-SLAB.EXT, `range_points` points read and written at a time, earlier
        outputs removed first: the in-memory path and run, and (slab size, streamed path, run)
        for each slab size."""
        in_memory = os.path.join(self.scratch, name + "-memory" + extension)
        if os.path.exists(in_memory):
            os.remove(in_memory)
        memory = self.run([source, in_memory] + parameters)
        streamed_runs = []
        for slab_points in slab_sizes:
            streamed = os.path.join(self.scratch, f"{name}-{slab_points}{extension}")
            if os.path.exists(streamed):
                os.remove(streamed)
            streamed_runs.append((slab_points, streamed, self.run(
                [source, streamed, "--memory-limit", "1G"] + parameters, slab_points,
                range_points)))
        return in_memory, memory, streamed_runs

    def same_as_in_memory(self, name, source, parameters, slab_sizes, expect=None,
                          extension=None, range_points=None):
        """The streamed outputs (into `extension`, by default the input's, LAZ into LAS) against
        the output in memory; `range_points` points read and written at a time."""
        extension = extension or os.path.splitext(source)[1].replace(".laz", ".las")
        in_memory = os.path.join(self.scratch, name + "-memory" + extension)
        result = self.run([source, in_memory] + parameters)
        self.check(result.returncode == 0, f"{name}: the run in memory ({result.stderr.strip()})")
        if expect is not None:
            self.check(expect in result.stdout, f"{name}: the run in memory says '{expect}'")
        for slab_points in slab_sizes:
            streamed = os.path.join(self.scratch, f"{name}-{slab_points}{extension}")
            result = self.run([source, streamed, "--memory-limit", "1G"] + parameters, slab_points,
                              range_points)
            slabs = [line for line in result.stdout.splitlines() if "along" in line]
            self.check(result.returncode == 0 and os.path.exists(streamed) and
                       self.read(streamed) == self.read(in_memory),
                       f"{name}, slabs of at most {slab_points} points ({slabs}): the same "
                       f"bytes as in memory {result.stderr.strip()}")
            self.check(not self.temporary_left(), f"{name}: no temporary file left")
            if slab_points and not name.startswith("extra"):
                # Not on a terminal: a line per slab, with the time left.
                progress = re.search(r"^slabs: +\d+ of \d+ done, \d+ s left$", result.stdout,
                                     re.MULTILINE)
                self.check(progress is not None and "\r" not in result.stdout,
                           f"{name}: a plain progress line per slab with the time left")
        return result.stdout


def check_refusals(c, source):
    output = os.path.join(c.scratch, "refused.las")
    result = c.run([source, output, "--memory-limit", "1G", "-r", "3", "-N", "3"], 200)
    c.check(result.returncode != 0 and "cannot fit" in result.stderr and
            not os.path.exists(output) and len(result.stderr.strip().splitlines()) == 1,
            f"a slab that cannot fit: one line, non-zero exit, no output ({result.stderr.strip()})")
    c.check(not c.temporary_left(), "the refusal leaves no temporary file")
    for arguments, words in (([source, os.path.join(c.scratch, "o.ply")], "into .las"),
                             ([source, os.path.join(c.scratch, "o.vtp")], "not yet"),
                             ([source, output, "-r", "3"], None)):
        size = "2X" if words is None else "1G"
        result = c.run(arguments + ["--memory-limit", size])
        expected = words or "is not a size"
        c.check(result.returncode != 0 and expected in result.stderr and not os.path.exists(output),
                f"refused: {' '.join(arguments[2:])} --memory-limit {size}: "
                f"{result.stderr.strip()}")
    # --copc-level on a file that is not COPC (COPC files: CheckStreamingCOPC.py): the run in
    # memory's warning, every point read.
    runs = [c.run([source, os.path.join(c.scratch, f"copc-{kind}.las"), "--copc-level", "0",
                   "-r", "1.2", "-N", "1"] + (["--memory-limit", "1G"] if kind == "streamed" else []),
                  8000)
            for kind in ("memory", "streamed")]
    c.check(runs[1].returncode == 0 and "not a COPC file" in runs[1].stderr and
            runs[1].stderr == runs[0].stderr and
            c.read(os.path.join(c.scratch, "copc-streamed.las")) ==
            c.read(os.path.join(c.scratch, "copc-memory.las")),
            f"--copc-level on a file that is not COPC: the warning and bytes of the run in "
            f"memory ({runs[1].stderr.strip()})")
    # An error after the bins are written: the output's folder does not exist.
    missing = os.path.join(c.scratch, "no-such-folder", "out.las")
    result = c.run([source, missing, "--memory-limit", "1G", "-r", "1.2", "-N", "2"], 30000)
    c.check(result.returncode != 0 and "no-such-folder" in result.stderr and
            not c.temporary_left(),
            f"an error while writing leaves no temporary file ({result.stderr.strip()})")


def check_classes(c, name, source, parameters, extension, slab_points):
    """--classes: the same bytes and the same warnings or error as in memory, and the same count
    of points filtered; no output after an error."""
    in_memory = os.path.join(c.scratch, name + "-memory" + extension)
    streamed = os.path.join(c.scratch, name + "-streamed" + extension)
    memory_run = c.run([source, in_memory] + parameters)
    streamed_run = c.run([source, streamed, "--memory-limit", "1G"] + parameters, slab_points,
                         23456)
    said = [re.findall(r"^classes: .*$", run.stdout, re.MULTILINE)
            for run in (memory_run, streamed_run)]
    failed = memory_run.returncode != 0
    c.check(streamed_run.returncode == memory_run.returncode and
            streamed_run.stderr == memory_run.stderr and said[0] == said[1] and
            (c.read(streamed) == c.read(in_memory) if not failed else
             not os.path.exists(streamed)) and not c.temporary_left(),
            f"{name}: the same {'error' if failed else 'bytes'}, warnings and count as in memory "
            f"({said[1]} {streamed_run.stderr.strip()})")


def check_limit_too_small(c, source):
    """A limit below what the program holds besides its slabs says so and names a limit that
    does."""
    output = os.path.join(c.scratch, "too-small.las")
    if os.path.exists(output):  # the run that the hint allows wrote it last time
        os.remove(output)
    result = c.run([source, output, "--memory-limit", "16M", "-r", "3", "-N", "3"])
    hint = re.search(r"give --memory-limit (\d+)M or more$", result.stderr.strip())
    c.check(result.returncode != 0 and "does not cover what the program holds" in result.stderr
            and hint is not None and not os.path.exists(output),
            f"--memory-limit 16M: says why and the limit to give ({result.stderr.strip()})")
    if hint:
        enough = c.run([source, output, "--memory-limit", hint.group(1) + "M", "-r", "3", "-N", "3"])
        c.check(enough.returncode == 0, f"the limit it names is enough ({hint.group(1)}M): "
                f"{enough.stderr.strip()}")


def check_bad_text(c, text):
    """A malformed line near the end: the same one-line error as in memory, no output, no
    temporary file."""
    bad = os.path.join(c.scratch, "bad.xyz")
    with open(text) as stream, open(bad, "w") as out:
        out.write(stream.read() + "1.0 2.0 three 4\n")
    output = os.path.join(c.scratch, "bad-out.xyz")
    in_memory = c.run([bad, output, "-r", "1.2"])
    streamed = c.run([bad, output, "--memory-limit", "1G", "-r", "1.2"], 20000)
    c.check(streamed.returncode != 0 and streamed.stderr == in_memory.stderr and
            not os.path.exists(output) and not c.temporary_left(),
            f"a malformed text line: the same error as in memory ({streamed.stderr.strip()})")


def check_not_finite_text(c, text):
    """Points without coordinates (nan) pass through unchanged, with the in-memory warning."""
    with_nan = os.path.join(c.scratch, "nan.xyz")
    with open(text) as stream:
        lines = stream.read().splitlines(True)
    lines.insert(1000, "nan nan nan 7\n")
    lines.insert(30000, "1.0 inf 2.0 8\n")
    with open(with_nan, "w") as out:
        out.write("".join(lines))
    in_memory = os.path.join(c.scratch, "nan-memory.xyz")
    streamed = os.path.join(c.scratch, "nan-streamed.xyz")
    memory_run = c.run([with_nan, in_memory, "-r", "1.2", "-N", "2"])
    streamed_run = c.run([with_nan, streamed, "-r", "1.2", "-N", "2", "--memory-limit", "1G"],
                         20000)
    c.check(memory_run.returncode == 0 and streamed_run.returncode == 0 and
            c.read(in_memory) == c.read(streamed) and "2 point(s) have NaN" in streamed_run.stderr
            and streamed_run.stderr == memory_run.stderr,
            f"points not finite: the same bytes and warning as in memory "
            f"({streamed_run.stderr.strip()})")


def check_interrupt(c, source):
    output = os.path.join(c.scratch, "interrupted.las")
    # (A large radius: a run of seconds.)
    env = dict(os.environ, TMPDIR=c.tmp)
    process = subprocess.Popen([c.program, source, output, "--memory-limit", "1G", "-r", "5",
                                "-N", "2", "-t", "1"], stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL, env=env)
    deadline = time.time() + 60
    while time.time() < deadline and not any(c.temporary_left()):
        time.sleep(0.02)
    seen = bool(c.temporary_left())
    time.sleep(0.3)
    process.send_signal(signal.SIGINT)
    code = process.wait(60)
    c.check(seen and code == 128 + signal.SIGINT and not c.temporary_left() and not os.path.exists(output),
            f"Ctrl-C during the run: exit {code}, temporary files removed "
            f"(seen before: {seen}), no output")


def laz_path(las_dir):
    return os.path.join(las_dir, "..", "laz", "autzen_trim.laz")


def check_samples(c, las_dir):
    """The shared samples: Autzen as LAS, LAZ and LAS 1.4, extra bytes, into LAS and LAZ, and
    with --classes."""
    autzen = os.path.join(las_dir, "autzen_trim.las")
    c.same_as_in_memory("autzen", autzen, [], [40000, 20000])
    c.same_as_in_memory("autzen-laz", os.path.join(las_dir, "..", "laz", "autzen_trim.laz"),
                        ["-r", "5", "-N", "2"], [30000])
    c.same_as_in_memory("autzen-1.4", os.path.join(las_dir, "autzen_trim_7.las"),
                        ["-r", "5"], [30000])
    c.same_as_in_memory("extra-bytes", os.path.join(las_dir, "extrabytes.las"), [], [0])
    # LAZ output: the pointwise (formats 0 to 3) and the layered (6 to 8) compressors, the
    # ranges written cutting the chunks of 50,000 points.
    c.same_as_in_memory("autzen-into-laz", autzen, ["-r", "5", "-N", "2"], [40000],
                        extension=".laz", range_points=37000)
    c.same_as_in_memory("autzen-laz-into-laz",
                        os.path.join(las_dir, "..", "laz", "autzen_trim.laz"),
                        ["-r", "5", "-N", "2"], [30000], extension=".laz")
    c.same_as_in_memory("autzen-1.4-into-laz", os.path.join(las_dir, "autzen_trim_7.las"),
                        ["-r", "5"], [30000], extension=".laz", range_points=23456)
    # Into text and PCD: every dimension as columns or fields, RGB and the display colours,
    # extra bytes.
    for name, source in (("autzen", autzen), ("autzen-laz", laz_path(las_dir)),
                         ("autzen-1.4", os.path.join(las_dir, "autzen_trim_7.las")),
                         ("extra-bytes", os.path.join(las_dir, "extrabytes.las"))):
        for extension in (".txt", ".pcd"):
            c.same_as_in_memory(name + "-into" + extension, source, ["-r", "5", "-N", "2"],
                                [30000], extension=extension, range_points=23456)
    # --classes (Autzen: classes 1 and 2): only the chosen classes filtered, the others
    # passed through; the in-memory errors and warning.
    laz = os.path.join(las_dir, "..", "laz", "autzen_trim.laz")
    for name, source, parameters, extension in (
            ("classes-automatic", autzen, ["--classes", "2"], ".las"),
            ("classes-laz", laz, ["--classes", "1,2", "-r", "5", "-N", "2"], ".laz"),
            ("classes-1.4", os.path.join(las_dir, "autzen_trim_7.las"),
             ["--classes", "2", "-r", "5"], ".las"),
            ("classes-intensity", autzen, ["--classes", ",".join(map(str, range(30))),
                                           "--class-array", "Intensity", "-r", "5"], ".las"),
            ("classes-none", autzen, ["--classes", "17", "-r", "5"], ".las"),
            ("classes-missing", autzen, ["--classes", "2", "--class-array", "Nope"], ".las"),
            ("classes-float", autzen, ["--classes", "2", "--class-array", "GpsTime"], ".las"),
            ("classes-rgb", autzen, ["--classes", "2", "--class-array", "RGB"], ".las")):
        check_classes(c, name, source, parameters, extension, 8000)


def check_laz_and_classes(c, points, shuffled, text):
    """LAZ output with ranges that cut its chunks, --classes, and --classes with text input
    (the run in memory's error)."""
    # LAZ output: 60,000 points make a chunk of 50,000 and one of 10,000; ranges of 7,000 and
    # 50,000 points read and written at a time cut the chunks or fall on their boundary.
    for range_points in (7000, 50000, None):
        c.same_as_in_memory(f"into-laz-{range_points}", shuffled,
                            ["-r", "1.2", "-n", "0.1", "-N", "2"], [20000], extension=".laz",
                            range_points=range_points)
    # --classes on a shuffled file: class 2 on the terrain's ridges, 6 elsewhere.
    classified = os.path.join(c.scratch, "survey-classes.las")
    order = np.random.default_rng(11).permutation(len(points))
    write_las(classified, points[order], np.where(points[order, 2] > 0.5, 2, 6))
    check_classes(c, "classes-explicit", classified,
                  ["--classes", "2", "-r", "1.2", "-n", "0.1", "-N", "2"], ".las", 15000)
    check_classes(c, "classes-automatic-laz", classified, ["--classes", "6"], ".laz", 30000)
    # A text file's columns are doubles: the run in memory's error, streamed too.
    output = os.path.join(c.scratch, "o.xyz")
    for array in ("intensity", "Classification"):
        arguments = [text, output, "--classes", "2", "--class-array", array]
        memory = c.run(arguments)
        streamed = c.run(arguments + ["--memory-limit", "1G"])
        c.check(memory.returncode == 1 and streamed.returncode == 1 and
                streamed.stderr == memory.stderr and len(streamed.stderr.splitlines()) == 1 and
                not os.path.exists(output) and not c.temporary_left(),
                f"--classes with text input, '{array}': the run in memory's error "
                f"({streamed.stderr.strip()} / {memory.stderr.strip()})")


def main(program, scratch, las_dir=None):
    """The generated surveys, the refusals and the clean-up; with LAS_DATA_DIR, the shared
    samples instead."""
    os.makedirs(scratch, exist_ok=True)
    c = Checks(program, scratch)
    if las_dir:
        check_samples(c, las_dir)
        return 1 if c.failures else 0
    points = survey(60000, 7)
    ordered = os.path.join(scratch, "survey.las")
    write_las(ordered, points)
    shuffled = os.path.join(scratch, "survey-shuffled.las")
    write_las(shuffled, points[np.random.default_rng(3).permutation(len(points))])
    text = os.path.join(scratch, "survey.xyz")
    write_text(text, points, True, " ")
    shuffled_text = os.path.join(scratch, "survey-shuffled.txt")
    write_text(shuffled_text, points[np.random.default_rng(5).permutation(len(points))], False,
               "\t")
    for name, source in (("ordered", ordered), ("shuffled", shuffled), ("text", text),
                         ("shuffled-text", shuffled_text)):
        c.same_as_in_memory(name + "-explicit", source, ["-r", "1.2", "-n", "0.1", "-N", "2"],
                            [0, 30000, 20000])
        c.same_as_in_memory(name + "-automatic", source, [], [0, 40000, 35000],
                            expect="following the density")
    check_laz_and_classes(c, points, shuffled, text)
    check_bad_text(c, text)
    check_not_finite_text(c, text)
    # One thread in the slabs, two in memory (the default on this machine's two cores).
    one_thread = os.path.join(scratch, "one-thread.las")
    result = c.run([shuffled, one_thread, "-r", "1.2", "-n", "0.1", "-N", "2", "-t", "1",
                    "--memory-limit", "1G"], 20000)
    c.check(result.returncode == 0 and
            c.read(one_thread) == c.read(os.path.join(scratch, "shuffled-explicit-memory.las")),
            "one thread in the slabs: the same bytes as in memory")
    check_refusals(c, ordered)
    check_limit_too_small(c, ordered)
    check_interrupt(c, ordered)
    return 1 if c.failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))

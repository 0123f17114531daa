"""Every LAZ file of the sample folder decoded by laz-perf (an independent LAZ implementation,
the npm package, run by Node.js) and by the formats library: the same point records, byte for
byte. Then LAZ files we write (from LAS samples of formats 0 to 3 and 6 to 8, and from each LAZ file)
decode in laz-perf to the records they were given. Files laz-perf cannot read (the old pointwise compressor of LASzip 1.x) are said (ours
does not read them either: IO.TestLAZFiles.compressor-1.2r0 checks its one-line error). Prints both decoders' times.

    python3 CheckWithLazPerf.py LAZRECORDS LAZPERF_PACKAGE LAS_FOLDER SCRATCH_FOLDER

The LAZ files are in LAS_FOLDER/../laz.

Exits with 77 (skipped, with the reason) when Node.js or the laz-perf package is missing: the
test command installs the package (.ci/install-lazperf) when Node.js is there.
"""
import glob
import os
import shutil
import subprocess
import sys

# Files laz-perf is known not to read (LASzip 1.x's pointwise compressor, item version 1).
NOT_FOR_LAZPERF = {"simple-laszip-compressor-version-1.2r0.laz"}
# LAS samples written as LAZ (formats 0 to 3 and 6 to 8, with and without extra bytes).
WRITTEN_FROM_LAS = ["autzen_trim.las", "simple.las", "100-points.las", "extrabytes.las",
                    "4_6_crop.las", "test1_4.las", "autzen_trim_7.las"]


def main():
    ours, package, las_folder, scratch = sys.argv[1:5]
    folder = os.path.join(las_folder, "..", "laz")
    node = shutil.which("node")
    if not node:
        print("skipped: Node.js (node) is not installed, so laz-perf cannot run")
        return 77
    if not os.path.isfile(os.path.join(package, "package.json")):
        print(f"skipped: the laz-perf package is not in '{package}' (bash .ci/install-lazperf)")
        return 77
    os.makedirs(scratch, exist_ok=True)
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "lazperf-records.js")
    failures = []
    files = sorted(glob.glob(os.path.join(folder, "*.laz")))
    for path in files:
        name = os.path.basename(path)
        theirs_out = os.path.join(scratch, name + ".lazperf")
        ours_out = os.path.join(scratch, name + ".ours")
        theirs = subprocess.run([node, script, package, path, theirs_out],
                                capture_output=True, text=True)
        mine = subprocess.run([ours, path, ours_out], capture_output=True, text=True)
        if name in NOT_FOR_LAZPERF:
            print(f"{name}: not read by laz-perf ({(theirs.stderr or theirs.stdout).strip()[:80]}"
                  f"); ours: {(mine.stderr or mine.stdout).strip()}")
            continue
        same = (theirs.returncode == 0 and mine.returncode == 0
                and open(theirs_out, "rb").read() == open(ours_out, "rb").read())
        print(f"{'ok' if same else 'FAILED'}: {name}: {theirs.stdout.strip()} | "
              f"{mine.stdout.strip()} {theirs.stderr.strip()} {mine.stderr.strip()}")
        if not same:
            failures.append(name)
    if not files:
        print(f"FAILED: no LAZ file in '{folder}'")
        return 1
    # Written by us, read by laz-perf.
    sources = files + [os.path.join(las_folder, name) for name in WRITTEN_FROM_LAS]
    for path in sources:
        name = os.path.basename(path)
        if name in NOT_FOR_LAZPERF or not os.path.isfile(path):
            continue
        given = os.path.join(scratch, name + ".given")
        written = os.path.join(scratch, name + ".written.laz")
        theirs_out = os.path.join(scratch, name + ".written.lazperf")
        mine = subprocess.run([ours, path, given, written], capture_output=True, text=True)
        if mine.returncode != 0 and "are not written" in mine.stderr:
            print(f"{name}: not written as LAZ: {mine.stderr.strip()}")
            continue
        theirs = subprocess.run([node, script, package, written, theirs_out],
                                capture_output=True, text=True)
        same = (mine.returncode == 0 and theirs.returncode == 0
                and open(given, "rb").read() == open(theirs_out, "rb").read())
        print(f"{'ok' if same else 'FAILED'}: {name} written as LAZ, read by laz-perf: "
              f"{mine.stdout.strip()} | {theirs.stdout.strip()} {mine.stderr.strip()} "
              f"{theirs.stderr.strip()}")
        if not same:
            failures.append(name + " written")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

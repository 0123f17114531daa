"""Every LAZ file of the sample folder decoded by laz-perf (an independent LAZ implementation,
the npm package, run by Node.js) and by the formats library: the same point records, byte for
byte. Files laz-perf cannot read (the old pointwise compressor of LASzip 1.x) are said (ours
does not read them either: IO.TestLAZFiles.compressor-1.2r0 checks its one-line error). Prints both decoders' times.

    python3 CheckWithLazPerf.py LAZRECORDS LAZPERF_PACKAGE LAZ_FOLDER SCRATCH_FOLDER

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


def main():
    ours, package, folder, scratch = sys.argv[1:5]
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
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

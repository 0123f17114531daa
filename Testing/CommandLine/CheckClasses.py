"""pcbilateral --classes on a real airborne survey (shared/data/las/autzen_trim.las, LAS 1.2 point
format 3, classes 1 and 2):
- with --classes 2, every point record of another class is written back byte for byte as it was
  read, and most class-2 points move (their coordinates, and nothing else of their records);
- the program says how many points it filtered;
- a list that is not integers, a class array the file lacks and a class array that is not
  integers are one-line errors with exit status 1 and no output file.

    CheckClasses.py PCBILATERAL LAS_FOLDER SCRATCH
"""
import os
import re
import struct
import subprocess
import sys

import numpy as np


def point_records(path):
    """The point records of a LAS file (uncompressed), as a 2-D byte array."""
    data = open(path, "rb").read()
    offset, = struct.unpack_from("<I", data, 96)
    length, = struct.unpack_from("<H", data, 105)
    count, = struct.unpack_from("<I", data, 107)
    return np.frombuffer(data, np.uint8, count * length, offset).reshape(count, length)


def main(program, folder, scratch):
    os.makedirs(scratch, exist_ok=True)
    source = os.path.join(folder, "autzen_trim.las")
    output = os.path.join(scratch, "ground.las")
    failures = []
    run = subprocess.run([program, source, output, "--classes", "2"], capture_output=True,
                         text=True)
    before, after = point_records(source), point_records(output)
    classes = before[:, 15] & 0x1F  # format 3: the class is the low 5 bits of byte 15
    ground = classes == 2
    said = re.search(r"classes: +2 in 'Classification': (\d+) points filtered", run.stdout)
    if run.returncode != 0 or not said or int(said.group(1)) != int(ground.sum()):
        failures.append(f"exit {run.returncode}, expected {ground.sum()} points filtered:\n"
                        f"{run.stdout}{run.stderr}")
    if not np.array_equal(before[~ground], after[~ground]):
        failures.append(f"{np.count_nonzero(np.any(before[~ground] != after[~ground], axis=1))} "
                        "records of other classes changed")
    moved = np.any(before[ground, :12] != after[ground, :12], axis=1)
    if moved.sum() < 0.5 * ground.sum() or not np.array_equal(before[ground, 12:],
                                                              after[ground, 12:]):
        failures.append(f"{moved.sum()} of {ground.sum()} ground points moved, or more than "
                        "their coordinates changed")
    print(f"{ground.sum()} of {len(classes)} points of class 2, {moved.sum()} moved; "
          f"{np.count_nonzero(~ground)} others unchanged")
    for arguments, message in (
            (["--classes", "2,ground"], "is not a list of whole numbers"),
            (["--classes", "2", "--class-array", "Nope"], "has no point array 'Nope'"),
            (["--classes", "2", "--class-array", "GpsTime"], "must hold one integer per point")):
        refused = os.path.join(scratch, "refused.las")
        run = subprocess.run([program, source, refused] + arguments, capture_output=True,
                             text=True)
        lines = run.stderr.strip().splitlines()
        if run.returncode != 1 or len(lines) != 1 or message not in lines[0] or \
                os.path.exists(refused):
            failures.append(f"{arguments}: exit {run.returncode}, stderr {run.stderr!r}")
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))

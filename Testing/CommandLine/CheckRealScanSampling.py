"""pcbilateral reports the spread of a cloud's sampling (the 5th, 50th and 95th percentiles of the
nearest-neighbour distance, measured on a sample of the points): on the three real scans, each
within 10% of the percentiles over all points that shared/data/real/README.md lists (in mm).

    CheckRealScanSampling.py PCBILATERAL FOLDER SCRATCH
"""
import os
import re
import subprocess
import sys

# The README's 5th / 50th / 95th percentiles, in millimetres (the files are in metres).
EXPECTED = {"room_scan2": (0.31, 27, 109), "kinect_capture0001": (3.4, 4.3, 5.5),
            "terrain_samp11": (31, 800, 1568)}
SAMPLING = re.compile(r"sampling: +nearest-neighbour distance (\S+) \(5%\), (\S+) \(median\), "
                      r"(\S+) \(95%\)")

program, folder, scratch = sys.argv[1:4]
os.makedirs(scratch, exist_ok=True)
failures = 0
for name, expected in EXPECTED.items():
    run = subprocess.run([program, os.path.join(folder, name + ".ply"),
                          os.path.join(scratch, name + ".ply"), "-N", "1"],
                         capture_output=True, text=True)
    match = SAMPLING.search(run.stdout)
    if run.returncode != 0 or not match:
        print(f"FAILED: {name}: no sampling line (status {run.returncode}):\n{run.stdout}{run.stderr}")
        failures += 1
        continue
    found = [1000 * float(value) for value in match.groups()]
    wrong = [f"{f:.3g} mm against {e} mm" for f, e in zip(found, expected) if abs(f / e - 1) > 0.1]
    print(("FAILED: " if wrong else "ok:     ") + f"{name}: " +
          " / ".join(f"{f:.3g}" for f in found) + f" mm (README: {expected})" +
          (": " + ", ".join(wrong) if wrong else ""))
    failures += bool(wrong)
sys.exit(1 if failures else 0)

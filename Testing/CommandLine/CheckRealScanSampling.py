"""pcbilateral on the three real scans of shared/data/real:
- it reports the spread of the cloud's sampling (the 5th, 50th and 95th percentiles of the
  nearest-neighbour distance, measured on a sample of the points), each within 10% of the
  percentiles over all points that the folder's README.md lists (in mm);
- the automatic radius follows the density on the room scan (its local spacing varies more than
  4 times across the surface), and not on the depth frame or the terrain, whose spacing varies
  less than 3 times;
- the depth frame's quantised depths are read as structured noise: a sigma of several
  millimetres (its plane patches read 6.5 mm), where the fits' small balls alone saw 0.5 mm.

    CheckRealScanSampling.py PCBILATERAL FOLDER SCRATCH
"""
import os
import re
import subprocess
import sys

# The README's 5th / 50th / 95th percentiles, in millimetres (the files are in metres), whether
# the radius follows the density, and the noise sigma's bounds in millimetres.
EXPECTED = {"room_scan2": ((0.31, 27, 109), True, (2, 10)),
            "kinect_capture0001": ((3.4, 4.3, 5.5), False, (4, 10)),
            "terrain_samp11": ((31, 800, 1568), False, (100, 500))}
SAMPLING = re.compile(r"sampling: +nearest-neighbour distance (\S+) \(5%\), (\S+) \(median\), "
                      r"(\S+) \(95%\); local spacing varies (\S+) times")
SIGMA = re.compile(r"noise sigma (\S+)")
FOLLOWS = re.compile(r"^radius: .*, following the density", re.M)


def check(name, expected, output):
    """The problems with one scan's output."""
    percentiles, follows, sigma_bounds = expected
    match, sigma = SAMPLING.search(output), SIGMA.search(output)
    if not match or not sigma:
        return [f"no sampling or noise line:\n{output}"]
    found = [1000 * float(value) for value in match.groups()[:3]]
    spread = float(match.group(4))
    wrong = [f"{f:.3g} mm against {e} mm" for f, e in zip(found, percentiles)
             if abs(f / e - 1) > 0.1]
    if bool(FOLLOWS.search(output)) != follows:
        wrong.append(f"the radius {'does not follow' if follows else 'follows'} the density "
                     f"(spacing varies {spread:.3g} times)")
    if (spread > 4.0) != follows or (not follows and spread > 3.0):
        wrong.append(f"the spacing varies {spread:.3g} times")
    noise = 1000 * float(sigma.group(1))
    if not sigma_bounds[0] <= noise <= sigma_bounds[1]:
        wrong.append(f"noise sigma {noise:.3g} mm, expected {sigma_bounds[0]} to "
                     f"{sigma_bounds[1]} mm")
    print(("FAILED: " if wrong else "ok:     ") + f"{name}: " +
          " / ".join(f"{f:.3g}" for f in found) + f" mm (README: {percentiles}), spacing varies "
          f"{spread:.3g} times, noise {noise:.3g} mm" + (": " + ", ".join(wrong) if wrong else ""))
    return wrong


program, folder, scratch = sys.argv[1:4]
os.makedirs(scratch, exist_ok=True)
failures = 0
for name, expected in EXPECTED.items():
    run = subprocess.run([program, os.path.join(folder, name + ".ply"),
                          os.path.join(scratch, name + ".ply"), "-N", "1"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        print(f"FAILED: {name}: status {run.returncode}:\n{run.stdout}{run.stderr}")
        failures += 1
        continue
    failures += bool(check(name, expected, run.stdout))
sys.exit(1 if failures else 0)

"""The real-scan figure of docs/parameters.md: a cross-section of the bridge deck in the airborne LiDAR tile
autzen_trim.las, as scanned, after the paper's heuristic parameters and after the automatic ones.

    python3 autzen_profile.py INPUT.las PAPER.las AUTOMATIC.las OUT.png

PAPER.las and AUTOMATIC.las come from `pcbilateral INPUT.las PAPER.las --paper` and
`pcbilateral INPUT.las AUTOMATIC.las`. Needs the pointcloudbilateral Python package on the path
and matplotlib (Debian: python3-matplotlib). The section is a 12 ft wide strip across the
bridge deck (found by its flat, elevated cells, about 31 ft above the ground), seen along the
bridge; its points (the deck and its two parapets, about 3 ft high) are plotted across the
bridge against their height.
"""
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from pointcloudbilateral import vtkLASPointCloudReader  # noqa: E402
from vtkmodules.numpy_interface import dataset_adapter as dsa  # noqa: E402

# The deck's centre and direction in the tile's coordinates (US survey feet).
CENTRE = np.array([636505.0, 849395.0])
ALONG = np.array([0.385, 0.923])
ACROSS = np.array([ALONG[1], -ALONG[0]])
HALF_WIDTH, HALF_LENGTH = 6.0, 11.0


def section(path):
    reader = vtkLASPointCloudReader()
    reader.SetFileName(path)
    reader.Update()
    points = np.asarray(dsa.WrapDataObject(reader.GetOutput()).Points)
    offset = points[:, :2] - CENTRE
    along, across = offset @ ALONG, offset @ ACROSS
    # (The river bank under the bridge, 30 ft lower, is left out.)
    keep = (np.abs(along) < HALF_WIDTH) & (np.abs(across) < HALF_LENGTH) & (points[:, 2] > 430)
    return across[keep], points[keep, 2], np.flatnonzero(keep)


inputs = sys.argv[1:4]
titles = ["as scanned", "paper's heuristic\n(r = 15.9 ft, rn = r, N = 1)",
          "automatic\n(r = 8.0 ft, rn = 0.24 ft, N = 2)"]
figure, axes = plt.subplots(1, 3, figsize=(12, 3.0), sharex=True, sharey=True)
for axis, path, title in zip(axes, inputs, titles):
    x, z, _ = section(path)
    axis.scatter(x, z, s=6, c="k", linewidths=0)
    axis.set_title(title, fontsize=10)
    axis.set_xlabel("across the bridge (ft)")
axes[0].set_ylabel("height (ft)")
figure.tight_layout()
figure.savefig(sys.argv[4], dpi=90)
print(f"wrote {sys.argv[4]}")

#!/usr/bin/env python3
"""Structure metrics for point clouds without ground truth (docs/structure-metrics.md).

A real scan has no true surface to measure a denoising against, but most scans contain structure
whose shape is known: planes (walls, floors, table tops) and the sharp lines where two planes meet.
This script finds that structure on the INPUT only, then measures, on the same point indices
before and after a filter (which keeps the points' order and count):

- plane residual: plane patches (the k nearest points of seeds spread over the area, kept
  when a RANSAC plane holds most of them and they are flat, not curved nor a blob); for each
  patch, the RMS distance of its inlier points to the least-squares plane of those same points,
  refitted on the filtered positions for "after". Reported: the median over patches of the
  patch's RMS, before and after, and the median over patches of each patch's after/before
  ratio ("how much flatter the typical patch gets"). The median, not the RMS over patches,
  because a few patches that are not planes (a cushion, a cable) slip through any planarity
  test and would dominate an RMS, and because the noise of a real scan varies from patch to
  patch (range-dependent noise) so an RMS would measure the noisiest part only.
- corner residual: large planes (walls, floor, ceiling) found by RANSAC over the whole cloud
  (the hypotheses are the patches' planes, so that a sparse far wall gets one), and the pairs of
  them that meet: their intersection line passes through points of both. The points within a
  band around each line are kept, and their distance to the two-plane model (the smaller
  distance to the two planes, each fitted on the input away from the line and kept fixed) is
  pooled over all lines as an RMS, before and after: a filter that rounds a corner moves those
  points off both planes and the ratio rises above 1.

All the metric's parameters are constants below, fixed before any filtered result was looked at;
the thresholds are relative to scales measured on the input (a patch's robust residual, the
planes' residual and nearest-neighbour spacing), since the scans' units differ by orders of
magnitude.

  pcb_structure.py INPUT --filtered OUT [OUT ...]    evaluate filtered files
  pcb_structure.py INPUT --run "label: ARGS" [...]   run pcbilateral INPUT tmp.ply ARGS, evaluate
  pcb_structure.py INPUT --grid                      a hand-tuning grid of explicit parameters
  pcb_structure.py --self-test                       the metric on generated data (ctest)

numpy only (no scipy, no VTK); run with /usr/bin/python3.
"""
import argparse
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time

import numpy as np

# --- The metric's fixed parameters (docs/structure-metrics.md); not to be tuned. ---------------
SEED = 20251125                # every random choice (seeds, RANSAC samples, subsamples)
PATCH_POINTS = 300             # k: a patch is a seed's k nearest points
PATCH_SEEDS_TRIED = 1000       # at most this many seeds (a seed inside a kept patch is skipped)
PATCH_COUNT = 200              # stop after this many planar patches
PATCH_HYPOTHESES = 100         # RANSAC (least median of squares) samples per patch
INLIER_SIGMAS = 3.0            # inlier: |distance| < 3 robust sigma (1.4826 x median |distance|)
PATCH_MIN_INLIERS = 0.8        # planar patch: at least 80% of its points are inliers,
PATCH_MAX_CURVATURE = 1.15     # its plane's RMS at most 1.15 x a quadric's (not curved),
PATCH_MAX_THICKNESS = 0.5      # and its robust sigma under 0.5 x its in-plane extent (not a blob)
PLANE_MAX_COUNT = 12           # large planes: at most 12, found one after another,
PLANE_MIN_FRACTION = 0.005     # each filling at least 0.5% of the cloud's cells (below),
PLANE_INLIER_SIGMAS = 3.0      # its inliers within 3 x the patches' median robust sigma
PLANE_CELL_SPACINGS = 4.0      # a plane's size: the grid cells (4 median spacings) its inliers fill
SCORING_POINTS = 20000         # candidate planes are scored on this many points drawn once
CORNER_MIN_ANGLE = 30.0        # two planes whose normals differ by less (degrees) make no corner
BAND_SIGMAS = 3.0              # band around a line: b = max(3 sigma, 2 s) of the two planes
BAND_SPACINGS = 2.0            #   (sigma: robust residual; s: median nearest-neighbour distance)
SUPPORT_BANDS = 4.0            # a line's stretch counts where both planes have inliers within 4 b
SUPPORT_MIN_POINTS = 3         #   of it, at least 3 of each per stretch of 2 b along the line
FIT_BANDS = (2.0, 8.0)         # corner model: each plane refitted on its inliers 2 b to 8 b away
CORNER_MIN_POINTS = 30         # a corner line needs at least 30 band points
SPACING_SAMPLES = 2000         # median nearest-neighbour distance over this many points
# The hand-tuning grid (--grid): r in spacings, rn in noise sigmas, N.
GRID_R = (4, 8, 12, 16, 24)
GRID_RN = (3, 5, 8)
GRID_N = (1, 2, 3)
CORNER_LIMIT = 1.15            # the grid's best planes subject to corner ratio <= this
# Version 2 of the plane metric, added after version 1's results (docs/structure-metrics.md):
# the plane ratio over the "thin" patches alone, whose robust sigma is at most this many times
# the patches' median (on the room scan, a quarter of the patches are 30 times thicker than the
# rest: clutter and mixed pixels far from the scanner, not planes at the filter's scale).
THIN_PATCH_SIGMAS = 3.0


# --- Reading ------------------------------------------------------------------------------------
PLY_TYPES = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2",
             "int16": "i2", "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4",
             "uint": "u4", "uint32": "u4", "float": "f4", "float32": "f4", "double": "f8",
             "float64": "f8"}


def read_ply_header(stream):
    """The format and the elements [(name, count, [(type, name)])] of a PLY header."""
    if stream.readline().strip() != b"ply":
        raise ValueError("not a PLY file")
    fmt, elements = None, []
    while True:
        line = stream.readline()
        if not line:
            raise ValueError("PLY header without end_header")
        words = line.decode("ascii", "replace").split()
        if not words or words[0] in ("comment", "obj_info"):
            continue
        if words[0] == "end_header":
            return fmt, elements
        if words[0] == "format":
            fmt = words[1]
        elif words[0] == "element":
            elements.append((words[1], int(words[2]), []))
        elif words[0] == "property":
            if words[1] == "list":
                elements[-1][2].append(("list", words[-1]))
            else:
                elements[-1][2].append((PLY_TYPES[words[1]], words[2]))


def read_ply(path):
    with open(path, "rb") as stream:
        fmt, elements = read_ply_header(stream)
        if fmt not in ("binary_little_endian", "ascii"):
            raise ValueError(f"{path}: PLY format {fmt} not read")
        skip = 0
        for name, count, properties in elements:
            if name == "vertex":
                break
            if fmt == "ascii":
                skip += count
            elif any(t == "list" for t, _ in properties):
                raise ValueError(f"{path}: a list element before the vertices")
            else:
                stream.seek(count * np.dtype([(n, "<" + t) for t, n in properties]).itemsize, 1)
        else:
            raise ValueError(f"{path}: no vertex element")
        if any(t == "list" for t, _ in properties):
            raise ValueError(f"{path}: list property in the vertex element")
        names = [n for _, n in properties]
        columns = [names.index(axis) for axis in "xyz"]
        if fmt == "ascii":
            lines = stream.read().split(b"\n")[skip:skip + count]
            table = np.array([line.split() for line in lines], dtype=float)
            return table[:, columns]
        dtype = np.dtype([(n, "<" + t) for t, n in properties])
        table = np.frombuffer(stream.read(count * dtype.itemsize), dtype=dtype, count=count)
        return np.stack([table[axis].astype(float) for axis in "xyz"], axis=1)


def read_text(path):
    """x y z in the first three columns (blanks or commas); non-numeric lines are skipped."""
    rows = []
    with open(path, encoding="utf-8", errors="replace") as stream:
        for line in stream:
            words = line.replace(",", " ").split()
            try:
                rows.append([float(w) for w in words[:3]])
            except ValueError:
                continue
    table = np.array([r for r in rows if len(r) == 3], dtype=float)
    return table.reshape(-1, 3)


def read_cloud(path):
    if path.lower().endswith(".ply"):
        return read_ply(path)
    if path.lower().endswith((".txt", ".xyz", ".csv", ".asc", ".pts")):
        return read_text(path)
    raise ValueError(f"{path}: only .ply and text x y z files are read")


# --- Geometry -----------------------------------------------------------------------------------
def fit_plane(points):
    """Least-squares plane (centre, unit normal) and the covariance's eigenvalues, ascending."""
    centre = points.mean(axis=0)
    values, vectors = np.linalg.eigh(np.cov((points - centre).T))
    return centre, vectors[:, 0], values


def plane_rms(points):
    centre, normal, _ = fit_plane(points)
    return float(np.sqrt(np.mean(((points - centre) @ normal) ** 2)))


def robust_sigma(distances):
    return 1.4826 * float(np.median(np.abs(distances)))


def nearest_indices(points, centre, count):
    """Indices of the count nearest points of centre (brute force: no scipy needed)."""
    squared = np.einsum("ij,ij->i", points - centre, points - centre)
    nearest = np.argpartition(squared, count)[:count]
    return nearest[np.argsort(squared[nearest], kind="stable")]


def median_spacing(points, rng, samples=SPACING_SAMPLES):
    """Median nearest-neighbour distance over a fixed-seed sample of points."""
    chosen = rng.choice(len(points), size=min(samples, len(points)), replace=False)
    found = []
    for start in range(0, len(chosen), 64):
        block = points[chosen[start:start + 64]]
        squared = ((points[None, :, :] - block[:, None, :]) ** 2).sum(axis=2)
        squared[np.arange(len(block)), chosen[start:start + 64]] = np.inf
        found.append(np.sqrt(squared.min(axis=1)))
    return float(np.median(np.concatenate(found)))


def lmeds_plane(points, rng, hypotheses=PATCH_HYPOTHESES):
    """RANSAC by least median of squares (needs no threshold): the plane through 3 sampled points
    whose median |distance| is smallest; returns (centre, normal)."""
    triples = np.array([rng.choice(len(points), 3, replace=False) for _ in range(hypotheses)])
    a, b, c = points[triples[:, 0]], points[triples[:, 1]], points[triples[:, 2]]
    normals = np.cross(b - a, c - a)
    lengths = np.linalg.norm(normals, axis=1)
    valid = lengths > 0
    normals, a = normals[valid] / lengths[valid, None], a[valid]
    distances = np.abs(np.einsum("hj,ij->hi", normals, points) - (normals * a).sum(1)[:, None])
    best = int(np.argmin(np.median(distances, axis=1)))
    return a[best], normals[best]


def quadric_rms(points, centre, normal):
    """RMS residual of the height over the plane fitted by a quadric of the in-plane
    coordinates, to tell a curved patch from a flat one."""
    helper = np.eye(3)[int(np.argmin(np.abs(normal)))]
    u = np.cross(normal, helper)
    u /= np.linalg.norm(u)
    v = np.cross(normal, u)
    local = points - centre
    x, y, h = local @ u, local @ v, local @ normal
    design = np.stack([x * x, x * y, y * y, x, y, np.ones_like(x)], axis=1)
    coefficients = np.linalg.lstsq(design, h, rcond=None)[0]
    return float(np.sqrt(np.mean((design @ coefficients - h) ** 2)))


# --- Structure on the input ---------------------------------------------------------------------
def planar_patch(points, indices, rng):
    """The inlier indices and robust sigma of a planar patch, or None if it is not one."""
    patch = points[indices]
    centre, normal = lmeds_plane(patch, rng)
    sigma = robust_sigma((patch - centre) @ normal)
    if sigma <= 0:
        return None
    inliers = np.abs((patch - centre) @ normal) < INLIER_SIGMAS * sigma
    if inliers.sum() < 10:
        return None
    centre, normal, values = fit_plane(patch[inliers])
    distances = (patch - centre) @ normal
    sigma = robust_sigma(distances[inliers])
    inliers = np.abs(distances) < INLIER_SIGMAS * sigma
    if inliers.mean() < PATCH_MIN_INLIERS or sigma <= 0:
        return None
    kept = patch[inliers]
    centre, normal, values = fit_plane(kept)
    if sigma > PATCH_MAX_THICKNESS * np.sqrt(values[1]):
        return None
    if plane_rms(kept) > PATCH_MAX_CURVATURE * quadric_rms(kept, centre, normal):
        return None
    return indices[inliers], sigma, centre, normal


def cell_keys(points, size):
    """One integer per grid cell of the given size: counting the distinct cells a plane's
    inliers occupy measures its area, not its number of points, so the dense patch at the foot
    of a scanner does not outweigh a sparse far wall."""
    cells = np.floor((points - points.min(axis=0)) / size).astype(np.int64)
    return (cells[:, 0] * 2097152 + cells[:, 1]) * 2097152 + cells[:, 2]


def spread_seeds(points, spacing, rng):
    """Seeds spread over the area, not over the points: one random point of each grid cell
    (PLANE_CELL_SPACINGS median spacings), the cells in a random order. Drawn over the points,
    the seeds of a terrestrial scan would all fall near the scanner, where it is densest."""
    order = rng.permutation(len(points))
    _, first = np.unique(cell_keys(points[order], PLANE_CELL_SPACINGS * spacing),
                         return_index=True)
    return order[first[rng.permutation(len(first))]]


def find_patches(points, spacing, rng):
    """Planar patches: seeds spread over the area in a fixed-seed order, a seed inside a kept
    patch skipped."""
    order = spread_seeds(points, spacing, rng)[:PATCH_SEEDS_TRIED]
    covered = np.zeros(len(points), dtype=bool)
    patches = []
    count = min(PATCH_POINTS, len(points) - 1)
    for seed in order:
        if covered[seed]:
            continue
        found = planar_patch(points, nearest_indices(points, points[seed], count), rng)
        if found is None:
            continue
        covered[found[0]] = True
        patches.append(found)
        if len(patches) == PATCH_COUNT:
            break
    return patches


def grow_plane(points, free, centre, normal, threshold):
    """The free points within threshold of a plane refitted by least squares on them, three
    times; the plane's sigma is then measured on its inliers."""
    for _ in range(3):
        inliers = np.flatnonzero(free & (np.abs((points - centre) @ normal) < threshold))
        if len(inliers) < 3:
            break
        centre, normal, _ = fit_plane(points[inliers])
    sigma = robust_sigma((points[inliers] - centre) @ normal) if len(inliers) else 0.0
    return {"centre": centre, "normal": normal, "inliers": inliers, "sigma": sigma}


def find_planes(points, patches, spacing, rng):
    """Large planes, one after another: among the patches' planes (the hypotheses), the one
    whose inliers among the free points (within PLANE_INLIER_SIGMAS x the patches' median
    sigma: one threshold for all, or a thick slab through clutter would win) cover the most
    grid cells, grown over the whole cloud (grow_plane); until the best covers under
    PLANE_MIN_FRACTION of the cells."""
    threshold = PLANE_INLIER_SIGMAS * float(np.median([p[1] for p in patches]))
    scoring = rng.choice(len(points), size=min(SCORING_POINTS, len(points)), replace=False)
    keys = cell_keys(points[scoring], PLANE_CELL_SPACINGS * spacing)
    minimum = PLANE_MIN_FRACTION * len(np.unique(keys))
    free = np.ones(len(points), dtype=bool)
    candidates = [(p[2], p[3]) for p in patches]
    planes = []
    while len(planes) < PLANE_MAX_COUNT and candidates:
        usable = free[scoring]
        sample, sample_keys = points[scoring][usable], keys[usable]
        areas = [len(np.unique(sample_keys[np.abs((sample - c) @ n) < threshold]))
                 for c, n in candidates]
        best = int(np.argmax(areas))
        if areas[best] < minimum:
            break
        plane = grow_plane(points, free, *candidates.pop(best), threshold)
        if len(plane["inliers"]) < 3:
            continue
        free[plane["inliers"]] = False
        planes.append(plane)
    return planes


def plane_line(first, second):
    """A point on the intersection line of two planes and its unit direction."""
    direction = np.cross(first["normal"], second["normal"])
    direction /= np.linalg.norm(direction)
    matrix = np.array([first["normal"], second["normal"], direction])
    rhs = np.array([first["normal"] @ first["centre"], second["normal"] @ second["centre"], 0.0])
    return np.linalg.solve(matrix, rhs), direction


def line_coordinates(points, origin, direction):
    """Position along the line and distance to it of each point."""
    local = points - origin
    along = local @ direction
    return along, np.linalg.norm(local - along[:, None] * direction, axis=1)


def corner_model_plane(points, plane, candidates, distance, low, high):
    """A plane of the two-plane model: refitted on its inliers between low and high from the
    line (away from the rounding a filter might do), the global plane if too few are there."""
    near = candidates[(distance >= low) & (distance < high)]
    if len(near) < 20:
        return plane["centre"], plane["normal"]
    centre, normal, _ = fit_plane(points[near])
    return centre, normal


def find_corner(points, owner, planes, pair, rng):
    """The band points and the two-plane model of the line where planes[pair] meet, or None."""
    first, second = planes[pair[0]], planes[pair[1]]
    if abs(first["normal"] @ second["normal"]) > np.cos(np.radians(CORNER_MIN_ANGLE)):
        return None
    origin, direction = plane_line(first, second)
    both = np.concatenate([first["inliers"], second["inliers"]])
    spacing = median_spacing(points[both], rng, samples=min(500, len(both)))
    band = max(BAND_SIGMAS * max(first["sigma"], second["sigma"]), BAND_SPACINGS * spacing)
    along, distance = line_coordinates(points, origin, direction)
    stretch = np.floor(along / (2 * band)).astype(np.int64)
    supported = None
    for plane in (first, second):
        near = plane["inliers"][distance[plane["inliers"]] < SUPPORT_BANDS * band]
        bins, counts = np.unique(stretch[near], return_counts=True)
        bins = set(bins[counts >= SUPPORT_MIN_POINTS].tolist())
        supported = bins if supported is None else supported & bins
    if not supported:
        return None
    on_line = np.isin(stretch, np.fromiter(supported, dtype=np.int64))
    band_points = np.flatnonzero(on_line & (distance < band) &
                                 ((owner < 0) | (owner == pair[0]) | (owner == pair[1])))
    if len(band_points) < CORNER_MIN_POINTS:
        return None
    model = []
    for plane in (first, second):
        candidates = plane["inliers"][on_line[plane["inliers"]]]
        model.append(corner_model_plane(points, plane, candidates, distance[candidates],
                                        FIT_BANDS[0] * band, FIT_BANDS[1] * band))
    return {"indices": band_points, "model": model, "band": band, "pair": pair}


def find_structure(points):
    """Patches, large planes and corner lines of the input, and the scales measured on it."""
    rng = np.random.default_rng(SEED)
    spacing = median_spacing(points, rng)
    patches = find_patches(points, spacing, rng)
    if not patches:
        raise ValueError("no planar patch found")
    planes = find_planes(points, patches, spacing, rng)
    owner = np.full(len(points), -1)
    for number, plane in enumerate(planes):
        owner[plane["inliers"]] = number
    corners = []
    for i in range(len(planes)):
        for j in range(i + 1, len(planes)):
            corner = find_corner(points, owner, planes, (i, j), rng)
            if corner is not None:
                corners.append(corner)
    return {"patches": patches, "planes": planes, "corners": corners,
            "spacing": spacing,
            "sigma": float(np.median([p[1] for p in patches]))}


# --- The metrics --------------------------------------------------------------------------------
def patch_residuals(points, structure):
    """Each patch's RMS distance of its inliers to their own least-squares plane."""
    return np.array([plane_rms(points[p[0]]) for p in structure["patches"]])


def corner_distances(points, structure):
    """Distance of each corner's band points to its fixed two-plane model, all lines pooled."""
    found = []
    for corner in structure["corners"]:
        band = points[corner["indices"]]
        (c1, n1), (c2, n2) = corner["model"]
        found.append(np.minimum(np.abs((band - c1) @ n1), np.abs((band - c2) @ n2)))
    return found


def evaluate(before, after, structure):
    """The plane and corner residuals before and after, and their ratios."""
    if after.shape != before.shape:
        raise ValueError(f"the filtered cloud has {len(after)} points, the input {len(before)}: "
                         "the metrics need the same points in the same order")
    plane_before = patch_residuals(before, structure)
    plane_after = patch_residuals(after, structure)
    sigmas = np.array([patch[1] for patch in structure["patches"]])
    thin = sigmas <= THIN_PATCH_SIGMAS * structure["sigma"]
    result = {"plane_before": float(np.median(plane_before)),
              "plane_after": float(np.median(plane_after)),
              "plane_ratio": float(np.median(plane_after / plane_before)),
              "thin_ratio": float(np.median(plane_after[thin] / plane_before[thin])),
              "thin_patches": int(thin.sum()),
              "corner_before": float("nan"), "corner_after": float("nan"),
              "corner_ratio": float("nan")}
    if structure["corners"]:
        rms = [float(np.sqrt(np.mean(np.concatenate(corner_distances(cloud, structure)) ** 2)))
               for cloud in (before, after)]
        result.update(corner_before=rms[0], corner_after=rms[1], corner_ratio=rms[1] / rms[0])
    return result


# --- Running pcbilateral and the table ----------------------------------------------------------
def parse_run_output(text):
    """The parameters pcbilateral says it used (its radius, normal radius and iterations lines)."""
    found = {}
    for key, label in (("radius", "r"), ("normal radius", "rn"), ("iterations", "N")):
        match = re.search(rf"^{key}:\s*([0-9.eE+-]+)", text, re.M)
        if match:
            found[label] = float(match.group(1))
    return found


def run_filter(program, source, arguments, folder):
    """Runs pcbilateral source -> a file in folder; returns (output path, parameters, seconds)."""
    output = os.path.join(folder, "filtered.ply")
    command = [program, source, output] + shlex.split(arguments)
    start = time.monotonic()
    done = subprocess.run(command, capture_output=True, text=True)
    seconds = time.monotonic() - start
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed: {done.stderr.strip() or done.stdout}")
    if "--remove-isolated" in arguments:
        raise ValueError("--remove-isolated changes the points: the metrics need them all")
    return output, parse_run_output(done.stdout), seconds


def describe(parameters):
    if not parameters:
        return "-"
    return ", ".join(f"{k} {v:.4g}" for k, v in parameters.items())


TABLE_HEADER = ("| run | parameters | plane before | plane after | plane ratio | plane ratio, thin "
                "patches (v2) | corner before | corner after | corner ratio | patches (thin) | "
                "corner lines | time (s) |\n"
                "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")


def table_row(label, parameters, result, structure, seconds):
    seconds_text = "-" if seconds is None else f"{seconds:.1f}"
    return (f"| {label} | {describe(parameters)} | {result['plane_before']:.3g} | "
            f"{result['plane_after']:.3g} | {result['plane_ratio']:.2f} | "
            f"{result['thin_ratio']:.2f} | "
            f"{result['corner_before']:.3g} | {result['corner_after']:.3g} | "
            f"{result['corner_ratio']:.2f} | {len(structure['patches'])} "
            f"({result['thin_patches']}) | "
            f"{len(structure['corners'])} | {seconds_text} |")


def summary(path, points, structure, seconds):
    lines = [f"{path}: {len(points)} points; structure found in {seconds:.1f} s: "
             f"{len(structure['patches'])} planar patches, {len(structure['planes'])} large "
             f"planes, {len(structure['corners'])} corner lines "
             f"({sum(len(c['indices']) for c in structure['corners'])} band points); median "
             f"nearest-neighbour distance s = {structure['spacing']:.4g}, patches' median "
             f"robust sigma = {structure['sigma']:.4g}"]
    return "\n".join(lines)


def grid_runs(structure):
    """(label, arguments) of the hand-tuning grid: r in median spacings, rn in noise sigmas."""
    spacing, sigma = structure["spacing"], structure["sigma"]
    runs = []
    for r in GRID_R:
        for rn in GRID_RN:
            for n in GRID_N:
                runs.append((f"grid r {r}s, rn {rn}sigma, N {n}",
                             f"-r {r * spacing:.9g} -n {rn * sigma:.9g} -N {n}"))
    return runs


def best_of_grid(rows):
    """The grid's best plane ratio among the runs whose corner ratio is at most CORNER_LIMIT."""
    allowed = [row for row in rows if row[0].startswith("grid") and
               (np.isnan(row[2]["corner_ratio"]) or row[2]["corner_ratio"] <= CORNER_LIMIT)]
    if not allowed:
        return f"no grid setting keeps the corner ratio at or under {CORNER_LIMIT}"
    lines = []
    for key, name in (("plane_ratio", "plane ratio"), ("thin_ratio", "plane ratio, thin patches")):
        label, parameters, result = min(allowed, key=lambda row: row[2][key])[:3]
        lines.append(f"best of the grid for the {name} with corner ratio <= {CORNER_LIMIT}: "
                     f"{label} ({describe(parameters)}): {name} {result[key]:.2f}, corner "
                     f"ratio {result['corner_ratio']:.2f}")
    return "\n".join(lines)


# --- Self-test ------------------------------------------------------------------------------------
def room_corner(rng, per_face=12000, sigma=0.004):
    """The clean points and the noise offsets of three unit squares meeting at right angles at
    the origin (the corner of a room), Gaussian noise of the given sigma along each face's
    normal."""
    clean, offsets = [], []
    for axis in range(3):
        face = rng.random((per_face, 3))
        face[:, axis] = 0.0
        noise = np.zeros_like(face)
        noise[:, axis] = rng.normal(0.0, sigma, per_face)
        clean.append(face)
        offsets.append(noise)
    return np.concatenate(clean), np.concatenate(offsets)


def round_edges(clean, radius):
    """The clean corner with each of its three edges rounded by a quarter-circle fillet of the
    given radius: a point of a face within radius of an edge moves onto the arc, the one at the
    edge onto the bisector, (1 - 1/sqrt 2) radius from each face."""
    rounded = clean.copy()
    for a, b in ((0, 1), (0, 2), (1, 2)):
        for face, other in ((a, b), (b, a)):
            near = (rounded[:, face] == 0.0) & (rounded[:, other] < radius)
            angle = (1.0 - rounded[near, other] / radius) * np.pi / 4
            rounded[near, face] = radius - radius * np.cos(angle)
            rounded[near, other] = radius - radius * np.sin(angle)
    return rounded


def write_ply(path, points, binary=True):
    """A PLY with double x y z and an extra property, to check the reader on both formats."""
    header = ["ply", f"format {'binary_little_endian' if binary else 'ascii'} 1.0",
              f"element vertex {len(points)}", "property double x", "property double y",
              "property double z", "property uchar flag", "element face 0",
              "property list uchar int vertex_indices", "end_header", ""]
    with open(path, "wb") as stream:
        stream.write("\n".join(header).encode("ascii"))
        if binary:
            table = np.zeros(len(points), dtype=[("x", "<f8"), ("y", "<f8"), ("z", "<f8"),
                                                 ("flag", "u1")])
            table["x"], table["y"], table["z"] = points.T
            stream.write(table.tobytes())
        else:
            stream.write("".join(f"{x!r} {y!r} {z!r} 7\n" for x, y, z in points).encode())


def self_test():
    """The metric on a generated room corner with known noise; returns the problems found."""
    sigma = 0.004
    rng = np.random.default_rng(7)
    clean, offsets = room_corner(rng, sigma=sigma)
    noisy = clean + offsets
    problems = []
    with tempfile.TemporaryDirectory() as folder:
        for binary in (True, False):
            path = os.path.join(folder, f"corner_{binary}.ply")
            write_ply(path, noisy, binary)
            if not np.array_equal(read_ply(path), noisy):
                problems.append(f"PLY reader ({'binary' if binary else 'ascii'}): wrong points")
    structure = find_structure(noisy)
    print(summary("generated corner", noisy, structure, 0.0))
    if len(structure["planes"]) != 3 or len(structure["corners"]) != 3:
        problems.append(f"{len(structure['planes'])} planes and {len(structure['corners'])} "
                        "corner lines found, 3 and 3 expected")
    cases = {"noise removed": clean, "edges rounded": round_edges(clean, 0.08) + offsets}
    results = {name: evaluate(noisy, cloud, structure) for name, cloud in cases.items()}
    for name, result in results.items():
        print(f"{name}: " + ", ".join(f"{k} {v:.4g}" for k, v in result.items()))
    plane = results["noise removed"]["plane_before"]
    if abs(plane / sigma - 1) > 0.15:
        problems.append(f"plane residual {plane:.4g}, not within 15% of the noise {sigma}")
    if not results["noise removed"]["plane_ratio"] < 0.05:
        problems.append("noise removed: plane ratio not near 0")
    if not results["noise removed"]["corner_ratio"] < 0.5:
        problems.append("noise removed: corner ratio not under 0.5")
    if not results["edges rounded"]["corner_ratio"] > 1.5:
        problems.append("edges rounded: corner ratio not above 1.5 (clearly above 1.15)")
    return problems


# --- Command line ---------------------------------------------------------------------------------
def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input", nargs="?", help="the input cloud (.ply, or text x y z)")
    parser.add_argument("--filtered", nargs="+", default=[], metavar="OUT",
                        help="filtered files of INPUT (same points, same order) to evaluate")
    parser.add_argument("--run", action="append", default=[], metavar="'LABEL: ARGS'",
                        help="run pcbilateral INPUT tmp.ply ARGS and evaluate (repeatable)")
    parser.add_argument("--grid", action="store_true", help="run the hand-tuning grid too")
    parser.add_argument("--pcbilateral", default=None, help="the program (default: "
                        "build/bin/pcbilateral of the repository)")
    parser.add_argument("--self-test", action="store_true", help="check the metric, exit status")
    arguments = parser.parse_args(argv)
    if not arguments.self_test and not arguments.input:
        parser.error("INPUT is needed (or --self-test)")
    if arguments.pcbilateral is None:
        repository = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
        arguments.pcbilateral = os.path.join(repository, "build", "bin", "pcbilateral")
    return arguments


def evaluate_all(arguments, points, structure):
    """The table's rows: (label, parameters, result, seconds) for each file and run."""
    rows = []
    for path in arguments.filtered:
        result = evaluate(points, read_cloud(path), structure)
        rows.append((os.path.basename(path), {}, result, None))
        print(table_row(os.path.basename(path), {}, result, structure, None), flush=True)
    runs = [tuple(part.strip() for part in run.split(":", 1)) if ":" in run else (run, run)
            for run in arguments.run]
    if arguments.grid:
        runs += grid_runs(structure)
    with tempfile.TemporaryDirectory() as folder:
        for label, run_arguments in runs:
            output, parameters, seconds = run_filter(arguments.pcbilateral, arguments.input,
                                                     run_arguments, folder)
            rows.append((label, parameters, evaluate(points, read_cloud(output), structure),
                         seconds))
            print(table_row(label, parameters, rows[-1][2], structure, seconds), flush=True)
    return rows


def main(argv):
    arguments = parse_arguments(argv)
    if arguments.self_test:
        problems = self_test()
        for problem in problems:
            print("FAILED:", problem)
        print("self-test passed" if not problems else "self-test failed")
        return 1 if problems else 0
    start = time.monotonic()
    points = read_cloud(arguments.input)
    structure = find_structure(points)
    print(summary(arguments.input, points, structure, time.monotonic() - start))
    print()
    print(TABLE_HEADER, flush=True)
    rows = evaluate_all(arguments, points, structure)
    if arguments.grid:
        print()
        print(best_of_grid(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

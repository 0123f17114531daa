"""pcbilateral --memory-limit with --copc-level and --copc-bounds: a COPC file's octree levels or
box, filtered in slabs, give the same file, byte for byte, the same warnings and the same points
as the run in memory, into LAS, LAZ, text and PCD; on a file that is not COPC, the run in
memory's warning and every point.

Cases (PDAL's COPC sample, shared/data/laz/1.2-with-color.copc.laz: 1,065 points of format 7 in
an octree of 4 levels, 8-bit colours in 16-bit fields): levels 0 to 1, 0 to 2 and every level
(-1), a box, a box with a level, a box that holds no point (the run in memory's error), with
--classes; several slab sizes and ranges of 37 points, which cut the octree's nodes; explicit
and automatic parameters; its twin 1.2-with-color.las (not COPC) and a PCD file with
--copc-level.

    CheckStreamingCOPC.py PCBILATERAL LAS_FOLDER SCRATCH
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from CheckStreaming import Checks  # noqa: E402
from CheckStreamingClasses import classified_survey, same_as_in_memory, write_pcd  # noqa: E402

BOX = ["--copc-bounds", "637000,638200.5,850000,852500,420,560"]


def main(program, folder, scratch):
    os.makedirs(scratch, exist_ok=True)
    c = Checks(program, scratch)
    copc = os.path.join(folder, "..", "laz", "1.2-with-color.copc.laz")
    twin = os.path.join(folder, "1.2-with-color.las")
    # (A radius that moves most points: 29 of level 2's 287, 136 of the box's 207.)
    explicit = ["-r", "150", "-n", "50", "-N", "1"]
    for name, part in (("level1", ["--copc-level", "1"]), ("level2", ["--copc-level", "2"]),
                       ("every-level", ["--copc-level", "-1"]), ("box", BOX),
                       ("box-level2", BOX + ["--copc-level", "2"])):
        for extension in (".las", ".laz", ".txt", ".pcd"):
            same_as_in_memory(c, f"{name}{extension}", copc, extension, part + explicit,
                              [0, 150] if name == "every-level" else [0, 150, 70],
                              range_points=37, classes=False)
    same_as_in_memory(c, "box-2-iterations", copc, ".laz", BOX + ["-r", "80", "-n", "50", "-N", "2"],
                      [0, 150], range_points=37, classes=False)
    same_as_in_memory(c, "level2-automatic", copc, ".las", ["--copc-level", "2"], [0],
                      range_points=37, classes=False)
    same_as_in_memory(c, "box-automatic", copc, ".laz", BOX, [0], range_points=37,
                      classes=False)
    same_as_in_memory(c, "box-classes", copc, ".las", BOX + explicit + ["--classes", "2"],
                      [0, 70], range_points=37)
    same_as_in_memory(c, "level2-classes", copc, ".pcd",
                      ["--copc-level", "2", "--classes", "1"] + explicit, [70], range_points=37)
    empty = ["--copc-bounds", "0,1,0,1,0,1"]
    same_as_in_memory(c, "empty-box", copc, ".las", empty + explicit, [0], classes=False)
    same_as_in_memory(c, "not-copc", twin, ".las", ["--copc-level", "1"] + explicit, [0, 150],
                      range_points=37, classes=False)
    pcd = os.path.join(scratch, "survey.pcd")
    write_pcd(pcd, *classified_survey(23), "binary")
    same_as_in_memory(c, "not-copc-pcd", pcd, ".pcd", BOX + ["-r", "1.2", "-N", "1"], [0, 8000],
                      classes=False)
    return 1 if c.failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))

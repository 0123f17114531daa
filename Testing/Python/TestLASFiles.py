"""The LAS reader and writer on every file of the LAS sample folder (PDAL's test files).

Each file is also decoded here, independently, with `struct` (the LAS 1.4 R15 layout): the
point count, the header's bounds, and the first and last points' coordinates, intensity,
return number, classification, scan angle (degrees), GPS time and colour must be what the
reader gives. Files whose header promises more than they hold must give one error line and no
points. Each readable file, written back by the writer, must have the same point records byte
for byte.

    python3 TestLASFiles.py LAS_FOLDER SCRATCH_FOLDER

Exits with 77 (skipped) when LAS_FOLDER is empty or missing.
"""
import glob
import math
import os
import struct
import sys

from pointcloudbilateral import vtkLASPointCloudReader, vtkLASPointCloudWriter
from vtkmodules.vtkCommonCore import vtkCommand

# The damaged files of the folder's README.md; the independent decoding below must agree.
DAMAGED = {"bad_vlr_count.las", "garbage_nVariableLength.las", "1.2-no-points.las"}


def decode(data):
    """The header and the first and last point records, or None for a damaged file."""
    if len(data) < 227 or data[:4] != b"LASF":
        return None
    minor = data[25]
    header_size, offset, vlr_count = struct.unpack_from("<HII", data, 94)
    point_format, length, count = struct.unpack_from("<BHI", data, 104)
    if minor >= 4:
        wide = struct.unpack_from("<Q", data, 247)[0]
        if wide or point_format > 5:
            count = wide
    at = header_size
    for _ in range(vlr_count):
        if at + 54 > offset:
            return None
        at += 54 + struct.unpack_from("<H", data, at + 20)[0]
        if at > offset:
            return None
    if offset > len(data) or count > (len(data) - offset) // length:
        return None
    scale = struct.unpack_from("<3d", data, 131)
    shift = struct.unpack_from("<3d", data, 155)
    mx, nx, my, ny, mz, nz = struct.unpack_from("<6d", data, 179)
    # The bounds of all the points (the header's may be wrong: spurious.las has a point
    # outside them, which is what it is for).
    bounds = (nx, mx, ny, my, nz, mz)
    if count:
        body = data[offset: offset + count * length]
        xyz = [struct.unpack_from("<3i", body, k * length) for k in range(count)]
        bounds = []
        for axis in range(3):
            values = [p[axis] for p in xyz]
            bounds += [min(values) * scale[axis] + shift[axis],
                       max(values) * scale[axis] + shift[axis]]
    header = dict(format=point_format, length=length, count=count, offset=offset, scale=scale,
                  bounds=tuple(bounds), header_bounds=(nx, mx, ny, my, nz, mz))
    points = []
    for index in (0, count - 1) if count else ():
        record = data[offset + index * length: offset + (index + 1) * length]
        xyz = struct.unpack_from("<3i", record, 0)
        point = dict(xyz=[xyz[k] * scale[k] + shift[k] for k in range(3)],
                     Intensity=struct.unpack_from("<H", record, 12)[0])
        if point_format <= 5:
            point["ReturnNumber"] = record[14] & 7
            point["Classification"] = record[15] & 31
            point["ScanAngleRank"] = struct.unpack_from("<b", record, 16)[0]
            gps_at = 20 if point_format in (1, 3, 4, 5) else None
            rgb_at = {2: 20, 3: 28, 5: 28}.get(point_format)
        else:
            point["ReturnNumber"] = record[14] & 15
            point["Classification"] = record[16]
            # Stored in units of 0.006 degree, read in degrees as a float.
            degrees = struct.unpack_from("<h", record, 18)[0] * 0.006
            point["ScanAngle"] = struct.unpack("<f", struct.pack("<f", degrees))[0]
            gps_at = 22
            rgb_at = 30 if point_format in (7, 8, 10) else None
        if gps_at is not None:
            point["GpsTime"] = struct.unpack_from("<d", record, gps_at)[0]
        if rgb_at is not None:
            point["RGB"] = list(struct.unpack_from("<3H", record, rgb_at))
        points.append((index, point))
    return header, points


def point_records(path):
    data = open(path, "rb").read()
    header, _ = decode(data)
    start = header["offset"]
    return data[start: start + header["count"] * header["length"]]


def same(a, b):
    return a == b or (isinstance(a, float) and math.isnan(a) and math.isnan(b))


def main():
    folder, scratch = sys.argv[1], sys.argv[2]
    files = sorted(glob.glob(os.path.join(folder, "*.las")) +
                   glob.glob(os.path.join(folder, "permutations", "*.las")))
    if not folder or not files:
        print(f"skipped: no LAS files in '{folder}' (set PCB_LAS_DATA_DIR)")
        return 77
    os.makedirs(scratch, exist_ok=True)
    failures = []

    def check(condition, message):
        if not condition:
            failures.append(message)
            print("FAILED:", message)

    for path in files:
        name = os.path.basename(path)
        expected = decode(open(path, "rb").read())
        check((expected is None) == (name in DAMAGED), f"{name}: the independent decoding "
              f"{'rejects' if expected is None else 'accepts'} it")
        reader = vtkLASPointCloudReader()
        reader.SetFileName(path)
        errors = []
        reader.AddObserver(vtkCommand.ErrorEvent, lambda *args: errors.append(1))
        reader.Update()
        cloud = reader.GetOutput()
        message = reader.GetErrorMessage()
        if expected is None:
            check(message.startswith(path) and "\n" not in message and len(errors) == 1,
                  f"{name}: damaged, but the error is '{message}' ({len(errors)} errors)")
            check(cloud.GetNumberOfPoints() == 0, f"{name}: points read from a damaged file")
            print(f"{name}: {message}")
            continue
        header, points = expected
        check(message == "", f"{name}: {message}")
        check(cloud.GetNumberOfPoints() == header["count"],
              f"{name}: {cloud.GetNumberOfPoints()} points, the header says {header['count']}")
        check(cloud.GetNumberOfVerts() == header["count"], f"{name}: one vertex per point")
        if header["count"]:
            bounds = cloud.GetBounds()
            check(bounds == header["bounds"],
                  f"{name}: bounds {bounds}, decoded here {header['bounds']}")
            if any(abs(bounds[k] - header["header_bounds"][k]) > header["scale"][k // 2]
                   for k in range(6)):
                print(f"{name}: note: the points go beyond the header's bounds "
                      f"{header['header_bounds']}")
        data = cloud.GetPointData()
        for index, point in points:
            check(list(cloud.GetPoint(index)) == point["xyz"],
                  f"{name}: point {index} at {cloud.GetPoint(index)}, expected {point['xyz']}")
            for field, value in point.items():
                if field == "xyz":
                    continue
                array = data.GetArray(field)
                got = (list(array.GetTuple(index)) if array.GetNumberOfComponents() > 1
                       else array.GetTuple1(index)) if array else None
                check(array is not None and (same(got, value) or got == value),
                      f"{name}: point {index}: {field} {got}, expected {value}")
        # Written back unchanged: the same point records.
        out = os.path.join(scratch, name)
        writer = vtkLASPointCloudWriter()
        writer.SetFileName(out)
        writer.SetInputData(cloud)
        writer.Write()
        check(writer.GetErrorMessage() == "", f"{name}: {writer.GetErrorMessage()}")
        if writer.GetErrorMessage() == "":
            check(point_records(out) == point_records(path),
                  f"{name}: the point records written differ from the file's")
        print(f"{name}: {header['count']} points, format {header['format']}: checked")
    print(f"{len(files)} files, {len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

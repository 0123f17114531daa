// The scale benchmark's tile generator (LidarTile.h): a tile written a block at a time reads
// back, LAS and LAZ, with the points the generator gives all at once; the LAS file has the
// bytes WriteLAS gives for all the points at once (the lidar20M file's way); the same count
// writes the same bytes twice.
#include "LidarTile.h"

#include "LASHeader.h"
#include "LASReader.h"
#include "LASWriter.h"
#include "LAZReader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace
{
using pcbilateral_benchmark::LidarTile;
using pcbilateral_benchmark::WriteLidarTile;

int failures = 0;

void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::fprintf(stderr, "FAILED: %s\n", what.c_str());
    ++failures;
  }
}

std::vector<char> Bytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The file's points, read back with the formats library.
std::vector<double> ReadBack(const std::string& path, std::uint64_t& count)
{
  pcbilateral::LASFileBytes file;
  pcbilateral::LASFileInfo info;
  count = 0;
  if (!file.Open(path).empty() ||
      !pcbilateral::ParseLASHeader(file.Data(), file.Size(), path, info, true).empty())
  {
    return {};
  }
  count = info.Header.NumberOfPoints;
  std::vector<std::uint8_t> decompressed;
  const std::uint8_t* records = nullptr;
  if (!pcbilateral::UncompressedLASRecords(
        file.Data(), file.Size(), info, path, decompressed, records)
         .empty())
  {
    count = 0;
    return {};
  }
  std::vector<double> xyz(3 * count);
  std::vector<void*> columns(info.Dimensions.size(), nullptr);
  pcbilateral::DecodeLASPoints(info, records, count, xyz.data(), columns.data());
  return xyz;
}

/// The whole tile in one block: what the in-memory benchmark uses.
std::vector<double> AllAtOnce(std::size_t points)
{
  std::vector<double> xyz(3 * points);
  LidarTile(points).Next(points, xyz.data());
  return xyz;
}

/// The lidar20M file's way: all the points at once through WriteLAS.
std::string WriteAllAtOnce(const std::string& path, const std::vector<double>& xyz)
{
  const std::size_t points = xyz.size() / 3;
  double bounds[6] = { 1e300, 1e300, 1e300, -1e300, -1e300, -1e300 };
  for (std::size_t i = 0; i < points; ++i)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      bounds[axis] = std::min(bounds[axis], xyz[3 * i + axis]);
      bounds[3 + axis] = std::max(bounds[3 + axis], xyz[3 * i + axis]);
    }
  }
  pcbilateral::LASFileInfo info = pcbilateral::DefaultLASFileInfo(points, bounds, true, false);
  for (int axis = 0; axis < 3; ++axis)
  {
    info.Header.Scale[axis] = 0.001;
  }
  const std::vector<const void*> zeros(info.Dimensions.size(), nullptr);
  return pcbilateral::WriteLAS(path, info, points, xyz.data(), zeros.data());
}

void CheckTile(const std::string& folder, std::size_t points)
{
  const std::string tag = std::to_string(points);
  const std::string las = folder + "/tile" + tag + ".las", laz = folder + "/tile" + tag + ".laz";
  const std::string again = folder + "/again" + tag + ".las",
                    once = folder + "/once" + tag + ".las";
  Check(WriteLidarTile(las, points).empty(), "writing " + las);
  Check(WriteLidarTile(laz, points).empty(), "writing " + laz);
  Check(WriteLidarTile(again, points).empty(), "writing " + again);
  const std::vector<double> expected = AllAtOnce(points);
  Check(WriteAllAtOnce(once, expected).empty(), "writing " + once);
  Check(Bytes(las) == Bytes(again), tag + " points: the same bytes twice");
  Check(Bytes(las) == Bytes(once), tag + " points: the bytes of WriteLAS given all points at once");
  for (const std::string& path : { las, laz })
  {
    std::uint64_t count = 0;
    const std::vector<double> xyz = ReadBack(path, count);
    Check(count == points && xyz.size() == expected.size(), path + ": the point count");
    double worst = xyz.size() == expected.size() ? 0.0 : 1.0;
    for (std::size_t i = 0; i < std::min(xyz.size(), expected.size()); ++i)
    {
      worst = std::max(worst, std::abs(xyz[i] - expected[i]));
    }
    Check(worst <= 0.0005 + 1e-9, path + ": the points within half a millimetre");
  }
  for (const std::string& path : { las, laz, again, once })
  {
    std::remove(path.c_str());
  }
}
} // namespace

int main(int argc, char* argv[])
{
  const std::string folder = argc > 1 ? argv[1] : ".";
  // Less than one block, and several blocks with a partial last one (and a partial LAZ chunk).
  CheckTile(folder, 12345);
  CheckTile(folder, 2 * 1000000 + 70001);
  Check(!WriteLidarTile(folder + "/no/such/folder/tile.laz", 10).empty(), "an unwritable path");
  Check(!WriteLidarTile(folder + "/empty.las", 0).empty(), "no points");
  if (failures == 0)
  {
    std::printf("the tile generator: passed\n");
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

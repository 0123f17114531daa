#include "LidarTile.h"

#include "LASHeader.h"
#include "LASWriteParts.h"
#include "LASWriter.h"
#include "LAZWriter.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

namespace pcbilateral_benchmark
{
namespace
{
constexpr double Width = 5000.0;
constexpr double Block = 60.0;
constexpr double OffsetX = 600000.0, OffsetY = 5000000.0, Noise = 0.05;
/// A whole number of LAZ chunks, so the LAZ file's chunks are all full but the last.
constexpr std::size_t PointsPerBlock = 20 * pcbilateral::LAZWrittenChunkSize;

double Ground(double x, double y)
{
  return 120.0 + 12.0 * std::sin(x / 700.0) * std::cos(y / 900.0) + 0.004 * x;
}

bool EndsWithLAZ(const std::string& path)
{
  if (path.size() < 4)
  {
    return false;
  }
  std::string end = path.substr(path.size() - 4);
  std::transform(
    end.begin(), end.end(), end.begin(), [](unsigned char c) { return std::tolower(c); });
  return end == ".laz";
}

/// The tile's header: its bounds set the offsets (a first pass over the generated points).
pcbilateral::LASFileInfo TileInfo(std::size_t points)
{
  double bounds[6] = { 1e300, 1e300, 1e300, -1e300, -1e300, -1e300 };
  LidarTile tile(points);
  std::vector<double> xyz(3 * std::min(points, PointsPerBlock));
  for (std::size_t done = 0; done < points;)
  {
    const std::size_t count = std::min(PointsPerBlock, points - done);
    tile.Next(count, xyz.data());
    for (std::size_t i = 0; i < count; ++i)
    {
      for (int axis = 0; axis < 3; ++axis)
      {
        bounds[axis] = std::min(bounds[axis], xyz[3 * i + axis]);
        bounds[3 + axis] = std::max(bounds[3 + axis], xyz[3 * i + axis]);
      }
    }
    done += count;
  }
  // Point format 1 (GPS time, no colour), millimetres: what airborne surveys deliver.
  pcbilateral::LASFileInfo info = pcbilateral::DefaultLASFileInfo(points, bounds, true, false);
  for (int axis = 0; axis < 3; ++axis)
  {
    info.Header.Scale[axis] = 0.001;
  }
  return info;
}

std::string WriteTileLAS(const std::string& path,
  const pcbilateral::LASFileInfo& info,
  std::size_t points)
{
  pcbilateral::LASStreamWriter writer;
  std::string problem = writer.Open(path, info, points);
  const std::vector<const void*> zeros(info.Dimensions.size(), nullptr);
  LidarTile tile(points);
  std::vector<double> xyz(3 * std::min(points, PointsPerBlock));
  for (std::size_t done = 0; done < points && problem.empty();)
  {
    const std::size_t count = std::min(PointsPerBlock, points - done);
    tile.Next(count, xyz.data());
    problem = writer.Append(count, xyz.data(), zeros.data());
    done += count;
  }
  return problem.empty() ? writer.Close() : problem;
}

bool WriteAt(std::FILE* file, std::uint64_t offset, const std::vector<std::uint8_t>& bytes)
{
  return fseeko(file, static_cast<off_t>(offset), SEEK_SET) == 0 &&
         std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
}

/// The chunks block by block after the head's place, then the chunk table and the head.
std::string WriteTileLAZChunks(std::FILE* file,
  const pcbilateral::LASFileInfo& info,
  std::size_t points)
{
  const pcbilateral::LASPartsLayout layout(info, points, true);
  if (!layout.Problem().empty())
  {
    return layout.Problem();
  }
  const std::vector<const void*> zeros(info.Dimensions.size(), nullptr);
  LidarTile tile(points);
  std::vector<double> xyz(3 * std::min(points, PointsPerBlock));
  pcbilateral::LASPartSummary whole;
  std::vector<std::uint64_t> chunkPoints, chunkBytes;
  std::uint64_t written = layout.PointDataOffset() + 8;
  for (std::size_t done = 0; done < points;)
  {
    const std::size_t count = std::min(PointsPerBlock, points - done);
    tile.Next(count, xyz.data());
    pcbilateral::LAZPart part;
    pcbilateral::LASPartSummary summary;
    const std::string problem = pcbilateral::CompressLAZPart(
      info, layout.Compression(), count, xyz.data(), zeros.data(), part, summary);
    if (!problem.empty())
    {
      return problem;
    }
    if (!WriteAt(file, written, part.Bytes))
    {
      return std::string("write failed (") + std::strerror(errno) + ")";
    }
    pcbilateral::MergeLASPartSummary(whole, summary);
    chunkPoints.insert(chunkPoints.end(), part.ChunkPoints.begin(), part.ChunkPoints.end());
    chunkBytes.insert(chunkBytes.end(), part.ChunkBytes.begin(), part.ChunkBytes.end());
    written += part.Bytes.size();
    done += count;
  }
  std::vector<std::uint8_t> tail = pcbilateral::EncodeLAZChunkTable(chunkPoints, chunkBytes, true);
  const std::uint64_t tableOffset = written;
  const std::uint64_t pointBytes = tableOffset - layout.PointDataOffset() + tail.size();
  std::vector<std::uint8_t> head = layout.Head(whole, pointBytes);
  for (int b = 0; b < 8; ++b)
  {
    head.push_back(static_cast<std::uint8_t>(tableOffset >> (8 * b)));
  }
  const std::vector<std::uint8_t> evlrs = layout.Tail();
  tail.insert(tail.end(), evlrs.begin(), evlrs.end());
  if (!WriteAt(file, tableOffset, tail) || !WriteAt(file, 0, head))
  {
    return std::string("write failed (") + std::strerror(errno) + ")";
  }
  return std::string();
}

std::string WriteTileLAZ(const std::string& path,
  const pcbilateral::LASFileInfo& info,
  std::size_t points)
{
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file)
  {
    return path + ": cannot open for writing (" + std::strerror(errno) + ")";
  }
  std::string problem = WriteTileLAZChunks(file, info, points);
  if (std::fclose(file) != 0 && problem.empty())
  {
    problem = std::string("write failed (") + std::strerror(errno) + ")";
  }
  if (!problem.empty())
  {
    std::remove(path.c_str());
    return path + ": " + problem;
  }
  return problem;
}
} // namespace

LidarTile::LidarTile(std::size_t points)
  : Generator(20171029)
  , Depth(static_cast<double>(points) / Width)
{
}

void LidarTile::Next(std::size_t count, double* xyz)
{
  for (std::size_t i = 0; i < count; ++i)
  {
    const double x = this->Generator.Uniform(0.0, Width);
    const double y = this->Generator.Uniform(0.0, this->Depth);
    double z = Ground(x, y);
    // The block's building, from a hash of the block's indices (the same for every point).
    const auto bx = static_cast<std::uint64_t>(x / Block);
    const auto by = static_cast<std::uint64_t>(y / Block);
    std::uint64_t h = (bx * 0x9E3779B97F4A7C15ull) ^ (by * 0xC2B2AE3D27D4EB4Full);
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 32;
    if ((h & 1) != 0)
    {
      const double size = 15.0 + static_cast<double>((h >> 8) % 31);
      const double height = 4.0 + static_cast<double>((h >> 16) % 22);
      const double lx = x - bx * Block, ly = y - by * Block;
      const double margin = (Block - size) / 2.0;
      if (lx > margin && lx < Block - margin && ly > margin && ly < Block - margin)
      {
        // Ground level at the block's centre: roofs are flat.
        z = Ground((bx + 0.5) * Block, (by + 0.5) * Block) + height;
      }
    }
    xyz[3 * i] = OffsetX + x;
    xyz[3 * i + 1] = OffsetY + y;
    xyz[3 * i + 2] = z + Noise * this->Generator.Gaussian();
  }
}

std::string WriteLidarTile(const std::string& path, std::size_t points)
{
  if (points == 0)
  {
    return path + ": a tile needs at least one point";
  }
  const pcbilateral::LASFileInfo info = TileInfo(points);
  return EndsWithLAZ(path) ? WriteTileLAZ(path, info, points) : WriteTileLAS(path, info, points);
}

} // namespace pcbilateral_benchmark

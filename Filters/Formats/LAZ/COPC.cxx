#include "COPC.h"

#include "LASBinary.h"
#include "LAZReader.h"
#include "PointPieces.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>
#include <set>
#include <tuple>
#include <utility>

namespace pcbilateral
{

namespace
{
using las::Load;
using las::Str;

constexpr std::size_t InfoBytes = 160;
constexpr std::size_t EntryBytes = 32;
/// Deeper keys would overflow the 32-bit key coordinates (2^level cells per axis).
constexpr std::int32_t DeepestLevel = 30;

const LASRecord* FindInfoRecord(const LASFileInfo& info)
{
  for (const LASRecord& record : info.VLRs)
  {
    if (record.UserId == "copc" && record.RecordId == 1)
    {
      return &record;
    }
  }
  return nullptr;
}

std::string DecodeInfo(const LASFileInfo& file, COPCInfo& info)
{
  const LASRecord* record = FindInfoRecord(file);
  if (!record)
  {
    return "not a COPC file: no COPC info record (VLR \"copc\" 1)";
  }
  if (record->Data.size() != InfoBytes)
  {
    return "the COPC info record holds " + Str(record->Data.size()) + " bytes, not 160";
  }
  const std::uint8_t* at = record->Data.data();
  for (int axis = 0; axis < 3; ++axis)
  {
    info.Center[axis] = Load<double>(at + 8 * axis);
  }
  info.HalfSize = Load<double>(at + 24);
  info.Spacing = Load<double>(at + 32);
  info.RootPageOffset = Load<std::uint64_t>(at + 40);
  info.RootPageSize = Load<std::uint64_t>(at + 48);
  info.GpsTimeMinimum = Load<double>(at + 56);
  info.GpsTimeMaximum = Load<double>(at + 64);
  const bool finite = std::isfinite(info.Center[0]) && std::isfinite(info.Center[1]) &&
                      std::isfinite(info.Center[2]) && std::isfinite(info.HalfSize);
  if (!finite || !(info.HalfSize > 0))
  {
    return "the COPC info record's octree centre or size is not a finite positive cube";
  }
  const int format = file.Header.PointFormat;
  if (format < 6 || format > 8)
  {
    return "a COPC file holds point format 6, 7 or 8, not " + Str(format);
  }
  return std::string();
}

/// Where a page lies; the error says which page is meant.
std::string CheckPage(std::uint64_t offset, std::uint64_t bytes, std::size_t size)
{
  const std::string page =
    "the COPC hierarchy page of " + Str(bytes) + " bytes at byte " + Str(offset);
  if (bytes == 0 || bytes % EntryBytes != 0)
  {
    return page + " is not a whole number of 32-byte entries";
  }
  if (offset > size || bytes > size - offset)
  {
    return page + " lies beyond the end of the file (" + Str(size) + " bytes)";
  }
  return std::string();
}

struct Entry
{
  std::int32_t Key[4] = { 0, 0, 0, 0 };
  std::uint64_t Offset = 0;
  std::int32_t Bytes = 0;
  std::int32_t Points = 0;
};

Entry DecodeEntry(const std::uint8_t* at)
{
  Entry entry;
  for (int i = 0; i < 4; ++i)
  {
    entry.Key[i] = Load<std::int32_t>(at + 4 * i);
  }
  entry.Offset = Load<std::uint64_t>(at + 16);
  entry.Bytes = Load<std::int32_t>(at + 24);
  entry.Points = Load<std::int32_t>(at + 28);
  return entry;
}

std::string KeyName(const Entry& entry)
{
  return std::to_string(entry.Key[0]) + "-" + std::to_string(entry.Key[1]) + "-" +
         std::to_string(entry.Key[2]) + "-" + std::to_string(entry.Key[3]);
}

std::string CheckKey(const Entry& entry)
{
  const std::int32_t level = entry.Key[0];
  if (level < 0 || level > DeepestLevel)
  {
    return "a COPC hierarchy entry has level " + std::to_string(level);
  }
  const std::int64_t cells = std::int64_t(1) << level;
  for (int axis = 1; axis < 4; ++axis)
  {
    if (entry.Key[axis] < 0 || entry.Key[axis] >= cells)
    {
      return "the COPC node " + KeyName(entry) + " lies outside its level's " + Str(cells) +
             " cells per axis";
    }
  }
  return std::string();
}

/// Walks the pages, checking each entry, and gathers the nodes holding points.
class HierarchyWalk
{
public:
  HierarchyWalk(const std::uint8_t* data, std::size_t size, const std::vector<LAZChunk>& chunks)
    : Data(data)
    , Size(size)
    , Chunks(chunks)
    , Used(chunks.size(), false)
  {
  }

  std::string Run(std::uint64_t rootOffset, std::uint64_t rootBytes, COPCHierarchy& hierarchy);

private:
  std::string Visit(const Entry& entry, COPCHierarchy& hierarchy);
  std::string AddNode(const Entry& entry, COPCHierarchy& hierarchy);

  const std::uint8_t* Data;
  std::size_t Size;
  const std::vector<LAZChunk>& Chunks;
  std::vector<bool> Used;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> Pending;
  std::set<std::uint64_t> PagesSeen;
  std::set<std::tuple<std::int32_t, std::int32_t, std::int32_t, std::int32_t>> KeysSeen;
  std::uint64_t PageBytes = 0;
};

std::string HierarchyWalk::Run(std::uint64_t rootOffset,
  std::uint64_t rootBytes,
  COPCHierarchy& hierarchy)
{
  this->Pending.emplace_back(rootOffset, rootBytes);
  while (!this->Pending.empty())
  {
    const auto [offset, bytes] = this->Pending.back();
    this->Pending.pop_back();
    std::string problem = CheckPage(offset, bytes, this->Size);
    if (problem.empty() && !this->PagesSeen.insert(offset).second)
    {
      problem = "the COPC hierarchy page at byte " + Str(offset) +
                " is referred to twice (the pages form a loop)";
    }
    // Pages of a valid file do not overlap, so together they cannot exceed the file.
    this->PageBytes += bytes;
    if (problem.empty() && this->PageBytes > this->Size)
    {
      problem = "the COPC hierarchy pages add up to more bytes than the file holds";
    }
    for (std::uint64_t at = offset; problem.empty() && at < offset + bytes; at += EntryBytes)
    {
      problem = this->Visit(DecodeEntry(this->Data + at), hierarchy);
    }
    if (!problem.empty())
    {
      return problem;
    }
    ++hierarchy.Pages;
  }
  return std::string();
}

std::string HierarchyWalk::Visit(const Entry& entry, COPCHierarchy& hierarchy)
{
  std::string problem = CheckKey(entry);
  if (!problem.empty())
  {
    return problem;
  }
  if (entry.Points == -1)
  {
    if (entry.Bytes <= 0)
    {
      return "the COPC node " + KeyName(entry) + " refers to a child page of " +
             std::to_string(entry.Bytes) + " bytes";
    }
    this->Pending.emplace_back(entry.Offset, static_cast<std::uint64_t>(entry.Bytes));
    return std::string();
  }
  if (!this->KeysSeen.emplace(entry.Key[0], entry.Key[1], entry.Key[2], entry.Key[3]).second)
  {
    return "the COPC node " + KeyName(entry) + " is listed twice";
  }
  if (entry.Points < -1)
  {
    return "the COPC node " + KeyName(entry) + " has " + std::to_string(entry.Points) + " points";
  }
  return entry.Points == 0 ? std::string() : this->AddNode(entry, hierarchy);
}

std::string HierarchyWalk::AddNode(const Entry& entry, COPCHierarchy& hierarchy)
{
  const auto found = std::partition_point(this->Chunks.begin(),
    this->Chunks.end(),
    [&](const LAZChunk& chunk) { return chunk.Offset < entry.Offset; });
  const std::string node = "the COPC node " + KeyName(entry) + " (" + std::to_string(entry.Points) +
                           " points, " + std::to_string(entry.Bytes) + " bytes at byte " +
                           Str(entry.Offset) + ")";
  if (found == this->Chunks.end() || found->Offset != entry.Offset)
  {
    return node + " does not start a chunk of the LAZ chunk table";
  }
  if (found->Bytes != static_cast<std::uint64_t>(entry.Bytes) ||
      found->Points != static_cast<std::uint64_t>(entry.Points))
  {
    return node + " is not its chunk of the LAZ chunk table (" + Str(found->Points) + " points, " +
           Str(found->Bytes) + " bytes)";
  }
  if (found->Points > LAZMostPointsPerByte * found->Bytes + 1)
  {
    return node + ": impossible in so few compressed bytes";
  }
  const auto index = static_cast<std::size_t>(found - this->Chunks.begin());
  if (this->Used[index])
  {
    return node + " shares its chunk with another node";
  }
  this->Used[index] = true;
  COPCNode added;
  added.Level = entry.Key[0];
  added.X = entry.Key[1];
  added.Y = entry.Key[2];
  added.Z = entry.Key[3];
  added.Chunk = *found;
  added.ChunkIndex = index;
  hierarchy.Nodes.push_back(added);
  hierarchy.Levels = std::max(hierarchy.Levels, added.Level + 1);
  return std::string();
}
} // namespace

bool IsCOPC(const LASFileInfo& info)
{
  return FindInfoRecord(info) != nullptr;
}

std::string ReadCOPCHierarchy(const std::uint8_t* data,
  std::size_t size,
  const LASFileInfo& info,
  const std::string& sourceName,
  COPCHierarchy& hierarchy)
{
  hierarchy = COPCHierarchy();
  std::string problem = DecodeInfo(info, hierarchy.Info);
  LAZParameters parameters;
  std::vector<LAZChunk> chunks;
  const LASHeader& h = info.Header;
  if (problem.empty())
  {
    problem = ParseLAZParameters(info.LASzipRecord, h.PointFormat, h.RecordLength, parameters);
  }
  if (problem.empty())
  {
    problem =
      ReadLAZChunkTable(data, size, h.OffsetToPointData, h.NumberOfPoints, parameters, chunks);
  }
  if (problem.empty())
  {
    HierarchyWalk walk(data, size, chunks);
    problem = walk.Run(hierarchy.Info.RootPageOffset, hierarchy.Info.RootPageSize, hierarchy);
  }
  std::uint64_t points = 0;
  for (const COPCNode& node : hierarchy.Nodes)
  {
    points += node.Chunk.Points;
  }
  if (problem.empty() && points != h.NumberOfPoints)
  {
    problem = "the COPC hierarchy's nodes hold " + Str(points) + " points, the header says " +
              Str(h.NumberOfPoints);
  }
  std::sort(hierarchy.Nodes.begin(),
    hierarchy.Nodes.end(),
    [](const COPCNode& a, const COPCNode& b) { return a.ChunkIndex < b.ChunkIndex; });
  return problem.empty() ? problem : sourceName + ": " + problem;
}

void COPCNodeBounds(const COPCInfo& info, const COPCNode& node, double bounds[6])
{
  const double edge = 2 * info.HalfSize / std::ldexp(1.0, node.Level);
  const std::int32_t key[3] = { node.X, node.Y, node.Z };
  for (int axis = 0; axis < 3; ++axis)
  {
    bounds[2 * axis] = info.Center[axis] - info.HalfSize + key[axis] * edge;
    bounds[2 * axis + 1] = bounds[2 * axis] + edge;
  }
}

std::vector<COPCNode> SelectCOPCNodes(const COPCHierarchy& hierarchy,
  const LASHeader& header,
  const COPCQuery& query)
{
  std::vector<COPCNode> chosen;
  for (const COPCNode& node : hierarchy.Nodes)
  {
    if (query.MaxLevel >= 0 && node.Level > query.MaxLevel)
    {
      continue;
    }
    bool meets = true;
    if (query.UseBounds)
    {
      double cube[6];
      COPCNodeBounds(hierarchy.Info, node, cube);
      for (int axis = 0; axis < 3; ++axis)
      {
        const double margin = std::abs(header.Scale[axis]);
        meets = meets && cube[2 * axis] - margin <= query.Bounds[2 * axis + 1] &&
                cube[2 * axis + 1] + margin >= query.Bounds[2 * axis];
      }
    }
    if (meets)
    {
      chosen.push_back(node);
    }
  }
  return chosen;
}

std::vector<COPCNode> COPCPieceOfNodes(const std::vector<COPCNode>& chosen, int piece, int pieces)
{
  std::uint64_t total = 0;
  for (const COPCNode& node : chosen)
  {
    total += node.Chunk.Points;
  }
  const PointRange share = PieceOfPoints(total, piece, pieces);
  std::vector<COPCNode> own;
  std::uint64_t first = 0;
  for (const COPCNode& node : chosen)
  {
    if (first >= share.First && first - share.First < share.Count)
    {
      own.push_back(node);
    }
    first += node.Chunk.Points;
  }
  return own;
}

std::uint64_t KeepCOPCPointsInside(const LASHeader& h,
  const double bounds[6],
  std::uint8_t* records,
  std::uint64_t count)
{
  std::uint64_t kept = 0;
  for (std::uint64_t i = 0; i < count; ++i)
  {
    const std::uint8_t* record = records + i * h.RecordLength;
    bool inside = true;
    for (int axis = 0; axis < 3; ++axis)
    {
      const double value = Load<std::int32_t>(record + 4 * axis) * h.Scale[axis] + h.Offset[axis];
      inside = inside && value >= bounds[2 * axis] && value <= bounds[2 * axis + 1];
    }
    if (inside)
    {
      if (kept != i)
      {
        std::memmove(records + kept * h.RecordLength, record, h.RecordLength);
      }
      ++kept;
    }
  }
  return kept;
}

std::string ReadCOPCPoints(const std::uint8_t* data,
  std::size_t size,
  const LASFileInfo& info,
  const std::string& sourceName,
  const COPCQuery& query,
  std::vector<std::uint8_t>& records,
  std::uint64_t& count)
{
  records.clear();
  count = 0;
  COPCHierarchy hierarchy;
  std::string problem = ReadCOPCHierarchy(data, size, info, sourceName, hierarchy);
  if (!problem.empty())
  {
    return problem;
  }
  std::vector<LAZChunk> chunks;
  const std::vector<COPCNode> chosen = SelectCOPCNodes(hierarchy, info.Header, query);
  for (const COPCNode& node : COPCPieceOfNodes(chosen, query.Piece, query.NumberOfPieces))
  {
    chunks.push_back(node.Chunk);
    count += node.Chunk.Points;
  }
  const LASHeader& h = info.Header;
  try
  {
    records.resize(count * h.RecordLength);
  }
  catch (const std::bad_alloc&)
  {
    return sourceName + ": not enough memory for " + Str(count) + " points";
  }
  problem = DecompressLAZChunks(data, info, sourceName, chunks, records.data());
  if (problem.empty() && query.UseBounds)
  {
    count = KeepCOPCPointsInside(h, query.Bounds, records.data(), count);
    records.resize(count * h.RecordLength);
  }
  if (!problem.empty())
  {
    records.clear();
    count = 0;
  }
  return problem;
}

} // namespace pcbilateral

// COPC reading (COPC.h) on PDAL's COPC sample (shared/data/laz/1.2-with-color.copc.laz, 1,065
// points of format 7 in 65 octree nodes of 4 levels) and its LAS twin (shared/data/las,
// format 3, another order): every level gives the points of its nodes and those above, a box
// gives exactly the twin's points inside it, and a damaged hierarchy gives a one-line error.
//   TestCOPC CASE LAS_DATA_DIR   (the LAZ files are in LAS_DATA_DIR/../laz)
#include "CoreTesting.h"
#include "LASPointKey.h"

#include "COPC.h"
#include "LASReader.h"
#include "LAZReader.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>
#include <vector>

namespace
{
std::string LASFolder;

std::string COPCPath()
{
  return LASFolder + "/../laz/1.2-with-color.copc.laz";
}

std::vector<std::uint8_t> FileBytes(const std::string& path)
{
  const std::string text = pcbilateral_testing::FileContents(path);
  return std::vector<std::uint8_t>(text.begin(), text.end());
}

struct Read
{
  pcbilateral::LASFileInfo Info;
  std::vector<std::uint8_t> Records;
  std::uint64_t Count = 0;
  std::string Error;
};

/// The points of a COPC file (held in `bytes`) that `query` asks for.
Read ReadCOPC(const std::vector<std::uint8_t>& bytes, const pcbilateral::COPCQuery& query)
{
  Read result;
  result.Error = pcbilateral::ParseLASHeader(bytes.data(), bytes.size(), "copc", result.Info, true);
  if (result.Error.empty())
  {
    result.Error = pcbilateral::ReadCOPCPoints(
      bytes.data(), bytes.size(), result.Info, "copc", query, result.Records, result.Count);
  }
  return result;
}

std::multiset<std::string> Keys(const pcbilateral::LASHeader& h,
  const std::uint8_t* records,
  std::uint64_t count)
{
  std::multiset<std::string> keys;
  for (std::uint64_t i = 0; i < count; ++i)
  {
    keys.insert(PointKey(h, records + i * h.RecordLength));
  }
  return keys;
}

/// The twin's points inside a box (all of them without one), found by testing every point.
std::multiset<std::string> TwinKeys(const double* box)
{
  const std::vector<std::uint8_t> bytes = FileBytes(LASFolder + "/1.2-with-color.las");
  pcbilateral::LASFileInfo info;
  const std::string error =
    pcbilateral::ParseLASHeader(bytes.data(), bytes.size(), "twin", info, true);
  PCB_CHECK(error.empty(), "%s", error.c_str());
  const pcbilateral::LASHeader& h = info.Header;
  std::multiset<std::string> keys;
  for (std::uint64_t i = 0; error.empty() && i < h.NumberOfPoints; ++i)
  {
    const std::uint8_t* record = bytes.data() + h.OffsetToPointData + i * h.RecordLength;
    bool inside = true;
    for (int axis = 0; box && axis < 3; ++axis)
    {
      std::int32_t stored;
      std::memcpy(&stored, record + 4 * axis, 4);
      const double value = stored * h.Scale[axis] + h.Offset[axis];
      inside = inside && value >= box[2 * axis] && value <= box[2 * axis + 1];
    }
    if (inside)
    {
      keys.insert(PointKey(h, record));
    }
  }
  return keys;
}

pcbilateral::COPCHierarchy Hierarchy(const std::vector<std::uint8_t>& bytes,
  pcbilateral::LASFileInfo& info)
{
  pcbilateral::COPCHierarchy hierarchy;
  std::string error = pcbilateral::ParseLASHeader(bytes.data(), bytes.size(), "copc", info, true);
  if (error.empty())
  {
    error = pcbilateral::ReadCOPCHierarchy(bytes.data(), bytes.size(), info, "copc", hierarchy);
  }
  PCB_CHECK(error.empty(), "%s", error.c_str());
  return hierarchy;
}

/// Level -1 without a box: every point, in file order, the same records as plain LAZ reading,
/// and the twin's points.
void AllPoints()
{
  const std::vector<std::uint8_t> bytes = FileBytes(COPCPath());
  const Read copc = ReadCOPC(bytes, pcbilateral::COPCQuery());
  PCB_CHECK(copc.Error.empty(), "%s", copc.Error.c_str());
  std::vector<std::uint8_t> plain(copc.Info.Header.NumberOfPoints * copc.Info.Header.RecordLength);
  const std::string error = pcbilateral::DecompressLAZPoints(bytes.data(),
    bytes.size(),
    copc.Info,
    "copc",
    0,
    copc.Info.Header.NumberOfPoints,
    plain.data());
  PCB_CHECK(error.empty() && copc.Count == 1065 && copc.Records == plain,
    "%llu points, %s the records of plain LAZ reading",
    static_cast<unsigned long long>(copc.Count),
    copc.Records == plain ? "" : "not");
  PCB_CHECK(Keys(copc.Info.Header, copc.Records.data(), copc.Count) == TwinKeys(nullptr),
    "the COPC file's points are not its twin's");
}

/// Prints the octree; each level L gives exactly the records of the nodes of level L or less,
/// in file order, and their counts add up.
void Levels()
{
  const std::vector<std::uint8_t> bytes = FileBytes(COPCPath());
  pcbilateral::LASFileInfo info;
  const pcbilateral::COPCHierarchy hierarchy = Hierarchy(bytes, info);
  const Read all = ReadCOPC(bytes, pcbilateral::COPCQuery());
  std::vector<std::uint64_t> perLevel(static_cast<std::size_t>(hierarchy.Levels), 0);
  std::printf("%zu nodes, %d levels, %zu pages; halfsize %g, spacing %g\n",
    hierarchy.Nodes.size(),
    hierarchy.Levels,
    hierarchy.Pages,
    hierarchy.Info.HalfSize,
    hierarchy.Info.Spacing);
  for (const pcbilateral::COPCNode& node : hierarchy.Nodes)
  {
    std::printf("  %d-%d-%d-%d: %llu points at byte %llu\n",
      node.Level,
      node.X,
      node.Y,
      node.Z,
      static_cast<unsigned long long>(node.Chunk.Points),
      static_cast<unsigned long long>(node.Chunk.Offset));
    perLevel[static_cast<std::size_t>(node.Level)] += node.Chunk.Points;
  }
  PCB_CHECK(hierarchy.Levels == 4 && hierarchy.Nodes.size() == 65,
    "%d levels and %zu nodes, expected 4 and 65",
    hierarchy.Levels,
    hierarchy.Nodes.size());
  std::uint64_t upTo = 0;
  const std::size_t length = info.Header.RecordLength;
  for (int level = 0; level < hierarchy.Levels; ++level)
  {
    upTo += perLevel[static_cast<std::size_t>(level)];
    pcbilateral::COPCQuery query;
    query.MaxLevel = level;
    const Read read = ReadCOPC(bytes, query);
    std::vector<std::uint8_t> expected;
    for (const pcbilateral::COPCNode& node : hierarchy.Nodes)
    {
      const auto begin = all.Records.begin() + static_cast<long>(node.Chunk.FirstPoint * length);
      if (node.Level <= level)
      {
        expected.insert(
          expected.end(), begin, begin + static_cast<long>(node.Chunk.Points * length));
      }
    }
    std::printf("level %d: %llu points (%llu of this level)\n",
      level,
      static_cast<unsigned long long>(read.Count),
      static_cast<unsigned long long>(perLevel[static_cast<std::size_t>(level)]));
    PCB_CHECK(read.Error.empty() && read.Count == upTo && read.Records == expected,
      "level %d: %llu points, expected %llu (%s)",
      level,
      static_cast<unsigned long long>(read.Count),
      static_cast<unsigned long long>(upTo),
      read.Error.c_str());
  }
  PCB_CHECK(perLevel[0] > 0 && perLevel[0] < 1065 && upTo == 1065,
    "level 0 holds %llu points, all levels %llu",
    static_cast<unsigned long long>(perLevel[0]),
    static_cast<unsigned long long>(upTo));
}

/// Boxes give the twin's points inside them, decoding fewer nodes than the whole file.
void Bounds()
{
  const std::vector<std::uint8_t> bytes = FileBytes(COPCPath());
  pcbilateral::LASFileInfo info;
  const pcbilateral::COPCHierarchy hierarchy = Hierarchy(bytes, info);
  const double* b = info.Header.Bounds; // min x, min y, min z, max x, max y, max z
  const double boxes[][6] = {
    { b[0], b[3], b[1], b[4], b[2], b[5] },
    { b[0], 0.5 * (b[0] + b[3]), b[1], 0.5 * (b[1] + b[4]), b[2], b[5] },
    { 638000, 638500.25, 851500, 852000, 400, 450 },
    { b[0] + 100, b[0] + 300, b[4] - 400, b[4] - 100, -1e9, 1e9 },
    { 0, 1, 0, 1, 0, 1 },
  };
  for (const auto& box : boxes)
  {
    pcbilateral::COPCQuery query;
    query.UseBounds = true;
    std::copy(box, box + 6, query.Bounds);
    const Read read = ReadCOPC(bytes, query);
    const std::multiset<std::string> expected = TwinKeys(box);
    const std::size_t nodes = pcbilateral::SelectCOPCNodes(hierarchy, info.Header, query).size();
    std::printf("box %.2f %.2f %.2f %.2f %.2f %.2f: %llu points (twin: %zu), %zu of %zu nodes\n",
      box[0],
      box[1],
      box[2],
      box[3],
      box[4],
      box[5],
      static_cast<unsigned long long>(read.Count),
      expected.size(),
      nodes,
      hierarchy.Nodes.size());
    PCB_CHECK(
      read.Error.empty() && Keys(read.Info.Header, read.Records.data(), read.Count) == expected,
      "the box's points are not the twin's inside it (%s)",
      read.Error.c_str());
    PCB_CHECK(&box == &boxes[0] || nodes < hierarchy.Nodes.size(), "no node was culled");
  }
}

/// Pieces of a distributed read decode whole nodes of their own: put end to end they are the
/// one-piece read, record for record, and each chosen node is decoded by exactly one piece.
void Pieces()
{
  const std::vector<std::uint8_t> bytes = FileBytes(COPCPath());
  pcbilateral::LASFileInfo info;
  const pcbilateral::COPCHierarchy hierarchy = Hierarchy(bytes, info);
  pcbilateral::COPCQuery levelOne;
  levelOne.MaxLevel = 1;
  pcbilateral::COPCQuery box;
  box.UseBounds = true;
  const double corner[6] = { 637000, 638200.5, 850000, 852500, 420, 560 };
  std::copy(corner, corner + 6, box.Bounds);
  pcbilateral::COPCQuery deepest;
  deepest.MaxLevel = 3;
  for (pcbilateral::COPCQuery query : { levelOne, box, deepest })
  {
    const Read whole = ReadCOPC(bytes, query);
    const std::vector<pcbilateral::COPCNode> chosen =
      pcbilateral::SelectCOPCNodes(hierarchy, info.Header, query);
    for (int pieces : { 2, 3, 7 })
    {
      std::vector<std::uint8_t> joined;
      std::size_t decoded = 0;
      std::size_t largest = 0;
      for (int piece = 0; piece < pieces; ++piece)
      {
        query.Piece = piece;
        query.NumberOfPieces = pieces;
        const Read part = ReadCOPC(bytes, query);
        PCB_CHECK(part.Error.empty(), "%s", part.Error.c_str());
        joined.insert(joined.end(), part.Records.begin(), part.Records.end());
        const std::size_t own = pcbilateral::COPCPieceOfNodes(chosen, piece, pieces).size();
        decoded += own;
        largest = std::max(largest, own);
      }
      std::printf("level %d, box %d, %d pieces: %llu points; %zu of %zu nodes decoded, at most "
                  "%zu by one piece\n",
        query.MaxLevel,
        query.UseBounds ? 1 : 0,
        pieces,
        static_cast<unsigned long long>(whole.Count),
        decoded,
        chosen.size(),
        largest);
      PCB_CHECK(joined == whole.Records, "the pieces end to end are not the one-piece read");
      PCB_CHECK(decoded == chosen.size(), "a node was decoded by more than one piece, or none");
      PCB_CHECK(largest < chosen.size(), "one piece decoded every chosen node");
    }
  }
}

/// A damaged copy of the file gives one line naming it and the problem.
void ExpectError(std::vector<std::uint8_t> bytes, const char* fragment)
{
  pcbilateral::COPCQuery query;
  query.MaxLevel = 1;
  const Read read = ReadCOPC(bytes, query);
  PCB_CHECK(read.Error.rfind("copc: ", 0) == 0 && read.Error.find(fragment) != std::string::npos &&
              read.Error.find('\n') == std::string::npos && read.Count == 0,
    "expected one line about '%s', got '%s'",
    fragment,
    read.Error.c_str());
  std::printf("%s\n", read.Error.c_str());
}

template<typename T>
void Put(std::vector<std::uint8_t>& bytes, std::size_t at, T value)
{
  if (at + sizeof(T) > bytes.size())
  {
    std::fprintf(stderr, "Put: byte %zu is beyond the %zu bytes of the file\n", at, bytes.size());
    std::abort(); // a mistake of the test's own
  }
  std::memcpy(bytes.data() + at, &value, sizeof(T));
}

/// The sample with its hierarchy cut into pages, as large files have: the root page holds the
/// root node and a child-page entry (count -1) for each level-1 node, whose page holds that
/// node and its descendants. The pages replace the hierarchy EVLR's data (the file's end).
std::vector<std::uint8_t> SplitIntoPages(const std::vector<std::uint8_t>& good)
{
  constexpr std::size_t rootOffsetAt = 429 + 40;
  std::uint64_t root;
  std::uint64_t rootBytes;
  std::memcpy(&root, good.data() + rootOffsetAt, 8);
  std::memcpy(&rootBytes, good.data() + rootOffsetAt + 8, 8);
  PCB_CHECK(root + rootBytes == good.size(), "the hierarchy is not at the end of the file");
  std::vector<std::array<std::uint8_t, 32>> entries(rootBytes / 32);
  for (std::size_t k = 0; k < entries.size(); ++k)
  {
    std::memcpy(entries[k].data(), good.data() + root + 32 * k, 32);
  }
  auto key = [](const std::array<std::uint8_t, 32>& e, int i)
  {
    std::int32_t value;
    std::memcpy(&value, e.data() + 4 * i, 4);
    return value;
  };
  std::vector<std::array<std::uint8_t, 32>> rootPage;
  std::vector<std::vector<std::array<std::uint8_t, 32>>> children;
  for (const auto& e : entries)
  {
    if (key(e, 0) == 0)
    {
      rootPage.push_back(e);
    }
    if (key(e, 0) == 1)
    {
      rootPage.push_back(e); // its offset and counts are set below
      children.emplace_back();
      for (const auto& d : entries)
      {
        const int shift = key(d, 0) - 1;
        if (shift >= 0 && (key(d, 1) >> shift) == key(e, 1) && (key(d, 2) >> shift) == key(e, 2) &&
            (key(d, 3) >> shift) == key(e, 3))
        {
          children.back().push_back(d);
        }
      }
    }
  }
  std::vector<std::uint8_t> bytes(good.begin(), good.begin() + static_cast<long>(root));
  std::uint64_t at = root + 32 * rootPage.size();
  std::size_t child = 0;
  for (auto& e : rootPage)
  {
    if (key(e, 0) == 1)
    {
      const auto pageBytes = static_cast<std::int32_t>(32 * children[child++].size());
      std::memcpy(e.data() + 16, &at, 8);
      std::memcpy(e.data() + 24, &pageBytes, 4);
      const std::int32_t minusOne = -1;
      std::memcpy(e.data() + 28, &minusOne, 4);
      at += static_cast<std::uint64_t>(pageBytes);
    }
    bytes.insert(bytes.end(), e.begin(), e.end());
  }
  for (const auto& page : children)
  {
    for (const auto& e : page)
    {
      bytes.insert(bytes.end(), e.begin(), e.end());
    }
  }
  const std::uint64_t newRootBytes = 32 * rootPage.size();
  const std::uint64_t evlrBytes = bytes.size() - root;
  std::memcpy(bytes.data() + rootOffsetAt + 8, &newRootBytes, 8);
  std::memcpy(bytes.data() + root - 60 + 20, &evlrBytes, 8); // the EVLR's length
  return bytes;
}

/// A hierarchy in pages gives the same nodes and points as in one page; a child page pointing
/// back to the root is a loop.
void ChildPages()
{
  const std::vector<std::uint8_t> one = FileBytes(COPCPath());
  const std::vector<std::uint8_t> paged = SplitIntoPages(one);
  pcbilateral::LASFileInfo info;
  const pcbilateral::COPCHierarchy hierarchy = Hierarchy(paged, info);
  std::printf(
    "%zu pages, %zu nodes, %d levels\n", hierarchy.Pages, hierarchy.Nodes.size(), hierarchy.Levels);
  PCB_CHECK(hierarchy.Pages == 5 && hierarchy.Nodes.size() == 65 && hierarchy.Levels == 4,
    "%zu pages, %zu nodes",
    hierarchy.Pages,
    hierarchy.Nodes.size());
  for (int level = -1; level < 4; ++level)
  {
    pcbilateral::COPCQuery query;
    query.MaxLevel = level;
    query.UseBounds = level == 2;
    const double box[6] = { 637000, 638200.5, 850000, 852500, 420, 560 };
    std::copy(box, box + 6, query.Bounds);
    const Read a = ReadCOPC(one, query);
    const Read b = ReadCOPC(paged, query);
    PCB_CHECK(b.Error.empty() && a.Count == b.Count && a.Records == b.Records,
      "level %d: %llu points in pages, %llu in one page (%s)",
      level,
      static_cast<unsigned long long>(b.Count),
      static_cast<unsigned long long>(a.Count),
      b.Error.c_str());
  }
  std::vector<std::uint8_t> loop = paged;
  std::uint64_t root;
  std::uint64_t rootBytes;
  std::memcpy(&root, paged.data() + 429 + 40, 8);
  std::memcpy(&rootBytes, paged.data() + 429 + 48, 8);
  const std::size_t last = paged.size() - 32; // the last child page's last entry
  Put<std::uint64_t>(loop, last + 16, root);
  Put<std::int32_t>(loop, last + 24, static_cast<std::int32_t>(rootBytes));
  Put<std::int32_t>(loop, last + 28, -1);
  ExpectError(loop, "(the pages form a loop)");
  std::vector<std::uint8_t> lying = paged;
  Put<std::int32_t>(lying, static_cast<std::size_t>(root) + 32 + 24, 1 << 20); // a page's size
  ExpectError(lying, "lies beyond the end of the file");
}

void Damaged()
{
  const std::vector<std::uint8_t> good = FileBytes(COPCPath());
  // The info VLR's data starts at byte 429 (375 + 54); its root page offset is at 40 in it.
  constexpr std::size_t rootOffsetAt = 429 + 40;
  std::uint64_t root;
  std::uint64_t rootBytes;
  std::memcpy(&root, good.data() + rootOffsetAt, 8);
  std::memcpy(&rootBytes, good.data() + rootOffsetAt + 8, 8);
  auto entry = [&](int index) { return static_cast<std::size_t>(root + 32 * index); };

  std::vector<std::uint8_t> bytes = good;
  Put<std::uint64_t>(bytes, rootOffsetAt, good.size() + 100);
  ExpectError(bytes, "lies beyond the end of the file");
  bytes = good;
  Put<std::uint64_t>(bytes, rootOffsetAt + 8, 33);
  ExpectError(bytes, "not a whole number of 32-byte entries");
  bytes = good;
  Put<std::int32_t>(bytes, entry(0) + 24, 600); // the root node's byte size lies
  ExpectError(bytes, "is not its chunk of the LAZ chunk table");
  bytes = good;
  Put<std::int32_t>(bytes, entry(1) + 28, 20); // a point count lies
  ExpectError(bytes, "is not its chunk");
  bytes = good;
  Put<std::uint64_t>(bytes, entry(2) + 16, 1718); // an offset inside a chunk
  ExpectError(bytes, "does not start a chunk");
  bytes = good;
  // The last entry becomes a child page: the root page itself, a loop.
  const int last = static_cast<int>(rootBytes / 32) - 1;
  Put<std::uint64_t>(bytes, entry(last) + 16, root);
  Put<std::int32_t>(bytes, entry(last) + 24, static_cast<std::int32_t>(rootBytes));
  Put<std::int32_t>(bytes, entry(last) + 28, -1);
  ExpectError(bytes, "(the pages form a loop)");
  bytes = good;
  Put<std::int32_t>(bytes, entry(3) + 28, 0); // a node emptied: its points are not counted
  ExpectError(bytes, "nodes hold 1048 points, the header says 1065");
  bytes = good;
  Put<std::int32_t>(bytes, entry(4) + 4, 9); // x beyond the 8 cells of level 3
  ExpectError(bytes, "lies outside its level's 8 cells per axis");
  bytes = good;
  std::memcpy(bytes.data() + entry(5), bytes.data() + entry(6), 16); // a key twice
  ExpectError(bytes, "is listed twice");
  bytes = good;
  Put<double>(bytes, 429 + 24, -1.0);
  ExpectError(bytes, "not a finite positive cube");
  ExpectError(FileBytes(LASFolder + "/../laz/simple.laz"), "not a COPC file");
}
} // namespace

int main(int argc, char* argv[])
{
  LASFolder = argc > 2 ? argv[2] : ".";
  return RunNamedCase(argc,
    argv,
    {
      { "all-points", AllPoints },
      { "levels", Levels },
      { "bounds", Bounds },
      { "pieces", Pieces },
      { "damaged-hierarchy", Damaged },
      { "child-pages", ChildPages },
    });
}

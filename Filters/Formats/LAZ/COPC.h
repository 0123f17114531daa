// COPC (Cloud Optimized Point Cloud, version 1.0): a LAZ 1.4 file of point format 6, 7 or 8
// whose variable-size chunks are the nodes of an octree, described by the "copc" info VLR
// (record 1) and the hierarchy pages (EVLR "copc" 1000). Reading a level of detail or the
// points inside a box decodes only the chunks of the nodes chosen. Plain C++17, no VTK types.
#ifndef pcbilateral_COPC_h
#define pcbilateral_COPC_h

#include "LASHeader.h"
#include "LAZFormat.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcbilateral
{

/// The COPC info VLR, decoded.
struct COPCInfo
{
  /// The centre of the root node, in real (scaled and offset) coordinates.
  double Center[3] = { 0, 0, 0 };
  /// Half the edge of the root node (a cube).
  double HalfSize = 0;
  /// The distance between points at the root level, halved at each level.
  double Spacing = 0;
  std::uint64_t RootPageOffset = 0;
  std::uint64_t RootPageSize = 0;
  double GpsTimeMinimum = 0;
  double GpsTimeMaximum = 0;
};

/// A node of the octree that holds points: its key, and the LAZ chunk holding its points.
struct COPCNode
{
  std::int32_t Level = 0;
  std::int32_t X = 0;
  std::int32_t Y = 0;
  std::int32_t Z = 0;
  /// The chunk, as ReadLAZChunkTable gives it (offset, bytes, points, first point).
  LAZChunk Chunk;
  /// Its index in the file's chunk table.
  std::size_t ChunkIndex = 0;
};

/// The whole octree: the nodes holding points, in file order (that of their chunks).
struct COPCHierarchy
{
  COPCInfo Info;
  std::vector<COPCNode> Nodes;
  /// The number of levels (the deepest node's level plus one).
  int Levels = 0;
  /// The hierarchy pages read (one, or more when pages refer to child pages).
  std::size_t Pages = 0;
};

/// Which points of a COPC file to read.
struct COPCQuery
{
  /// The deepest level read; -1 for every level.
  int MaxLevel = -1;
  /// Whether only the points inside Bounds are read.
  bool UseBounds = false;
  /// xmin, xmax, ymin, ymax, zmin, zmax in real coordinates; a point on a face is inside.
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  /// The share of a distributed read (VTK's pieces, one per MPI rank): piece Piece of
  /// NumberOfPieces gets whole nodes (COPCPieceOfNodes); one piece is every chosen node.
  int Piece = 0;
  int NumberOfPieces = 1;
};

/// Whether a file ParseLASHeader accepted has a COPC info VLR (user "copc", record 1).
bool IsCOPC(const LASFileInfo& info);

/**
 * Decodes and checks a COPC file's octree: the info VLR (160 bytes, a positive finite size),
 * point format 6 to 8, every hierarchy page inside the file and a whole number of 32-byte
 * entries, no page read twice (a loop), keys within their level, no key twice, each node's
 * offset, byte size and point count those of a chunk of the LAZ chunk table, no chunk twice, and
 * the nodes' points adding up to the header's count. Returns an empty string, or a one-line
 * message starting with `sourceName`.
 */
std::string ReadCOPCHierarchy(const std::uint8_t* data,
  std::size_t size,
  const LASFileInfo& info,
  const std::string& sourceName,
  COPCHierarchy& hierarchy);

/// A node's cube: xmin, xmax, ymin, ymax, zmin, zmax in real coordinates.
void COPCNodeBounds(const COPCInfo& info, const COPCNode& node, double bounds[6]);

/**
 * The nodes `query` asks for: those of level MaxLevel or less, and with UseBounds those whose
 * cube, widened by one coordinate step of the file (a writer may place a point on a face of its
 * node, rounded), meets the box. In file order.
 */
std::vector<COPCNode> SelectCOPCNodes(const COPCHierarchy& hierarchy,
  const LASHeader& header,
  const COPCQuery& query);

/**
 * Piece `piece` of `pieces` of the nodes `chosen` (in file order): the nodes whose first point,
 * counted over `chosen`, lies in that piece's PieceOfPoints share of their points. Each piece
 * decodes only its own nodes, contiguous and in file order, so that the pieces put end to end
 * are the one-piece read; a node is not split, so the counts differ by up to a node's points.
 */
std::vector<COPCNode> COPCPieceOfNodes(const std::vector<COPCNode>& chosen, int piece, int pieces);

/// Keeps the records (`h`'s layout) whose real coordinates (integer times scale plus offset) lie
/// inside `bounds` (xmin, xmax, ymin, ymax, zmin, zmax; a point on a face is inside), moved to
/// the front in order; returns their count.
std::uint64_t KeepCOPCPointsInside(const LASHeader& h,
  const double bounds[6],
  std::uint8_t* records,
  std::uint64_t count);

/**
 * Reads the points of a COPC file `query` asks for: ReadCOPCHierarchy, SelectCOPCNodes,
 * COPCPieceOfNodes for the query's piece, then only those nodes' chunks are decompressed (in
 * parallel, DecompressLAZChunks), and with UseBounds only the points whose real coordinates
 * (integer times scale plus offset) lie inside the box are kept. `records` gets the points' records
 * in file order, `count` of them. Returns an empty string or a one-line message starting with
 * `sourceName`.
 */
std::string ReadCOPCPoints(const std::uint8_t* data,
  std::size_t size,
  const LASFileInfo& info,
  const std::string& sourceName,
  const COPCQuery& query,
  std::vector<std::uint8_t>& records,
  std::uint64_t& count);

} // namespace pcbilateral

#endif

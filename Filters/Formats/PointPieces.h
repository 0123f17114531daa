// The share of a file's points that one piece of a distributed read holds (VTK's streaming
// pieces, one per MPI rank under ParaView). Plain C++17.
#ifndef pcbilateral_PointPieces_h
#define pcbilateral_PointPieces_h

#include <cstdint>

namespace pcbilateral
{

/// Points [First, First + Count) of a file.
struct PointRange
{
  std::uint64_t First = 0;
  std::uint64_t Count = 0;
};

/**
 * Piece `piece` of `pieces` of `total` points: [floor(piece * total / pieces),
 * floor((piece + 1) * total / pieces)), contiguous, in file order, every point in exactly one
 * piece, the counts differing by at most one. One piece (or none asked for: pieces < 1) is the
 * whole file; a piece number outside [0, pieces) holds no point.
 */
inline PointRange PieceOfPoints(std::uint64_t total, int piece, int pieces)
{
  if (pieces <= 1)
  {
    return piece == 0 || pieces < 1 ? PointRange{ 0, total } : PointRange{ total, 0 };
  }
  if (piece < 0 || piece >= pieces)
  {
    return PointRange{ total, 0 };
  }
  // floor(p * total / n) without overflow: p * (total / n) + floor(p * (total % n) / n).
  const auto n = static_cast<std::uint64_t>(pieces);
  const auto start = [&](std::uint64_t p) { return p * (total / n) + p * (total % n) / n; };
  const auto p = static_cast<std::uint64_t>(piece);
  return PointRange{ start(p), start(p + 1) - start(p) };
}

} // namespace pcbilateral

#endif

// What a run keeps by point id while it iterates, shared by the paper's scheduler and the
// edge-aware mode. Plain C++17, no VTK types.
#ifndef pcbilateral_PointState_h
#define pcbilateral_PointState_h

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcbilateral
{

/// Where a removed point stopped, by id.
struct StoppedPoint
{
  std::uint32_t Id;
  double Position[3];
};

/// What a run keeps by point id, besides the octree's layout.
struct PointState
{
  /// Positions; a removed point's is set to where it stopped. May be empty while the octree
  /// holds the points (a whole cloud's run: the positions are then not held twice); removed
  /// points are then listed in Stopped instead.
  std::vector<double> Positions;
  std::vector<StoppedPoint> Stopped;
  /// Estimated normals, when asked for (else empty).
  std::vector<double> Normals;
  std::vector<std::uint8_t> Removed;
  const double* OrientationNormals = nullptr;
  /// Ids from this one on are ghosts: neighbours only, never filtered, never moved.
  std::size_t FirstGhost = 0;
};

} // namespace pcbilateral

#endif

// The points every room of the core reads, and their bounding box. Plain C++17, no VTK types.
#ifndef pcbilateral_PointCloudView_h
#define pcbilateral_PointCloudView_h

#include <cmath>
#include <cstddef>

namespace pcbilateral
{

/// Whether a point's three coordinates are finite: others (NaN, infinities) are passed through
/// and never neighbours.
inline bool IsFinitePoint(const double p[3])
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

/// The points to filter. Arrays are interleaved x y z, NumberOfPoints triples.
struct PointCloudView
{
  std::size_t NumberOfPoints = 0;
  const double* Positions = nullptr;
  /// Optional: each estimated normal is flipped to agree with this one.
  const double* OrientationNormals = nullptr;
};

/// The finite points of a cloud and their bounding box (NaN and infinite points are left out).
struct CloudExtent
{
  std::size_t NumberOfFinitePoints = 0;
  double Min[3] = { 0.0, 0.0, 0.0 };
  double Max[3] = { 0.0, 0.0, 0.0 };
  double LargestExtent() const;
  /// The largest absolute value of a coordinate.
  double LargestMagnitude() const;
  /// Whether both corners are finite.
  bool IsFinite() const;
};

/// The extent of the finite points among a cloud's points.
CloudExtent MeasureCloud(const PointCloudView& cloud);

/// MeasureCloud, asking the calling thread's progress scope (ProgressPoint) whether to stop
/// every 65,536 points: on a stop, `stopped` is set and the extent is that of the points seen.
CloudExtent MeasureCloudUnlessStopped(const PointCloudView& cloud, bool& stopped);
/// The extent of two parts of one cloud together.
CloudExtent MergeExtents(const CloudExtent& a, const CloudExtent& b);

/// Whether p lies in box (xmin, xmax, ymin, ymax, zmin, zmax), bounds included.
inline bool InsideBox(const double box[6], const double p[3])
{
  return p[0] >= box[0] && p[0] <= box[1] && p[1] >= box[2] && p[1] <= box[3] && p[2] >= box[4] &&
         p[2] <= box[5];
}

} // namespace pcbilateral

#endif

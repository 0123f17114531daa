// A radius that follows the density (the automatic mode on unevenly sampled clouds, beyond the
// paper): each point's radius from its local spacing, rounded to bands a factor sqrt(2) apart,
// and which points a band's run needs as neighbours. Plain C++17, no VTK types.
//
// Why bands and not one radius per point: a band is a set of points that share one radius, so
// it runs through the paper's scheduler unchanged (the octree and its colour classes are built
// for one radius), with every other point within its reach as a neighbour only (a ghost, as in
// a distributed run). Each iteration runs every band on the positions the last iteration wrote;
// a point's result then depends on its band's radius and on the positions of the points within
// that radius alone, as in the fixed-radius filter, so it is the same bits for any number of
// threads, any order of the points and any split into parts (see docs/parameters.md).
#ifndef pcbilateral_RadiusBands_h
#define pcbilateral_RadiusBands_h

#include "CloudMeasurement.h"
#include "PointCloudView.h"

#include <cstddef>
#include <cstdint>
#include <unordered_set>
#include <vector>

namespace pcbilateral
{
struct BilateralParameters;

struct RadiusBands
{
  /// Band b has radius Radius[b] and normal radius NormalRadius[b], in increasing radius.
  std::vector<double> Radius;
  std::vector<double> NormalRadius;
  /// Each point's band; NoBand for a point that is not finite.
  std::vector<std::uint16_t> BandOfPoint;
  static constexpr std::uint16_t NoBand = 0xffff;

  bool Empty() const { return this->Radius.empty(); }
  double SmallestRadius() const { return this->Radius.front(); }
  double LargestRadius() const { return this->Radius.back(); }
};

/// The bands of the points of `cloud` where the radius follows the density
/// (RadiusFollowsDensity): each point's radius is the radius `chosen` for the whole cloud (at
/// its SurfaceSpacing, by the paper's rule or the edge-aware mode's) scaled as the paper's rule
/// (RadiusAt) scales from that spacing to the point's local spacing, rounded in a geometric
/// sequence of ratio sqrt(2) through the chosen radius, so that equal spacings give equal radii
/// in every part of a distributed cloud. Bands that no point uses are left out.
RadiusBands AssignRadiusBands(const PointCloudView& cloud,
  const CloudScales& scales,
  const BilateralParameters& userParameters,
  const BilateralParameters& chosen,
  int threads);

/// Whether a position lies within `reach` of one of a set of points (more precisely: in one of
/// the cells of size `reach` that hold one of them, or of their 26 neighbour cells, so some
/// positions up to 2 sqrt(3) reach away pass too: a band's run ignores neighbours beyond its
/// radius, so a few too many cost only time).
class NearPoints
{
public:
  /// `origin`: a corner of the cloud, so that cell coordinates stay small.
  NearPoints(const std::vector<double>& positions, double reach, const double origin[3]);
  bool Near(const double p[3]) const;

private:
  std::int64_t CellOf(const double p[3], int axis) const;
  double Reach;
  double Origin[3];
  std::unordered_set<std::uint64_t> Cells;
};

} // namespace pcbilateral

#endif

// How the point spacing varies across a cloud: the local spacing around any position, read from
// the nearest-neighbour distances of the measurement's samples on a coarse grid. Plain C++17,
// no VTK types.
//
// Why a coarse grid and not a search per point: a scan from one position is sampled 100 to 300
// times more densely next to the scanner than on its far walls, and the density changes over
// distances much larger than the filter's radius. The samples (8192 points chosen by
// a hash of their coordinates, the same in every process of a distributed run) see that change;
// a table over 64 cells along the cloud's largest extent reads it back for every point at the
// cost of one lookup, where a nearest-neighbour search per point would cost about one filter
// iteration at a small radius.
#ifndef pcbilateral_SpacingField_h
#define pcbilateral_SpacingField_h

#include "PointCloudView.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcbilateral
{

class SpacingField
{
public:
  /// Cells along the largest extent of the samples' bounding box.
  static constexpr int CellsAlongLargestExtent = 64;
  /// A cell's value is the median of at least this many samples, weighted by the area each
  /// covers and clipped at twice their plain median: those of the cell and of the rings of
  /// cells around it, grown until they hold that many.
  /// (The median of 24 nearest-neighbour distances of points spread at random varies by about 12%:
  /// an evenly sampled cloud's field then spreads over about 1.5 times.)
  static constexpr std::size_t FewestSamples = 24;

  SpacingField() = default;

  /**
   * The field of the samples at `positions` (interleaved x y z) with their nearest-neighbour
   * distances (`distances`, one per sample; those not finite or not above 0, e.g. a point with
   * a duplicate, are left out). The result depends on the set of samples alone, not on their
   * order or on the number of threads (0: all cores). Not valid when fewer than FewestSamples
   * samples are usable or they have no extent.
   */
  SpacingField(const std::vector<double>& positions,
    const std::vector<double>& distances,
    int threads = 0);

  bool IsValid() const { return !this->SortedDistances.empty(); }

  /// The local nearest-neighbour distance around p (clamped to the grid when p lies outside).
  double At(const double p[3]) const;

  /// At() for each point of a cloud (0 for points that are not finite). Parallel; the values do
  /// not depend on the number of threads.
  std::vector<double> AtPoints(const PointCloudView& cloud, int threads) const;

  /// The ratio of the 95th to the 5th percentile of the field at the samples, each sample
  /// weighted by the area its point covers (the square of its spacing; isolated samples, whose
  /// own nearest neighbour is 4 times farther than the field there, left out): how many times
  /// the spacing varies across the surface.
  double GetSpread() const;
  /// The median of the field at the samples, each weighted by the area its point covers (the
  /// square of its spacing): the spacing of most of the surface, not of most of the points.
  double GetAreaWeightedMedian() const { return this->AreaWeightedMedian; }

private:
  std::size_t CellIndex(const double p[3]) const;
  /// The percentiles by area of the field's values at the (not isolated) samples.
  void ReadPercentiles(std::vector<double> atSamples);
  /// The clipped median by area of the usable samples' distances in the cells around `cell`, out
  /// to the first ring that brings the count to FewestSamples.
  double MedianAround(std::size_t cell) const;

  double Origin[3] = { 0.0, 0.0, 0.0 };
  double CellSize = 0.0;
  std::int64_t Dimensions[3] = { 0, 0, 0 };
  /// The usable samples' distances grouped by cell: cell c's are SortedDistances[CellStart[c]]
  /// to SortedDistances[CellStart[c + 1] - 1].
  std::vector<std::uint32_t> CellStart;
  std::vector<double> SortedDistances;
  double LowPercentile = 0.0;
  double HighPercentile = 0.0;
  double AreaWeightedMedian = 0.0;
};

} // namespace pcbilateral

#endif

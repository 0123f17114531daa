// Filtering only some of a cloud's points (for example some LiDAR classes): the chosen points
// are filtered as a cloud of their own, the others keep their exact coordinates and are no
// one's neighbours, so that no class pulls another. Plain C++17, no VTK types.
#ifndef pcbilateral_ChosenPoints_h
#define pcbilateral_ChosenPoints_h

#include "BilateralFilter.h"
#include "PointCloudView.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcbilateral
{
/**
 * The chosen points of a cloud, gathered in their order into a cloud of their own (positions
 * and, when the cloud has them, orientation normals). Running the filter on View() gives the
 * chosen points exactly the bits a run on a cloud of them alone gives; SpreadResult puts that
 * result back in the whole cloud.
 */
class ChosenPoints
{
public:
  /// chosen: one flag per point of the cloud (non-zero: filtered).
  ChosenPoints(const PointCloudView& cloud, const std::vector<std::uint8_t>& chosen);

  /// The chosen points, as a cloud; valid while this object lives.
  PointCloudView View() const;
  std::size_t GetNumberOfChosenPoints() const { return this->Ids.size(); }

  /**
   * The result of a run on View(), for the whole cloud: the chosen points' positions, normals,
   * removal flags and radii from it; the others keep their input positions, get zero normals
   * and radii and are never removed. Counts, parameters and measured scales are the run's
   * (measured on the chosen points). withNormals: whether the run computed normals (with no
   * chosen point, its result cannot tell).
   */
  BilateralResult SpreadResult(BilateralResult chosenResult, bool withNormals) const;

private:
  const PointCloudView Cloud;
  std::vector<std::size_t> Ids;
  std::vector<double> Positions;
  std::vector<double> Orientation;
};

} // namespace pcbilateral

#endif

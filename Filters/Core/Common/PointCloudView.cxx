#include "PointCloudView.h"
#include "ProgressCheck.h"

#include <algorithm>
#include <limits>

namespace pcbilateral
{

double CloudExtent::LargestExtent() const
{
  return std::max(
    { this->Max[0] - this->Min[0], this->Max[1] - this->Min[1], this->Max[2] - this->Min[2] });
}

double CloudExtent::LargestMagnitude() const
{
  double largest = 0.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    largest = std::max({ largest, std::abs(this->Min[axis]), std::abs(this->Max[axis]) });
  }
  return largest;
}

bool CloudExtent::IsFinite() const
{
  return IsFinitePoint(this->Min) && IsFinitePoint(this->Max);
}

namespace
{
/// The extent of the finite points; `stop(done)` is asked between blocks of points.
template<typename Stop>
CloudExtent MeasureCloudIn(const PointCloudView& cloud, Stop stop)
{
  CloudExtent extent;
  const double infinity = std::numeric_limits<double>::infinity();
  double low[3] = { infinity, infinity, infinity }, high[3] = { -infinity, -infinity, -infinity };
  std::size_t finite = 0;
  constexpr std::size_t Block = std::size_t(1) << 16;
  for (std::size_t first = 0; first < cloud.NumberOfPoints; first += Block)
  {
    if (stop(first))
    {
      break;
    }
    const std::size_t end = std::min(cloud.NumberOfPoints, first + Block);
    for (std::size_t i = first; i < end; ++i)
    {
      const double* p = cloud.Positions + 3 * i;
      if (!IsFinitePoint(p))
      {
        continue;
      }
      for (int axis = 0; axis < 3; ++axis)
      {
        low[axis] = std::min(low[axis], p[axis]);
        high[axis] = std::max(high[axis], p[axis]);
      }
      ++finite;
    }
  }
  if (finite > 0)
  {
    extent.NumberOfFinitePoints = finite;
    std::copy_n(low, 3, extent.Min);
    std::copy_n(high, 3, extent.Max);
  }
  return extent;
}
} // namespace

CloudExtent MeasureCloud(const PointCloudView& cloud)
{
  return MeasureCloudIn(cloud, [](std::size_t) { return false; });
}

CloudExtent MeasureCloudUnlessStopped(const PointCloudView& cloud, bool& stopped)
{
  stopped = false;
  return MeasureCloudIn(
    cloud, [&](std::size_t done) { return stopped = ProgressPoint(done, cloud.NumberOfPoints); });
}

CloudExtent MergeExtents(const CloudExtent& a, const CloudExtent& b)
{
  if (a.NumberOfFinitePoints == 0)
  {
    return b;
  }
  if (b.NumberOfFinitePoints == 0)
  {
    return a;
  }
  CloudExtent merged;
  merged.NumberOfFinitePoints = a.NumberOfFinitePoints + b.NumberOfFinitePoints;
  for (int axis = 0; axis < 3; ++axis)
  {
    merged.Min[axis] = std::min(a.Min[axis], b.Min[axis]);
    merged.Max[axis] = std::max(a.Max[axis], b.Max[axis]);
  }
  return merged;
}

} // namespace pcbilateral

// Interleaved xyz as the core's input, for the core's tests. Plain C++17.
#ifndef pcbilateral_CloudView_h
#define pcbilateral_CloudView_h

#include "PointCloudView.h"

#include <cstddef>
#include <vector>

namespace pcbilateral_testing
{

/// `count` points of interleaved xyz from `xyz` on, positions only.
inline pcbilateral::PointCloudView ViewOf(const double* xyz, std::size_t count)
{
  pcbilateral::PointCloudView view;
  view.NumberOfPoints = count;
  view.Positions = xyz;
  return view;
}

/// All the points of interleaved xyz, positions only.
inline pcbilateral::PointCloudView ViewOf(const std::vector<double>& xyz)
{
  return ViewOf(xyz.data(), xyz.size() / 3);
}

} // namespace pcbilateral_testing

#endif

// The invariant that lets the cell-colouring scheduler place filtered points without locks:
// the r-dilations of two processing cells of the same colour share no leaf. Checked over
// random clouds, radii and root sizes, including radii as large as the cloud.
// Also checks the other half of the argument: a filtered point moves by less than r.
#include "BilateralFilter.h"
#include "CloudView.h"
#include "CoreTesting.h"
#include "ProcessingOctree.h"

#include <cmath>
#include <random>
#include <unordered_map>
#include <vector>

namespace
{
using pcbilateral::LatticeCoord;
using pcbilateral::ProcessingOctree;

/// Checks the invariant for one octree; returns the number of cells checked.
std::size_t CheckDilationsShareNoLeaf(const ProcessingOctree& octree, double radius)
{
  const double* origin = octree.GetRootOrigin();
  const double cellSize = octree.GetCellSize();
  const double leafSize = octree.GetLeafSize();
  PCB_CHECK(cellSize >= 2.1 * radius, "cell size %g below 2.1 r = %g", cellSize, 2.1 * radius);
  PCB_CHECK(octree.GetProcessingDepth() >= 1, "depth %d", octree.GetProcessingDepth());

  // Leaf -> the cell whose dilation claimed it, one map per colour.
  std::vector<std::unordered_map<LatticeCoord, std::size_t, pcbilateral::LatticeCoordHash>> owner(
    8);
  for (std::size_t cell = 0; cell < octree.GetNumberOfProcessingCells(); ++cell)
  {
    const LatticeCoord& c = octree.GetCellCoord(cell);
    const std::int64_t cellIndex[3] = { c.X, c.Y, c.Z };
    std::int64_t first[3], last[3];
    for (int axis = 0; axis < 3; ++axis)
    {
      // The closed box of the cell grown by r (and a hair, for rounding), in leaf indices.
      const double low = origin[axis] + cellSize * cellIndex[axis] - radius * (1 + 1e-9);
      const double high = origin[axis] + cellSize * (cellIndex[axis] + 1) + radius * (1 + 1e-9);
      first[axis] = static_cast<std::int64_t>(std::floor((low - origin[axis]) / leafSize));
      last[axis] = static_cast<std::int64_t>(std::floor((high - origin[axis]) / leafSize));
    }
    auto& claimed = owner[ProcessingOctree::ColourOf(c)];
    for (auto z = static_cast<std::int32_t>(first[2]); z <= last[2]; ++z)
    {
      for (auto y = static_cast<std::int32_t>(first[1]); y <= last[1]; ++y)
      {
        for (auto x = static_cast<std::int32_t>(first[0]); x <= last[0]; ++x)
        {
          const auto inserted = claimed.emplace(LatticeCoord{ x, y, z }, cell);
          PCB_CHECK(inserted.second || inserted.first->second == cell,
            "cells %zu and %zu of colour %d both reach leaf (%lld, %lld, %lld)",
            inserted.first->second,
            cell,
            ProcessingOctree::ColourOf(c),
            static_cast<long long>(x),
            static_cast<long long>(y),
            static_cast<long long>(z));
        }
      }
    }
  }
  return octree.GetNumberOfProcessingCells();
}
} // namespace

int main()
{
  std::mt19937_64 random(20171029);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t cellsChecked = 0;
  for (int trial = 0; trial < 60; ++trial)
  {
    // Boxes of varied shape and offset, radii from tiny to larger than the box.
    const double extent[3] = { 0.1 + 10 * unit(random),
      0.1 + 10 * unit(random),
      trial % 3 == 0 ? 0.0 : 0.1 + 10 * unit(random) };
    const double offset[3] = { 1000 * (unit(random) - 0.5), 1e6 * unit(random), -5 * unit(random) };
    const double largest = std::max({ extent[0], extent[1], extent[2] });
    const double radius = largest * std::pow(10.0, -2.5 + 3.0 * unit(random));
    const std::size_t count = 200 + static_cast<std::size_t>(3000 * unit(random));

    std::vector<double> points(3 * count);
    double boundsMin[3] = { 1e300, 1e300, 1e300 };
    double boundsMax[3] = { -1e300, -1e300, -1e300 };
    for (std::size_t i = 0; i < count; ++i)
    {
      for (int axis = 0; axis < 3; ++axis)
      {
        points[3 * i + axis] = offset[axis] + extent[axis] * unit(random);
        boundsMin[axis] = std::min(boundsMin[axis], points[3 * i + axis]);
        boundsMax[axis] = std::max(boundsMax[axis], points[3 * i + axis]);
      }
    }
    ProcessingOctree octree(boundsMin, boundsMax, radius);
    octree.Load(points.data(), count);
    PCB_CHECK(octree.GetNumberOfPoints() == count,
      "trial %d: %zu of %zu points placed",
      trial,
      octree.GetNumberOfPoints(),
      count);
    cellsChecked += CheckDilationsShareNoLeaf(octree, radius);

    // A filtered point stays within r of where it was.
    pcbilateral::BilateralParameters parameters;
    parameters.Radius = radius;
    parameters.NormalRadius = radius * (0.1 + 2 * unit(random));
    parameters.NumberOfIterations = 1;
    parameters.NumberOfThreads = 2;
    const pcbilateral::PointCloudView cloud = pcbilateral_testing::ViewOf(points.data(), count);
    const auto result = pcbilateral::RunBilateralFilter(cloud, parameters);
    double largestMove = 0.0;
    for (std::size_t i = 0; i < count; ++i)
    {
      const double* a = &points[3 * i];
      const double* b = &result.Positions[3 * i];
      largestMove = std::max(largestMove,
        std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                  (a[2] - b[2]) * (a[2] - b[2])));
    }
    PCB_CHECK(
      largestMove < radius, "trial %d: a point moved by %g >= r = %g", trial, largestMove, radius);
  }
  std::printf("checked %zu processing cells\n", cellsChecked);
  return PCB_TEST_RESULT();
}

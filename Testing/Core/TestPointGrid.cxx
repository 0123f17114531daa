// The core's uniform grid (Neighbours/PointGrid): every ball search returns exactly the points a
// brute force finds, in both layouts, for cells from much smaller to much larger than the balls,
// on a surface, on scattered points and on a cloud whose cells cannot be packed into 64 bits
// (the Any layout then falls back to ByCoordinates). Also: the ByCoordinates layout visits points
// in the order of their coordinates.
#include "CoreTesting.h"
#include "PointGrid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace
{
using pcbilateral::PointGrid;

/// n points: on a wavy sheet, or scattered in a box, scaled by `size`.
std::vector<double> MakePoints(std::size_t n, bool sheet, double size, unsigned seed)
{
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> xyz;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double x = uniform(random), y = uniform(random);
    const double z = sheet ? 0.1 * std::sin(6.0 * x) * std::cos(4.0 * y) : uniform(random);
    xyz.insert(xyz.end(), { size * x, size * y, size * z });
  }
  return xyz;
}

/// The ids within radius of centre, by brute force and through the grid, sorted.
void CheckBall(const PointGrid& grid,
  const std::vector<double>& xyz,
  const double centre[3],
  double radius,
  const char* what)
{
  std::vector<std::uint32_t> expected, found;
  for (std::size_t i = 0; i < xyz.size() / 3; ++i)
  {
    const double dx = xyz[3 * i] - centre[0], dy = xyz[3 * i + 1] - centre[1],
                 dz = xyz[3 * i + 2] - centre[2];
    if (dx * dx + dy * dy + dz * dz <= radius * radius)
    {
      expected.push_back(static_cast<std::uint32_t>(i));
    }
  }
  grid.ForEachInBall(
    centre, radius, [&](std::size_t at, double) { found.push_back(grid.GetIds()[at]); });
  std::sort(found.begin(), found.end());
  PCB_CHECK(found == expected,
    "%s: ball of radius %g at (%g, %g, %g): %zu points found, %zu expected",
    what,
    radius,
    centre[0],
    centre[1],
    centre[2],
    found.size(),
    expected.size());
}

void CheckLayout(const std::vector<double>& xyz, double cellSize, PointGrid::PointOrder order)
{
  std::vector<std::uint32_t> ids(xyz.size() / 3);
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    ids[i] = static_cast<std::uint32_t>(i);
  }
  const double origin[3] = { 0.0, 0.0, 0.0 };
  PointGrid grid;
  PCB_CHECK(grid.Build(xyz.data(), ids, origin, cellSize, order), "the grid could not be built");
  PCB_CHECK(grid.Size() == ids.size(), "the grid holds %zu of %zu points", grid.Size(), ids.size());
  const char* what = order == PointGrid::PointOrder::Any ? "Any" : "ByCoordinates";
  std::mt19937_64 random(11);
  for (int query = 0; query < 200; ++query)
  {
    // Centres at points and between them, radii from a fraction of a cell to many cells.
    const std::size_t i = random() % ids.size();
    double centre[3] = { xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] };
    if (query % 2)
    {
      centre[query % 3] += cellSize * 0.37;
    }
    const double radius = cellSize * std::ldexp(1.0, static_cast<int>(random() % 8) - 3);
    CheckBall(grid, xyz, centre, radius, what);
  }
}
} // namespace

int main(int argc, char* argv[])
{
  return RunNamedCase(argc,
    argv,
    { { "Balls",
        []
        {
          for (const bool sheet : { true, false })
          {
            const std::vector<double> xyz = MakePoints(4000, sheet, 1.0, sheet ? 1 : 2);
            for (const double cellSize : { 0.004, 0.02, 0.1, 0.5 })
            {
              CheckLayout(xyz, cellSize, PointGrid::PointOrder::Any);
              CheckLayout(xyz, cellSize, PointGrid::PointOrder::ByCoordinates);
            }
          }
        } },
      { "Unpackable",
        []
        {
          // Two copies of a cloud, one 2^22 cells of 1/64 further along x, and a point as far along
          // y and z: 69 bits of packed coordinates, where packing would fold the copies onto each
          // other. Then 2^20 cells (63 bits): packed.
          for (const double far : { 65536.0, 16384.0 })
          {
            std::vector<double> xyz = MakePoints(1500, false, 1.0, 3);
            for (std::size_t i = 0, n = xyz.size(); i < n; i += 3)
            {
              xyz.insert(xyz.end(), { xyz[i] + far, xyz[i + 1], xyz[i + 2] });
            }
            xyz.insert(xyz.end(), { 0.0, far, far });
            CheckLayout(xyz, 1.0 / 64.0, PointGrid::PointOrder::Any);
          }
        } } });
}

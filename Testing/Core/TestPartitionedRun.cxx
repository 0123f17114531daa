// What a distributed run relies on: a part of the cloud, numbered in any order, filtered with the
// points of the other parts within reach as ghosts and with the whole cloud's extent, gives
// exactly the bits that one run over the whole cloud gives its points. Iterations are run one at
// a time, the ghosts refreshed in between, as the distributed VTK filter does.
#include "BilateralFilter.h"
#include "CoreTesting.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

namespace
{
using pcbilateral::BilateralParameters;
using pcbilateral::BilateralResult;
using pcbilateral::BilateralStatus;
using pcbilateral::PointCloudView;

/// A noisy, folded sheet with some exact duplicates: neighbours in every direction, edges, and
/// ties in the order of a leaf.
std::vector<double> MakeCloud(std::size_t count, unsigned seed)
{
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.004);
  std::vector<double> xyz;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (i % 50 == 49)
    {
      xyz.insert(xyz.end(), xyz.end() - 3, xyz.end()); // an exact duplicate of the last point
      continue;
    }
    const double u = uniform(random);
    const double v = uniform(random);
    xyz.push_back(u + noise(random));
    xyz.push_back(v + noise(random));
    xyz.push_back(0.3 * std::abs(u - 0.5) + noise(random));
  }
  return xyz;
}

bool SameBits(const double* a, const double* b)
{
  return std::memcmp(a, b, 3 * sizeof(double)) == 0;
}

/// Filters `xyz` split into `parts` slabs along x, each part's points shuffled, with
/// `iterations` single-iteration runs per part; returns the positions in the original order.
std::vector<double> RunPartitioned(const std::vector<double>& xyz,
  const BilateralParameters& parameters,
  int parts,
  unsigned seed)
{
  const std::size_t n = xyz.size() / 3;
  PointCloudView whole;
  whole.NumberOfPoints = n;
  whole.Positions = xyz.data();
  BilateralParameters single = parameters;
  single.GlobalExtent = pcbilateral::MeasureCloud(whole);
  single.NumberOfIterations = 1;
  const pcbilateral::RadiiUsed radii = pcbilateral::ResolveRadii(parameters, *single.GlobalExtent);
  single.Radius = radii.Radius;
  single.NormalRadius = radii.NormalRadius;

  // Uneven slabs: part k holds x in [bounds[k], bounds[k+1]).
  std::vector<double> bounds{ -1e9 };
  for (int k = 1; k < parts; ++k)
  {
    bounds.push_back(std::pow(static_cast<double>(k) / parts, 1.5));
  }
  bounds.push_back(1e9);
  std::vector<std::vector<std::size_t>> owned(parts);
  std::vector<int> owner(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const int k = static_cast<int>(
                    std::upper_bound(bounds.begin(), bounds.end(), xyz[3 * i]) - bounds.begin()) -
                  1;
    owned[k].push_back(i);
    owner[i] = k;
  }
  std::mt19937 random(seed);
  for (auto& ids : owned)
  {
    std::shuffle(ids.begin(), ids.end(), random);
  }

  std::vector<double> current = xyz;
  std::vector<std::uint8_t> removed(n, 0);
  for (int iteration = 0; iteration < parameters.NumberOfIterations; ++iteration)
  {
    std::vector<double> next = current;
    for (int k = 0; k < parts; ++k)
    {
      // Own points first, then the other parts' points within reach of this part's slab
      // (more than needed: the filter masks what is out of reach), in reverse order.
      std::vector<std::size_t> local;
      for (const std::size_t i : owned[k])
      {
        if (!removed[i])
        {
          local.push_back(i);
        }
      }
      const std::size_t ownedCount = local.size();
      const double reach = 1.5 * single.Radius;
      for (std::size_t i = n; i-- > 0;)
      {
        const double x = current[3 * i];
        if (!removed[i] && owner[i] != k && x >= bounds[k] - reach && x < bounds[k + 1] + reach)
        {
          local.push_back(i);
        }
      }
      std::vector<double> localXyz;
      for (const std::size_t i : local)
      {
        localXyz.insert(localXyz.end(), &current[3 * i], &current[3 * i] + 3);
      }
      PointCloudView cloud;
      cloud.NumberOfPoints = local.size();
      cloud.Positions = localXyz.data();
      cloud.NumberOfGhostPoints = local.size() - ownedCount;
      const BilateralResult result = pcbilateral::RunBilateralFilter(cloud, single);
      PCB_CHECK(
        result.Status == BilateralStatus::Completed, "part %d: %s", k, result.Error.c_str());
      if (result.Status != BilateralStatus::Completed)
      {
        return next;
      }
      for (std::size_t j = 0; j < local.size(); ++j)
      {
        const double* p = &result.Positions[3 * j];
        if (j >= ownedCount)
        {
          PCB_CHECK(SameBits(p, &localXyz[3 * j]), "part %d: a ghost point moved", k);
          PCB_CHECK(!result.Removed[j], "part %d: a ghost point was removed", k);
          continue;
        }
        std::copy(p, p + 3, &next[3 * local[j]]);
        removed[local[j]] = result.Removed[j];
      }
    }
    current = next;
  }
  return current;
}

void CheckSameBitsAsOneRun(const BilateralParameters& parameters, int parts, unsigned seed)
{
  const std::vector<double> xyz = MakeCloud(6000, seed);
  PointCloudView cloud;
  cloud.NumberOfPoints = xyz.size() / 3;
  cloud.Positions = xyz.data();
  const BilateralResult reference = pcbilateral::RunBilateralFilter(cloud, parameters);
  PCB_CHECK(reference.Status == BilateralStatus::Completed, "%s", reference.Error.c_str());
  const std::vector<double> partitioned = RunPartitioned(xyz, parameters, parts, seed + 1);

  std::size_t differing = 0, moved = 0;
  for (std::size_t i = 0; i < cloud.NumberOfPoints; ++i)
  {
    differing += SameBits(&reference.Positions[3 * i], &partitioned[3 * i]) ? 0 : 1;
    moved += SameBits(&reference.Positions[3 * i], &xyz[3 * i]) ? 0 : 1;
  }
  PCB_CHECK(differing == 0,
    "%d parts, %d iterations, radius %g: %zu of %zu points differ from one run",
    parts,
    parameters.NumberOfIterations,
    parameters.Radius,
    differing,
    cloud.NumberOfPoints);
  PCB_CHECK(moved > cloud.NumberOfPoints / 2, "only %zu points moved", moved);
  std::printf("%d parts, %d iteration(s), radius %g: %zu points, %zu moved, %zu differ\n",
    parts,
    parameters.NumberOfIterations,
    parameters.Radius,
    cloud.NumberOfPoints,
    moved,
    differing);
}
} // namespace

int main()
{
  BilateralParameters parameters;
  parameters.Radius = 0.05;
  parameters.NormalRadius = 0.02;
  parameters.NumberOfIterations = 3;
  for (const int parts : { 1, 2, 3, 5 })
  {
    CheckSameBitsAsOneRun(parameters, parts, 7u + static_cast<unsigned>(parts));
  }
  // The automatic radius, resolved from the whole cloud, and removal of isolated points.
  parameters.Radius = 0.0;
  parameters.NormalRadius = 0.0;
  parameters.NumberOfIterations = 2;
  parameters.RemoveIsolatedPoints = true;
  CheckSameBitsAsOneRun(parameters, 3, 99u);
  return PCB_TEST_RESULT();
}

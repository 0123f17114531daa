// What a distributed run relies on: a part of the cloud, numbered in any order, filtered with the
// points of the other parts within reach as ghosts and with the whole cloud's extent, gives
// exactly the bits that one run over the whole cloud gives its points. The parts are driven by
// the shipped run loop (pcbilateral::BilateralRun, as the distributed VTK filter drives it on
// each process) with an in-process ghost exchange.
#include "BilateralFilter.h"
#include "CloudMeasurement.h"
#include "CloudView.h"
#include "CoreTesting.h"
#include "SampleShapes.h"
#include "TestClouds.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <numeric>
#include <random>
#include <vector>

namespace
{
using pcbilateral::BilateralParameters;
using pcbilateral::BilateralResult;
using pcbilateral::BilateralStatus;
using pcbilateral::PointCloudView;
using pcbilateral_testing::ViewOf;

/// A noisy, folded sheet with some exact duplicates: neighbours in every direction, edges, and
/// ties in the order of a leaf.
std::vector<double> MakeCloud(std::size_t count, unsigned seed)
{
  pcbilateral_samples::Random random(seed);
  auto uniform = [&random]() { return random.Uniform(); };
  auto noise = [&random]() { return 0.004 * random.Gaussian(); };
  std::vector<double> xyz;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (i % 50 == 49)
    {
      xyz.insert(xyz.end(), xyz.end() - 3, xyz.end()); // an exact duplicate of the last point
      continue;
    }
    const double u = uniform();
    const double v = uniform();
    xyz.push_back(u + noise());
    xyz.push_back(v + noise());
    xyz.push_back(0.3 * std::abs(u - 0.5) + noise());
  }
  return xyz;
}

bool SameBits(const double* a, const double* b)
{
  return std::memcmp(a, b, 3 * sizeof(double)) == 0;
}

/// The parts of a distributed run: part k holds the points with x in [bounds[k], bounds[k+1])
/// of uneven slabs, in a shuffled order.
struct Partition
{
  std::vector<std::vector<std::size_t>> Owned; ///< each part's points' indices in the cloud
  std::vector<std::vector<double>> Xyz;        ///< each part's points
};

Partition SplitIntoSlabs(const std::vector<double>& xyz, int parts, unsigned seed)
{
  std::vector<double> bounds{ -1e9 };
  for (int k = 1; k < parts; ++k)
  {
    bounds.push_back(std::pow(static_cast<double>(k) / parts, 1.5));
  }
  bounds.push_back(1e9);
  Partition partition;
  partition.Owned.resize(parts);
  partition.Xyz.resize(parts);
  for (std::size_t i = 0; i < xyz.size() / 3; ++i)
  {
    const auto k = std::upper_bound(bounds.begin(), bounds.end(), xyz[3 * i]) - bounds.begin() - 1;
    partition.Owned[k].push_back(i);
  }
  std::mt19937 random(seed);
  for (int k = 0; k < parts; ++k)
  {
    std::shuffle(partition.Owned[k].begin(), partition.Owned[k].end(), random);
    for (const std::size_t i : partition.Owned[k])
    {
      partition.Xyz[k].insert(partition.Xyz[k].end(), &xyz[3 * i], &xyz[3 * i] + 3);
    }
  }
  return partition;
}

/// The automatic mode's scales, as the distributed filter shares them: each part's share of
/// the whole cloud's selection, gathered (here in reverse order of parts) and measured.
pcbilateral::CloudScales MeasureSharedScales(const Partition& partition,
  const pcbilateral::CloudExtent& whole)
{
  const double fraction = pcbilateral::MeasuredFraction(whole.NumberOfFinitePoints);
  std::vector<double> selection;
  for (std::size_t k = partition.Xyz.size(); k-- > 0;)
  {
    const std::vector<double> own =
      pcbilateral::SelectMeasurementPoints(ViewOf(partition.Xyz[k]), fraction);
    selection.insert(selection.end(), own.begin(), own.end());
  }
  return pcbilateral::MeasureSelection(selection, fraction, 0);
}

/// One iteration of every part: the ghost exchange hands each part the other parts' points
/// within its reach boxes (the ranks' exchange, without MPI), then the part steps.
void ExchangeGhostsAndStep(const std::vector<std::unique_ptr<pcbilateral::BilateralRun>>& runs)
{
  const int parts = static_cast<int>(runs.size());
  std::vector<std::vector<double>> offered(parts);
  std::vector<std::vector<double>> reach(parts);
  for (int k = 0; k < parts; ++k)
  {
    offered[k] = runs[k]->GetPositionsForOthers();
    reach[k] = runs[k]->GetGhostReaches();
  }
  for (int k = 0; k < parts; ++k)
  {
    // The other parts' points in this part's reach, in reverse order of parts.
    std::vector<double> ghosts;
    for (int other = parts; other-- > 0;)
    {
      for (std::size_t i = 0; other != k && i < offered[other].size(); i += 3)
      {
        const double* p = &offered[other][i];
        for (std::size_t b = 0; b < reach[k].size(); b += 6)
        {
          if (pcbilateral::InsideBox(&reach[k][b], p))
          {
            ghosts.insert(ghosts.end(), p, p + 3);
            break;
          }
        }
      }
    }
    const BilateralStatus status = runs[k]->Step(ghosts);
    PCB_CHECK(status == BilateralStatus::Completed, "part %d: %s", k, runs[k]->GetError().c_str());
  }
}

/// In-process stand-in for the processes of a distributed run: each part is driven by its own
/// pcbilateral::BilateralRun, exactly as vtkPPointCloudBilateralFilter drives one per process,
/// with the ghost exchange between iterations. Returns the positions in the original order.
std::vector<double> RunPartitioned(const std::vector<double>& xyz,
  const BilateralParameters& parameters,
  int parts,
  unsigned seed)
{
  const Partition partition = SplitIntoSlabs(xyz, parts, seed);
  std::vector<std::unique_ptr<pcbilateral::BilateralRun>> runs;
  for (int k = 0; k < parts; ++k)
  {
    runs.push_back(
      std::make_unique<pcbilateral::BilateralRun>(ViewOf(partition.Xyz[k]), parameters));
  }
  // The whole cloud's extent, as the processes' reduction gives it.
  pcbilateral::CloudExtent whole;
  for (const auto& run : runs)
  {
    whole = pcbilateral::MergeExtents(whole, run->GetLocalExtent());
  }
  pcbilateral::CloudScales scales;
  if (runs[0]->NeedsScales())
  {
    scales = MeasureSharedScales(partition, whole);
  }
  bool iterate = true;
  for (const auto& run : runs)
  {
    iterate = run->Start(whole, &scales) && iterate;
  }
  while (iterate)
  {
    ExchangeGhostsAndStep(runs);
    iterate = runs[0]->HasNextIteration();
  }

  std::vector<double> result(xyz.size());
  for (int k = 0; k < parts; ++k)
  {
    const BilateralResult partResult = runs[k]->Finish();
    PCB_CHECK(
      partResult.Status == BilateralStatus::Completed, "part %d: %s", k, partResult.Error.c_str());
    for (std::size_t j = 0; j < partition.Owned[k].size(); ++j)
    {
      std::copy_n(&partResult.Positions[3 * j], 3, &result[3 * partition.Owned[k][j]]);
    }
  }
  return result;
}

/// Returns whether the one run's radius followed the density.
bool CheckSameBitsAsOneRun(const BilateralParameters& parameters,
  int parts,
  unsigned seed,
  const std::vector<double>& xyz)
{
  const PointCloudView cloud = ViewOf(xyz);
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
  std::printf("%d parts, %d iteration(s), radius %g%s: %zu points, %zu moved, %zu differ\n",
    parts,
    parameters.NumberOfIterations,
    parameters.Radius,
    reference.RadiusFollowsDensity ? " (following the density)" : "",
    cloud.NumberOfPoints,
    moved,
    differing);
  return reference.RadiusFollowsDensity;
}

bool CheckSameBitsAsOneRun(const BilateralParameters& parameters, int parts, unsigned seed)
{
  return CheckSameBitsAsOneRun(parameters, parts, seed, MakeCloud(6000, seed));
}

/// Given parameters on 1, 2, 3 and 5 parts (seeds seed + parts), then the automatic ones,
/// chosen from the whole cloud's measured scales, with removal of isolated points on 3 parts.
void CheckGivenAndAutomatic(bool edgeAware, int iterations, unsigned seed, unsigned automaticSeed)
{
  BilateralParameters parameters;
  parameters.EdgeAware = edgeAware;
  parameters.Radius = 0.05;
  parameters.NormalRadius = 0.02;
  parameters.NumberOfIterations = iterations;
  for (const int parts : { 1, 2, 3, 5 })
  {
    CheckSameBitsAsOneRun(parameters, parts, seed + static_cast<unsigned>(parts));
  }
  parameters.Radius = 0.0;
  parameters.NormalRadius = 0.0;
  parameters.NumberOfIterations = 2;
  parameters.RemoveIsolatedPoints = true;
  CheckSameBitsAsOneRun(parameters, 3, automaticSeed);
  // A cloud whose density falls 100 times: the automatic radius follows it (a band of radii,
  // each run with the points of the other bands and parts within reach as ghosts).
  const std::vector<double> sheet =
    pcbilateral_testing::DensityVaryingSheet(8000, 100.0, 0.002, automaticSeed);
  PCB_CHECK(CheckSameBitsAsOneRun(parameters, 3, automaticSeed, sheet),
    "the radius did not follow the density");
}
} // namespace

int main()
{
  CheckGivenAndAutomatic(false, 3, 7u, 99u);
  // The edge-aware mode reads its neighbours' filtered normals: its ghosts reach further
  // (EdgeAwareReachInRadii radii), and must still give one run's bits.
  CheckGivenAndAutomatic(true, 2, 17u, 199u);
  return PCB_TEST_RESULT();
}

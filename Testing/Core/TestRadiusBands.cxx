// A radius that follows the density (RadiusBands.h): the measurement of how the spacing varies,
// and the filter with one radius per band, against references that do not use bands.
//   Measurement  the spacing field on a sheet whose density falls 100 times, against the true
//                spacing, and on an evenly sampled cube (no bands there);
//   FixedRuns    each iteration equals, bit for bit, one fixed-radius run over the whole cloud
//                per band radius, each band's points taken from the run of its radius (so the
//                scheduler, given each band's points and the others within reach, computes what
//                it computes for a whole cloud at that radius);
//   BruteForce   every point against all points within its own radius, by the kernel's
//                single-point function, without octree, bands or ghosts (to 1e-12 of the
//                radius: the sums run in another order);
//   Determinism  the same bits for 1, 2 and 4 threads and for the points in reverse order.
// Splits into parts with ghosts: Core.TestPartitionedRun.
#include "AutomaticRule.h"
#include "BilateralFilter.h"
#include "BilateralKernel.h"
#include "CloudMeasurement.h"
#include "CloudView.h"
#include "CoreTesting.h"
#include "TestClouds.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <vector>

namespace
{
using pcbilateral::BilateralParameters;
using pcbilateral::BilateralResult;
using pcbilateral::BilateralStatus;
using pcbilateral_testing::SameBits;
using pcbilateral_testing::ViewOf;

constexpr std::size_t SheetPoints = 12000;
constexpr double SheetDensityRatio = 100.0;
constexpr double SheetNoise = 0.002;

std::vector<double> Sheet()
{
  return pcbilateral_testing::DensityVaryingSheet(
    SheetPoints, SheetDensityRatio, SheetNoise, 20261125u);
}

/// The automatic radius with a given normal radius and number of iterations: the radius follows
/// the sheet's density.
BilateralParameters AutomaticRadius(int iterations)
{
  BilateralParameters parameters;
  parameters.NormalRadius = 4.0 * SheetNoise;
  parameters.NumberOfIterations = iterations;
  return parameters;
}

void CheckMeasurement()
{
  const std::vector<double> sheet = Sheet();
  const pcbilateral::CloudScales scales = pcbilateral::MeasureWholeCloud(ViewOf(sheet), 0);
  PCB_CHECK(scales.Valid && scales.LocalSpacing, "not measured: %s", scales.Problem.c_str());
  if (!scales.LocalSpacing)
  {
    return;
  }
  const pcbilateral::SpacingField& field = *scales.LocalSpacing;
  // The field is in units of nearest-neighbour distances (their median by area), which
  // SpacingPerNeighbourDistance turns into the spacing of the rule: that is compared (from 0.65 to
  // 1.25 times: measured 0.70 to 0.95)
  // (the field reads a block of cells around each place, across which the density changes).
  for (const double u : { 0.1, 0.3, 0.5, 0.7, 0.9 })
  {
    const double p[3] = { u, 0.5, 0.3 * std::abs(u - 0.5) };
    const double expected =
      pcbilateral_testing::NearestNeighbourDistanceAt(u, SheetPoints, SheetDensityRatio);
    const double measured = scales.SpacingPerNeighbourDistance * field.At(p);
    std::printf("u %.1f: local spacing %.5f, true %.5f\n", u, measured, expected);
    PCB_CHECK(measured > 0.65 * expected && measured < 1.25 * expected,
      "at u = %g the field gives %g for a spacing of %g",
      u,
      measured,
      expected);
  }
  // A density ratio of 100 is a spacing ratio of 10, of which the 5th and 95th percentiles by
  // area (u = 0.05 and 0.95) see 10^0.9 = 7.9.
  std::printf("spread %.2f, surface spacing %.5f, spacing of the fits %.5f, field median by area "
              "%.5f, spacing per distance %.3f\n",
    field.GetSpread(),
    pcbilateral::SurfaceSpacing(scales),
    scales.PointSpacing,
    field.GetAreaWeightedMedian(),
    scales.SpacingPerNeighbourDistance);
  PCB_CHECK(field.GetSpread() > 6.0 && field.GetSpread() < 10.0, "spread %g", field.GetSpread());
  PCB_CHECK(pcbilateral::RadiusFollowsDensity(scales, BilateralParameters()), "one radius");
  // The spacing of most of the surface: the area's median lies at u = 0.5, where the spacing
  // is 0.5 / sqrt(density there); the points' median lies much closer to the dense end.
  const double surface =
    pcbilateral_testing::NearestNeighbourDistanceAt(0.5, SheetPoints, SheetDensityRatio);
  PCB_CHECK(pcbilateral::SurfaceSpacing(scales) > 0.8 * surface &&
              pcbilateral::SurfaceSpacing(scales) < 1.25 * surface,
    "surface spacing %g, expected about %g",
    pcbilateral::SurfaceSpacing(scales),
    surface);

  BilateralParameters given;
  given.Radius = 0.05;
  PCB_CHECK(!pcbilateral::RadiusFollowsDensity(scales, given), "a given radius is kept");
  const std::vector<double> cube = pcbilateral_testing::NoisyCube(20000, 0.002, 5u);
  const pcbilateral::CloudScales even = pcbilateral::MeasureWholeCloud(ViewOf(cube), 0);
  std::printf("evenly sampled cube: spread %.2f\n", even.LocalSpacing->GetSpread());
  PCB_CHECK(even.LocalSpacing && even.LocalSpacing->GetSpread() < 1.7,
    "the cube's spacing spread is %g",
    even.LocalSpacing ? even.LocalSpacing->GetSpread() : 0.0);
  PCB_CHECK(!pcbilateral::RadiusFollowsDensity(even, BilateralParameters()), "bands on a cube");
}

/// The distinct radii of the points.
std::vector<double> DistinctRadii(std::vector<double> radii)
{
  std::sort(radii.begin(), radii.end());
  radii.erase(std::unique(radii.begin(), radii.end()), radii.end());
  return radii;
}

/// One iteration of every point at its own radius, made of fixed-radius runs over the whole
/// cloud (positions `current`), one per radius, on the octree of the input's extent.
std::vector<double> IterationOfFixedRuns(const std::vector<double>& current,
  const pcbilateral::CloudExtent& inputExtent,
  const std::vector<double>& pointRadius,
  double normalRadius)
{
  std::vector<double> next = current;
  for (const double radius : DistinctRadii(pointRadius))
  {
    BilateralParameters fixed;
    fixed.Radius = radius;
    fixed.NormalRadius = normalRadius;
    fixed.NumberOfIterations = 1;
    pcbilateral::BilateralRun run(ViewOf(current), fixed);
    if (run.Start(inputExtent))
    {
      run.Step();
    }
    const BilateralResult whole = run.Finish();
    for (std::size_t i = 0; i < pointRadius.size(); ++i)
    {
      if (pointRadius[i] == radius)
      {
        std::copy_n(&whole.Positions[3 * i], 3, &next[3 * i]);
      }
    }
  }
  return next;
}

void CheckFixedRuns()
{
  const std::vector<double> sheet = Sheet();
  for (const int iterations : { 1, 2 })
  {
    const BilateralResult banded =
      pcbilateral::RunBilateralFilter(ViewOf(sheet), AutomaticRadius(iterations));
    PCB_CHECK(banded.Status == BilateralStatus::Completed && banded.RadiusFollowsDensity,
      "the radius does not follow the density: %s",
      banded.Error.c_str());
    const std::vector<double> radii = DistinctRadii(banded.PointRadius);
    std::printf("%d iteration(s): %zu radii from %g to %g\n",
      iterations,
      radii.size(),
      banded.RadiusRange[0],
      banded.RadiusRange[1]);
    PCB_CHECK(radii.size() >= 4, "only %zu radii", radii.size());
    const pcbilateral::CloudExtent extent = pcbilateral::MeasureCloud(ViewOf(sheet));
    std::vector<double> reference = sheet;
    for (int k = 0; k < iterations; ++k)
    {
      reference = IterationOfFixedRuns(
        reference, extent, banded.PointRadius, AutomaticRadius(0).NormalRadius);
    }
    std::size_t differing = 0;
    for (std::size_t i = 0; i < reference.size(); ++i)
    {
      differing += std::memcmp(&reference[i], &banded.Positions[i], sizeof(double)) != 0;
    }
    PCB_CHECK(differing == 0, "%zu coordinates differ from the fixed-radius runs", differing);
    PCB_CHECK(!SameBits(reference, sheet), "nothing moved");
  }
}

void CheckBruteForce()
{
  const std::vector<double> sheet = Sheet();
  const BilateralResult banded = pcbilateral::RunBilateralFilter(ViewOf(sheet), AutomaticRadius(1));
  const double normalRadius = AutomaticRadius(0).NormalRadius;
  const std::size_t n = sheet.size() / 3;
  double worst = 0.0;
  std::size_t moved = 0;
  pcbilateral::CandidateNeighbours candidates;
  for (std::size_t i = 0; i < n; ++i)
  {
    // Every point is a candidate: the kernel keeps those within the point's own radius.
    const double radius = banded.PointRadius[i];
    candidates.Clear();
    for (std::size_t j = 0; j < n; ++j)
    {
      candidates.Append(&sheet[3 * j], &sheet[3 * j + 1], &sheet[3 * j + 2], 1);
    }
    const pcbilateral::FilteredPoint filtered = pcbilateral::FilterPoint(
      &sheet[3 * i], candidates, pcbilateral::KernelConstants(radius, normalRadius));
    for (int axis = 0; axis < 3; ++axis)
    {
      const double expected =
        sheet[3 * i + axis] +
        (filtered.Filtered ? filtered.Displacement * filtered.Normal[axis] : 0.0);
      worst = std::max(worst, std::abs(expected - banded.Positions[3 * i + axis]) / radius);
    }
    moved += filtered.Filtered;
  }
  std::printf(
    "brute force: %zu of %zu points moved; largest difference %.3g radii\n", moved, n, worst);
  PCB_CHECK(worst < 1e-12, "the banded run differs from the brute force by %g radii", worst);
  PCB_CHECK(moved > n / 2, "only %zu points moved", moved);
}

void CheckDeterminism()
{
  const std::vector<double> sheet = Sheet();
  BilateralParameters parameters = AutomaticRadius(2);
  parameters.NumberOfThreads = 1;
  const BilateralResult one = pcbilateral::RunBilateralFilter(ViewOf(sheet), parameters);
  for (const int threads : { 2, 4 })
  {
    parameters.NumberOfThreads = threads;
    const BilateralResult many = pcbilateral::RunBilateralFilter(ViewOf(sheet), parameters);
    PCB_CHECK(SameBits(one.Positions, many.Positions), "%d threads differ from 1", threads);
  }
  // The points in reverse order: each point gets the same bits.
  std::vector<double> reversed(sheet.size());
  const std::size_t n = sheet.size() / 3;
  for (std::size_t i = 0; i < n; ++i)
  {
    std::copy_n(&sheet[3 * i], 3, &reversed[3 * (n - 1 - i)]);
  }
  parameters.NumberOfThreads = 2;
  const BilateralResult backwards = pcbilateral::RunBilateralFilter(ViewOf(reversed), parameters);
  std::vector<double> unreversed(sheet.size());
  for (std::size_t i = 0; i < n; ++i)
  {
    std::copy_n(&backwards.Positions[3 * (n - 1 - i)], 3, &unreversed[3 * i]);
  }
  PCB_CHECK(SameBits(one.Positions, unreversed), "the points in reverse order differ");
}
} // namespace

int main(int argc, char* argv[])
{
  return RunNamedCase(argc,
    argv,
    { { "Measurement", CheckMeasurement },
      { "FixedRuns", CheckFixedRuns },
      { "BruteForce", CheckBruteForce },
      { "Determinism", CheckDeterminism } });
}

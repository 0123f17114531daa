// The measurement of a cloud's spacing and noise (the automatic mode's input), on generated
// clouds whose noise is known: planes, spheres, cubes and cylinders, 10k to 1M points, noise
// from 0.05% to 2% of the diagonal, uniform and scan-line density, with and without 1% outliers.
//
//   TestCloudMeasurement Accuracy      spacing within 10%, sigma within 25% of the truth
//   TestCloudMeasurement Determinism   the same bits for 1, 2 and 4 threads; given samples
//   TestCloudMeasurement Rule          the rule's parameters on small clouds: error to the
//                                      true surface against the old defaults and the paper's
#include "BilateralFilter.h"
#include "AutomaticRule.h"
#include "CloudMeasurement.h"
#include "CoreTesting.h"
#include "SampleShapes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>
#include <unordered_map>

namespace
{
using namespace pcbilateral_samples;

/// The mean distance from a point to its nearest other point, by a plain grid (a check
/// independent of the code under test), over at most 20,000 evenly spread points (the mean is
/// then known to a fraction of a percent, and the test stays fast).
double MeanNearestNeighbourDistance(const std::vector<double>& xyz, double cellSize)
{
  const std::size_t n = xyz.size() / 3;
  auto cellOf = [&](const double* p, int axis)
  { return static_cast<std::int64_t>(std::floor(p[axis] / cellSize)); };
  auto key = [](std::int64_t x, std::int64_t y, std::int64_t z)
  {
    return (static_cast<std::uint64_t>(x & 0x1FFFFF) << 42) |
           (static_cast<std::uint64_t>(y & 0x1FFFFF) << 21) |
           static_cast<std::uint64_t>(z & 0x1FFFFF);
  };
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* p = xyz.data() + 3 * i;
    cells[key(cellOf(p, 0), cellOf(p, 1), cellOf(p, 2))].push_back(i);
  }
  const std::size_t stride = std::max<std::size_t>(1, n / 20000);
  double sum = 0.0;
  std::size_t queries = 0;
  for (std::size_t i = 0; i < n; i += stride)
  {
    ++queries;
    const double* p = xyz.data() + 3 * i;
    double best = 1e300;
    // Rings of cells until the nearest point found is closer than the ring's inner distance.
    for (std::int64_t ring = 1;; ++ring)
    {
      best = 1e300;
      for (std::int64_t dx = -ring; dx <= ring; ++dx)
        for (std::int64_t dy = -ring; dy <= ring; ++dy)
          for (std::int64_t dz = -ring; dz <= ring; ++dz)
          {
            const auto found =
              cells.find(key(cellOf(p, 0) + dx, cellOf(p, 1) + dy, cellOf(p, 2) + dz));
            if (found == cells.end())
            {
              continue;
            }
            for (std::size_t j : found->second)
            {
              if (j != i)
              {
                const double* q = xyz.data() + 3 * j;
                best = std::min(best,
                  (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                    (p[2] - q[2]) * (p[2] - q[2]));
              }
            }
          }
      if (std::sqrt(best) <= static_cast<double>(ring) * cellSize)
      {
        break;
      }
    }
    sum += std::sqrt(best);
  }
  return sum / static_cast<double>(queries);
}

struct ShapeCase
{
  const char* Name;
  std::function<std::unique_ptr<Shape>()> Make;
  double Area; // of the surface, to size the reference grid
};

std::vector<ShapeCase> Shapes()
{
  return {
    { "plane", [] { return std::unique_ptr<Shape>(new Plane()); }, 1.0 },
    { "sphere", [] { return std::unique_ptr<Shape>(new Sphere()); }, M_PI },
    { "cube", [] { return std::unique_ptr<Shape>(Cube()); }, 6.0 },
    { "cylinder", [] { return std::unique_ptr<Shape>(new CutCylinder()); }, 0.8 * M_PI },
  };
}

pcbilateral::PointCloudView View(const NoisyCloud& cloud)
{
  pcbilateral::PointCloudView view;
  view.NumberOfPoints = cloud.NumberOfPoints();
  view.Positions = cloud.Positions.data();
  return view;
}

void Accuracy()
{
  struct Size
  {
    std::size_t Points;
    bool ScanLines;
    double Outliers;
  };
  // Every shape and noise level at 10k and 100k points with both densities, with and without
  // outliers (spread over the combinations), and a few clouds of 1M points.
  const double noises[] = { 0.0005, 0.002, 0.005, 0.02 };
  const Size sizes[] = {
    { 10000, false, 0.0 }, { 10000, true, 0.01 }, { 100000, false, 0.01 }, { 100000, true, 0.0 }
  };
  struct Big
  {
    const char* Shape;
    double Noise;
    bool ScanLines;
    double Outliers;
  };
  const Big bigs[] = { { "cube", 0.0005, false, 0.0 },
    { "sphere", 0.02, true, 0.01 },
    { "plane", 0.005, true, 0.0 },
    { "cylinder", 0.0005, true, 0.01 } };
  double worstSpacing = 0.0, worstSigma = 0.0;
  std::uint64_t seed = 1;
  auto run =
    [&](const ShapeCase& shapeCase, std::size_t n, double noise, bool scanLines, double outliers)
  {
    const auto shape = shapeCase.Make();
    const NoisyCloud cloud = MakeNoisyCloud(*shape, n, noise, scanLines, outliers, seed++);
    const double trueSpacing =
      MeanNearestNeighbourDistance(cloud.Clean, 2.0 * std::sqrt(shapeCase.Area / n));
    const auto start = std::chrono::steady_clock::now();
    const pcbilateral::CloudScales scales = pcbilateral::MeasureScales(View(cloud));
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double spacingRatio = scales.PointSpacing / trueSpacing;
    const double sigmaRatio = scales.NoiseSigma / cloud.Sigma;
    worstSpacing = std::max(worstSpacing, std::abs(spacingRatio - 1.0));
    worstSigma = std::max(worstSigma, std::abs(sigmaRatio - 1.0));
    std::printf("%-9s %8zu %-8s %4.0f%% noise %5.2f%%  spacing %.3g/%.3g = %.3f  sigma "
                "%.3g/%.3g = %.3f  rho %.3g rounds %d  %.3fs\n",
      shapeCase.Name,
      n,
      scanLines ? "scan" : "uniform",
      100 * outliers,
      100 * noise,
      scales.PointSpacing,
      trueSpacing,
      spacingRatio,
      scales.NoiseSigma,
      cloud.Sigma,
      sigmaRatio,
      scales.NeighbourhoodRadius,
      scales.NumberOfRounds,
      seconds);
    PCB_CHECK(scales.Valid, "%s: %s", shapeCase.Name, scales.Problem.c_str());
    PCB_CHECK(std::abs(spacingRatio - 1.0) <= 0.10,
      "%s n=%zu noise %g: spacing ratio %.3f",
      shapeCase.Name,
      n,
      noise,
      spacingRatio);
    PCB_CHECK(std::abs(sigmaRatio - 1.0) <= 0.25,
      "%s n=%zu noise %g: sigma ratio %.3f",
      shapeCase.Name,
      n,
      noise,
      sigmaRatio);
  };
  for (const ShapeCase& shapeCase : Shapes())
  {
    for (double noise : noises)
    {
      for (const Size& size : sizes)
      {
        run(shapeCase, size.Points, noise, size.ScanLines, size.Outliers);
      }
    }
  }
  for (const Big& big : bigs)
  {
    for (const ShapeCase& shapeCase : Shapes())
    {
      if (std::strcmp(shapeCase.Name, big.Shape) == 0)
      {
        run(shapeCase, 1000000, big.Noise, big.ScanLines, big.Outliers);
      }
    }
  }
  std::printf("worst relative error: spacing %.3f, sigma %.3f\n", worstSpacing, worstSigma);
}

bool SameScales(const pcbilateral::CloudScales& a, const pcbilateral::CloudScales& b)
{
  return a.Valid == b.Valid && a.PointSpacing == b.PointSpacing && a.NoiseSigma == b.NoiseSigma &&
         a.SurfaceDensity == b.SurfaceDensity && a.NeighbourhoodRadius == b.NeighbourhoodRadius &&
         a.NumberOfFittedSamples == b.NumberOfFittedSamples &&
         a.NumberOfRounds == b.NumberOfRounds && a.CurvatureExcess == b.CurvatureExcess &&
         a.FeatureFraction == b.FeatureFraction && a.CreaseFraction == b.CreaseFraction;
}

void Determinism()
{
  const auto cube = Cube();
  const NoisyCloud cloud = MakeNoisyCloud(*cube, 100000, 0.005, true, 0.01, 42);
  pcbilateral::ScaleMeasurementOptions options;
  options.NumberOfThreads = 1;
  const pcbilateral::CloudScales one = pcbilateral::MeasureScales(View(cloud), options);
  PCB_CHECK(one.Valid, "%s", one.Problem.c_str());
  for (int threads : { 2, 4 })
  {
    options.NumberOfThreads = threads;
    const pcbilateral::CloudScales other = pcbilateral::MeasureScales(View(cloud), options);
    PCB_CHECK(SameScales(one, other),
      "%d threads: spacing %.17g vs %.17g, sigma %.17g vs %.17g",
      threads,
      other.PointSpacing,
      one.PointSpacing,
      other.NoiseSigma,
      one.NoiseSigma);
  }

  // The order of the points does not matter (the samples and the fits' sums are ordered by
  // coordinates), so a distributed run, whose parts list the points in any order, measures the
  // same bits.
  {
    std::vector<std::size_t> order(cloud.NumberOfPoints());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::mt19937 random(5);
    std::shuffle(order.begin(), order.end(), random);
    std::vector<double> shuffled;
    for (const std::size_t i : order)
    {
      shuffled.insert(
        shuffled.end(), cloud.Positions.begin() + 3 * i, cloud.Positions.begin() + 3 * i + 3);
    }
    pcbilateral::PointCloudView shuffledView;
    shuffledView.NumberOfPoints = order.size();
    shuffledView.Positions = shuffled.data();
    options.NumberOfThreads = 2;
    const pcbilateral::CloudScales other = pcbilateral::MeasureScales(shuffledView, options);
    PCB_CHECK(SameScales(one, other),
      "shuffled points: spacing %.17g vs %.17g, sigma %.17g vs %.17g",
      other.PointSpacing,
      one.PointSpacing,
      other.NoiseSigma,
      one.NoiseSigma);

    // The selection of a cloud too large to measure whole: the parts of a split cloud select
    // the points the whole cloud selects, and their gathered selections, in any order, measure
    // the same bits.
    const double fraction = 0.3;
    const std::vector<double> whole = pcbilateral::SelectMeasurementPoints(View(cloud), fraction);
    const double kept = static_cast<double>(whole.size() / 3) / cloud.NumberOfPoints();
    PCB_CHECK(std::abs(kept - fraction) < 0.01, "%g of the points selected, not 0.3", kept);
    std::vector<double> gathered;
    for (std::size_t part = 3; part-- > 0;)
    {
      pcbilateral::PointCloudView partView;
      partView.Positions = shuffled.data() + 3 * (part * order.size() / 3);
      partView.NumberOfPoints = (part + 1) * order.size() / 3 - part * order.size() / 3;
      const std::vector<double> own = pcbilateral::SelectMeasurementPoints(partView, fraction);
      gathered.insert(gathered.end(), own.begin(), own.end());
    }
    const pcbilateral::CloudScales fromWhole = pcbilateral::MeasureSelection(whole, fraction, 1);
    const pcbilateral::CloudScales fromParts = pcbilateral::MeasureSelection(gathered, fraction, 2);
    PCB_CHECK(fromWhole.Valid && SameScales(fromWhole, fromParts),
      "selection from parts: spacing %.17g vs %.17g, sigma %.17g vs %.17g",
      fromParts.PointSpacing,
      fromWhole.PointSpacing,
      fromParts.NoiseSigma,
      fromWhole.NoiseSigma);
    PCB_CHECK(std::abs(fromWhole.PointSpacing / one.PointSpacing - 1) < 0.05 &&
                std::abs(fromWhole.NoiseSigma / one.NoiseSigma - 1) < 0.10,
      "a 0.3 selection: spacing %g vs %g, sigma %g vs %g",
      fromWhole.PointSpacing,
      one.PointSpacing,
      fromWhole.NoiseSigma,
      one.NoiseSigma);
  }

  // Given sample indices: every 97th point, a different sample that measures the same scales.
  options.NumberOfThreads = 1;
  for (std::size_t i = 0; i < cloud.NumberOfPoints(); i += 97)
  {
    options.SampleIndices.push_back(i);
  }
  const pcbilateral::CloudScales given = pcbilateral::MeasureScales(View(cloud), options);
  PCB_CHECK(
    given.NumberOfSamples == options.SampleIndices.size(), "%zu samples", given.NumberOfSamples);
  PCB_CHECK(!SameScales(one, given), "the given samples were not used");
  PCB_CHECK(std::abs(given.PointSpacing / one.PointSpacing - 1) < 0.05 &&
              std::abs(given.NoiseSigma / one.NoiseSigma - 1) < 0.05,
    "given samples: spacing %g vs %g, sigma %g vs %g",
    given.PointSpacing,
    one.PointSpacing,
    given.NoiseSigma,
    one.NoiseSigma);

  // A quarter of the cloud, as a distributed run would gather it, with PointFraction = 0.25:
  // the whole cloud's spacing.
  std::vector<double> quarter;
  for (std::size_t i = 0; i < cloud.NumberOfPoints(); ++i)
  {
    if (i % 4 == 1)
    {
      quarter.insert(
        quarter.end(), cloud.Positions.begin() + 3 * i, cloud.Positions.begin() + 3 * i + 3);
    }
  }
  pcbilateral::PointCloudView quarterView;
  quarterView.NumberOfPoints = quarter.size() / 3;
  quarterView.Positions = quarter.data();
  pcbilateral::ScaleMeasurementOptions quarterOptions;
  quarterOptions.PointFraction = 0.25;
  const pcbilateral::CloudScales part = pcbilateral::MeasureScales(quarterView, quarterOptions);
  PCB_CHECK(std::abs(part.PointSpacing / one.PointSpacing - 1) < 0.05 &&
              std::abs(part.NoiseSigma / one.NoiseSigma - 1) < 0.10,
    "a quarter: spacing %g vs %g, sigma %g vs %g",
    part.PointSpacing,
    one.PointSpacing,
    part.NoiseSigma,
    one.NoiseSigma);

  // Non-finite points are skipped, a degenerate cloud is reported, not measured.
  std::vector<double> withNaN = cloud.Positions;
  for (std::size_t i = 0; i < withNaN.size(); i += 3 * 1000)
  {
    withNaN[i] = std::nan("");
  }
  pcbilateral::PointCloudView nanView;
  nanView.NumberOfPoints = withNaN.size() / 3;
  nanView.Positions = withNaN.data();
  const pcbilateral::CloudScales skipped = pcbilateral::MeasureScales(nanView);
  PCB_CHECK(skipped.Valid && std::abs(skipped.NoiseSigma / one.NoiseSigma - 1) < 0.05,
    "with NaN points: sigma %g vs %g",
    skipped.NoiseSigma,
    one.NoiseSigma);
  std::vector<double> line;
  for (int i = 0; i < 1000; ++i)
  {
    line.insert(line.end(), { 0.001 * i, 0.0, 0.0 });
  }
  pcbilateral::PointCloudView lineView;
  lineView.NumberOfPoints = 1000;
  lineView.Positions = line.data();
  PCB_CHECK(!pcbilateral::MeasureScales(lineView).Valid, "a straight line measured as a surface");
  std::vector<double> few(30, 0.5);
  pcbilateral::PointCloudView fewView;
  fewView.NumberOfPoints = 10;
  fewView.Positions = few.data();
  PCB_CHECK(!pcbilateral::MeasureScales(fewView).Valid, "10 points measured");
}

/// The RMS distance of the non-outliers to the true surface, and the same for those whose clean
/// position is near a sharp edge (as pcb_quality measures them).
std::pair<double, double> Errors(const Shape& shape,
  const NoisyCloud& cloud,
  const std::vector<double>& positions)
{
  const double band = 3.0 * cloud.Sigma + 0.03 * shape.Diagonal();
  double sum = 0.0, edgeSum = 0.0;
  std::size_t count = 0, edgeCount = 0;
  for (std::size_t i = 0; i < cloud.NumberOfPoints(); ++i)
  {
    if (cloud.Outlier[i])
    {
      continue;
    }
    const double d =
      shape.Distance({ positions[3 * i], positions[3 * i + 1], positions[3 * i + 2] });
    sum += d * d;
    ++count;
    if (shape.EdgeDistance(
          { cloud.Clean[3 * i], cloud.Clean[3 * i + 1], cloud.Clean[3 * i + 2] }) <= band)
    {
      edgeSum += d * d;
      ++edgeCount;
    }
  }
  return { std::sqrt(sum / count), edgeCount ? std::sqrt(edgeSum / edgeCount) : 0.0 };
}

void Rule()
{
  // Any parameter the user gave overrides only itself.
  pcbilateral::CloudScales scales;
  scales.Valid = true;
  scales.PointSpacing = 0.01;
  scales.NoiseSigma = 0.002;
  scales.FeatureFraction = 0.2; // edges: not flat
  scales.CreaseFraction = 0.2;  // and not smooth
  pcbilateral::BilateralParameters user;
  user.NumberOfIterations = 0;
  user.NumberOfThreads = 3;
  const pcbilateral::AutomaticRule rule;
  // The general rule's radius for these scales, which the flat and smooth rules scale.
  const double generalRadius = rule.RadiusInSpacings * 0.01 + rule.RadiusInSigmas * 0.002;
  pcbilateral::BilateralParameters chosen = pcbilateral::ChooseParameters(scales, user);
  PCB_CHECK(chosen.Radius == generalRadius &&
              chosen.NormalRadius == rule.NormalRadiusInSigmas * 0.002 &&
              chosen.NumberOfIterations == rule.NumberOfIterations && chosen.NumberOfThreads == 3,
    "automatic: r %g rn %g N %d",
    chosen.Radius,
    chosen.NormalRadius,
    chosen.NumberOfIterations);
  user.Radius = 0.5;
  chosen = pcbilateral::ChooseParameters(scales, user);
  PCB_CHECK(chosen.Radius == 0.5 && chosen.NormalRadius == rule.NormalRadiusInSigmas * 0.002,
    "given r: r %g rn %g",
    chosen.Radius,
    chosen.NormalRadius);
  user.Radius = 0.0;
  user.NormalRadius = 0.3;
  user.NumberOfIterations = 7;
  chosen = pcbilateral::ChooseParameters(scales, user);
  PCB_CHECK(
    chosen.Radius == generalRadius && chosen.NormalRadius == 0.3 && chosen.NumberOfIterations == 7,
    "given rn and N: r %g rn %g N %d",
    chosen.Radius,
    chosen.NormalRadius,
    chosen.NumberOfIterations);
  // A flat cloud: a larger radius and one more iteration, unless given.
  scales.FeatureFraction = 0.0;
  scales.CurvatureExcess = 0.0;
  user = pcbilateral::BilateralParameters();
  user.NumberOfIterations = 0;
  chosen = pcbilateral::ChooseParameters(scales, user);
  PCB_CHECK(chosen.Radius == rule.FlatRadiusFactor * generalRadius &&
              chosen.NumberOfIterations == rule.FlatIterations,
    "flat: r %g N %d",
    chosen.Radius,
    chosen.NumberOfIterations);
  // A smooth surface with thin noise (no crease, sigma below half a spacing, not flat): a
  // larger radius, plain averaging along the normal (rn = r) and one iteration, unless given.
  scales.CurvatureExcess = 0.3;
  scales.FeatureFraction = 0.1;
  scales.CreaseFraction = 0.0;
  PCB_CHECK(!pcbilateral::IsFlat(scales) && pcbilateral::IsSmoothWithThinNoise(scales),
    "a curved cloud without creases, sigma 0.2 spacings: smooth with thin noise expected");
  chosen = pcbilateral::ChooseParameters(scales, user);
  const double smoothRadius = rule.SmoothRadiusFactor * generalRadius;
  PCB_CHECK(chosen.Radius == smoothRadius && chosen.NormalRadius == smoothRadius &&
              chosen.NumberOfIterations == rule.SmoothIterations,
    "smooth, thin noise: r %g rn %g N %d",
    chosen.Radius,
    chosen.NormalRadius,
    chosen.NumberOfIterations);
  user.NormalRadius = 0.001;
  chosen = pcbilateral::ChooseParameters(scales, user);
  PCB_CHECK(chosen.Radius == smoothRadius && chosen.NormalRadius == 0.001,
    "smooth, given rn: r %g rn %g",
    chosen.Radius,
    chosen.NormalRadius);
  user.NormalRadius = 0.0;
  scales.NoiseSigma = 0.006; // thicker than half a spacing: the general rule
  PCB_CHECK(!pcbilateral::IsSmoothWithThinNoise(scales), "sigma 0.6 spacings: not thin noise");
  scales.NoiseSigma = 0.002;
  scales.CreaseFraction = 0.05; // creases: the general rule
  PCB_CHECK(!pcbilateral::IsSmoothWithThinNoise(scales), "5%% of creased samples: not smooth");
  scales.Valid = false;
  user = pcbilateral::BilateralParameters();
  user.NumberOfIterations = 0;
  chosen = pcbilateral::ChooseParameters(scales, user);
  PCB_CHECK(chosen.Radius == 0.0 && chosen.NormalRadius == 0.0 && chosen.NumberOfIterations == 0,
    "unmeasured cloud: r %g rn %g N %d (0 expected: the paper's heuristic)",
    chosen.Radius,
    chosen.NormalRadius,
    chosen.NumberOfIterations);

  // Quality on a few of pcb_quality's small cases (same clouds: same seeds), against the best
  // of its grid search as printed in README.md, with 5% of margin on the targets, and against
  // the paper's heuristic.
  struct QualityCase
  {
    const char* Name;
    std::function<std::unique_ptr<Shape>()> Make;
    double Noise;
    bool ScanLines;
    double Outliers;
    std::uint64_t Seed;
    double GridBestRms, GridBestEdgeRms; // 0: a smooth shape
  };
  const QualityCase cases[] = {
    { "cube 20k 0.5% uniform", [] { return Cube(); }, 0.005, false, 0.0, 103, 0.00306, 0.00465 },
    { "sharp edge 20k 0.5% scan +1% outliers",
      [] { return SharpEdge(); },
      0.005,
      true,
      0.01,
      111,
      0.00191,
      0.00391 },
    { "cut cylinder 20k 0.1% uniform",
      [] { return std::unique_ptr<Shape>(new CutCylinder(0.2)); },
      0.001,
      false,
      0.0,
      115,
      0.000454,
      0.000768 },
    // The one case where the paper's heuristic beat the general rule (0.000614 against
    // 0.000626): a smooth surface with thin noise.
    { "sphere 20k 0.1% scan +1% outliers",
      [] { return std::unique_ptr<Shape>(new Sphere()); },
      0.001,
      true,
      0.01,
      123,
      0.000652,
      0.0 },
    { "sphere 20k 0.5% uniform",
      [] { return std::unique_ptr<Shape>(new Sphere()); },
      0.005,
      false,
      0.0,
      124,
      0.00186,
      0.0 },
    { "terrain 20k 0.5% uniform",
      [] { return std::unique_ptr<Shape>(new Terrain()); },
      0.005,
      false,
      0.0,
      138,
      0.000584,
      0.0 },
  };
  for (const QualityCase& c : cases)
  {
    const auto shape = c.Make();
    const NoisyCloud cloud =
      MakeNoisyCloud(*shape, 20000, c.Noise, c.ScanLines, c.Outliers, c.Seed);
    pcbilateral::BilateralParameters automatic;
    automatic.NumberOfIterations = 0;
    const pcbilateral::CloudScales measured = pcbilateral::MeasureScales(View(cloud));
    automatic = pcbilateral::ChooseParameters(measured, automatic);
    // Only the terrain is flat: the others have edges or bend at the filter's scale. Only the
    // sphere at 0.1% noise is smooth with thin noise: the sphere at 0.5% has thicker noise, the
    // others have creases.
    const bool terrain = std::strncmp(c.Name, "terrain", 7) == 0;
    const bool thinNoiseSphere = std::strncmp(c.Name, "sphere 20k 0.1%", 15) == 0;
    PCB_CHECK(pcbilateral::IsFlat(measured) == terrain &&
                pcbilateral::IsSmoothWithThinNoise(measured) == thinNoiseSphere,
      "%s: flat %d, smooth with thin noise %d (curvature excess %.4f, features %.3f, creases "
      "%.3f, sigma / spacing %.3f)",
      c.Name,
      pcbilateral::IsFlat(measured),
      pcbilateral::IsSmoothWithThinNoise(measured),
      measured.CurvatureExcess,
      measured.FeatureFraction,
      measured.CreaseFraction,
      measured.NoiseSigma / measured.PointSpacing);
    const auto autoErrors =
      Errors(*shape, cloud, pcbilateral::RunBilateralFilter(View(cloud), automatic).Positions);
    pcbilateral::BilateralParameters paper; // r = sqrt(20 / n) x extent, rn = r, N = 1
    paper.Automatic = pcbilateral::AutomaticParameters::Paper;
    const auto paperErrors =
      Errors(*shape, cloud, pcbilateral::RunBilateralFilter(View(cloud), paper).Positions);
    std::printf("%s: automatic (r %.4g, rn %.4g, N %d) RMS %.4g edge %.4g; grid best %.4g / "
                "%.4g; paper %.4g\n",
      c.Name,
      automatic.Radius,
      automatic.NormalRadius,
      automatic.NumberOfIterations,
      autoErrors.first,
      autoErrors.second,
      c.GridBestRms,
      c.GridBestEdgeRms,
      paperErrors.first);
    const double rmsTarget = c.GridBestEdgeRms > 0 ? 1.5 : 1.25;
    PCB_CHECK(autoErrors.first <= 1.05 * rmsTarget * c.GridBestRms,
      "%s: RMS %g vs best %g",
      c.Name,
      autoErrors.first,
      c.GridBestRms);
    PCB_CHECK(c.GridBestEdgeRms == 0 || autoErrors.second <= 1.05 * 1.25 * c.GridBestEdgeRms,
      "%s: edge RMS %g vs best %g",
      c.Name,
      autoErrors.second,
      c.GridBestEdgeRms);
    PCB_CHECK(autoErrors.first < paperErrors.first,
      "%s: RMS %g, the paper's heuristic %g",
      c.Name,
      autoErrors.first,
      paperErrors.first);
  }
}

} // namespace

int main(int argc, char* argv[])
{
  return RunNamedCase(
    argc, argv, { { "Accuracy", Accuracy }, { "Determinism", Determinism }, { "Rule", Rule } });
}

// The measurement of a cloud's spacing and noise (the automatic mode's input), on generated
// clouds whose noise is known: planes, spheres, cubes and cylinders, 10k to 1M points, noise
// from 0.05% to 2% of the diagonal, uniform and scan-line density, with and without 1% outliers.
//
//   TestCloudMeasurement Accuracy      spacing within 10%, sigma within 25% of the truth
//   TestCloudMeasurement Determinism   the same bits for 1, 2 and 4 threads; given samples
//   TestCloudMeasurement Rule          the rule's parameters on small clouds: error to the
//                                      true surface against the old defaults and the paper's
#include "BilateralFilter.h"
#include "CloudMeasurement.h"
#include "CoreTesting.h"
#include "SampleShapes.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <unordered_map>

namespace
{
using namespace pcbilateral_samples;

/// The mean distance from each point to its nearest other point, by a plain grid (a check
/// independent of the code under test).
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
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
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
  return sum / static_cast<double>(n);
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
    a.NumberOfFittedSamples == b.NumberOfFittedSamples && a.NumberOfRounds == b.NumberOfRounds;
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
    PCB_CHECK(SameScales(one, other), "%d threads: spacing %.17g vs %.17g, sigma %.17g vs %.17g",
      threads, other.PointSpacing, one.PointSpacing, other.NoiseSigma, one.NoiseSigma);
  }

  // Given sample indices: every 97th point, a different sample that measures the same scales.
  options.NumberOfThreads = 1;
  for (std::size_t i = 0; i < cloud.NumberOfPoints(); i += 97)
  {
    options.SampleIndices.push_back(i);
  }
  const pcbilateral::CloudScales given = pcbilateral::MeasureScales(View(cloud), options);
  PCB_CHECK(given.NumberOfSamples == options.SampleIndices.size(), "%zu samples",
    given.NumberOfSamples);
  PCB_CHECK(!SameScales(one, given), "the given samples were not used");
  PCB_CHECK(std::abs(given.PointSpacing / one.PointSpacing - 1) < 0.05 &&
      std::abs(given.NoiseSigma / one.NoiseSigma - 1) < 0.05,
    "given samples: spacing %g vs %g, sigma %g vs %g", given.PointSpacing, one.PointSpacing,
    given.NoiseSigma, one.NoiseSigma);

  // A quarter of the cloud, as a distributed run would gather it, with PointFraction = 0.25:
  // the whole cloud's spacing.
  std::vector<double> quarter;
  for (std::size_t i = 0; i < cloud.NumberOfPoints(); ++i)
  {
    if (i % 4 == 1)
    {
      quarter.insert(quarter.end(), cloud.Positions.begin() + 3 * i,
        cloud.Positions.begin() + 3 * i + 3);
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
    "a quarter: spacing %g vs %g, sigma %g vs %g", part.PointSpacing, one.PointSpacing,
    part.NoiseSigma, one.NoiseSigma);

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
    "with NaN points: sigma %g vs %g", skipped.NoiseSigma, one.NoiseSigma);
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

} // namespace

int main(int argc, char* argv[])
{
  return RunNamedCase(argc, argv, { { "Accuracy", Accuracy }, { "Determinism", Determinism } });
}

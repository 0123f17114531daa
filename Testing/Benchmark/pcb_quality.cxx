// pcb_quality: how well the filter denoises generated clouds with exact ground truth, for the
// automatic parameters against a grid search, the paper's heuristic and the old default.
// Built with the project (core only), run by hand (see docs/parameters.md):
//
//   pcb_quality [--quick] [--no-grid] [--only SUBSTRING] [--csv FILE]
//       each case: a shape (cube, sharp edge, cylinder with a planar cut, sphere, CAD part,
//       terrain), noise 0.1%, 0.5% or 1% of the diagonal, 20k to 1M points, uniform or
//       scan-line density, with or without 1% outliers. Prints a Markdown table of the RMS
//       distance to the true surface (outliers left out) and the same near sharp edges (the
//       points whose noise-free position is within 3 sigma of an edge; the wide band, 3 sigma +
//       3% of the diagonal, in the last columns),
//       for: the best of a grid over r, rn and N (judged by each measure separately), the
//       paper's heuristic (r = sqrt(20/n) x extent, rn = r, N = 1), the old ParaView default
//       (r = 2.5% of the largest extent, rn = r, N = 1) and the automatic mode. --csv writes
//       every grid point; --quick runs the small cases only. The grid: r from 3 spacings or
//       4 sigma to 36 spacings or 20 sigma, rn from 1.5 to 7.5 sigma, N from 1 to 4 (coarser
//       for 100k points; around the automatic r for 1M points). --no-grid leaves the grid out
//       (its columns print as "–"): the quick check of a change to the automatic rule, whose
//       grid bests stay those of the last full run as long as the measurement is unchanged.
//   pcb_quality --cost
//       times MeasureWholeCloud against one filter iteration with the automatic radius, 1
//       thread, on a 600k-point cube and a 1M-point sphere (noise 0.5%): the fastest of 9
//       measurements and of 3 iterations, alternated.
#include "AutomaticRule.h"
#include "BilateralFilter.h"
#include "CloudMeasurement.h"
#include "GroundTruth.h"
#include "SampleShapes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace
{
using namespace pcbilateral_samples;
using namespace pcbilateral_benchmark;

struct Case
{
  std::string ShapeName;
  std::function<std::unique_ptr<Shape>()> Make;
  std::size_t Points;
  double Noise; // fraction of the diagonal
  bool ScanLines;
  double Outliers;
  bool Big; // left out by --quick; coarser grid
};

/// N iterations with radius r and normal radius rn, one at a time so that every N up to the
/// last is measured on the way (the same as a run of N iterations but for the order of sums).
std::vector<Quality> RunChain(const Truth& truth, double r, double rn, int iterations)
{
  std::vector<Quality> qualities;
  std::vector<double> positions = truth.Cloud->Positions;
  pcbilateral::BilateralParameters parameters;
  parameters.Radius = r;
  parameters.NormalRadius = rn;
  parameters.NumberOfIterations = 1;
  parameters.NumberOfThreads = 1;
  for (int k = 0; k < iterations; ++k)
  {
    const pcbilateral::BilateralResult result =
      pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(positions), parameters);
    if (result.Status != pcbilateral::BilateralStatus::Completed)
    {
      std::fprintf(stderr, "run failed: %s\n", result.Error.c_str());
      std::exit(EXIT_FAILURE);
    }
    positions = result.Positions;
    qualities.push_back(truth.Measure(positions));
  }
  return qualities;
}

Quality RunOnce(const Truth& truth, const pcbilateral::BilateralParameters& given)
{
  pcbilateral::BilateralParameters parameters = given;
  parameters.NumberOfThreads = 1;
  const pcbilateral::BilateralResult result = pcbilateral::RunBilateralFilter(
    pcbilateral_testing::ViewOf(truth.Cloud->Positions), parameters);
  return truth.Measure(result.Positions);
}

std::vector<Case> Cases(bool quick)
{
  auto cube = [] { return Cube(); };
  auto sharpEdge = [] { return SharpEdge(); };
  auto cutCylinder = [] { return std::unique_ptr<Shape>(new CutCylinder(0.2)); };
  auto sphere = [] { return std::unique_ptr<Shape>(new Sphere()); };
  auto cadPart = [] { return CadPart(); };
  auto terrain = [] { return std::unique_ptr<Shape>(new Terrain()); };
  const std::vector<std::pair<std::string, std::function<std::unique_ptr<Shape>()>>> shapes = {
    { "cube", cube },
    { "sharp edge", sharpEdge },
    { "cut cylinder", cutCylinder },
    { "sphere", sphere },
    { "CAD part", cadPart },
    { "terrain", terrain }
  };
  std::vector<Case> cases;
  for (const auto& shape : shapes)
  {
    for (double noise : { 0.001, 0.005, 0.01 })
    {
      cases.push_back({ shape.first, shape.second, 20000, noise, false, 0.0, false });
      cases.push_back({ shape.first, shape.second, 20000, noise, true, 0.01, false });
    }
    cases.push_back({ shape.first, shape.second, 100000, 0.005, true, 0.0, true });
  }
  cases.push_back({ "cube", cube, 1000000, 0.001, false, 0.01, true });
  cases.push_back({ "sphere", sphere, 1000000, 0.001, true, 0.0, true });
  if (quick)
  {
    cases.erase(
      std::remove_if(cases.begin(), cases.end(), [](const Case& c) { return c.Big; }), cases.end());
  }
  return cases;
}

int Cost()
{
  struct Workload
  {
    const char* Name;
    std::unique_ptr<Shape> Surface;
    std::size_t Points;
  };
  Workload workloads[] = { { "cube600k", Cube(), 600000 },
    { "sphere1M", std::unique_ptr<Shape>(new Sphere()), 1000000 } };
  std::printf("| cloud | measurement | one iteration (r = %s) | ratio |\n", "automatic");
  std::printf("| --- | --- | --- | --- |\n");
  for (Workload& workload : workloads)
  {
    const NoisyCloud cloud = MakeNoisyCloud(*workload.Surface, workload.Points, 0.005, false, 0, 7);
    // Both on one thread, each the fastest of several runs, alternated: on a shared machine
    // other jobs only ever add time.
    pcbilateral::CloudScales scales;
    pcbilateral::BilateralParameters parameters;
    double measuring = std::numeric_limits<double>::infinity();
    double filtering = std::numeric_limits<double>::infinity();
    for (int round = 0; round < 3; ++round)
    {
      for (int run = 0; run < 3; ++run)
      {
        const auto start = std::chrono::steady_clock::now();
        // What the filter runs: the whole cloud's measurement (on its selection when large).
        scales = pcbilateral::MeasureWholeCloud(pcbilateral_testing::ViewOf(cloud.Positions), 1);
        measuring = std::min(measuring, Seconds(start));
      }
      parameters = pcbilateral::ChooseParameters(scales, pcbilateral::BilateralParameters());
      parameters.NumberOfIterations = 1;
      parameters.NumberOfThreads = 1;
      const auto start = std::chrono::steady_clock::now();
      pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(cloud.Positions), parameters);
      filtering = std::min(filtering, Seconds(start));
    }
    std::printf("| %s | %.3f s | %.3f s (r = %.4g, rn = %.4g) | %.1f%% |\n",
      workload.Name,
      measuring,
      filtering,
      parameters.Radius,
      parameters.NormalRadius,
      100.0 * measuring / filtering);
  }
  return EXIT_SUCCESS;
}

std::string Describe(const Case& c)
{
  char text[160];
  std::snprintf(text,
    sizeof text,
    "%s %zuk %.1f%% %s%s",
    c.ShapeName.c_str(),
    c.Points / 1000,
    100 * c.Noise,
    c.ScanLines ? "scan" : "uniform",
    c.Outliers > 0 ? " +1% outliers" : "");
  return text;
}

struct Options
{
  bool Quick = false;
  bool Grid = true;
  std::string Only;
  FILE* Csv = nullptr;
};

enum class Command
{
  Table,
  Cost,
  Usage
};

/// Reads the options; --cost ends the reading (the rest is ignored, as before).
Command ParseArguments(int argc, char* argv[], Options& options)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    if (argument == "--quick")
    {
      options.Quick = true;
    }
    else if (argument == "--no-grid")
    {
      options.Grid = false;
    }
    else if (argument == "--only" && i + 1 < argc)
    {
      options.Only = argv[++i];
    }
    else if (argument == "--csv" && i + 1 < argc)
    {
      options.Csv = std::fopen(argv[++i], "w");
    }
    else if (argument == "--cost")
    {
      return Command::Cost;
    }
    else
    {
      return Command::Usage;
    }
  }
  return Command::Table;
}

/// The grid's radii (none with --no-grid), in the measured units: geometric from min(3 s,
/// 4 sigma) to max(36 s, 20 sigma). The 1M-point cases, where the wide grid would take hours,
/// search around the automatic radius (0.5 to 2 times) instead.
std::vector<double> GridRadii(const Case& c, bool grid, double s, double sigma, double automatic)
{
  std::vector<double> radii;
  if (grid && c.Points >= 1000000)
  {
    for (double k : { 0.5, 0.7, 1.0, 1.4, 2.0 })
    {
      radii.push_back(k * automatic);
    }
  }
  else if (grid)
  {
    const double ratio = c.Big ? 1.7 : 1.45;
    for (double r = std::min(3 * s, 4 * sigma); r <= std::max(36 * s, 20 * sigma) * 1.01;
         r *= ratio)
    {
      radii.push_back(r);
    }
  }
  return radii;
}

/// The best of the grid by each measure, and where ("r/s, rn/sigma, N").
struct GridBest
{
  Quality Best{ 1e300, 1e300, 1e300 };
  std::string RmsAt, EdgeAt;
};

/// The grid over the radii, rn from 1.5 to 7.5 sigma and N from 1 to 4 (coarser for the big
/// cases); every point written to the CSV file when there is one.
GridBest SearchGrid(const Truth& truth,
  const Case& c,
  const std::string& name,
  const std::vector<double>& radii,
  double s,
  double sigma,
  FILE* csv)
{
  std::vector<double> normalRadii;
  for (double k :
    c.Big ? std::vector<double>{ 2.5, 5, 7.5 } : std::vector<double>{ 1.5, 2.2, 3.3, 5, 7.5 })
  {
    normalRadii.push_back(k * sigma);
  }
  const int iterations = c.Big ? 3 : 4;
  GridBest grid;
  for (double r : radii)
  {
    for (double rn : normalRadii)
    {
      const std::vector<Quality> chain = RunChain(truth, r, rn, iterations);
      for (int n = 0; n < iterations; ++n)
      {
        char at[64];
        std::snprintf(at, sizeof at, "%.1f, %.1f, %d", r / s, rn / sigma, n + 1);
        if (chain[n].Rms < grid.Best.Rms)
        {
          grid.Best.Rms = chain[n].Rms;
          grid.RmsAt = at;
        }
        if (truth.EdgePoints > 0 && chain[n].EdgeRms < grid.Best.EdgeRms)
        {
          grid.Best.EdgeRms = chain[n].EdgeRms;
          grid.EdgeAt = at;
        }
        if (truth.EdgePoints > 0)
        {
          grid.Best.WideEdgeRms = std::min(grid.Best.WideEdgeRms, chain[n].WideEdgeRms);
        }
        if (csv)
        {
          std::fprintf(csv,
            "%s,%.6g,%.6g,%.6g,%.6g,%d,%.6g,%.6g,%.6g\n",
            name.c_str(),
            s,
            sigma,
            r,
            rn,
            n + 1,
            chain[n].Rms,
            chain[n].EdgeRms,
            chain[n].WideEdgeRms);
        }
      }
    }
  }
  if (csv)
  {
    std::fflush(csv);
  }
  return grid;
}

std::string Format(const char* pattern, double value)
{
  char text[32];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

/// The qualities of the paper's heuristic, the old default and the automatic mode.
struct Contenders
{
  Quality Paper, Old, Automatic;
};

/// One row of the table; the grid's columns are "–" without a grid, the edge columns without
/// edges.
void PrintRow(const std::string& name,
  const Truth& truth,
  const Quality& noisy,
  const GridBest* grid,
  const Contenders& q)
{
  const bool hasEdges = truth.EdgePoints > 0;
  auto edge = [&](const Quality& quality)
  { return hasEdges ? Format("%.3g", quality.EdgeRms) : "–"; };
  const std::string gridBest =
    grid ? Format("%.3g", grid->Best.Rms) + " (" + grid->RmsAt + ")" : "–";
  const std::string gridBestEdge =
    grid && hasEdges ? Format("%.3g", grid->Best.EdgeRms) + " (" + grid->EdgeAt + ")" : "–";
  const std::string ratio = grid ? Format("%.2f", q.Automatic.Rms / grid->Best.Rms) : "–";
  const std::string edgeRatio =
    grid && hasEdges ? Format("%.2f", q.Automatic.EdgeRms / grid->Best.EdgeRms) : "–";
  const std::string wide =
    hasEdges ? Format("%.3g", q.Automatic.WideEdgeRms) + " / " +
                 (grid ? Format("%.3g", grid->Best.WideEdgeRms) : "–") + " / " +
                 (grid ? Format("%.2f", q.Automatic.WideEdgeRms / grid->Best.WideEdgeRms) : "–")
             : "–";
  std::printf("| %s | %.3g | %s | %s | %.3g / %s | %.3g / %s | %.3g | %s | %s | %s | %s |\n",
    name.c_str(),
    noisy.Rms,
    gridBest.c_str(),
    gridBestEdge.c_str(),
    q.Paper.Rms,
    edge(q.Paper).c_str(),
    q.Old.Rms,
    edge(q.Old).c_str(),
    q.Automatic.Rms,
    edge(q.Automatic).c_str(),
    ratio.c_str(),
    edgeRatio.c_str(),
    wide.c_str());
  std::fflush(stdout);
}

/// The automatic parameters for the measured scales, printed to stderr with the measures the
/// rule reads.
pcbilateral::BilateralParameters AutomaticFor(const std::string& name,
  const pcbilateral::CloudScales& scales)
{
  const pcbilateral::BilateralParameters automatic =
    pcbilateral::ChooseParameters(scales, pcbilateral::BilateralParameters());
  std::fprintf(stderr,
    "%s: spacing %.4g, sigma %.4g, curvature excess %.4g, feature fraction %.4g, crease fraction "
    "%.4g: r %.4g, rn "
    "%.4g, N %d\n",
    name.c_str(),
    scales.PointSpacing,
    scales.NoiseSigma,
    scales.CurvatureExcess,
    scales.FeatureFraction,
    scales.CreaseFraction,
    automatic.Radius,
    automatic.NormalRadius,
    automatic.NumberOfIterations);
  return automatic;
}

/// The paper's heuristic (r = sqrt(20 / n) x extent, rn = r, N = 1), the old ParaView default
/// (r = 2.5% of the largest extent, rn = r, N = 1) and the automatic parameters.
Contenders RunContenders(const Truth& truth, const pcbilateral::BilateralParameters& automatic)
{
  const pcbilateral::CloudExtent extent =
    pcbilateral::MeasureCloud(pcbilateral_testing::ViewOf(truth.Cloud->Positions));
  pcbilateral::BilateralParameters paper;
  paper.Automatic = pcbilateral::AutomaticParameters::Paper;
  pcbilateral::BilateralParameters old;
  old.Radius = 0.025 * extent.LargestExtent();
  old.NormalRadius = old.Radius;
  old.NumberOfIterations = 1;
  Contenders q;
  q.Paper = RunOnce(truth, paper);
  q.Old = RunOnce(truth, old);
  q.Automatic = RunOnce(truth, automatic);
  return q;
}

void RunCase(const Case& c, const std::string& name, std::uint64_t seed, const Options& options)
{
  const std::unique_ptr<Shape> shape = c.Make();
  const NoisyCloud cloud = MakeNoisyCloud(*shape, c.Points, c.Noise, c.ScanLines, c.Outliers, seed);
  const Truth truth(*shape, cloud);
  const Quality noisy = truth.Measure(cloud.Positions);
  pcbilateral::ScaleMeasurementOptions measurement;
  measurement.NumberOfThreads = 1;
  const pcbilateral::CloudScales scales =
    pcbilateral::MeasureScales(pcbilateral_testing::ViewOf(cloud.Positions), measurement);
  const double s = scales.PointSpacing, sigma = scales.NoiseSigma;
  const pcbilateral::BilateralParameters automatic = AutomaticFor(name, scales);
  const std::vector<double> radii = GridRadii(c, options.Grid, s, sigma, automatic.Radius);
  const GridBest grid = SearchGrid(truth, c, name, radii, s, sigma, options.Csv);
  PrintRow(name, truth, noisy, options.Grid ? &grid : nullptr, RunContenders(truth, automatic));
}
} // namespace

int main(int argc, char* argv[])
{
  Options options;
  switch (ParseArguments(argc, argv, options))
  {
    case Command::Cost:
      return Cost();
    case Command::Usage:
      std::fprintf(stderr,
        "usage: %s [--quick] [--no-grid] [--only SUBSTRING] [--csv FILE] | --cost\n",
        argv[0]);
      return EXIT_FAILURE;
    case Command::Table:
      break;
  }
  if (options.Csv)
  {
    std::fprintf(options.Csv, "case,spacing,sigma,r,rn,N,rms,edge_rms,wide_edge_rms\n");
  }
  std::printf("| case | noisy RMS | grid best RMS (r/s, rn/σ, N) | grid best edge RMS (r/s, rn/σ, "
              "N) | paper | old default | automatic RMS | automatic edge RMS | auto/best RMS | "
              "auto/best edge | wide edge RMS: automatic / grid best / ratio |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  std::uint64_t seed = 100;
  for (const Case& c : Cases(options.Quick))
  {
    ++seed;
    const std::string name = Describe(c);
    if (options.Only.empty() || name.find(options.Only) != std::string::npos)
    {
      RunCase(c, name, seed, options);
    }
  }
  if (options.Csv)
  {
    std::fclose(options.Csv);
  }
  return EXIT_SUCCESS;
}

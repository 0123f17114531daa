// pcb_edges: sharp edges under noise (issues 15 and 25). For generated shapes with exact ground
// truth, the best of a grid search over each method's parameters, judged by the RMS distance to
// the true surface of the points near sharp edges (edge RMS: the points whose noise-free
// position is within 3 sigma of an edge; "wide": within 3 sigma + 3% of the diagonal) and of all
// points (RMS), in 1e-3 of the shape's bounding-box diagonal, with the time of one run (2
// threads unless --threads says otherwise, elapsed time, the minimum of 5) at the best edge
// setting:
//   - the paper's filter (r, rn, N),
//   - the edge-aware mode (EdgeAware on; r, rn, N),
//   - CGAL's jet_smooth_point_set (k) and bilateral_smooth_point_set (Huang et al. 2013: k,
//     sharpness angle, iterations, after pca_estimate_normals with the same k), when CGAL was
//     found at configure time (Debian's libcgal-dev; for this benchmark only);
// then the cheapest edge-aware setting that reaches CGAL bilateral's best edge RMS and the
// paper's best RMS, with its time, and the automatic mode (ChooseParameters) in both modes, the
// edge-aware one with its time and that of the automatic choice (MeasureScales and the rule).
// Built with the project, run by hand (see docs/edge-aware.md):
//
//   pcb_edges [--only SUBSTRING] [--no-cgal] [--no-grid] [--threads N] [--cpu-time]
//       --no-grid leaves out the grids of the paper's filter and of the edge-aware mode (the
//       quick check of a change to the automatic rule); --cpu-time times processor time.
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
#include <functional>
#include <string>
#include <vector>

#ifdef PCB_HAVE_CGAL
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif
#include <CGAL/bilateral_smooth_point_set.h>
#include <CGAL/jet_smooth_point_set.h>
#include <CGAL/pca_estimate_normals.h>
#include <CGAL/property_map.h>
#endif

namespace
{
using namespace pcbilateral_samples;
using namespace pcbilateral_benchmark;

/// Threads of every method's runs (--threads).
int Threads = 2;
/// Whether the times are processor time (--cpu-time: all threads' user and system time) rather
/// than elapsed time: less sensitive to the other work of a shared machine, but it counts the
/// time threads spend waiting for each other when they spin.
bool ProcessorTime = false;

/// The time of one run, the minimum of 5: the methods run on the same threads, and the minimum
/// is the least disturbed by the other work of a shared machine.
double TimeRuns(const std::function<void()>& run)
{
  double best = 1e300;
  for (int k = 0; k < 5; ++k)
  {
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = CpuSeconds();
    run();
    best = std::min(best, ProcessorTime ? CpuSeconds() - cpuStart : Seconds(start));
  }
  return best;
}

/// The best of a method over its grid: each setting is a function giving the positions after
/// 1, 2, ... steps of it (a chain), so that every number of iterations is measured on the way.
struct Best
{
  Quality ByEdge{ 1e300, 1e300, 1e300 }; // the setting with the best edge RMS (its RMS too)
  Quality ByRms{ 1e300, 1e300, 1e300 };  // the setting with the best RMS
  std::string EdgeAt, RmsAt;
  std::function<std::vector<double>()> RunBestEdge; // one whole run at the best edge setting
  double Time = 0.0;
  /// Every setting, with a measure of its cost (neighbours per point x steps), for the cheapest
  /// one that reaches a target.
  struct Setting
  {
    Quality Result;
    std::string At;
    double Cost;
    std::function<std::vector<double>()> Run;
  };
  std::vector<Setting> All;

  void Consider(const Quality& q,
    const std::string& at,
    bool hasEdges,
    const std::function<std::vector<double>()>& run)
  {
    if (hasEdges ? q.EdgeRms < this->ByEdge.EdgeRms : q.Rms < this->ByEdge.Rms)
    {
      this->ByEdge = q;
      this->EdgeAt = at;
      this->RunBestEdge = run;
    }
    if (q.Rms < this->ByRms.Rms)
    {
      this->ByRms = q;
      this->RmsAt = at;
    }
  }

  void TimeBest()
  {
    this->Time = TimeRuns([this] { this->RunBestEdge(); });
  }
};

std::vector<double> RunFilter(const std::vector<double>& input,
  pcbilateral::BilateralParameters parameters)
{
  parameters.NumberOfThreads = Threads;
  pcbilateral::BilateralResult result =
    pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(input), parameters);
  if (result.Status != pcbilateral::BilateralStatus::Completed)
  {
    std::fprintf(stderr, "run failed: %s\n", result.Error.c_str());
    std::exit(EXIT_FAILURE);
  }
  return std::move(result.Positions);
}

std::vector<double> RunFilter(const std::vector<double>& input,
  double r,
  double rn,
  int iterations,
  bool edgeAware)
{
  pcbilateral::BilateralParameters parameters;
  parameters.Radius = r;
  parameters.NormalRadius = rn;
  parameters.NumberOfIterations = iterations;
  parameters.EdgeAware = edgeAware;
  return RunFilter(input, parameters);
}

Best SearchFilter(const Truth& truth, double s, double sigma, bool edgeAware)
{
  Best best;
  const bool hasEdges = truth.EdgePoints > 0;
  const std::vector<double>& input = truth.Cloud->Positions;
  // r in steps of about 2^(1/4) from 12 s: the cheapest setting reaching a target is found
  // within a factor 1.4 in cost (neighbours x iterations), not 2.
  for (double rs : { 6.0, 8.5, 12.0, 14.0, 17.0, 20.0, 24.0 })
  {
    for (double rnSigma : { 2.2, 3.3, 5.0, 7.5, 11.0, 16.0 })
    {
      const double r = rs * s, rn = rnSigma * sigma;
      std::vector<double> positions = input;
      for (int n = 1; n <= 4; ++n)
      {
        positions = RunFilter(positions, r, rn, 1, edgeAware);
        char at[64];
        std::snprintf(at, sizeof at, "r %.1fs, rn %.1fσ, N %d", rs, rnSigma, n);
        const Quality quality = truth.Measure(positions);
        auto run = [&input, r, rn, n, edgeAware] { return RunFilter(input, r, rn, n, edgeAware); };
        best.Consider(quality, at, hasEdges, run);
        best.All.push_back({ quality, at, rs * rs * n, run });
      }
    }
  }
  return best;
}

#ifdef PCB_HAVE_CGAL
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using PointWithNormal = std::pair<Point, Vector>;
#ifdef CGAL_LINKED_WITH_TBB
using CgalConcurrency = CGAL::Parallel_tag;
#else
using CgalConcurrency = CGAL::Sequential_tag;
#endif

std::vector<double> Flatten(const std::vector<Point>& points)
{
  std::vector<double> positions;
  positions.reserve(3 * points.size());
  for (const Point& p : points)
  {
    positions.insert(positions.end(), { p.x(), p.y(), p.z() });
  }
  return positions;
}

std::vector<Point> Points(const std::vector<double>& positions)
{
  std::vector<Point> points;
  for (std::size_t i = 0; i < positions.size(); i += 3)
  {
    points.emplace_back(positions[i], positions[i + 1], positions[i + 2]);
  }
  return points;
}

std::vector<double> RunJet(const std::vector<double>& input, unsigned k)
{
  std::vector<Point> points = Points(input);
  CGAL::jet_smooth_point_set<CgalConcurrency>(points, k);
  return Flatten(points);
}

Best SearchJet(const Truth& truth)
{
  Best best;
  for (unsigned k : { 12u, 24u, 48u, 96u, 192u })
  {
    const std::vector<double>& input = truth.Cloud->Positions;
    char at[32];
    std::snprintf(at, sizeof at, "k %u", k);
    best.Consider(truth.Measure(RunJet(input, k)),
      at,
      truth.EdgePoints > 0,
      [&input, k] { return RunJet(input, k); });
  }
  return best;
}

/// pca_estimate_normals with k, then `iterations` of bilateral_smooth_point_set; `each` sees
/// the positions after every iteration.
std::vector<double> RunCgalBilateral(const std::vector<double>& input,
  unsigned k,
  double angle,
  int iterations,
  const std::function<void(int, const std::vector<double>&)>& each = {})
{
  std::vector<PointWithNormal> points;
  for (std::size_t i = 0; i < input.size(); i += 3)
  {
    points.emplace_back(Point(input[i], input[i + 1], input[i + 2]), Vector(0, 0, 0));
  }
  const auto maps = CGAL::parameters::point_map(CGAL::First_of_pair_property_map<PointWithNormal>())
                      .normal_map(CGAL::Second_of_pair_property_map<PointWithNormal>());
  CGAL::pca_estimate_normals<CgalConcurrency>(points, k, maps);
  std::vector<double> positions;
  for (int n = 1; n <= iterations; ++n)
  {
    CGAL::bilateral_smooth_point_set<CgalConcurrency>(points, k, maps.sharpness_angle(angle));
    positions.clear();
    for (const PointWithNormal& p : points)
    {
      positions.insert(positions.end(), { p.first.x(), p.first.y(), p.first.z() });
    }
    if (each)
    {
      each(n, positions);
    }
  }
  return positions;
}

Best SearchCgalBilateral(const Truth& truth)
{
  Best best;
  const std::vector<double>& input = truth.Cloud->Positions;
  for (unsigned k : { 48u, 96u, 192u })
  {
    for (double angle : { 10.0, 15.0, 25.0 })
    {
      RunCgalBilateral(input,
        k,
        angle,
        5,
        [&](int n, const std::vector<double>& positions)
        {
          char at[64];
          std::snprintf(at, sizeof at, "k %u, %.0f°, N %d", k, angle, n);
          best.Consider(truth.Measure(positions),
            at,
            truth.EdgePoints > 0,
            [&input, k, angle, n] { return RunCgalBilateral(input, k, angle, n); });
        });
    }
  }
  return best;
}
#endif

struct Case
{
  std::string Name;
  std::function<std::unique_ptr<Shape>()> Make;
  double Noise;
};

std::vector<Case> Cases()
{
  auto cube = [] { return Cube(); };
  auto sharpEdge = [] { return SharpEdge(); };
  auto cutCylinder = [] { return std::unique_ptr<Shape>(new CutCylinder(0.2)); };
  auto sphere = [] { return std::unique_ptr<Shape>(new Sphere()); };
  auto cylinder = [] { return std::unique_ptr<Shape>(new CutCylinder()); };
  // The first eight keep their seeds (501 to 508) from the first measurements.
  return { { "cube", cube, 0.005 },
    { "cube", cube, 0.01 },
    { "sharp edge", sharpEdge, 0.005 },
    { "sharp edge", sharpEdge, 0.01 },
    { "cut cylinder", cutCylinder, 0.005 },
    { "cut cylinder", cutCylinder, 0.01 },
    { "sphere", sphere, 0.005 },
    { "sphere", sphere, 0.01 },
    { "cube", cube, 0.001 },
    { "sharp edge", sharpEdge, 0.001 },
    { "cut cylinder", cutCylinder, 0.001 },
    { "cylinder", cylinder, 0.005 } };
}

struct Options
{
  std::string Only;
  bool Cgal = true;
  bool Grid = true;
};

/// The options; false for an unknown one.
bool ParseArguments(int argc, char* argv[], Options& options)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    if (argument == "--only" && i + 1 < argc)
    {
      options.Only = argv[++i];
    }
    else if (argument == "--no-cgal")
    {
      options.Cgal = false;
    }
    else if (argument == "--no-grid")
    {
      options.Grid = false;
    }
    else if (argument == "--cpu-time")
    {
      ProcessorTime = true;
    }
    else if (argument == "--threads" && i + 1 < argc)
    {
      Threads = std::max(1, std::atoi(argv[++i]));
    }
    else
    {
      return false;
    }
  }
#ifndef PCB_HAVE_CGAL
  options.Cgal = false;
#endif
  return true;
}

void PrintHeader()
{
  std::printf("Edge RMS (3 sigma band) / wide edge RMS (3 sigma + 3%% of the diagonal) / RMS in "
              "1e-3 of the diagonal (20k points, uniform), each method at its best edge setting "
              "(3 sigma band; the best RMS without edges); then its best RMS; time of one run at "
              "that setting (%d threads, %s, minimum of 5)\n\n",
    Threads,
    ProcessorTime ? "processor time" : "elapsed");
  std::printf(
    "| case | noisy | paper: edge / wide / RMS (setting) | paper best RMS | edge-aware: edge / "
    "wide / RMS (setting) | edge-aware best RMS | CGAL jet: edge / wide / RMS (k) | CGAL "
    "bilateral: edge / wide / RMS (setting) | time paper / edge-aware / jet / CGAL bilateral | "
    "cheapest edge-aware setting reaching the targets: edge / RMS, time | automatic paper: edge "
    "/ wide / RMS | automatic edge-aware: edge / wide / RMS (setting), time (choice) | automatic "
    "edge-aware against CGAL bilateral's best: edge, time; RMS / noisy RMS |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
}

/// The first four characters of the value's decimal text (truncated, not rounded).
std::string FourCharacters(double value)
{
  return std::to_string(value).substr(0, 4);
}

/// "edge / wide / RMS", "–" for the edges without edges.
std::string Measures(const Quality& q, bool hasEdges)
{
  char text[96];
  if (hasEdges)
  {
    std::snprintf(text, sizeof text, "%.2f / %.2f / %.2f", q.EdgeRms, q.WideEdgeRms, q.Rms);
  }
  else
  {
    std::snprintf(text, sizeof text, "– / – / %.2f", q.Rms);
  }
  return text;
}

/// A method at its best edge setting: "edge / wide / RMS (setting)".
std::string QualityText(const Best& b, bool hasEdges)
{
  return Measures(b.ByEdge, hasEdges) + " (" + b.EdgeAt + ")";
}

/// A method at its best RMS setting: "RMS (setting)".
std::string BestRmsText(const Best& b)
{
  char text[96];
  std::snprintf(text, sizeof text, "%.2f (%s)", b.ByRms.Rms, b.RmsAt.c_str());
  return text;
}

/// The automatic mode (ChooseParameters) in both modes, the edge-aware one timed with the
/// automatic choice.
struct Automatic
{
  std::string PaperText, AwareText;
  Quality Aware;
  double Time = 0.0;
};

Automatic RunAutomatic(const Truth& truth, const pcbilateral::CloudScales& scales)
{
  const bool hasEdges = truth.EdgePoints > 0;
  const std::vector<double>& input = truth.Cloud->Positions;
  Automatic automatic;
  pcbilateral::BilateralParameters user;
  const pcbilateral::BilateralParameters paper = pcbilateral::ChooseParameters(scales, user);
  automatic.PaperText = Measures(truth.Measure(RunFilter(input, paper)), hasEdges);
  user.EdgeAware = true;
  const pcbilateral::BilateralParameters aware = pcbilateral::ChooseParameters(scales, user);
  automatic.Aware = truth.Measure(RunFilter(input, aware));
  automatic.Time = TimeRuns([&] { RunFilter(input, aware); });
  pcbilateral::ScaleMeasurementOptions options;
  options.NumberOfThreads = Threads;
  const double choice = TimeRuns(
    [&]
    {
      const pcbilateral::CloudScales measured =
        pcbilateral::MeasureScales(pcbilateral_testing::ViewOf(input), options);
      pcbilateral::ChooseParameters(measured, user);
    });
  char text[200];
  std::snprintf(text,
    sizeof text,
    " (r %.1fs, rn %.1fσ, N %d), %.3f s (%.3f s)",
    aware.Radius / scales.PointSpacing,
    aware.NormalRadius / scales.NoiseSigma,
    aware.NumberOfIterations,
    automatic.Time,
    choice);
  automatic.AwareText = Measures(automatic.Aware, hasEdges) + text;
  return automatic;
}

/// CGAL's columns, their times and CGAL bilateral's edge target ("–" and no target without
/// CGAL).
struct CgalColumns
{
  std::string Jet = "–";
  std::string Bilateral = "–";
  std::string Times; ///< " / jet / bilateral s"
  double BilateralEdgeRms = 1e300;
  double BilateralTime = 0.0;
};

#ifdef PCB_HAVE_CGAL
CgalColumns CompareWithCgal(const Truth& truth)
{
  const bool hasEdges = truth.EdgePoints > 0;
  Best jet = SearchJet(truth);
  Best bilateral = SearchCgalBilateral(truth);
  jet.TimeBest();
  bilateral.TimeBest();
  CgalColumns columns;
  columns.Jet = QualityText(jet, hasEdges);
  columns.Bilateral = QualityText(bilateral, hasEdges);
  columns.BilateralEdgeRms = hasEdges ? bilateral.ByEdge.EdgeRms : 1e300;
  columns.BilateralTime = bilateral.Time;
  char timeText[160];
  std::snprintf(timeText, sizeof timeText, " / %.3f / %.3f s", jet.Time, bilateral.Time);
  columns.Times = timeText;
  return columns;
}
#endif

/// The cheapest edge-aware setting (fewest neighbours x iterations) with an edge RMS at most
/// edgeTarget and an RMS at most rmsTarget: "edge / RMS (setting), time", and how much faster
/// than CGAL bilateral when it ran; "–" when none reaches them.
std::string CheapestText(const Best& edgeAware,
  double edgeTarget,
  double rmsTarget,
  bool hasEdges,
  double cgalTime)
{
  const Best::Setting* cheapest = nullptr;
  for (const Best::Setting& setting : edgeAware.All)
  {
    if (setting.Result.EdgeRms <= edgeTarget && setting.Result.Rms <= rmsTarget &&
        (!cheapest || setting.Cost < cheapest->Cost))
    {
      cheapest = &setting;
    }
  }
  if (!cheapest)
  {
    return "–";
  }
  Best timing;
  timing.RunBestEdge = cheapest->Run;
  timing.TimeBest();
  char edge[16] = "–";
  if (hasEdges)
  {
    std::snprintf(edge, sizeof edge, "%.2f", cheapest->Result.EdgeRms);
  }
  char text[200];
  std::snprintf(text,
    sizeof text,
    "%s / %.2f (%s), %.3f s%s",
    edge,
    cheapest->Result.Rms,
    cheapest->At.c_str(),
    timing.Time,
    cgalTime > 0 ? (", " + FourCharacters(cgalTime / timing.Time) + "x faster").c_str() : "");
  return text;
}

/// The automatic edge-aware mode against CGAL bilateral's best: "edge ratio, time ratio; RMS
/// ratio to the noisy cloud's".
std::string AgainstText(const Automatic& automatic,
  const CgalColumns& cgal,
  const Quality& noisy,
  bool hasEdges)
{
  char text[160];
  std::snprintf(text,
    sizeof text,
    "%s, %s; %.3fx",
    hasEdges && cgal.BilateralTime > 0
      ? (FourCharacters(automatic.Aware.EdgeRms / cgal.BilateralEdgeRms) + "x").c_str()
      : "–",
    cgal.BilateralTime > 0 ? (FourCharacters(automatic.Time / cgal.BilateralTime) + "x").c_str()
                           : "–",
    automatic.Aware.Rms / noisy.Rms);
  return text;
}

void RunCase(const Case& c, const char* name, std::uint64_t seed, const Options& options)
{
  const std::unique_ptr<Shape> shape = c.Make();
  const NoisyCloud cloud = MakeNoisyCloud(*shape, 20000, c.Noise, false, 0.0, seed);
  const Truth truth(*shape, cloud, 1e3 / shape->Diagonal());
  const bool hasEdges = truth.EdgePoints > 0;
  const Quality noisy = truth.Measure(cloud.Positions);
  pcbilateral::ScaleMeasurementOptions measurement;
  measurement.NumberOfThreads = Threads;
  const pcbilateral::CloudScales scales =
    pcbilateral::MeasureScales(pcbilateral_testing::ViewOf(cloud.Positions), measurement);
  const Automatic automatic = RunAutomatic(truth, scales);
  Best paper, edgeAware;
  if (options.Grid)
  {
    paper = SearchFilter(truth, scales.PointSpacing, scales.NoiseSigma, false);
    edgeAware = SearchFilter(truth, scales.PointSpacing, scales.NoiseSigma, true);
    paper.TimeBest();
    edgeAware.TimeBest();
  }
  // The targets of the cheapest edge-aware setting: an edge RMS at most CGAL bilateral's best
  // (or, without CGAL, the paper's best) and an RMS at most the paper's best.
  CgalColumns columns;
  columns.BilateralEdgeRms = hasEdges ? paper.ByEdge.EdgeRms : 1e300;
  columns.Times = " s";
#ifdef PCB_HAVE_CGAL
  if (options.Cgal)
  {
    columns = CompareWithCgal(truth);
  }
#endif
  char times[160];
  std::snprintf(
    times, sizeof times, "%.3f / %.3f%s", paper.Time, edgeAware.Time, columns.Times.c_str());
  const std::string cheapText =
    options.Grid
      ? CheapestText(
          edgeAware, columns.BilateralEdgeRms, paper.ByRms.Rms, hasEdges, columns.BilateralTime)
      : "–";
  std::printf("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
    name,
    Measures(noisy, hasEdges).c_str(),
    options.Grid ? QualityText(paper, hasEdges).c_str() : "–",
    options.Grid ? BestRmsText(paper).c_str() : "–",
    options.Grid ? QualityText(edgeAware, hasEdges).c_str() : "–",
    options.Grid ? BestRmsText(edgeAware).c_str() : "–",
    columns.Jet.c_str(),
    columns.Bilateral.c_str(),
    times,
    cheapText.c_str(),
    automatic.PaperText.c_str(),
    automatic.AwareText.c_str(),
    AgainstText(automatic, columns, noisy, hasEdges).c_str());
  std::fflush(stdout);
}
} // namespace

int main(int argc, char* argv[])
{
  Options options;
  if (!ParseArguments(argc, argv, options))
  {
    std::fprintf(stderr,
      "usage: %s [--only SUBSTRING] [--no-cgal] [--no-grid] [--threads N] [--cpu-time]\n",
      argv[0]);
    return EXIT_FAILURE;
  }
#if defined(PCB_HAVE_CGAL) && defined(CGAL_LINKED_WITH_TBB)
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, Threads);
#endif
  PrintHeader();
  std::uint64_t seed = 500;
  for (const Case& c : Cases())
  {
    ++seed;
    char name[96];
    std::snprintf(name, sizeof name, "%s %.1f%%", c.Name.c_str(), 100 * c.Noise);
    if (options.Only.empty() || std::string(name).find(options.Only) != std::string::npos)
    {
      RunCase(c, name, seed, options);
    }
  }
  return EXIT_SUCCESS;
}

// pcb_edges: sharp edges under strong noise (issue 15). For generated shapes with exact ground
// truth, the best of a grid search over each method's parameters, judged by the RMS distance to
// the true surface of the points near sharp edges (edge RMS) and of all points (RMS), in 1e-3 of
// the shape's bounding-box diagonal, with the time of one run (1 thread, processor time, the
// minimum of 5) at the best edge setting:
//   - the paper's filter (r, rn, N),
//   - the edge-aware mode (EdgeAware on; r, rn, N),
//   - CGAL's jet_smooth_point_set (k) and bilateral_smooth_point_set (Huang et al. 2013: k,
//     sharpness angle, iterations, after pca_estimate_normals with the same k), when CGAL was
//     found at configure time (Debian's libcgal-dev; for this benchmark only);
// then the cheapest edge-aware setting that reaches CGAL bilateral's best edge RMS and the
// paper's best RMS, with its time, and the automatic mode's rule (ChooseParameters) in both
// modes.
// Built with the project, run by hand (see docs/edge-aware.md):
//
//   pcb_edges [--only SUBSTRING] [--no-cgal]
#include "AutomaticRule.h"
#include "BilateralFilter.h"
#include "CloudMeasurement.h"
#include "GroundTruth.h"
#include "SampleShapes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#ifdef PCB_HAVE_CGAL
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/bilateral_smooth_point_set.h>
#include <CGAL/jet_smooth_point_set.h>
#include <CGAL/pca_estimate_normals.h>
#include <CGAL/property_map.h>
#endif

namespace
{
using namespace pcbilateral_samples;
using namespace pcbilateral_benchmark;

/// The best of a method over its grid: each setting is a function giving the positions after
/// 1, 2, ... steps of it (a chain), so that every number of iterations is measured on the way.
struct Best
{
  Quality ByEdge{ 1e300, 1e300 }; // the setting with the best edge RMS (its RMS too)
  Quality ByRms{ 1e300, 1e300 };  // the setting with the best RMS
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

  /// The processor time of one run (every method runs on one thread), the minimum of 5: less
  /// sensitive than the elapsed time to the other work of a shared machine, which must not
  /// weigh on one method's time and not on another's.
  void TimeBest()
  {
    this->Time = 1e300;
    for (int k = 0; k < 5; ++k)
    {
      const double start = CpuSeconds();
      this->RunBestEdge();
      this->Time = std::min(this->Time, CpuSeconds() - start);
    }
  }
};

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
  parameters.NumberOfThreads = 1;
  parameters.EdgeAware = edgeAware;
  pcbilateral::BilateralResult result =
    pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(input), parameters);
  if (result.Status != pcbilateral::BilateralStatus::Completed)
  {
    std::fprintf(stderr, "run failed: %s\n", result.Error.c_str());
    std::exit(EXIT_FAILURE);
  }
  return std::move(result.Positions);
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
  CGAL::jet_smooth_point_set<CGAL::Sequential_tag>(points, k);
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
  CGAL::pca_estimate_normals<CGAL::Sequential_tag>(points, k, maps);
  std::vector<double> positions;
  for (int n = 1; n <= iterations; ++n)
  {
    CGAL::bilateral_smooth_point_set<CGAL::Sequential_tag>(points, k, maps.sharpness_angle(angle));
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
  return { { "cube", cube, 0.005 },
    { "cube", cube, 0.01 },
    { "sharp edge", sharpEdge, 0.005 },
    { "sharp edge", sharpEdge, 0.01 },
    { "cut cylinder", cutCylinder, 0.005 },
    { "cut cylinder", cutCylinder, 0.01 },
    { "sphere", sphere, 0.005 },
    { "sphere", sphere, 0.01 } };
}

struct Options
{
  std::string Only;
  bool Cgal = true;
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
  std::printf("Edge RMS / RMS in 1e-3 of the diagonal (20k points, uniform), each method at its "
              "best edge setting; then its best RMS; time of one run at the best edge setting "
              "(1 thread, processor time, minimum of 5)\n\n");
  std::printf(
    "| case | noisy | paper: edge / RMS (setting) | paper best RMS | edge-aware: edge / "
    "RMS (setting) | edge-aware best RMS | CGAL jet: edge / RMS (k) | CGAL bilateral: "
    "edge / RMS (setting) | time paper / edge-aware / jet / CGAL bilateral | cheapest edge-aware "
    "setting reaching the targets: edge / RMS, time | automatic rule: paper, edge-aware |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
}

/// The first four characters of the value's decimal text (truncated, not rounded).
std::string FourCharacters(double value)
{
  return std::to_string(value).substr(0, 4);
}

/// The noisy cloud's column: edge RMS / RMS, "–" for the edge without edges.
std::string NoisyText(const Quality& noisy, bool hasEdges)
{
  return (hasEdges ? FourCharacters(noisy.EdgeRms) : std::string("–")) + " / " +
         FourCharacters(noisy.Rms);
}

/// The automatic mode's rule (ChooseParameters) as it is, in both modes: "paper, edge-aware
/// (setting)".
std::string AutomaticText(const Truth& truth, const pcbilateral::CloudScales& scales)
{
  const bool hasEdges = truth.EdgePoints > 0;
  pcbilateral::BilateralParameters automatic =
    pcbilateral::ChooseParameters(scales, pcbilateral::BilateralParameters());
  automatic.NumberOfThreads = 1;
  const std::vector<double>& input = truth.Cloud->Positions;
  const Quality autoPaper = truth.Measure(RunFilter(
    input, automatic.Radius, automatic.NormalRadius, automatic.NumberOfIterations, false));
  const Quality autoAware = truth.Measure(
    RunFilter(input, automatic.Radius, automatic.NormalRadius, automatic.NumberOfIterations, true));
  char autoText[160];
  std::snprintf(autoText,
    sizeof autoText,
    "%s%.2f, %s%.2f (r %.1fs, rn %.1fσ, N %d)",
    hasEdges ? (FourCharacters(autoPaper.EdgeRms) + " / ").c_str() : "– / ",
    autoPaper.Rms,
    hasEdges ? (FourCharacters(autoAware.EdgeRms) + " / ").c_str() : "– / ",
    autoAware.Rms,
    automatic.Radius / scales.PointSpacing,
    automatic.NormalRadius / scales.NoiseSigma,
    automatic.NumberOfIterations);
  return autoText;
}

/// A method at its best edge setting: "edge / RMS (setting)", "–" for the edge without edges.
std::string QualityText(const Best& b, bool hasEdges)
{
  char text[160];
  if (hasEdges)
  {
    std::snprintf(text, sizeof text, "%.2f / %.2f", b.ByEdge.EdgeRms, b.ByEdge.Rms);
  }
  else
  {
    std::snprintf(text, sizeof text, "– / %.2f", b.ByEdge.Rms);
  }
  return std::string(text) + " (" + b.EdgeAt + ")";
}

/// A method at its best RMS setting: "RMS (setting)".
std::string BestRmsText(const Best& b)
{
  char text[96];
  std::snprintf(text, sizeof text, "%.2f (%s)", b.ByRms.Rms, b.RmsAt.c_str());
  return text;
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

void RunCase(const Case& c, const char* name, std::uint64_t seed, [[maybe_unused]] bool cgal)
{
  const std::unique_ptr<Shape> shape = c.Make();
  const NoisyCloud cloud = MakeNoisyCloud(*shape, 20000, c.Noise, false, 0.0, seed);
  const Truth truth(*shape, cloud, 1e3 / shape->Diagonal());
  const bool hasEdges = truth.EdgePoints > 0;
  const Quality noisy = truth.Measure(cloud.Positions);
  pcbilateral::ScaleMeasurementOptions options;
  options.NumberOfThreads = 1;
  const pcbilateral::CloudScales scales =
    pcbilateral::MeasureScales(pcbilateral_testing::ViewOf(cloud.Positions), options);
  const std::string autoText = AutomaticText(truth, scales);
  Best paper = SearchFilter(truth, scales.PointSpacing, scales.NoiseSigma, false);
  Best edgeAware = SearchFilter(truth, scales.PointSpacing, scales.NoiseSigma, true);
  paper.TimeBest();
  edgeAware.TimeBest();
  // The targets of the cheapest edge-aware setting: an edge RMS at most CGAL bilateral's best
  // (or, without CGAL, the paper's best) and an RMS at most the paper's best.
  CgalColumns columns;
  columns.BilateralEdgeRms = hasEdges ? paper.ByEdge.EdgeRms : 1e300;
  columns.Times = " s";
#ifdef PCB_HAVE_CGAL
  if (cgal)
  {
    columns = CompareWithCgal(truth);
  }
#endif
  char times[160];
  std::snprintf(
    times, sizeof times, "%.3f / %.3f%s", paper.Time, edgeAware.Time, columns.Times.c_str());
  const std::string cheapText = CheapestText(
    edgeAware, columns.BilateralEdgeRms, paper.ByRms.Rms, hasEdges, columns.BilateralTime);
  std::printf("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
    name,
    NoisyText(noisy, hasEdges).c_str(),
    QualityText(paper, hasEdges).c_str(),
    BestRmsText(paper).c_str(),
    QualityText(edgeAware, hasEdges).c_str(),
    BestRmsText(edgeAware).c_str(),
    columns.Jet.c_str(),
    columns.Bilateral.c_str(),
    times,
    cheapText.c_str(),
    autoText.c_str());
  std::fflush(stdout);
}
} // namespace

int main(int argc, char* argv[])
{
  Options options;
  if (!ParseArguments(argc, argv, options))
  {
    std::fprintf(stderr, "usage: %s [--only SUBSTRING] [--no-cgal]\n", argv[0]);
    return EXIT_FAILURE;
  }
  PrintHeader();
  std::uint64_t seed = 500;
  for (const Case& c : Cases())
  {
    ++seed;
    char name[96];
    std::snprintf(name, sizeof name, "%s %.1f%%", c.Name.c_str(), 100 * c.Noise);
    if (options.Only.empty() || std::string(name).find(options.Only) != std::string::npos)
    {
      RunCase(c, name, seed, options.Cgal);
    }
  }
  return EXIT_SUCCESS;
}

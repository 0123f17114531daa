// The out-of-core run against one run in memory, on clouds held in memory but streamed as a file
// would be: the automatic parameters measured from the stream (on clouds larger than the
// measurement's selection, so that the selection is gathered as the points come), and the
// filtered positions, with slabs of several sizes and points in shuffled order.
#include "BilateralFilter.h"
#include "CloudView.h"
#include "CoreTesting.h"
#include "OutOfCoreRun.h"
#include "SampleShapes.h"
#include "TestClouds.h"

#include <cstring>
#include <numeric>
#include <random>
#include <vector>

namespace
{
using pcbilateral::BilateralParameters;
using pcbilateral::BilateralResult;

/// A cloud in memory read as a stream, a range at a time.
class PointsInMemory : public pcbilateral::StreamedPoints
{
public:
  explicit PointsInMemory(const std::vector<double>& xyz)
    : XYZ(xyz)
  {
  }
  std::uint64_t GetNumberOfPoints() const override { return this->XYZ.size() / 3; }
  std::string ReadPositions(std::uint64_t first, std::size_t count, double* positions) override
  {
    std::memcpy(positions, this->XYZ.data() + 3 * first, 3 * count * sizeof(double));
    return std::string();
  }

private:
  const std::vector<double>& XYZ;
};

/// The cloud's points in a shuffled order (a file in random spatial order).
std::vector<double> Shuffled(const std::vector<double>& xyz, unsigned seed)
{
  std::vector<std::size_t> order(xyz.size() / 3);
  std::iota(order.begin(), order.end(), std::size_t{ 0 });
  std::shuffle(order.begin(), order.end(), std::mt19937(seed));
  std::vector<double> shuffled;
  shuffled.reserve(xyz.size());
  for (std::size_t i : order)
  {
    shuffled.insert(shuffled.end(), &xyz[3 * i], &xyz[3 * i] + 3);
  }
  return shuffled;
}

/// The parameters the run in memory chose.
BilateralResult ChosenInMemory(const std::vector<double>& xyz,
  const BilateralParameters& parameters)
{
  BilateralResult chosen;
  pcbilateral::BilateralObserver observer;
  observer.ParametersChosen = [&chosen](const BilateralResult& result) { chosen = result; };
  pcbilateral::BilateralRun run(pcbilateral_testing::ViewOf(xyz), parameters, observer);
  run.Start(run.GetLocalExtent());
  return chosen;
}

bool SameDouble(double a, double b)
{
  return std::memcmp(&a, &b, sizeof a) == 0;
}

/// The streamed run's positions, with slabs of at most `slabPoints` points (0: one slab).
std::vector<double> Streamed(const std::vector<double>& xyz,
  const BilateralParameters& parameters,
  std::uint64_t slabPoints,
  BilateralResult* summary = nullptr)
{
  PointsInMemory points(xyz);
  pcbilateral::OutOfCoreSettings settings;
  settings.MemoryLimit = std::uint64_t{ 1 } << 30;
  settings.TemporaryDirectory = ".";
  settings.MaximumSlabPoints = slabPoints;
  pcbilateral::OutOfCoreRun run(points, parameters, settings);
  std::vector<double> positions = xyz;
  std::string problem = run.Measure();
  problem = problem.empty() ? run.Bucket() : problem;
  problem = problem.empty() ? run.Filter() : problem;
  problem = problem.empty() ? run.ReadFiltered(0, xyz.size() / 3, positions.data()) : problem;
  PCB_CHECK(problem.empty(), "%s", problem.c_str());
  std::printf("%zu slabs, a halo of %g\n", run.GetPlan().NumberOfSlabs, run.GetPlan().Halo);
  if (summary)
  {
    *summary = run.GetSummary();
  }
  return positions;
}

/// More points than the measurement's selection: the streamed run measures the same selection
/// (the same spacing, noise and parameters, bit for bit), whatever the order of the points.
void Selection()
{
  const std::vector<double> sheet = pcbilateral_testing::DensityVaryingSheet(700000, 2.0, 0.002, 5);
  for (const std::vector<double>& xyz : { sheet, Shuffled(sheet, 9) })
  {
    const BilateralParameters automatic;
    const BilateralResult inMemory = ChosenInMemory(xyz, automatic);
    BilateralResult streamed;
    PointsInMemory points(xyz);
    pcbilateral::OutOfCoreSettings settings;
    settings.MemoryLimit = 64u << 20; // (ranges of 65,536 points: the selection is pruned)
    settings.TemporaryDirectory = ".";
    pcbilateral::OutOfCoreRun run(points, automatic, settings);
    PCB_CHECK(run.Measure().empty(), "measured");
    streamed = run.GetSummary();
    PCB_CHECK(inMemory.Measured && SameDouble(inMemory.PointSpacing, streamed.PointSpacing) &&
                SameDouble(inMemory.NoiseSigma, streamed.NoiseSigma) &&
                SameDouble(inMemory.RadiusUsed, streamed.RadiusUsed) &&
                SameDouble(inMemory.NormalRadiusUsed, streamed.NormalRadiusUsed) &&
                inMemory.NumberOfIterationsUsed == streamed.NumberOfIterationsUsed,
      "spacing %.17g / %.17g, sigma %.17g / %.17g, radius %.17g / %.17g",
      inMemory.PointSpacing,
      streamed.PointSpacing,
      inMemory.NoiseSigma,
      streamed.NoiseSigma,
      inMemory.RadiusUsed,
      streamed.RadiusUsed);
  }
}

/// The filtered positions, bit for bit, for slabs of several sizes, the points in file order
/// or shuffled, with explicit and automatic parameters.
void Positions()
{
  // Stretched 4 times along x: slabs narrow beside the automatic halo (N^2 radii).
  std::vector<double> sheet = pcbilateral_testing::DensityVaryingSheet(120000, 8.0, 0.003, 3);
  for (std::size_t i = 0; i < sheet.size(); i += 3)
  {
    sheet[i] *= 4.0;
  }
  BilateralParameters explicitParameters;
  explicitParameters.Radius = 0.012;
  explicitParameters.NormalRadius = 0.004;
  explicitParameters.NumberOfIterations = 3;
  for (const BilateralParameters& parameters : { explicitParameters, BilateralParameters() })
  {
    for (const std::vector<double>& xyz : { sheet, Shuffled(sheet, 4) })
    {
      const std::vector<double> inMemory =
        pcbilateral::RunBilateralFilter(pcbilateral_testing::ViewOf(xyz), parameters).Positions;
      for (std::uint64_t slabPoints : { 70000u, 50000u })
      {
        PCB_CHECK(pcbilateral_testing::SameBits(inMemory, Streamed(xyz, parameters, slabPoints)),
          "slabs of at most %llu points: the same bits as in memory (radius %g)",
          static_cast<unsigned long long>(slabPoints),
          parameters.Radius);
      }
    }
  }
}

/// A slab and its halo that cannot fit is refused with a message, no result.
void Refusal()
{
  const std::vector<double> sheet = pcbilateral_testing::DensityVaryingSheet(20000, 2.0, 0.003, 3);
  PointsInMemory points(sheet);
  pcbilateral::OutOfCoreSettings settings;
  settings.MemoryLimit = std::uint64_t{ 1 } << 30;
  settings.TemporaryDirectory = ".";
  settings.MaximumSlabPoints = 100;
  BilateralParameters parameters;
  parameters.Radius = 0.05;
  pcbilateral::OutOfCoreRun run(points, parameters, settings);
  PCB_CHECK(run.Measure().empty(), "measured");
  const std::string problem = run.Bucket();
  PCB_CHECK(problem.find("cannot fit") != std::string::npos, "refused: '%s'", problem.c_str());
}
/// The memory limit chosen when none is given: none while the cloud fits 80% of the available
/// memory, that 80% beyond.
void AutomaticLimit()
{
  const std::uint64_t gigabyte = std::uint64_t{ 1 } << 30;
  const std::uint64_t fits = 8 * gigabyte / 10 / pcbilateral::InMemoryBytesPerPoint;
  PCB_CHECK(pcbilateral::AutomaticMemoryLimit(fits, gigabyte) == 0, "fits: in memory");
  PCB_CHECK(pcbilateral::AutomaticMemoryLimit(fits + 1000, gigabyte) == gigabyte / 10 * 8,
    "does not fit: streamed within 80%% of the available memory");
  PCB_CHECK(pcbilateral::AutomaticMemoryLimit(fits * 100, 0) == 0, "unknown: in memory");
}
} // namespace

int main(int argc, char* argv[])
{
  return RunNamedCase(argc,
    argv,
    { { "Selection", Selection },
      { "Positions", Positions },
      { "Refusal", Refusal },
      { "AutomaticLimit", AutomaticLimit } });
}

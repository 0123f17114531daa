#include "OutOfCoreRun.h"

#include "AutomaticRule.h"
#include "RadiusBands.h"
#include "TemporaryFiles.h"
#include "Threads.h"

#include <sys/statvfs.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

namespace pcbilateral
{

namespace
{
/// Bins along the slab axis: the unit of a slab. Each bin is a file on disk.
constexpr std::size_t NumberOfBins = 256;
/// A point in a bin or in a slab's results: its index in the file and its position.
struct IndexedPoint
{
  std::uint64_t Index;
  double Position[3];
};
/// Disk per point: a bin's record, then a result's.
constexpr std::uint64_t DiskBytesPerPoint = 2 * sizeof(IndexedPoint);
/// A result's index carries this bit when --remove-isolated removed the point.
constexpr std::uint64_t RemovedBit = std::uint64_t{ 1 } << 63;

std::string Describe(const std::string& path, const char* what)
{
  return path + ": " + what + " (" + std::strerror(errno) + ")";
}

/// Reads a file of IndexedPoint records in order, a buffer at a time.
class RecordReader
{
public:
  std::string Open(const std::string& path)
  {
    this->File.reset(std::fopen(path.c_str(), "rb"));
    this->Path = path;
    return this->File ? std::string() : Describe(path, "cannot be read");
  }
  /// The next record, or null at the end.
  const IndexedPoint* Next()
  {
    if (this->At == this->Buffer.size())
    {
      this->Buffer.resize(4096);
      const std::size_t read =
        this->File ? std::fread(this->Buffer.data(), sizeof(IndexedPoint), 4096, this->File.get())
                   : 0;
      this->Buffer.resize(read);
      this->At = 0;
      if (read == 0)
      {
        return nullptr;
      }
    }
    return &this->Buffer[this->At++];
  }
  /// The next record without taking it, or null at the end.
  const IndexedPoint* Peek()
  {
    const IndexedPoint* next = this->Next();
    if (next)
    {
      --this->At;
    }
    return next;
  }

private:
  struct Closer
  {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  std::unique_ptr<std::FILE, Closer> File;
  std::string Path;
  std::vector<IndexedPoint> Buffer;
  std::size_t At = 0;
};

/// The points to read at once: a bounded share of the memory limit, 8,192 to 1M points.
std::size_t ChunkPoints(const OutOfCoreSettings& settings)
{
  const std::uint64_t budget = settings.MemoryLimit > settings.ReservedBytes
                                 ? settings.MemoryLimit - settings.ReservedBytes
                                 : 0;
  return static_cast<std::size_t>(
    std::clamp<std::uint64_t>(budget / (16 * 64), std::uint64_t{ 8192 }, std::uint64_t{ 1 } << 20));
}
} // namespace

struct OutOfCoreRun::Internals
{
  StreamedPoints& Points;
  BilateralParameters User;
  OutOfCoreSettings Settings;
  int Threads = 1;
  std::size_t Chunk = 8192;
  CloudExtent Whole;
  bool HasScales = false;
  CloudScales Scales;
  BilateralParameters Chosen;
  bool FollowsDensity = false;
  bool Filterable = false;
  BilateralResult Summary;
  OutOfCorePlan Plan;
  TemporaryFiles Files;
  double BinWidth = 0.0;
  std::vector<std::uint64_t> BinCounts;
  std::vector<double> BinLargestRadius;
  /// Slab s is bins SlabFirstBin[s] to SlabFirstBin[s + 1] - 1.
  std::vector<std::size_t> SlabFirstBin;
  std::vector<RecordReader> Results;
  std::vector<std::string> WarningsSeen;
  /// Whether every filtered position kept is exactly a float (a PCD file's x y z are then F4).
  bool ResultsAreFloats = true;
  /// The filtered positions kept: min x, y, z, then max x, y, z (a LAS header's bounds).
  double ResultBounds[6] = { HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };

  Internals(StreamedPoints& points,
    const BilateralParameters& parameters,
    const OutOfCoreSettings& settings)
    : Points(points)
    , User(parameters)
    , Settings(settings)
  {
  }

  void Progress(const std::string& phase, double fraction) const
  {
    if (this->Settings.Progress)
    {
      this->Settings.Progress(phase, fraction);
    }
  }

  void Warn(const std::string& warning)
  {
    if (std::find(this->WarningsSeen.begin(), this->WarningsSeen.end(), warning) ==
        this->WarningsSeen.end())
    {
      this->WarningsSeen.push_back(warning);
      this->Summary.Warnings.push_back(warning);
    }
  }

  bool NeedsScales() const
  {
    return this->User.Automatic == AutomaticParameters::Measured &&
           (this->User.Radius == 0.0 || this->User.NormalRadius == 0.0 ||
             this->User.NumberOfIterations == 0);
  }

  /// The whole cloud's extent and, when the parameters need it, its measurement selection.
  std::string ReadExtentAndSelection(std::vector<double>& selection)
  {
    const std::uint64_t total = this->Points.GetNumberOfPoints();
    std::vector<double> chunk;
    for (std::uint64_t first = 0; first < total; first += this->Chunk)
    {
      const auto count =
        static_cast<std::size_t>(std::min<std::uint64_t>(this->Chunk, total - first));
      chunk.resize(3 * count);
      const std::string problem = this->Points.ReadPositions(first, count, chunk.data());
      if (!problem.empty())
      {
        return problem;
      }
      const PointCloudView view{ count, chunk.data(), nullptr };
      this->Whole = first == 0 ? MeasureCloud(view) : MergeExtents(this->Whole, MeasureCloud(view));
      if (this->NeedsScales())
      {
        // The selection of the whole cloud is the points whose hashed key lies below the
        // fraction of the final count; the fraction only falls as points come, so the points
        // kept at the fraction so far include it.
        const double fraction = MeasuredFraction(this->Whole.NumberOfFinitePoints);
        const std::vector<double> kept = SelectMeasurementPoints(view, fraction);
        selection.insert(selection.end(), kept.begin(), kept.end());
        if (selection.size() > 3 * 4 * MaximumMeasuredPoints)
        {
          const PointCloudView candidates{ selection.size() / 3, selection.data(), nullptr };
          selection = SelectMeasurementPoints(candidates, fraction);
        }
      }
      this->Progress("reading", static_cast<double>(first + count) / static_cast<double>(total));
    }
    return std::string();
  }

  /// The parameters, resolved as a BilateralRun over the whole cloud resolves them.
  void ResolveParameters()
  {
    BilateralObserver observer;
    observer.ParametersChosen = [this](const BilateralResult& chosen) { this->Summary = chosen; };
    observer.Warning = [this](const std::string& warning) { this->Warn(warning); };
    BilateralRun probe(PointCloudView(), this->User, observer);
    this->Filterable = probe.Start(this->Whole, this->HasScales ? &this->Scales : nullptr);
    if (!this->Filterable)
    {
      this->Summary.RadiusUsed = probe.GetRadius();
      this->Summary.NormalRadiusUsed = probe.GetNormalRadius();
      this->Summary.NumberOfIterationsUsed = probe.GetNumberOfIterations();
    }
    if (probe.GetStatus() == BilateralStatus::Failed)
    {
      this->Summary.Status = BilateralStatus::Failed;
      this->Summary.Error = probe.GetError();
    }
    this->Chosen = this->HasScales ? ChooseParameters(this->Scales, this->User) : this->User;
    this->FollowsDensity = this->HasScales && this->Scales.LocalSpacing &&
                           RadiusFollowsDensity(this->Scales, this->User);
    this->Summary.Warnings = this->WarningsSeen;
  }

  /// Writes each finite point of a chunk to its bin; where the radius follows the density,
  /// records each bin's largest radius and the radius ranges.
  std::string BinChunk(std::uint64_t first,
    const std::vector<double>& chunk,
    std::vector<std::FILE*>& bins)
  {
    const std::size_t count = chunk.size() / 3;
    RadiusBands bands;
    if (this->FollowsDensity)
    {
      bands = AssignRadiusBands(PointCloudView{ count, chunk.data(), nullptr },
        this->Scales,
        this->User,
        this->Chosen,
        this->Threads);
      this->MergeRanges(bands);
    }
    for (std::size_t i = 0; i < count; ++i)
    {
      const double* p = &chunk[3 * i];
      if (!IsFinitePoint(p))
      {
        continue;
      }
      const std::size_t bin = this->BinOf(p);
      const IndexedPoint record{ first + i, { p[0], p[1], p[2] } };
      if (std::fwrite(&record, sizeof record, 1, bins[bin]) != 1)
      {
        return Describe(this->Files.GetFolder(), "temporary file write failed");
      }
      ++this->BinCounts[bin];
      const double radius = bands.Empty() ? this->Summary.RadiusUsed
                            : bands.BandOfPoint[i] == RadiusBands::NoBand
                              ? 0.0
                              : bands.Radius[bands.BandOfPoint[i]];
      this->BinLargestRadius[bin] = std::max(this->BinLargestRadius[bin], radius);
    }
    return std::string();
  }

  void MergeRanges(const RadiusBands& bands)
  {
    if (bands.Empty())
    {
      return;
    }
    BilateralResult& s = this->Summary;
    const auto normal = std::minmax_element(bands.NormalRadius.begin(), bands.NormalRadius.end());
    const bool firstRange = !s.RadiusFollowsDensity;
    s.RadiusFollowsDensity = true;
    s.PointSpacing = SurfaceSpacing(this->Scales);
    s.RadiusRange[0] =
      firstRange ? bands.SmallestRadius() : std::min(s.RadiusRange[0], bands.SmallestRadius());
    s.RadiusRange[1] =
      firstRange ? bands.LargestRadius() : std::max(s.RadiusRange[1], bands.LargestRadius());
    s.NormalRadiusRange[0] =
      firstRange ? *normal.first : std::min(s.NormalRadiusRange[0], *normal.first);
    s.NormalRadiusRange[1] =
      firstRange ? *normal.second : std::max(s.NormalRadiusRange[1], *normal.second);
  }

  std::size_t BinOf(const double p[3]) const { return this->BinAt(p[this->Plan.Axis]); }

  /// Where bin `bin` starts along the axis.
  double BinStart(std::size_t bin) const
  {
    return this->Whole.Min[this->Plan.Axis] + static_cast<double>(bin) * this->BinWidth;
  }

  /// The halo in radii: N^2 for the paper's filter, whose every step reads its neighbours
  /// within one radius; N^2 + (c - 1) N for the edge-aware mode, whose iteration reads within c
  /// = EdgeAwareReachInRadii radii (the move reads the filtered normals within one radius, which
  /// read the normals within one more, which read the positions within one more).
  double HaloInRadii() const
  {
    const double iterations = this->Summary.NumberOfIterationsUsed;
    const double reach = IterationReachInRadii(this->User);
    return iterations * iterations + (reach - 1.0) * iterations;
  }

  /// The halo of bins [first, last]: HaloInRadii() times the largest radius of the bins it reaches,
  /// widened until it reaches no further bin; and the bins it reaches, which also take in every
  /// bin whose points could move into the halo in N - 1 iterations (each by less than its
  /// largest radius): a point never loaded then never comes within the halo, and every point
  /// that does moves by less than the radius the halo was taken from (docs/streaming.md).
  double HaloOf(std::size_t first, std::size_t last, std::size_t& low, std::size_t& high) const
  {
    const double iterations = this->Summary.NumberOfIterationsUsed;
    // (Margins for the rounding of the positions' arithmetic, as the ghost reach has.)
    const double margin = 1e-9 * this->Whole.LargestMagnitude();
    low = first;
    high = last;
    while (true)
    {
      double largest = 0.0;
      for (std::size_t b = low; b <= high; ++b)
      {
        largest = std::max(largest, this->BinLargestRadius[b]);
      }
      const double halo = this->HaloInRadii() * 1.01 * largest + margin;
      const double from = this->BinStart(first) - halo;
      const double to = this->BinStart(last + 1) + halo;
      std::size_t newLow = this->BinAt(from), newHigh = this->BinAt(to);
      for (std::size_t b = 0; b < newLow; ++b)
      {
        const double travel = (iterations - 1.0) * 1.01 * this->BinLargestRadius[b] + margin;
        newLow = this->BinStart(b + 1) + travel >= from ? b : newLow;
      }
      for (std::size_t b = NumberOfBins - 1; b > newHigh; --b)
      {
        const double travel = (iterations - 1.0) * 1.01 * this->BinLargestRadius[b] + margin;
        newHigh = this->BinStart(b) - travel <= to ? b : newHigh;
      }
      if (newLow >= low && newHigh <= high)
      {
        return halo;
      }
      low = std::min(low, newLow);
      high = std::max(high, newHigh);
    }
  }

  /// The bin holding coordinate `at` along the axis (clamped to the bins).
  std::size_t BinAt(double at) const
  {
    if (!(this->BinWidth > 0.0))
    {
      return 0;
    }
    const double bin = std::floor((at - this->Whole.Min[this->Plan.Axis]) / this->BinWidth);
    return static_cast<std::size_t>(std::clamp(bin, 0.0, static_cast<double>(NumberOfBins - 1)));
  }

  /// Whether bin b holds points of slab [first, last] or of its halo (a bin the halo takes in
  /// only for its radius holds none).
  bool HoldsSlabPoints(std::size_t b, std::size_t first, std::size_t last, double halo) const
  {
    const double slack = 1e-6 * this->BinWidth;
    return (b >= first && b <= last) ||
           (this->BinStart(b + 1) + slack >= this->BinStart(first) - halo &&
             this->BinStart(b) - slack <= this->BinStart(last + 1) + halo);
  }

  /// The points a slab and its halo load at most: those of the bins that hold some.
  std::uint64_t PointsOfSlab(std::size_t first, std::size_t last, double& halo) const
  {
    std::size_t low = 0, high = 0;
    halo = this->HaloOf(first, last, low, high);
    std::uint64_t points = 0;
    for (std::size_t b = low; b <= high; ++b)
    {
      points += this->HoldsSlabPoints(b, first, last, halo) ? this->BinCounts[b] : 0;
    }
    return points;
  }

  std::string PlanSlabs();
  std::string LoadSlab(std::size_t slab, std::vector<IndexedPoint>& points, std::size_t& core);
  std::string FilterSlab(std::size_t slab);
};

std::string OutOfCoreRun::Internals::PlanSlabs()
{
  // The edge-aware mode keeps each point's records, normals and filtered normals besides the
  // paper's arrays, and the neighbour lists of its first step up to a fixed budget.
  const std::uint64_t perPoint =
    this->User.EdgeAware ? EdgeAwareBytesPerSlabPoint : BytesPerSlabPoint;
  const std::uint64_t reserved =
    this->Settings.ReservedBytes + (this->User.EdgeAware ? EdgeAwareNeighbourListBytes : 0);
  const std::uint64_t budget =
    this->Settings.MemoryLimit > reserved ? this->Settings.MemoryLimit - reserved : 0;
  const std::uint64_t slabPoints = this->Settings.MaximumSlabPoints > 0
                                     ? std::min(this->Settings.MaximumSlabPoints, budget / perPoint)
                                     : budget / perPoint;
  std::size_t first = 0;
  while (first < NumberOfBins)
  {
    std::size_t last = first;
    double halo = 0.0;
    std::uint64_t points = this->PointsOfSlab(first, last, halo);
    if (points > slabPoints)
    {
      // A limit that holds this slab, in whole megabytes, so that the user knows what to give
      // rather than guess: 5% over the need, since the program's own memory, measured when the
      // run starts, varies a little from run to run.
      const std::uint64_t needed = (reserved + points * perPoint) / 20 * 21;
      const std::uint64_t megabyte = 1024 * 1024;
      std::ostringstream problem;
      if (budget / perPoint == 0)
      {
        problem << "the memory limit (" << MemorySizeText(this->Settings.MemoryLimit)
                << ") does not cover what the program holds besides the slabs ("
                << (reserved + megabyte - 1) / megabyte << " MB)";
      }
      else
      {
        problem << "a slab and its halo (" << points << " points, a halo of " << halo
                << ") cannot fit the memory limit (room for " << slabPoints << " points"
                << (slabPoints == this->Settings.MaximumSlabPoints ? ", as the slab cap asks" : "")
                << ")";
      }
      problem << ": give --memory-limit " << (needed + megabyte - 1) / megabyte << "M or more";
      return problem.str();
    }
    while (last + 1 < NumberOfBins)
    {
      double nextHalo = 0.0;
      const std::uint64_t nextPoints = this->PointsOfSlab(first, last + 1, nextHalo);
      if (nextPoints > slabPoints)
      {
        break;
      }
      ++last;
      halo = nextHalo;
      points = nextPoints;
    }
    this->SlabFirstBin.push_back(first);
    this->Plan.Halo = std::max(this->Plan.Halo, halo);
    this->Plan.LargestSlabPoints = std::max(this->Plan.LargestSlabPoints, points);
    first = last + 1;
  }
  this->SlabFirstBin.push_back(NumberOfBins);
  this->Plan.NumberOfSlabs = this->SlabFirstBin.size() - 1;
  return std::string();
}

/// The points of a slab and its halo, sorted by index; `core` counts those of the slab's own
/// bins, which come first.
std::string OutOfCoreRun::Internals::LoadSlab(std::size_t slab,
  std::vector<IndexedPoint>& points,
  std::size_t& core)
{
  const std::size_t first = this->SlabFirstBin[slab];
  const std::size_t last = this->SlabFirstBin[slab + 1] - 1;
  std::size_t low = 0, high = 0;
  const double halo = this->HaloOf(first, last, low, high);
  double unused = 0.0;
  const int axis = this->Plan.Axis;
  const double from = this->BinStart(first) - halo;
  const double to = this->BinStart(last + 1) + halo;
  points.clear();
  points.reserve(static_cast<std::size_t>(this->PointsOfSlab(first, last, unused)));
  std::vector<IndexedPoint> haloPoints;
  for (std::size_t b = low; b <= high; ++b)
  {
    const bool own = b >= first && b <= last;
    if (this->BinCounts[b] == 0 || !this->HoldsSlabPoints(b, first, last, halo))
    {
      continue;
    }
    RecordReader bin;
    const std::string path = this->Files.PathOf(b);
    std::string problem = bin.Open(path);
    if (!problem.empty())
    {
      return problem;
    }
    while (const IndexedPoint* p = bin.Next())
    {
      if (own)
      {
        points.push_back(*p);
      }
      else if (p->Position[axis] >= from && p->Position[axis] <= to)
      {
        haloPoints.push_back(*p);
      }
    }
  }
  core = points.size();
  points.insert(points.end(), haloPoints.begin(), haloPoints.end());
  return std::string();
}

std::string OutOfCoreRun::Internals::FilterSlab(std::size_t slab)
{
  std::vector<IndexedPoint> points;
  std::size_t core = 0;
  std::string problem = this->LoadSlab(slab, points, core);
  if (!problem.empty() || points.empty())
  {
    return problem;
  }
  std::vector<double> positions(3 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    std::copy_n(points[i].Position, 3, &positions[3 * i]);
  }
  BilateralObserver observer;
  observer.Warning = [this](const std::string& warning) { this->Warn(warning); };
  BilateralRun run(
    PointCloudView{ points.size(), positions.data(), nullptr }, this->User, observer);
  if (run.Start(this->Whole, this->HasScales ? &this->Scales : nullptr))
  {
    while (run.HasNextIteration())
    {
      run.Step();
    }
  }
  BilateralResult result = run.Finish();
  if (result.Status != BilateralStatus::Completed)
  {
    return result.Error.empty() ? std::string("the filter was stopped") : result.Error;
  }
  this->Summary.NumberOfNeighbourEvaluations += result.NumberOfNeighbourEvaluations;
  points.resize(core);
  for (std::size_t i = 0; i < core; ++i)
  {
    std::copy_n(&result.Positions[3 * i], 3, points[i].Position);
    if (!result.Removed.empty() && result.Removed[i])
    {
      points[i].Index |= RemovedBit;
      ++this->Summary.NumberOfRemovedPoints;
      continue;
    }
    for (int axis = 0; axis < 3; ++axis)
    {
      const double value = points[i].Position[axis];
      this->ResultsAreFloats = this->ResultsAreFloats && static_cast<float>(value) == value;
      this->ResultBounds[axis] = std::min(this->ResultBounds[axis], value);
      this->ResultBounds[3 + axis] = std::max(this->ResultBounds[3 + axis], value);
    }
  }
  std::sort(points.begin(),
    points.end(),
    [](const IndexedPoint& a, const IndexedPoint& b)
    { return (a.Index & ~RemovedBit) < (b.Index & ~RemovedBit); });
  const std::string path = this->Files.PathOf(NumberOfBins + slab);
  std::FILE* file = std::fopen(path.c_str(), "wb");
  const bool ok = file && std::fwrite(points.data(), sizeof(IndexedPoint), core, file) == core;
  if (!file || std::fclose(file) != 0 || !ok)
  {
    return Describe(path, "temporary file write failed");
  }
  return std::string();
}

void LeftAlonePoints::Add(const double* position)
{
  ++this->Count;
  for (int axis = 0; axis < 3; ++axis)
  {
    const double value = position[axis];
    this->Floats = this->Floats && (std::isnan(value) || static_cast<float>(value) == value);
  }
  if (std::isfinite(position[0]) && std::isfinite(position[1]) && std::isfinite(position[2]))
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      this->Bounds[axis] = std::min(this->Bounds[axis], position[axis]);
      this->Bounds[3 + axis] = std::max(this->Bounds[3 + axis], position[axis]);
    }
  }
}

void StreamedPoints::LeaveAlone(std::uint64_t first,
  std::size_t count,
  const std::uint8_t* chosen,
  double* positions)
{
  const bool firstPass = first >= this->LeftAlone.CountedUpTo;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (!chosen[i])
    {
      if (firstPass)
      {
        this->LeftAlone.Add(positions + 3 * i);
      }
      std::fill_n(positions + 3 * i, 3, std::numeric_limits<double>::quiet_NaN());
    }
  }
  if (firstPass)
  {
    this->LeftAlone.CountedUpTo = first + count;
  }
}

OutOfCoreRun::OutOfCoreRun(StreamedPoints& points,
  const BilateralParameters& parameters,
  const OutOfCoreSettings& settings)
  : Impl(std::make_unique<Internals>(points, parameters, settings))
{
  this->Impl->Threads = ResolveThreadCount(parameters.NumberOfThreads);
  this->Impl->Chunk = ChunkPoints(settings);
}

OutOfCoreRun::~OutOfCoreRun() = default;

std::string OutOfCoreRun::Measure()
{
  Internals& run = *this->Impl;
  std::vector<double> selection;
  std::string problem = run.ReadExtentAndSelection(selection);
  if (!problem.empty())
  {
    return problem;
  }
  if (run.NeedsScales() && run.Whole.NumberOfFinitePoints > 0)
  {
    const double fraction = MeasuredFraction(run.Whole.NumberOfFinitePoints);
    const PointCloudView candidates{ selection.size() / 3, selection.data(), nullptr };
    selection = SelectMeasurementPoints(candidates, fraction);
    run.Progress("measuring", 0.0);
    run.Scales = MeasureSelection(selection, fraction, run.Threads);
    run.HasScales = true;
  }
  const std::uint64_t nonFinite = run.Points.GetNumberOfPoints() - run.Whole.NumberOfFinitePoints -
                                  run.Points.GetNumberOfPointsLeftAlone();
  if (run.Whole.NumberOfFinitePoints == 0 && run.Points.GetNumberOfPointsLeftAlone() > 0)
  {
    run.Warn("no point has one of the chosen classes in '" + run.Points.GetClassArrayName() +
             "': every point is passed through unchanged");
  }
  if (nonFinite > 0)
  {
    // (The run in memory's warning: the slabs' runs never see these points.)
    run.Warn(std::to_string(nonFinite) +
             " point(s) have NaN or infinite coordinates: they are passed through unchanged and "
             "are never used as neighbours");
  }
  run.ResolveParameters();
  // (After: the parameters' summary replaces the whole summary.)
  run.Summary.NumberOfNonFinitePoints = static_cast<std::size_t>(nonFinite);
  if (run.Summary.Status == BilateralStatus::Failed)
  {
    return run.Summary.Error;
  }
  run.Summary.Status = BilateralStatus::Completed;
  return std::string();
}

const BilateralResult& OutOfCoreRun::GetSummary() const
{
  return this->Impl->Summary;
}

std::uint64_t OutOfCoreRun::GetDiskBytesNeeded() const
{
  return DiskBytesPerPoint * this->Impl->Whole.NumberOfFinitePoints;
}

bool OutOfCoreRun::AreFilteredPositionsFloats() const
{
  return this->Impl->ResultsAreFloats && this->Impl->Points.GetLeftAlonePoints().Floats;
}

void OutOfCoreRun::GetFilteredBounds(double bounds[6]) const
{
  const double* leftAlone = this->Impl->Points.GetLeftAlonePoints().Bounds;
  for (int axis = 0; axis < 3; ++axis)
  {
    bounds[axis] = std::min(this->Impl->ResultBounds[axis], leftAlone[axis]);
    bounds[3 + axis] = std::max(this->Impl->ResultBounds[3 + axis], leftAlone[3 + axis]);
  }
}

std::uint64_t OutOfCoreRun::GetNumberOfRemovedPoints() const
{
  return this->Impl->Summary.NumberOfRemovedPoints;
}

const OutOfCorePlan& OutOfCoreRun::GetPlan() const
{
  return this->Impl->Plan;
}

std::string OutOfCoreRun::Bucket()
{
  Internals& run = *this->Impl;
  if (!run.Filterable)
  {
    return std::string();
  }
  const std::string parent = run.Settings.TemporaryDirectory;
  struct statvfs space;
  if (::statvfs(parent.c_str(), &space) == 0 &&
      static_cast<std::uint64_t>(space.f_bavail) * space.f_frsize < this->GetDiskBytesNeeded())
  {
    std::ostringstream problem;
    problem << parent << ": " << this->GetDiskBytesNeeded() / 1048576
            << " MB of temporary files are needed and only "
            << static_cast<std::uint64_t>(space.f_bavail) * space.f_frsize / 1048576
            << " MB are free: set TMPDIR to a folder with room";
    return problem.str();
  }
  std::string problem = run.Files.Create(parent);
  if (!problem.empty())
  {
    return problem;
  }
  run.Plan.TemporaryFolder = run.Files.GetFolder();
  run.Plan.DiskBytes = this->GetDiskBytesNeeded();
  const CloudExtent& whole = run.Whole;
  for (int axis = 1; axis < 3; ++axis)
  {
    if (whole.Max[axis] - whole.Min[axis] > whole.Max[run.Plan.Axis] - whole.Min[run.Plan.Axis])
    {
      run.Plan.Axis = axis;
    }
  }
  run.BinWidth = (whole.Max[run.Plan.Axis] - whole.Min[run.Plan.Axis]) / NumberOfBins;
  run.BinCounts.assign(NumberOfBins, 0);
  run.BinLargestRadius.assign(NumberOfBins, 0.0);
  std::vector<std::FILE*> bins(NumberOfBins, nullptr);
  auto closeAll = [&bins]()
  {
    bool ok = true;
    for (std::FILE*& file : bins)
    {
      ok = (!file || std::fclose(file) == 0) && ok;
      file = nullptr;
    }
    return ok;
  };
  for (std::size_t b = 0; b < NumberOfBins; ++b)
  {
    const std::string path = run.Files.PathOf(b);
    bins[b] = std::fopen(path.c_str(), "wb");
    if (!bins[b])
    {
      closeAll();
      return Describe(path, "cannot be written");
    }
    std::setvbuf(bins[b], nullptr, _IOFBF, 1 << 14);
  }
  const std::uint64_t total = run.Points.GetNumberOfPoints();
  std::vector<double> chunk;
  for (std::uint64_t first = 0; first < total && problem.empty(); first += run.Chunk)
  {
    const auto count = static_cast<std::size_t>(std::min<std::uint64_t>(run.Chunk, total - first));
    chunk.resize(3 * count);
    problem = run.Points.ReadPositions(first, count, chunk.data());
    if (problem.empty())
    {
      problem = run.BinChunk(first, chunk, bins);
    }
    run.Progress("bucketing", static_cast<double>(first + count) / static_cast<double>(total));
  }
  if (!closeAll() && problem.empty())
  {
    problem = Describe(run.Files.GetFolder(), "temporary file write failed");
  }
  return problem.empty() ? run.PlanSlabs() : problem;
}

std::string OutOfCoreRun::Filter()
{
  Internals& run = *this->Impl;
  if (!run.Filterable)
  {
    return std::string();
  }
  const std::size_t slabs = run.Plan.NumberOfSlabs;
  for (std::size_t slab = 0; slab < slabs; ++slab)
  {
    run.Progress("slab " + std::to_string(slab + 1) + " of " + std::to_string(slabs),
      static_cast<double>(slab) / static_cast<double>(slabs));
    const std::string problem = run.FilterSlab(slab);
    if (!problem.empty())
    {
      return problem;
    }
  }
  // The bins are no longer needed: their room goes back to the disk before the output is
  // written.
  for (std::size_t b = 0; b < NumberOfBins; ++b)
  {
    std::remove(run.Files.PathOf(b).c_str());
  }
  run.Results.resize(slabs);
  for (std::size_t slab = 0; slab < slabs; ++slab)
  {
    const std::string problem = run.Results[slab].Open(run.Files.PathOf(NumberOfBins + slab));
    if (!problem.empty())
    {
      return problem;
    }
  }
  run.Progress("filtered", 1.0);
  return std::string();
}

std::string OutOfCoreRun::ReadFiltered(std::uint64_t first,
  std::size_t count,
  double* positions,
  std::uint8_t* removed)
{
  Internals& run = *this->Impl;
  const std::uint64_t end = first + count;
  if (removed)
  {
    std::fill_n(removed, count, std::uint8_t{ 0 });
  }
  for (RecordReader& results : run.Results)
  {
    while (const IndexedPoint* p = results.Peek())
    {
      const std::uint64_t index = p->Index & ~RemovedBit;
      if (index >= end)
      {
        break;
      }
      if (index < first)
      {
        return "the filtered points were read out of order";
      }
      std::copy_n(p->Position, 3, positions + 3 * (index - first));
      if (removed)
      {
        removed[index - first] = (p->Index & RemovedBit) ? 1 : 0;
      }
      results.Next();
    }
  }
  return std::string();
}

std::uint64_t ParseMemorySize(const std::string& text)
{
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !(value > 0.0) || !std::isfinite(value))
  {
    return 0;
  }
  const std::string unit(end);
  double scale = 1.0;
  if (unit == "K" || unit == "k" || unit == "KB" || unit == "KiB")
  {
    scale = 1024.0;
  }
  else if (unit == "M" || unit == "m" || unit == "MB" || unit == "MiB")
  {
    scale = 1048576.0;
  }
  else if (unit == "G" || unit == "g" || unit == "GB" || unit == "GiB")
  {
    scale = 1073741824.0;
  }
  else if (!unit.empty())
  {
    return 0;
  }
  const double bytes = value * scale;
  return bytes < 1.0 || bytes > 9e18 ? 0 : static_cast<std::uint64_t>(bytes);
}

std::uint64_t AvailableMemory()
{
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kilobytes = 0;
  std::string unit;
  while (meminfo >> key >> kilobytes >> unit)
  {
    if (key == "MemAvailable:")
    {
      return kilobytes * 1024;
    }
  }
  return 0;
}

std::uint64_t AutomaticMemoryLimit(std::uint64_t numberOfPoints, std::uint64_t available)
{
  const std::uint64_t limit = available / 10 * 8;
  return available == 0 || InMemoryBytesPerPoint * numberOfPoints <= limit ? 0 : limit;
}

std::uint64_t ResidentMemory()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    unsigned long long kilobytes = 0;
    if (std::sscanf(line.c_str(), "VmRSS: %llu kB", &kilobytes) == 1)
    {
      return kilobytes * 1024;
    }
  }
  return 0;
}

std::string TemporaryDirectoryFor(const std::string& outputPath)
{
  const char* tmpdir = std::getenv("TMPDIR");
  if (tmpdir != nullptr && *tmpdir != '\0')
  {
    return tmpdir;
  }
  const std::size_t slash = outputPath.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : outputPath.substr(0, slash + 1);
}

OutOfCoreSettings StreamingSettings(std::uint64_t limit,
  const std::string& outputPath,
  int numberOfThreads)
{
  OutOfCoreSettings settings;
  settings.MemoryLimit = limit;
  // The program, its libraries and the buffers of reading and writing.
  settings.ReservedBytes = ResidentMemory() + (96u << 20);
  settings.TemporaryDirectory = TemporaryDirectoryFor(outputPath);
  settings.NumberOfThreads = numberOfThreads;
  const char* slabPoints = std::getenv("PCB_STREAMING_SLAB_POINTS");
  settings.MaximumSlabPoints = slabPoints ? std::strtoull(slabPoints, nullptr, 10) : 0;
  return settings;
}

std::string MemoryLimitProblem(const OutOfCoreSettings& settings, bool edgeAware)
{
  const std::uint64_t reserved =
    settings.ReservedBytes + (edgeAware ? OutOfCoreRun::EdgeAwareNeighbourListBytes : 0);
  const std::uint64_t megabyte = 1024 * 1024;
  if (settings.MemoryLimit >= megabyte || settings.MemoryLimit >= reserved)
  {
    return std::string();
  }
  return MemorySizeText(settings.MemoryLimit) +
         " is far below what the program holds besides the slabs (" + MemorySizeText(reserved) +
         "); a size without a unit is in bytes: give e.g. 512M or 2G";
}

std::string MemorySizeText(std::uint64_t bytes)
{
  const std::uint64_t kilobyte = 1024, megabyte = 1024 * 1024;
  if (bytes >= megabyte)
  {
    char text[32];
    std::snprintf(text, sizeof text, "%.0f MB", static_cast<double>(bytes) / megabyte);
    return text;
  }
  return bytes >= kilobyte ? std::to_string(bytes / kilobyte) + " KB"
                           : std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
}

} // namespace pcbilateral

#include "EdgeAwareNormals.h"

#include "BilateralKernel.h"
#include "BitOperations.h"
#include "PointGrid.h"
#include "Threads.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <unordered_set>

namespace pcbilateral
{

namespace
{
constexpr double Pi = 3.14159265358979323846;
/// Points per block of a parallel loop: the calling thread polls for abort and reports
/// progress between blocks.
constexpr std::size_t PointsPerBlock = 2048;

/// How much of point i's move comes from the mean-normal heights along m_i rather than from the
/// projections on the neighbours' own tangent planes: 1 where the neighbourhood agrees with m_i
/// (a smooth surface, where the projections would swell a convex one), 0 where little of it
/// does (an edge), linear between (see EdgeAwareNormals.h).
double SmoothShare(const EdgeAwareHeights& sums)
{
  if (!(sums.DistanceWeightSum > 0.0))
  {
    return 1.0;
  }
  const double agreeing = sums.AgreeingWeightSum / sums.DistanceWeightSum;
  const double share =
    (agreeing - EdgeAwareEdgeAgreement) / (EdgeAwareSmoothAgreement - EdgeAwareEdgeAgreement);
  return std::min(1.0, std::max(0.0, share));
}

/**
 * The points that are neighbours (finite, not removed) in a grid of cells a bit wider than r,
 * anchored at the whole cloud's lower corner: a search that visits the 27 cells around a point
 * in the grid's order meets the neighbours in an order that depends on coordinates alone.
 * Returns false when the grid cannot index the cloud, which the run's precision limits rule
 * out (no cloud more than 1e8 radii wide).
 */
bool BuildNeighbourGrid(const PointState& state,
  const EdgeAwareSettings& settings,
  int threads,
  PointGrid& grid)
{
  // Cells a bit wider than r, so that rounding in the cell coordinates (relative 2^-52 of
  // them, at most about 1e15 here: see CheckPrecisionLimits) never puts two points less than r
  // apart two cells apart. The width depends on the whole cloud only, like the origin.
  const double coordinates = settings.CloudReach / settings.Radius + 2.0;
  const double cellSize = settings.Radius * (1.0 + 8.0 * 0x1.0p-52 * coordinates + 1e-12);
  std::vector<std::uint32_t> ids;
  ids.reserve(state.Removed.size());
  for (std::size_t id = 0; id < state.Removed.size(); ++id)
  {
    if (!state.Removed[id] && IsFinitePoint(state.Positions.data() + 3 * id))
    {
      ids.push_back(static_cast<std::uint32_t>(id));
    }
  }
  if (!grid.Build(state.Positions.data(),
        ids,
        settings.Origin,
        cellSize,
        PointGrid::PointOrder::ByCoordinates))
  {
    return false;
  }
  grid.ComputeNeighbourRuns(threads);
  return true;
}

/// One thread's neighbours of the current point, for the kernel's edge-aware functions: sorted
/// indices, and for step 1 the packed offsets q - p and distance weights.
struct Neighbourhood
{
  std::vector<std::uint32_t> Index;
  std::vector<double> Dx, Dy, Dz, Weight;
  std::size_t Count = 0;

  /// Scans the cells around sorted point i: the neighbours' indices and offsets, in an order
  /// fixed by coordinates alone (see BuildNeighbourGrid).
  void Select(const EdgeAwareKernel& kernel,
    const PointGrid& grid,
    double radiusSquared,
    std::size_t i)
  {
    const double p[3] = { grid.GetX()[i], grid.GetY()[i], grid.GetZ()[i] };
    const std::uint32_t* runs = grid.GetNeighbourRuns(grid.GetCellOfPoint(i));
    std::size_t count = 0;
    for (int run = 0; run < 9; ++run)
    {
      const std::uint32_t begin = runs[2 * run];
      const std::uint32_t end = runs[2 * run + 1];
      // Room for every candidate of the run and padding: the kernel writes each one.
      this->Reserve(count + (end - begin) + KernelLanes);
      count = kernel.Select(p,
        grid.GetX(),
        grid.GetY(),
        grid.GetZ(),
        begin,
        end,
        radiusSquared,
        this->Dx.data(),
        this->Dy.data(),
        this->Dz.data(),
        this->Index.data(),
        count);
    }
    this->Count = count;
  }

private:
  void Reserve(std::size_t size)
  {
    if (this->Index.size() >= size)
    {
      return;
    }
    // Grow geometrically, keeping what is packed: Select appends run after run.
    size = std::max(size, 2 * this->Index.size());
    for (auto* values : { &this->Dx, &this->Dy, &this->Dz, &this->Weight })
    {
      values->resize(size);
    }
    this->Index.resize(size);
  }
};

/// One thread's neighbourhoods: step 1 selects KernelLanes points' neighbours at a time, the
/// other steps use the first.
struct NeighbourhoodGroup
{
  Neighbourhood Hoods[KernelLanes];
};

/**
 * The neighbour lists the first step found, for the next steps: scanning the cells around a
 * point costs about three times its neighbours, reading a list once. Lists are kept up to a
 * memory budget; the points beyond it scan again, with the same result.
 */
class NeighbourCache
{
public:
  explicit NeighbourCache(std::size_t points)
    : Lists(points)
  {
  }

  /// Called for each point by the first step.
  void Keep(std::size_t i, const Neighbourhood& hood)
  {
    if (this->Used.fetch_add(hood.Count, std::memory_order_relaxed) + hood.Count <= Budget)
    {
      this->Lists[i].assign(hood.Index.begin(), hood.Index.begin() + hood.Count);
      this->Kept[i] = true;
    }
  }

  /// The sorted indices of the neighbours of sorted point i (and their number): the list
  /// kept, or the one found again in `hood`.
  /// Point i's neighbours, with `normals` (3 per sorted point) as theirs.
  SortedNeighbours Fetch(const EdgeAwareKernel& kernel,
    const PointGrid& grid,
    double radiusSquared,
    std::size_t i,
    Neighbourhood& hood,
    const double* normals) const
  {
    SortedNeighbours neighbours;
    if (this->Kept[i])
    {
      neighbours.Index = this->Lists[i].data();
      neighbours.Count = this->Lists[i].size();
    }
    else
    {
      hood.Select(kernel, grid, radiusSquared, i);
      neighbours.Index = hood.Index.data();
      neighbours.Count = hood.Count;
    }
    neighbours.X = grid.GetX();
    neighbours.Y = grid.GetY();
    neighbours.Z = grid.GetZ();
    neighbours.Normals = normals;
    return neighbours;
  }

  void Prepare() { this->Kept.assign(this->Lists.size(), 0); }

private:
  /// Neighbour entries kept at most: 256 MB of indices.
  static constexpr std::uint64_t Budget = std::uint64_t(1) << 26;
  std::vector<std::vector<std::uint32_t>> Lists;
  std::vector<std::uint8_t> Kept;
  std::atomic<std::uint64_t> Used{ 0 };
};

/// How many cells (Chebyshev) cell c lies from the nearest cell of `cells` (CellHashKey keys),
/// up to `far`. (Two cells may share a key: a far cell then counts as near, which costs only
/// time.)
int ChebyshevDistanceToSet(const std::int64_t c[3],
  const std::unordered_set<std::uint64_t>& cells,
  int far)
{
  for (int d = 1; d < far; ++d)
  {
    // The ring at distance d: the cube of side 2d + 1 (its inside was searched already, and
    // is searched again: rings are at most 5 cells wide).
    for (std::int64_t dz = -d; dz <= d; ++dz)
    {
      for (std::int64_t dy = -d; dy <= d; ++dy)
      {
        for (std::int64_t dx = -d; dx <= d; ++dx)
        {
          if (cells.count(CellHashKey(c[0] + dx, c[1] + dy, c[2] + dz)))
          {
            return d;
          }
        }
      }
    }
  }
  return far;
}

/// One edge-aware iteration's steps over the sorted points of its grid.
class EdgeAwareIteration
{
public:
  EdgeAwareIteration(PointState& state, const EdgeAwareSettings& settings, int threads)
    : State(state)
    , Settings(settings)
    , Threads(threads)
    , RadiusSquared(settings.Radius * settings.Radius)
    , Constants(settings.Radius, settings.NormalRadius)
    , Kernel(GetEdgeAwareKernel())
    , AgreementScale(1.0 / (1.0 - std::cos(EdgeAwareNormalAngle * Pi / 180.0)))
    , SmoothAgreementScale(1.0 / (1.0 - std::cos(EdgeAwareSmoothAngle * Pi / 180.0)))
    , Scratch(static_cast<std::size_t>(threads))
    , Counts(static_cast<std::size_t>(threads), 0)
  {
  }

  /// The whole iteration; false if aborted (the positions are then unchanged).
  bool Run(std::uint64_t& evaluations)
  {
    evaluations = 0;
    if (!BuildNeighbourGrid(this->State, this->Settings, this->Threads, this->Grid))
    {
      return false;
    }
    const std::size_t n = this->Grid.Size();
    this->Cache = std::make_unique<NeighbourCache>(n);
    this->Cache->Prepare();
    this->MeasureDistanceToOwnPoints();
    this->EstimateNormals();
    for (int pass = 0; pass < EdgeAwareNormalPasses; ++pass)
    {
      this->WriteRecords();
      this->FilterNormals(EdgeAwareNormalPasses - pass);
    }
    this->WriteRecords();
    this->Displace();
    if (this->Aborted)
    {
      return false;
    }
    for (const std::uint64_t count : this->Counts)
    {
      evaluations += count;
    }
    this->WriteBack();
    return true;
  }

private:
  /// Calls body(sorted index, the thread's neighbourhood, its visit count) for every point, in
  /// blocks run in parallel, polling for abort and reporting progress between blocks.
  template<typename Body>
  void ForEachPoint(const Body& body)
  {
    this->ForEachItem(this->Grid.Size(),
      PointsPerBlock,
      16,
      [&](std::size_t i, NeighbourhoodGroup& group, std::uint64_t& visited)
      { body(i, group.Hoods[0], visited); });
  }

  /// Calls body(item, the thread's neighbourhoods, its visit count) for items 0 to count - 1,
  /// in blocks of itemsPerBlock run in parallel (`chunk` items at a time), polling for abort
  /// and reporting progress between blocks.
  template<typename Body>
  void ForEachItem(std::size_t count, std::size_t itemsPerBlock, int chunk, const Body& body)
  {
    constexpr int Steps = EdgeAwareNormalPasses + 2;
    for (std::size_t begin = 0; begin < count && !this->Aborted; begin += itemsPerBlock)
    {
      const auto first = static_cast<std::int64_t>(begin);
      const auto last = static_cast<std::int64_t>(std::min(count, begin + itemsPerBlock));
#pragma omp parallel for schedule(dynamic, chunk) num_threads(this->Threads)
      for (std::int64_t i = first; i < last; ++i)
      {
        const int thread = CurrentThreadIndex();
        body(static_cast<std::size_t>(i), this->Scratch[thread], this->Counts[thread]);
      }
      if (this->Settings.ShouldAbort && this->Settings.ShouldAbort())
      {
        this->Aborted = true;
      }
      else if (this->Settings.Progress)
      {
        this->Settings.Progress(
          (this->Step + static_cast<double>(last) / static_cast<double>(count)) / Steps);
      }
    }
    ++this->Step;
  }

  /// Sorted point i's neighbours with the current normals (NeighbourCache::Fetch).
  SortedNeighbours Fetch(std::size_t i, Neighbourhood& hood) const
  {
    SortedNeighbours neighbours = this->Cache->Fetch(
      this->Kernel, this->Grid, this->RadiusSquared, i, hood, this->Normals.data());
    neighbours.Records = this->Records;
    neighbours.PaddingRow = this->Grid.Size();
    return neighbours;
  }

  /// Each sorted point's coordinates and current normal in one record of 8 values, 64-byte
  /// aligned, and a padding row after the last (see SortedNeighbours).
  void WriteRecords()
  {
    const std::size_t n = this->Grid.Size();
    constexpr std::size_t Row = 8;
    this->RecordStorage.assign(Row * (n + 1) + Row, 0.0);
    const auto address = reinterpret_cast<std::uintptr_t>(this->RecordStorage.data());
    this->Records = this->RecordStorage.data() + (64 - address % 64) % 64 / sizeof(double);
    for (std::size_t i = 0; i < n; ++i)
    {
      double* record = this->Records + Row * i;
      this->Position(i, record);
      std::copy_n(&this->Normals[3 * i], 3, record + 3);
    }
    std::fill_n(this->Records + Row * n, 3, 1e300);
  }

  const double* Position(std::size_t i, double p[3]) const
  {
    p[0] = this->Grid.GetX()[i];
    p[1] = this->Grid.GetY()[i];
    p[2] = this->Grid.GetZ()[i];
    return p;
  }

  /// For each sorted point, how many cells (one radius wide) its cell lies from the nearest
  /// cell holding one of this part's own points, counted up to EdgeAwareNormalPasses + 2. Each
  /// step reads its neighbours' results of the step before, within one radius, so a point's
  /// own displacement reads normals filtered within 1 radius, estimated within 2: a ghost more
  /// cells away than that is never read, and its steps are skipped. (Ghosts reach 3 radii, and
  /// where the radius follows the density a wide band's ghosts can be a dense part of the
  /// cloud.) A point within k radii of an own point lies within k cells of its cell.
  void MeasureDistanceToOwnPoints()
  {
    const std::size_t n = this->Grid.Size();
    this->CellsFromOwn.assign(n, 0);
    if (this->State.FirstGhost >= this->State.Removed.size())
    {
      return; // no ghosts
    }
    const std::uint32_t* ids = this->Grid.GetIds();
    auto key = [](const std::int64_t* c)
    {
      // Two cells may share a key: a far ghost then counts as near, which costs only time.
      return MixBits(
        MixBits(MixBits(static_cast<std::uint64_t>(c[0])) ^ static_cast<std::uint64_t>(c[1])) ^
        static_cast<std::uint64_t>(c[2]));
    };
    std::unordered_set<std::uint64_t> own;
    std::vector<std::uint8_t> cellHasOwn(this->Grid.GetNumberOfCells(), 0);
    for (std::size_t i = 0; i < n; ++i)
    {
      if (ids[i] < this->State.FirstGhost)
      {
        cellHasOwn[this->Grid.GetCellOfPoint(i)] = 1;
      }
    }
    for (std::uint32_t cell = 0; cell < cellHasOwn.size(); ++cell)
    {
      if (cellHasOwn[cell])
      {
        const std::int64_t* c = this->Grid.GetCellCoordinates(cell);
        own.insert(CellHashKey(c[0], c[1], c[2]));
      }
    }
    constexpr int Far = EdgeAwareNormalPasses + 2;
    std::vector<std::uint8_t> cellDistance(cellHasOwn.size(), 0);
#pragma omp parallel for schedule(dynamic, 256) num_threads(this->Threads)
    for (std::ptrdiff_t cell = 0; cell < static_cast<std::ptrdiff_t>(cellHasOwn.size()); ++cell)
    {
      if (cellHasOwn[cell])
      {
        continue;
      }
      cellDistance[cell] = static_cast<std::uint8_t>(ChebyshevDistanceToSet(
        this->Grid.GetCellCoordinates(static_cast<std::uint32_t>(cell)), own, Far));
    }
    for (std::size_t i = 0; i < n; ++i)
    {
      this->CellsFromOwn[i] = cellDistance[this->Grid.GetCellOfPoint(i)];
    }
  }

  /// 1. The paper's regression-plane normals, refitted with a residual weight; zero for points
  /// with too few neighbours. KernelLanes consecutive sorted points at a time, whose 3 x 3
  /// solves the kernel runs side by side.
  void EstimateNormals()
  {
    const std::size_t n = this->Grid.Size();
    this->Normals.assign(3 * n, 0.0);
    this->ForEachItem((n + KernelLanes - 1) / KernelLanes,
      PointsPerBlock / KernelLanes,
      2,
      [&](std::size_t group, NeighbourhoodGroup& hoods, std::uint64_t& visited)
      {
        PackedNeighbours points[KernelLanes];
        std::size_t ids[KernelLanes];
        std::size_t count = 0;
        for (std::size_t i = group * KernelLanes; i < std::min(n, (group + 1) * KernelLanes); ++i)
        {
          if (this->CellsFromOwn[i] > EdgeAwareNormalPasses + 1)
          {
            continue; // never read (MeasureDistanceToOwnPoints)
          }
          Neighbourhood& hood = hoods.Hoods[count];
          hood.Select(this->Kernel, this->Grid, this->RadiusSquared, i);
          this->Cache->Keep(i, hood);
          visited += hood.Count;
          if (hood.Count < MinimumNeighbourCount)
          {
            continue;
          }
          points[count] = {
            hood.Dx.data(), hood.Dy.data(), hood.Dz.data(), hood.Weight.data(), hood.Count
          };
          ids[count++] = i;
        }
        double normals[KernelLanes][3];
        bool found[KernelLanes];
        this->Kernel.PlaneNormals(points,
          count,
          this->Constants.DistanceScale,
          // Residuals weighed as the heights of step 3 (sigma_n = rn / 3).
          this->Constants.NormalScale,
          EdgeAwareRefits,
          normals,
          found);
        for (std::size_t point = 0; point < count; ++point)
        {
          if (found[point])
          {
            std::copy_n(normals[point], 3, &this->Normals[3 * ids[point]]);
          }
        }
      });
  }

  /// 2. Bilateral filtering of the normals, from one array into the other, for the points
  /// within `reach` cells of an own point (those whose result is read).
  void FilterNormals(int reach)
  {
    std::vector<double> filtered(3 * this->Grid.Size(), 0.0);
    this->ForEachPoint(
      [&](std::size_t i, Neighbourhood& hood, std::uint64_t& visited)
      {
        if (this->CellsFromOwn[i] > reach)
        {
          return;
        }
        const double* own = &this->Normals[3 * i];
        double* out = &filtered[3 * i];
        if (own[0] == 0.0 && own[1] == 0.0 && own[2] == 0.0)
        {
          return;
        }
        const SortedNeighbours neighbours = this->Fetch(i, hood);
        visited += neighbours.Count;
        double p[3], sum[3];
        this->Kernel.NormalSum(this->Position(i, p),
          neighbours,
          own,
          this->Constants.DistanceScale,
          this->AgreementScale,
          sum);
        const double length = std::sqrt((sum[0] * sum[0] + sum[1] * sum[1]) + sum[2] * sum[2]);
        if (!(length > 0.0))
        {
          std::copy(own, own + 3, out); // cannot happen with its own weight 1; kept safe
          return;
        }
        for (int axis = 0; axis < 3; ++axis)
        {
          out[axis] = sum[axis] / length;
        }
      });
    this->Normals.swap(filtered);
  }

  /// Stores point `id`'s filtered normal m, turned to agree with its orientation normal if any.
  void KeepNormal(std::uint32_t id, const double m[3])
  {
    double sign = 1.0;
    if (this->State.OrientationNormals)
    {
      const double* reference = this->State.OrientationNormals + 3 * static_cast<std::size_t>(id);
      sign = (m[0] * reference[0] + m[1] * reference[1]) + m[2] * reference[2] < 0.0 ? -1.0 : 1.0;
    }
    for (int axis = 0; axis < 3; ++axis)
    {
      this->State.Normals[3 * static_cast<std::size_t>(id) + axis] = sign * m[axis];
    }
  }

  /// 3. The move: the mean-normal height along the filtered normal where the neighbourhood is
  /// smooth, the projection on the neighbours' tangent planes near an edge, the other side of
  /// an edge left out by the agreement of the filtered normals. Only this part's own points
  /// move.
  void Displace()
  {
    const std::size_t n = this->Grid.Size();
    this->Moved.resize(3 * n);
    this->Isolated.assign(n, 0);
    this->ForEachPoint(
      [&](std::size_t i, Neighbourhood& hood, std::uint64_t& visited)
      {
        const std::uint32_t id = this->Grid.GetIds()[i];
        double p[3];
        std::copy_n(this->Position(i, p), 3, &this->Moved[3 * i]);
        if (id >= this->State.FirstGhost)
        {
          return;
        }
        const double* m = &this->Normals[3 * i];
        if (!this->State.Normals.empty())
        {
          this->KeepNormal(id, m);
        }
        if (m[0] == 0.0 && m[1] == 0.0 && m[2] == 0.0)
        {
          this->Isolated[i] = 1; // fewer than MinimumNeighbourCount neighbours
          return;
        }
        const SortedNeighbours neighbours = this->Fetch(i, hood);
        visited += neighbours.Count;
        EdgeAwareHeights sums;
        this->Kernel.HeightSums(p,
          neighbours,
          m,
          this->Constants.DistanceScale,
          this->Constants.NormalScale,
          this->AgreementScale,
          this->SmoothAgreementScale,
          sums);
        if (!(sums.WeightSum > 0.0))
        {
          this->Isolated[i] = 1;
          return;
        }
        const double smooth = SmoothShare(sums);
        const double height = smooth * sums.WeightedHeightSum / sums.WeightSum;
        for (int axis = 0; axis < 3; ++axis)
        {
          this->Moved[3 * i + axis] =
            p[axis] + (height * m[axis] + (1.0 - smooth) * sums.Projection[axis] / sums.WeightSum);
        }
      });
  }

  /// The moved positions (and removals) of this part's own points, by id.
  void WriteBack()
  {
    for (std::size_t i = 0; i < this->Grid.Size(); ++i)
    {
      const std::size_t id = this->Grid.GetIds()[i];
      if (id >= this->State.FirstGhost)
      {
        continue;
      }
      if (this->Isolated[i] && this->Settings.RemoveIsolatedPoints)
      {
        this->State.Removed[id] = 1;
        continue;
      }
      std::copy_n(&this->Moved[3 * i], 3, this->State.Positions.data() + 3 * id);
    }
  }

  PointState& State;
  const EdgeAwareSettings& Settings;
  const int Threads;
  const double RadiusSquared;
  const KernelConstants Constants;
  const EdgeAwareKernel Kernel;
  const double AgreementScale;
  const double SmoothAgreementScale;
  std::vector<NeighbourhoodGroup> Scratch;
  std::vector<std::uint64_t> Counts;
  PointGrid Grid;
  std::unique_ptr<NeighbourCache> Cache;
  /// By sorted index: the normals of the current step, the moved positions, the points left
  /// where they are for want of neighbours.
  std::vector<double> Normals;
  std::vector<double> Moved;
  /// WriteRecords.
  std::vector<double> RecordStorage;
  double* Records = nullptr;
  std::vector<std::uint8_t> Isolated;
  /// By sorted index: MeasureDistanceToOwnPoints.
  std::vector<std::uint8_t> CellsFromOwn;
  int Step = 0;
  bool Aborted = false;
};

} // namespace

bool RunEdgeAwareIteration(PointState& state,
  const EdgeAwareSettings& settings,
  std::uint64_t& evaluations)
{
#ifdef _OPENMP
  const int threads = std::max(1, settings.NumberOfThreads);
#else
  const int threads = 1;
#endif
  return EdgeAwareIteration(state, settings, threads).Run(evaluations);
}

} // namespace pcbilateral

#include "EdgeAwareNormals.h"

#include "BilateralKernel.h"
#include "PointGrid.h"
#include "Threads.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace pcbilateral
{

namespace
{
constexpr double Pi = 3.14159265358979323846;
/// Points per block of a parallel loop: the calling thread polls for abort and reports
/// progress between blocks.
constexpr std::size_t PointsPerBlock = 2048;

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
  if (!grid.Build(state.Positions.data(), ids, settings.Origin, cellSize))
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

} // namespace

bool RunEdgeAwareIteration(PointState& state,
  const EdgeAwareSettings& settings,
  std::uint64_t& evaluations)
{
  evaluations = 0;
#ifdef _OPENMP
  const int threads = std::max(1, settings.NumberOfThreads);
#else
  const int threads = 1;
#endif
  PointGrid grid;
  if (!BuildNeighbourGrid(state, settings, threads, grid))
  {
    return false;
  }
  const double radiusSquared = settings.Radius * settings.Radius;
  const std::size_t n = grid.Size();
  const KernelConstants constants(settings.Radius, settings.NormalRadius);
  const EdgeAwareKernel kernel = GetEdgeAwareKernel();
  const double agreementScale = 1.0 / (1.0 - std::cos(EdgeAwareNormalAngle * Pi / 180.0));
  std::vector<Neighbourhood> scratch(static_cast<std::size_t>(threads));
  std::vector<std::uint64_t> counts(static_cast<std::size_t>(threads), 0);

  // The loop over sorted points of one step, in blocks, polling between them.
  const int steps = EdgeAwareNormalPasses + 2;
  int step = 0;
  bool aborted = false;
  auto forEachPoint = [&](std::size_t count, const auto& body)
  {
    for (std::size_t begin = 0; begin < count && !aborted; begin += PointsPerBlock)
    {
      const auto first = static_cast<std::int64_t>(begin);
      const auto last = static_cast<std::int64_t>(std::min(count, begin + PointsPerBlock));
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
      for (std::int64_t i = first; i < last; ++i)
      {
        const int thread = CurrentThreadIndex();
        body(static_cast<std::size_t>(i), scratch[thread], counts[thread]);
      }
      if (settings.ShouldAbort && settings.ShouldAbort())
      {
        aborted = true;
      }
      else if (settings.Progress)
      {
        settings.Progress((step + static_cast<double>(last) / static_cast<double>(count)) / steps);
      }
    }
    ++step;
  };

  NeighbourCache cache(n);
  cache.Prepare();
  // 1. The paper's regression-plane normals; zero for points with too few neighbours.
  std::vector<double> normals(3 * n, 0.0);
  forEachPoint(n,
    [&](std::size_t i, Neighbourhood& hood, std::uint64_t& visited)
    {
      hood.Select(kernel, grid, radiusSquared, i);
      cache.Keep(i, hood);
      visited += hood.Count;
      if (hood.Count < MinimumNeighbourCount)
      {
        return;
      }
      kernel.PlaneNormal(hood.Dx.data(),
        hood.Dy.data(),
        hood.Dz.data(),
        hood.Count,
        constants.DistanceScale,
        hood.Weight.data(),
        &normals[3 * i]);
    });

  // 2. Bilateral filtering of the normals, from one array into the other.
  std::vector<double> filtered(3 * n, 0.0);
  for (int pass = 0; pass < EdgeAwareNormalPasses; ++pass)
  {
    forEachPoint(n,
      [&](std::size_t i, Neighbourhood& hood, std::uint64_t& visited)
      {
        const double* own = &normals[3 * i];
        double* out = &filtered[3 * i];
        out[0] = out[1] = out[2] = 0.0;
        if (own[0] == 0.0 && own[1] == 0.0 && own[2] == 0.0)
        {
          return;
        }
        const SortedNeighbours neighbours =
          cache.Fetch(kernel, grid, radiusSquared, i, hood, normals.data());
        visited += neighbours.Count;
        const double p[3] = { grid.GetX()[i], grid.GetY()[i], grid.GetZ()[i] };
        double sum[3];
        kernel.NormalSum(p, neighbours, own, constants.DistanceScale, agreementScale, sum);
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
    normals.swap(filtered);
  }

  // 3. The paper's displacement along the filtered normal, the other side of an edge left out
  // by the agreement of the filtered normals. Only this part's own points move.
  std::vector<double> moved(3 * n);
  std::vector<std::uint8_t> isolated(n, 0);
  const bool keepNormals = !state.Normals.empty();
  forEachPoint(n,
    [&](std::size_t i, Neighbourhood& hood, std::uint64_t& visited)
    {
      const std::uint32_t id = grid.GetIds()[i];
      const double p[3] = { grid.GetX()[i], grid.GetY()[i], grid.GetZ()[i] };
      std::copy(p, p + 3, &moved[3 * i]);
      if (id >= state.FirstGhost)
      {
        return;
      }
      const double* m = &normals[3 * i];
      if (keepNormals)
      {
        double sign = 1.0;
        if (state.OrientationNormals)
        {
          const double* reference = state.OrientationNormals + 3 * static_cast<std::size_t>(id);
          sign =
            (m[0] * reference[0] + m[1] * reference[1]) + m[2] * reference[2] < 0.0 ? -1.0 : 1.0;
        }
        for (int axis = 0; axis < 3; ++axis)
        {
          state.Normals[3 * static_cast<std::size_t>(id) + axis] = sign * m[axis];
        }
      }
      if (m[0] == 0.0 && m[1] == 0.0 && m[2] == 0.0)
      {
        isolated[i] = 1; // fewer than MinimumNeighbourCount neighbours
        return;
      }
      const SortedNeighbours neighbours =
        cache.Fetch(kernel, grid, radiusSquared, i, hood, normals.data());
      visited += neighbours.Count;
      double total, weighted;
      kernel.HeightSums(p,
        neighbours,
        m,
        constants.DistanceScale,
        constants.NormalScale,
        agreementScale,
        total,
        weighted);
      if (!(total > 0.0))
      {
        isolated[i] = 1;
        return;
      }
      const double displacement = weighted / total;
      for (int axis = 0; axis < 3; ++axis)
      {
        moved[3 * i + axis] = p[axis] + displacement * m[axis];
      }
    });
  if (aborted)
  {
    return false;
  }
  for (const std::uint64_t count : counts)
  {
    evaluations += count;
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t id = grid.GetIds()[i];
    if (id >= state.FirstGhost)
    {
      continue;
    }
    if (isolated[i] && settings.RemoveIsolatedPoints)
    {
      state.Removed[id] = 1;
      continue;
    }
    std::copy_n(&moved[3 * i], 3, state.Positions.data() + 3 * id);
  }
  return true;
}

} // namespace pcbilateral

#include "EdgeAwareNormals.h"

#include "BilateralKernel.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcbilateral
{

namespace
{
constexpr double Pi = 3.14159265358979323846;
/// Points per block of a parallel loop: the calling thread polls for abort and reports
/// progress between blocks.
constexpr std::size_t PointsPerBlock = 2048;

int ThreadIndex()
{
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

/**
 * The points that are neighbours (finite, not removed) sorted by grid cell, then by
 * coordinates: a neighbour search that visits the 27 cells around a point in a fixed order
 * meets the neighbours in an order that depends on coordinates alone.
 */
struct SortedGrid
{
  std::vector<std::uint32_t> Ids; // sorted index -> point id
  std::vector<double> X, Y, Z;
  std::vector<std::int64_t> CellKey;    // 3 per cell
  std::vector<std::uint32_t> CellBegin; // one more than cells
  std::vector<std::uint32_t> CellRuns;  // 9 (begin, end) per cell: its neighbour cells' points
  std::vector<std::uint32_t> CellOfPoint;
  double RadiusSquared = 0.0;

  void Build(const PointState& state, const EdgeAwareSettings& settings, int threads)
  {
    this->RadiusSquared = settings.Radius * settings.Radius;
    // Cells a bit wider than r, so that rounding in the cell coordinates (relative 2^-52 of
    // them, at most about 1e15 here: see CheckPrecisionLimits) never puts two points less than r
    // apart two cells apart. The width depends on the whole cloud only, like the origin.
    const double coordinates = settings.CloudReach / settings.Radius + 2.0;
    const double cellSize = settings.Radius * (1.0 + 8.0 * 0x1.0p-52 * coordinates + 1e-12);
    struct Entry
    {
      std::int64_t Key[3];
      double P[3];
      std::uint32_t Id;
    };
    std::vector<Entry> entries;
    entries.reserve(state.Removed.size());
    for (std::size_t id = 0; id < state.Removed.size(); ++id)
    {
      const double* p = state.Positions.data() + 3 * id;
      if (state.Removed[id] || !IsFinitePoint(p))
      {
        continue;
      }
      Entry entry;
      for (int axis = 0; axis < 3; ++axis)
      {
        entry.Key[axis] =
          static_cast<std::int64_t>(std::floor((p[axis] - settings.Origin[axis]) / cellSize));
        entry.P[axis] = p[axis];
      }
      entry.Id = static_cast<std::uint32_t>(id);
      entries.push_back(entry);
    }
    // Ties (equal coordinates) are points whose every result is equal too, so their order
    // does not matter.
    std::sort(entries.begin(),
      entries.end(),
      [](const Entry& a, const Entry& b)
      {
        for (int axis = 0; axis < 3; ++axis)
        {
          if (a.Key[axis] != b.Key[axis])
          {
            return a.Key[axis] < b.Key[axis];
          }
        }
        for (int axis = 0; axis < 3; ++axis)
        {
          if (a.P[axis] != b.P[axis])
          {
            return a.P[axis] < b.P[axis];
          }
        }
        return false;
      });
    const std::size_t n = entries.size();
    this->Ids.resize(n);
    this->X.resize(n);
    this->Y.resize(n);
    this->Z.resize(n);
    this->CellOfPoint.resize(n);
    this->CellKey.clear();
    this->CellBegin.clear();
    for (std::size_t i = 0; i < n; ++i)
    {
      const Entry& entry = entries[i];
      this->Ids[i] = entry.Id;
      this->X[i] = entry.P[0];
      this->Y[i] = entry.P[1];
      this->Z[i] = entry.P[2];
      const std::size_t cells = this->CellBegin.size();
      if (cells == 0 || !std::equal(entry.Key, entry.Key + 3, &this->CellKey[3 * (cells - 1)]))
      {
        this->CellKey.insert(this->CellKey.end(), entry.Key, entry.Key + 3);
        this->CellBegin.push_back(static_cast<std::uint32_t>(i));
      }
      this->CellOfPoint[i] = static_cast<std::uint32_t>(this->CellBegin.size() - 1);
    }
    const std::size_t cells = this->CellBegin.size();
    this->CellBegin.push_back(static_cast<std::uint32_t>(n));
    // The neighbour cells of a cell, as 9 runs of consecutive points: cells are sorted by x,
    // then y, then z key, so the cells (x, y, z - 1), (x, y, z) and (x, y, z + 1) that exist are
    // consecutive, and so are their points.
    this->CellRuns.assign(2 * 9 * cells, 0);
    const auto cellCount = static_cast<std::int64_t>(cells);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t cell = 0; cell < cellCount; ++cell)
    {
      const std::int64_t* key = &this->CellKey[3 * static_cast<std::size_t>(cell)];
      std::uint32_t* runs = &this->CellRuns[2 * 9 * static_cast<std::size_t>(cell)];
      for (std::int64_t dx = -1; dx <= 1; ++dx)
      {
        for (std::int64_t dy = -1; dy <= 1; ++dy, runs += 2)
        {
          std::int32_t first = -1, last = -1;
          for (std::int64_t dz = -1; dz <= 1; ++dz)
          {
            const std::int64_t wanted[3] = { key[0] + dx, key[1] + dy, key[2] + dz };
            const std::int32_t found = this->FindCell(wanted);
            if (found >= 0)
            {
              first = first < 0 ? found : first;
              last = found;
            }
          }
          if (first >= 0)
          {
            runs[0] = this->CellBegin[first];
            runs[1] = this->CellBegin[last + 1];
          }
        }
      }
    }
  }

  std::int32_t FindCell(const std::int64_t key[3]) const
  {
    std::size_t low = 0, high = this->CellBegin.size() - 1;
    while (low < high)
    {
      const std::size_t middle = (low + high) / 2;
      const std::int64_t* k = &this->CellKey[3 * middle];
      const bool less =
        k[0] != key[0] ? k[0] < key[0] : (k[1] != key[1] ? k[1] < key[1] : k[2] < key[2]);
      if (less)
      {
        low = middle + 1;
      }
      else
      {
        high = middle;
      }
    }
    if (low < this->CellBegin.size() - 1 && std::equal(key, key + 3, &this->CellKey[3 * low]))
    {
      return static_cast<std::int32_t>(low);
    }
    return -1;
  }
};

/// One thread's neighbours of the current point, for the kernel's edge-aware functions: sorted
/// indices, and for step 1 the packed offsets q - p and distance weights.
struct Neighbourhood
{
  std::vector<std::uint32_t> Index;
  std::vector<double> Dx, Dy, Dz, Weight;
  std::size_t Count = 0;

  /// Scans the cells around sorted point i: the neighbours' indices and offsets, in an order
  /// fixed by coordinates alone (see SortedGrid).
  void Select(const EdgeAwareKernel& kernel, const SortedGrid& grid, std::size_t i)
  {
    const double p[3] = { grid.X[i], grid.Y[i], grid.Z[i] };
    const std::uint32_t* runs =
      &grid.CellRuns[2 * 9 * static_cast<std::size_t>(grid.CellOfPoint[i])];
    std::size_t count = 0;
    for (int run = 0; run < 9; ++run)
    {
      const std::uint32_t begin = runs[2 * run];
      const std::uint32_t end = runs[2 * run + 1];
      // Room for every candidate of the run and padding: the kernel writes each one.
      this->Reserve(count + (end - begin) + KernelLanes);
      count = kernel.Select(p,
        grid.X.data(),
        grid.Y.data(),
        grid.Z.data(),
        begin,
        end,
        grid.RadiusSquared,
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
    const SortedGrid& grid,
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
      hood.Select(kernel, grid, i);
      neighbours.Index = hood.Index.data();
      neighbours.Count = hood.Count;
    }
    neighbours.X = grid.X.data();
    neighbours.Y = grid.Y.data();
    neighbours.Z = grid.Z.data();
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
  SortedGrid grid;
  grid.Build(state, settings, threads);
  const std::size_t n = grid.Ids.size();
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
        const int thread = ThreadIndex();
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
      hood.Select(kernel, grid, i);
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
        const SortedNeighbours neighbours = cache.Fetch(kernel, grid, i, hood, normals.data());
        visited += neighbours.Count;
        const double p[3] = { grid.X[i], grid.Y[i], grid.Z[i] };
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
      const std::uint32_t id = grid.Ids[i];
      const double p[3] = { grid.X[i], grid.Y[i], grid.Z[i] };
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
      const SortedNeighbours neighbours = cache.Fetch(kernel, grid, i, hood, normals.data());
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
    const std::size_t id = grid.Ids[i];
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

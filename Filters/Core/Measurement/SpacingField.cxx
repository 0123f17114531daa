#include "SpacingField.h"

#include "Threads.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>

namespace pcbilateral
{
namespace
{
/// The element of sorted spacings below which lies `fraction` of their total area (each covers
/// its square).
double PercentileByArea(const std::vector<double>& sorted, double fraction)
{
  double total = 0.0;
  for (double value : sorted)
  {
    total += value * value;
  }
  double area = 0.0;
  for (double value : sorted)
  {
    area += value * value;
    if (area >= fraction * total)
    {
      return value;
    }
  }
  return sorted.back();
}

/// The median of spacings weighted by the area each covers (its square), each first clipped at
/// twice their plain (lower) median: an element (or that bound), not an average, exact whatever the
/// order. Within a block of cells across which the density changes, the points of the dense
/// side outnumber the others, which the weights correct; the clipping keeps an outlier, far
/// from every other point, from counting for the area of a hundred.
double ClippedMedianByArea(std::vector<double>& values)
{
  std::sort(values.begin(), values.end());
  const double bound = 2.0 * values[(values.size() - 1) / 2];
  // (Clipping keeps them sorted.)
  for (double& value : values)
  {
    value = std::min(value, bound);
  }
  return PercentileByArea(values, 0.5);
}

/// A sample whose own nearest neighbour is this many times farther than the field's value at it
/// is isolated (an outlier off the surface): left out of the percentiles by area, where one
/// such point would count for the area of a hundred.
constexpr double IsolatedSpacing = 4.0;
} // namespace

SpacingField::SpacingField(const std::vector<double>& positions,
  const std::vector<double>& distances,
  int threads)
{
  std::vector<std::size_t> usable;
  std::vector<double> usablePositions;
  for (std::size_t s = 0; s < distances.size(); ++s)
  {
    const double* p = positions.data() + 3 * s;
    if (std::isfinite(distances[s]) && distances[s] > 0.0 && IsFinitePoint(p))
    {
      usable.push_back(s);
      usablePositions.insert(usablePositions.end(), p, p + 3);
    }
  }
  PointCloudView view;
  view.NumberOfPoints = usable.size();
  view.Positions = usablePositions.data();
  const CloudExtent extent = MeasureCloud(view);
  const double largest = extent.LargestExtent();
  if (usable.size() < FewestSamples || !(largest > 0.0) || !std::isfinite(largest))
  {
    return;
  }
  this->CellSize = largest / CellsAlongLargestExtent;
  std::size_t cells = 1;
  for (int axis = 0; axis < 3; ++axis)
  {
    this->Origin[axis] = extent.Min[axis];
    this->Dimensions[axis] = std::min<std::int64_t>(CellsAlongLargestExtent,
      1 + static_cast<std::int64_t>((extent.Max[axis] - extent.Min[axis]) / this->CellSize));
    cells *= static_cast<std::size_t>(this->Dimensions[axis]);
  }
  // The samples' distances grouped by cell (a counting sort): the order within a cell does not
  // matter, medians are taken by value.
  this->CellStart.assign(cells + 1, 0);
  std::vector<std::size_t> cellOfSample(usable.size());
  for (std::size_t k = 0; k < usable.size(); ++k)
  {
    cellOfSample[k] = this->CellIndex(&usablePositions[3 * k]);
    ++this->CellStart[cellOfSample[k] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c)
  {
    this->CellStart[c + 1] += this->CellStart[c];
  }
  this->SortedDistances.resize(usable.size());
  std::vector<std::uint32_t> fill(this->CellStart.begin(), this->CellStart.end() - 1);
  for (std::size_t k = 0; k < usable.size(); ++k)
  {
    this->SortedDistances[fill[cellOfSample[k]]++] = distances[usable[k]];
  }
  // Each cell that holds samples computed once (the samples' cells, in increasing order).
  std::vector<std::size_t> sampleCells(cellOfSample);
  std::sort(sampleCells.begin(), sampleCells.end());
  sampleCells.erase(std::unique(sampleCells.begin(), sampleCells.end()), sampleCells.end());
  std::vector<double> cellValues(sampleCells.size());
#pragma omp parallel for schedule(dynamic, 64) num_threads(ResolveThreadCount(threads))
  for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(sampleCells.size()); ++c)
  {
    cellValues[c] = this->MedianAround(sampleCells[c]);
  }
  std::vector<double> atSamples;
  for (std::size_t k = 0; k < usable.size(); ++k)
  {
    const double value = cellValues[static_cast<std::size_t>(
      std::lower_bound(sampleCells.begin(), sampleCells.end(), cellOfSample[k]) -
      sampleCells.begin())];
    if (distances[usable[k]] <= IsolatedSpacing * value)
    {
      atSamples.push_back(value);
    }
  }
  this->ReadPercentiles(std::move(atSamples));
}

void SpacingField::ReadPercentiles(std::vector<double> atSamples)
{
  // Percentiles by area: each sample counts as much as the area its point covers (the square of
  // its spacing), so that a small corner sampled a hundred times more densely than the rest
  // counts for its size, not for its number of points.
  std::sort(atSamples.begin(), atSamples.end());
  this->LowPercentile = PercentileByArea(atSamples, 0.05);
  this->AreaWeightedMedian = PercentileByArea(atSamples, 0.5);
  this->HighPercentile = PercentileByArea(atSamples, 0.95);
}

std::size_t SpacingField::CellIndex(const double p[3]) const
{
  std::size_t index = 0;
  for (int axis = 2; axis >= 0; --axis)
  {
    const double offset = (p[axis] - this->Origin[axis]) / this->CellSize;
    const std::int64_t last = this->Dimensions[axis] - 1;
    // (Clamped: the cloud's points may lie beyond its samples' box.)
    const std::int64_t cell = offset <= 0.0 ? 0
                              : offset >= static_cast<double>(last)
                                ? last
                                : std::min(last, static_cast<std::int64_t>(offset));
    index =
      index * static_cast<std::size_t>(this->Dimensions[axis]) + static_cast<std::size_t>(cell);
  }
  return index;
}

double SpacingField::MedianAround(std::size_t cell) const
{
  const std::int64_t nx = this->Dimensions[0], ny = this->Dimensions[1], nz = this->Dimensions[2];
  const std::int64_t centre[3] = { static_cast<std::int64_t>(cell) % nx,
    (static_cast<std::int64_t>(cell) / nx) % ny,
    static_cast<std::int64_t>(cell) / (nx * ny) };
  // The block of cells within `ring` of the centre, row by row: its samples' range in each row
  // (cells of a row are consecutive).
  auto forEachRow = [&](std::int64_t ring, auto&& row)
  {
    for (std::int64_t z = std::max<std::int64_t>(0, centre[2] - ring);
         z <= std::min(nz - 1, centre[2] + ring);
         ++z)
    {
      for (std::int64_t y = std::max<std::int64_t>(0, centre[1] - ring);
           y <= std::min(ny - 1, centre[1] + ring);
           ++y)
      {
        const std::int64_t first = (z * ny + y) * nx + std::max<std::int64_t>(0, centre[0] - ring);
        const std::int64_t last = (z * ny + y) * nx + std::min(nx - 1, centre[0] + ring);
        row(this->CellStart[static_cast<std::size_t>(first)],
          this->CellStart[static_cast<std::size_t>(last) + 1]);
      }
    }
  };
  // The smallest block holding FewestSamples samples (counted first, gathered once): blocks are
  // small where samples are dense, and the ring rarely grows beyond 4.
  const std::int64_t largestRing = std::max({ nx, ny, nz });
  std::int64_t ring = 0;
  for (; ring < largestRing; ++ring)
  {
    std::size_t count = 0;
    forEachRow(ring, [&](std::uint32_t begin, std::uint32_t end) { count += end - begin; });
    if (count >= FewestSamples)
    {
      break;
    }
  }
  std::vector<double> values;
  forEachRow(ring,
    [&](std::uint32_t begin, std::uint32_t end)
    {
      values.insert(
        values.end(), this->SortedDistances.begin() + begin, this->SortedDistances.begin() + end);
    });
  return ClippedMedianByArea(values);
}

double SpacingField::At(const double p[3]) const
{
  return this->IsValid() ? this->MedianAround(this->CellIndex(p)) : 0.0;
}

std::vector<double> SpacingField::AtPoints(const PointCloudView& cloud, int threads) const
{
  std::vector<double> values(cloud.NumberOfPoints, 0.0);
  if (!this->IsValid())
  {
    return values;
  }
  // Each cell that holds a point is computed once.
  const int threadCount = ResolveThreadCount(threads);
  const auto count = static_cast<std::ptrdiff_t>(cloud.NumberOfPoints);
  const std::size_t cells = this->CellStart.size() - 1;
  std::unique_ptr<std::atomic<std::uint8_t>[]> needed(new std::atomic<std::uint8_t>[cells]);
  for (std::size_t c = 0; c < cells; ++c)
  {
    needed[c].store(0, std::memory_order_relaxed);
  }
  std::vector<std::uint32_t> cellOfPoint(cloud.NumberOfPoints);
#pragma omp parallel for schedule(static) num_threads(threadCount)
  for (std::ptrdiff_t i = 0; i < count; ++i)
  {
    const double* p = cloud.Positions + 3 * i;
    cellOfPoint[i] = IsFinitePoint(p) ? static_cast<std::uint32_t>(this->CellIndex(p))
                                      : std::numeric_limits<std::uint32_t>::max();
    if (IsFinitePoint(p))
    {
      needed[cellOfPoint[i]].store(1, std::memory_order_relaxed);
    }
  }
  std::vector<double> cellValues(cells, 0.0);
#pragma omp parallel for schedule(dynamic, 64) num_threads(threadCount)
  for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(cells); ++c)
  {
    if (needed[c].load(std::memory_order_relaxed))
    {
      cellValues[c] = this->MedianAround(static_cast<std::size_t>(c));
    }
  }
#pragma omp parallel for schedule(static) num_threads(threadCount)
  for (std::ptrdiff_t i = 0; i < count; ++i)
  {
    if (cellOfPoint[i] != std::numeric_limits<std::uint32_t>::max())
    {
      values[i] = cellValues[cellOfPoint[i]];
    }
  }
  return values;
}

double SpacingField::GetSpread() const
{
  return this->LowPercentile > 0.0 ? this->HighPercentile / this->LowPercentile : 1.0;
}

} // namespace pcbilateral

#include "MeasurementSelection.h"

#include "BitOperations.h"
#include "CloudMeasurement.h"
#include "ProgressCheck.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace pcbilateral
{
namespace
{
/// A coordinate's bit pattern, the key's input.
std::uint64_t Bits(double value)
{
  // -0 and +0 are one point.
  value = value == 0.0 ? 0.0 : value;
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

/// The key that decides whether a point is in the measured selection (SelectMeasurementPoints),
/// from its MeasurementKey: another hash, so that the selection and the levels inside it are
/// independent.
std::uint64_t SelectionKey(std::uint64_t measurementKey)
{
  return MixBits(measurementKey ^ 0x5bd1e995ull);
}

} // namespace

std::uint64_t SelectionBound(double fraction)
{
  if (!(fraction > 0.0))
  {
    return 0; // (No key is below 0: nothing selected, as no key's double is below 0 or NaN.)
  }
  if (!(fraction < 1.0))
  {
    return std::numeric_limits<std::uint64_t>::max(); // (The callers select every point.)
  }
  const double threshold = std::ldexp(fraction, 64);
  auto bound = static_cast<std::uint64_t>(threshold);
  // (From 2^54, a double steps by more than 1: several keys below the threshold convert to it.)
  while (bound > 0 && static_cast<double>(bound - 1) >= threshold)
  {
    --bound;
  }
  while (static_cast<double>(bound) < threshold)
  {
    ++bound;
  }
  return bound;
}

std::uint64_t MeasurementKey(const double* p)
{
  return MixBits(MixBits(MixBits(Bits(p[0])) ^ Bits(p[1])) ^ Bits(p[2]));
}

double MeasuredFraction(std::size_t numberOfFinitePoints)
{
  return numberOfFinitePoints <= MaximumMeasuredPoints
           ? 1.0
           : static_cast<double>(MaximumMeasuredPoints) / static_cast<double>(numberOfFinitePoints);
}

std::vector<double> SelectWithKeys(const PointCloudView& cloud,
  double fraction,
  std::vector<std::uint64_t>* keys)
{
  const bool everyPoint = fraction >= 1.0;
  const std::uint64_t bound = everyPoint ? 0 : SelectionBound(fraction);
  // About fraction of the points and a margin, and one more slot: every point is written to the
  // next slot, and counted only when selected, so that no branch waits for the hashes.
  const double expected = fraction * static_cast<double>(cloud.NumberOfPoints);
  const auto slots =
    1 + static_cast<std::size_t>(std::min(
          expected + 6.0 * std::sqrt(expected) + 16.0, static_cast<double>(cloud.NumberOfPoints)));
  std::vector<double> selection(3 * slots);
  std::vector<std::uint64_t> selectedKeys(slots);
  std::size_t count = 0;
  // In blocks, between which the run's progress is reported and an abort asked (ProgressPoint;
  // the selection reads every point of a large cloud: the first half of the measurement).
  constexpr std::size_t Block = 16384;
  for (std::size_t first = 0; first < cloud.NumberOfPoints; first += Block)
  {
    if (ProgressPoint(first, 2 * static_cast<std::uint64_t>(cloud.NumberOfPoints)))
    {
      count = 0; // stopped: the caller asks too
      break;
    }
    const std::size_t end = std::min(cloud.NumberOfPoints, first + Block);
    for (std::size_t i = first; i < end; ++i)
    {
      const double* p = cloud.Positions + 3 * i;
      const std::uint64_t key = MeasurementKey(p);
      std::copy_n(p, 3, &selection[3 * count]);
      selectedKeys[count] = key;
      count += IsFinitePoint(p) & (everyPoint | (SelectionKey(key) < bound));
      if (count == selectedKeys.size())
      {
        selection.resize(2 * selection.size());
        selectedKeys.resize(2 * selectedKeys.size());
      }
    }
  }
  selection.resize(3 * count);
  if (keys != nullptr)
  {
    selectedKeys.resize(count);
    *keys = std::move(selectedKeys);
  }
  return selection;
}

std::vector<double> SelectMeasurementPoints(const PointCloudView& cloud, double fraction)
{
  return SelectWithKeys(cloud, fraction, nullptr);
}

} // namespace pcbilateral

#include "RadiusBands.h"

#include "AutomaticRule.h"
#include "BilateralParameters.h"
#include "BitOperations.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcbilateral
{
namespace
{
/// The band of a radius: the integer k nearest to 2 log2(radius / reference), computed from
/// the exponent and mantissa of the squared ratio, so that it needs no library function whose
/// last bit could differ between machines.
int BandIndex(double radius, double reference)
{
  const double ratio = radius / reference;
  int exponent = 0;
  const double mantissa = std::frexp(ratio * ratio, &exponent); // in [0.5, 1)
  return mantissa >= M_SQRT1_2 ? exponent : exponent - 1;
}

/// reference x 2^(k / 2), exactly as every part computes it.
double BandRadius(int k, double reference)
{
  const int whole = k >= 0 ? k / 2 : -((-k + 1) / 2);
  const bool half = k - 2 * whole == 1;
  return std::ldexp(reference, whole) * (half ? M_SQRT2 : 1.0);
}
} // namespace

RadiusBands AssignRadiusBands(const PointCloudView& cloud,
  const CloudScales& scales,
  const BilateralParameters& userParameters,
  const BilateralParameters& chosen,
  int threads)
{
  // Each point's radius is the chosen radius (at the spacing of most of the surface) scaled as
  // the paper's rule scales with the spacing, in either mode: the rule's factors cancel.
  const double referenceRadius = chosen.Radius;
  const RadiusTerms terms = RuleRadiusTerms(scales);
  const double sigmaTerm = terms.InSigmas * scales.NoiseSigma;
  const double atSurface = terms.InSpacings * SurfaceSpacing(scales) + sigmaTerm;
  const double perFieldUnit = terms.InSpacings * scales.SpacingPerNeighbourDistance;
  const std::vector<double> fieldValues = scales.LocalSpacing->AtPoints(cloud, threads);
  // Band indices, then the used ones numbered in increasing order.
  std::vector<int> indexOfPoint(cloud.NumberOfPoints, 0);
  int lowest = std::numeric_limits<int>::max(), highest = std::numeric_limits<int>::min();
  for (std::size_t i = 0; i < cloud.NumberOfPoints; ++i)
  {
    if (fieldValues[i] > 0.0)
    {
      const double radius =
        referenceRadius * ((perFieldUnit * fieldValues[i] + sigmaTerm) / atSurface);
      indexOfPoint[i] = BandIndex(radius, referenceRadius);
      lowest = std::min(lowest, indexOfPoint[i]);
      highest = std::max(highest, indexOfPoint[i]);
    }
  }
  RadiusBands bands;
  bands.BandOfPoint.assign(cloud.NumberOfPoints, RadiusBands::NoBand);
  if (lowest > highest)
  {
    return bands;
  }
  std::vector<std::uint16_t> bandOfIndex(
    static_cast<std::size_t>(highest - lowest) + 1, RadiusBands::NoBand);
  for (std::size_t i = 0; i < cloud.NumberOfPoints; ++i)
  {
    if (fieldValues[i] > 0.0)
    {
      bandOfIndex[static_cast<std::size_t>(indexOfPoint[i] - lowest)] = 0; // used
    }
  }
  for (std::size_t k = 0; k < bandOfIndex.size(); ++k)
  {
    if (bandOfIndex[k] != RadiusBands::NoBand)
    {
      bandOfIndex[k] = static_cast<std::uint16_t>(bands.Radius.size());
      const double radius = BandRadius(lowest + static_cast<int>(k), referenceRadius);
      bands.Radius.push_back(radius);
      bands.NormalRadius.push_back(NormalRadiusAt(scales, userParameters, chosen, radius));
    }
  }
  for (std::size_t i = 0; i < cloud.NumberOfPoints; ++i)
  {
    if (fieldValues[i] > 0.0)
    {
      bands.BandOfPoint[i] = bandOfIndex[static_cast<std::size_t>(indexOfPoint[i] - lowest)];
    }
  }
  return bands;
}

NearPoints::NearPoints(const std::vector<double>& positions, double reach, const double origin[3])
  : Reach(reach)
  , Origin{ origin[0], origin[1], origin[2] }
{
  std::unordered_set<std::uint64_t> occupied;
  std::vector<std::int64_t> cells;
  for (std::size_t i = 0; i + 2 < positions.size(); i += 3)
  {
    std::int64_t c[3];
    for (int axis = 0; axis < 3; ++axis)
    {
      c[axis] = this->CellOf(&positions[i], axis);
    }
    if (occupied.insert(CellHashKey(c[0], c[1], c[2])).second)
    {
      cells.insert(cells.end(), c, c + 3);
    }
  }
  for (std::size_t k = 0; k < cells.size(); k += 3)
  {
    for (int dz = -1; dz <= 1; ++dz)
    {
      for (int dy = -1; dy <= 1; ++dy)
      {
        for (int dx = -1; dx <= 1; ++dx)
        {
          this->Cells.insert(CellHashKey(cells[k] + dx, cells[k + 1] + dy, cells[k + 2] + dz));
        }
      }
    }
  }
}

bool NearPoints::Near(const double p[3]) const
{
  return this->Cells.count(
           CellHashKey(this->CellOf(p, 0), this->CellOf(p, 1), this->CellOf(p, 2))) > 0;
}

std::int64_t NearPoints::CellOf(const double p[3], int axis) const
{
  // (Runs check that the cloud is at most 1e8 radii wide; points move less than N radii.)
  return static_cast<std::int64_t>(std::floor((p[axis] - this->Origin[axis]) / this->Reach));
}

} // namespace pcbilateral

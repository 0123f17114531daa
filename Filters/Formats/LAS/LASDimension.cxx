#include "LASDimension.h"

#include <cmath>

namespace pcbilateral
{

std::size_t LASSizeOf(LASValueType type)
{
  switch (type)
  {
    case LASValueType::UInt8:
    case LASValueType::Int8:
      return 1;
    case LASValueType::UInt16:
    case LASValueType::Int16:
      return 2;
    case LASValueType::UInt32:
    case LASValueType::Int32:
    case LASValueType::Float32:
      return 4;
    default:
      return 8;
  }
}

std::size_t LASColumnBytes(const LASDimension& dimension)
{
  return LASSizeOf(dimension.ColumnType) * static_cast<std::size_t>(dimension.Components);
}

bool LASScalingIsExact(double scale, double offset)
{
  // The rounding errors of both ways stay far below half a step: (4 |raw| + 3 |offset /
  // scale|) 2^-53 < 0.2 for |raw| < 2^32, and raw * scale is never subnormal nor infinite.
  const double magnitude = std::fabs(scale);
  return std::isfinite(scale) && std::isfinite(offset) && magnitude >= 0x1p-900 &&
         magnitude <= 0x1p900 && std::fabs(offset) <= 0x1p48 * magnitude;
}

} // namespace pcbilateral

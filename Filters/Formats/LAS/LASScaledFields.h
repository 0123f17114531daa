// Scaled fields (the scan angle of formats 6-10, and extra bytes with a scale, an offset or a
// no-data value): their stored integers decoded into values and values encoded back into the
// same integers. Private to the LAS codec.
#ifndef pcbilateral_LASScaledFields_h
#define pcbilateral_LASScaledFields_h

#include "LASBinary.h"
#include "LASDimension.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace pcbilateral
{
namespace las
{

/// Dispatches on the stored integer type of a scaled field (8 to 32 bits).
template<typename Function>
void WithRawType(LASValueType type, Function function)
{
  switch (type)
  {
    case LASValueType::UInt8:
      return function(std::uint8_t());
    case LASValueType::Int8:
      return function(std::int8_t());
    case LASValueType::UInt16:
      return function(std::uint16_t());
    case LASValueType::Int16:
      return function(std::int16_t());
    case LASValueType::UInt32:
      return function(std::uint32_t());
    default:
      return function(std::int32_t());
  }
}

/// Calls function(Raw(), Value()) with the stored integer type and the decoded column's type
/// (float or double) of a scaled field.
template<typename Function>
void WithScaledTypes(const LASDimension& dimension, Function function)
{
  WithRawType(dimension.Type,
    [&](auto raw)
    {
      if (dimension.ColumnType == LASValueType::Float32)
      {
        function(raw, float());
      }
      else
      {
        function(raw, double());
      }
    });
}

/// The decoded value of a stored integer of a scaled field (NaN for its no-data value).
template<typename Raw>
double ScaledValue(Raw raw, const LASDimension& dimension, int component)
{
  if (dimension.HasNoData && static_cast<double>(raw) == dimension.NoData[component])
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return static_cast<double>(raw) * dimension.Scale[component] + dimension.Offset[component];
}

/// A scaled field's stored integers (Raw) decoded into its column (Value).
template<typename Raw, typename Value>
void DecodeScaled(const std::uint8_t* from,
  std::size_t stride,
  const LASDimension& dimension,
  std::uint8_t* to,
  std::size_t count)
{
  const int components = dimension.Components;
  for (std::size_t i = 0; i < count; ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      const Value value = static_cast<Value>(
        ScaledValue(Load<Raw>(from + i * stride + c * sizeof(Raw)), dimension, c));
      Store<Value>(to + (i * components + c) * sizeof(Value), value);
    }
  }
}

/// The stored integer of a value of a scaled field: rounded to the nearest step, NaN as the
/// no-data value (else 0), clamped to the type's range.
template<typename Raw>
Raw ScaledRaw(double value, const LASDimension& dimension, int component)
{
  if (std::isnan(value))
  {
    return static_cast<Raw>(dimension.HasNoData ? dimension.NoData[component] : 0.0);
  }
  const double raw = std::round((value - dimension.Offset[component]) / dimension.Scale[component]);
  return static_cast<Raw>(
    std::min<double>(std::max<double>(raw, static_cast<double>(std::numeric_limits<Raw>::lowest())),
      static_cast<double>(std::numeric_limits<Raw>::max())));
}

/// A scaled field's column (Value) encoded into its stored integers (Raw).
template<typename Raw, typename Value>
void EncodeScaled(const std::uint8_t* from,
  const LASDimension& dimension,
  std::uint8_t* to,
  std::size_t stride,
  std::size_t count)
{
  const int components = dimension.Components;
  for (std::size_t i = 0; i < count; ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      const double value = Load<Value>(from + (i * components + c) * sizeof(Value));
      Store<Raw>(to + i * stride + c * sizeof(Raw), ScaledRaw<Raw>(value, dimension, c));
    }
  }
}

} // namespace las
} // namespace pcbilateral

#endif

// One value of a PCD field, by its type and size: as a double, from a double, and as ascii
// text both ways. Private to the PCD reader and writer.
#ifndef pcbilateral_PCDValues_h
#define pcbilateral_PCDValues_h

#include "PCDFile.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

namespace pcbilateral
{

template<typename Value>
Value LoadPCDValue(const std::uint8_t* bytes)
{
  Value value;
  std::memcpy(&value, bytes, sizeof value);
  return value;
}

/// Calls `visit(Value{})` with the C++ type of the field's values.
template<typename Visitor>
auto VisitPCDType(const PCDField& field, Visitor&& visit)
{
  switch (field.Type == 'F'   ? 10 + field.Size
          : field.Type == 'I' ? 20 + field.Size
                              : 30 + field.Size)
  {
    case 14:
      return visit(float{});
    case 18:
      return visit(double{});
    case 21:
      return visit(std::int8_t{});
    case 22:
      return visit(std::int16_t{});
    case 24:
      return visit(std::int32_t{});
    case 28:
      return visit(std::int64_t{});
    case 31:
      return visit(std::uint8_t{});
    case 32:
      return visit(std::uint16_t{});
    case 34:
      return visit(std::uint32_t{});
    default:
      return visit(std::uint64_t{});
  }
}

inline double PCDValueAsDouble(const PCDField& field, const std::uint8_t* bytes)
{
  return VisitPCDType(
    field, [bytes](auto type) { return static_cast<double>(LoadPCDValue<decltype(type)>(bytes)); });
}

/// Stores `value` in the field's type: rounded to the nearest integer (NaN as 0, beyond the
/// type's range clamped) for integer fields.
inline void StorePCDValue(const PCDField& field, double value, std::uint8_t* bytes)
{
  VisitPCDType(field,
    [value, bytes](auto type)
    {
      using Value = decltype(type);
      Value stored;
      if constexpr (std::is_floating_point_v<Value>)
      {
        stored = static_cast<Value>(value);
      }
      else
      {
        const double rounded = std::isnan(value) ? 0.0 : std::nearbyint(value);
        const double low = static_cast<double>(std::numeric_limits<Value>::min());
        const double high = static_cast<double>(std::numeric_limits<Value>::max());
        stored = rounded <= low    ? std::numeric_limits<Value>::min()
                 : rounded >= high ? std::numeric_limits<Value>::max()
                                   : static_cast<Value>(rounded);
      }
      std::memcpy(bytes, &stored, sizeof stored);
    });
}

/// Appends one value as ascii text: the shortest digits that read back to it; "nan", "inf",
/// "-inf"; a packed colour's bits as an unsigned integer.
inline void AppendPCDText(const PCDField& field, const std::uint8_t* bytes, std::string& text)
{
  char buffer[64];
  char* end = buffer;
  if (field.Type == 'F' && IsPCDPackedColour(field))
  {
    end = std::to_chars(buffer, buffer + sizeof buffer, LoadPCDValue<std::uint32_t>(bytes)).ptr;
  }
  else
  {
    end = VisitPCDType(field,
      [&](auto type)
      {
        const auto value = LoadPCDValue<decltype(type)>(bytes);
        if constexpr (std::is_floating_point_v<decltype(type)>)
        {
          if (std::isnan(value))
          {
            return std::strcpy(buffer, "nan") + 3;
          }
        }
        return std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
      });
  }
  text.append(buffer, end);
}

/// Reads the lines of ascii data: one point per non-blank line.
struct PCDTextCursor
{
  const char* At;
  const char* End;
  /// The line of the file the cursor is on (1 for the file's first line).
  std::size_t Line;
  const char* LineEnd = nullptr;

  static bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

  /// Moves to the next line that holds something; false at the end of the data.
  bool NextLine()
  {
    if (this->LineEnd)
    {
      this->At = this->LineEnd == this->End ? this->End : this->LineEnd + 1;
      ++this->Line;
    }
    while (this->At < this->End)
    {
      const void* newline =
        std::memchr(this->At, '\n', static_cast<std::size_t>(this->End - this->At));
      this->LineEnd = newline ? static_cast<const char*>(newline) : this->End;
      if (!this->AtLineEnd())
      {
        return true;
      }
      this->At = this->LineEnd == this->End ? this->End : this->LineEnd + 1;
      ++this->Line;
    }
    return false;
  }

  /// Skips blanks; whether the line has no further value.
  bool AtLineEnd()
  {
    while (this->At < this->LineEnd && IsBlank(*this->At))
    {
      ++this->At;
    }
    return this->At == this->LineEnd;
  }

  /// Parses the next value of the line into the field's type; an error message or empty.
  std::string ParseValue(const PCDField& field, std::uint8_t* bytes)
  {
    if (this->AtLineEnd())
    {
      return "line " + std::to_string(this->Line) + ": fewer values than the fields take";
    }
    const char* start = this->At;
    while (this->At < this->LineEnd && !IsBlank(*this->At))
    {
      ++this->At;
    }
    const char* first = start + (*start == '+' ? 1 : 0);
    bool good = false;
    if (field.Type == 'F' && IsPCDPackedColour(field) && first < this->At && *first >= '0' &&
        *first <= '9' &&
        std::find_if(first, this->At, [](char c) { return c < '0' || c > '9'; }) == this->At)
    {
      // PCL writes a packed colour's bits as an unsigned integer (a float of them can be NaN).
      good = Parse<std::uint32_t>(first, bytes);
    }
    else
    {
      good = VisitPCDType(field, [&](auto type) { return Parse<decltype(type)>(first, bytes); });
    }
    if (!good)
    {
      return "line " + std::to_string(this->Line) + ": '" +
             std::string(start, std::min<std::size_t>(this->At - start, 40)) +
             "' is not a value of field '" + field.Name + "' (" + field.Type +
             std::to_string(field.Size) + ")";
    }
    return std::string();
  }

  template<typename Value>
  bool Parse(const char* first, std::uint8_t* bytes) const
  {
    Value value{};
    const auto result = std::from_chars(first, this->At, value);
    if (result.ec != std::errc() || result.ptr != this->At)
    {
      return false;
    }
    std::memcpy(bytes, &value, sizeof value);
    return true;
  }
};

} // namespace pcbilateral

#endif

// The little-endian fields of a LAS file: values and fixed-length strings at byte offsets, and
// the sizes of the header blocks of each version. Private to the LAS codec.
#ifndef pcbilateral_LASBinary_h
#define pcbilateral_LASBinary_h

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

namespace pcbilateral
{
namespace las
{

constexpr std::size_t LegacyHeaderSize = 227;

/// The size of the public header block of LAS 1.`versionMinor`: 227 bytes up to 1.2, 235 in
/// 1.3 (the waveform data's offset), 375 in 1.4 (the EVLRs and the 64-bit counts).
inline std::size_t HeaderSizeOfVersion(int versionMinor)
{
  return versionMinor >= 4 ? 375 : (versionMinor == 3 ? 235 : LegacyHeaderSize);
}

inline bool HostIsLittleEndian()
{
  const std::uint16_t one = 1;
  std::uint8_t first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

// The file is little-endian, as is every host this is built on (checked at run time).
template<typename T>
T Load(const std::uint8_t* at)
{
  T value;
  std::memcpy(&value, at, sizeof(T));
  return value;
}

template<typename T>
void Store(std::uint8_t* at, T value)
{
  std::memcpy(at, &value, sizeof(T));
}

/// A string of at most `length` bytes, ended by a zero byte when shorter.
inline std::string FixedString(const std::uint8_t* at, std::size_t length)
{
  const auto* begin = reinterpret_cast<const char*>(at);
  return std::string(begin, strnlen(begin, length));
}

/// `text` in `length` bytes, cut or padded with zero bytes.
inline void StoreString(std::uint8_t* at, const std::string& text, std::size_t length)
{
  std::memset(at, 0, length);
  std::memcpy(at, text.data(), std::min(text.size(), length));
}

/// Calls function(std::integral_constant<std::size_t, N>()) when `bytes` is N, one of the
/// sizes of the fields copied between records and columns (1, 2, 4, 6, 8 and 12 bytes), so that
/// the copy knows its size when compiled; returns false for other sizes.
template<typename Function>
bool WithFieldSize(std::size_t bytes, Function function)
{
  switch (bytes)
  {
    case 1:
      function(std::integral_constant<std::size_t, 1>());
      return true;
    case 2:
      function(std::integral_constant<std::size_t, 2>());
      return true;
    case 4:
      function(std::integral_constant<std::size_t, 4>());
      return true;
    case 6:
      function(std::integral_constant<std::size_t, 6>());
      return true;
    case 8:
      function(std::integral_constant<std::size_t, 8>());
      return true;
    case 12:
      function(std::integral_constant<std::size_t, 12>());
      return true;
    default:
      return false;
  }
}

inline std::string Str(std::uint64_t value)
{
  return std::to_string(value);
}

} // namespace las
} // namespace pcbilateral

#endif

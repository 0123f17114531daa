// The GPS time coder of LASzip, shared by the gpstime11 item (version 2) and the point14 item's
// GPS time layer (version 3), which number their codes differently. Private to the LAZ codec.
#ifndef pcbilateral_LAZGPSTime_h
#define pcbilateral_LAZGPSTime_h

#include "LAZEntropyDecoder.h"

#include <cstdint>

namespace pcbilateral
{
namespace laz
{

/// How a version numbers its codes: after a zero difference, and after a non-zero one.
struct GPSTimeCodes
{
  /// Symbols after a zero difference; code - ZeroOffset is 0 (a 32-bit difference), 1 (a time
  /// in full) or c >= 2 (a jump of c - 1 sequences). Codes below ZeroOffset: the same time.
  std::uint32_t ZeroSymbols;
  std::uint32_t ZeroOffset;
  /// Symbols after a non-zero difference; codes below 511 are multiples of the last difference,
  /// FullCode a time in full, codes above it jumps to another sequence.
  std::uint32_t MultiSymbols;
  std::uint32_t FullCode;
};

/// Version 2's codes (gpstime11): 511 leaves the time unchanged.
constexpr GPSTimeCodes GPSTimeCodesV2 = { 6, 1, 516, 512 };
/// Version 3's codes (point14's layer): the layer is only read when the time changed.
constexpr GPSTimeCodes GPSTimeCodesV3 = { 5, 0, 515, 511 };

/// Multiples of the last difference with a code of their own: 1 to 499, and -1 to -9.
constexpr std::int32_t GPSMulti = 500;
constexpr std::int32_t GPSMultiMinus = -10;

/// multiple x difference wrapped to 32 bits, as both sides of the coder compute it.
inline std::int32_t GPSMultiply(std::int64_t multiple, std::int32_t difference)
{
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(multiple * difference));
}

/**
 * What both sides of the GPS time coder keep (GPSTimeSequences decodes, GPSTimeEncoder in
 * LAZGPSTimeEncoder.h encodes, IntegerCoder being each side's integer coder): up to four
 * sequences of times followed at once (a scanner may interleave them), each with its last time
 * and its last difference, and the models.
 */
template<typename IntegerCoder>
class GPSTimeState
{
public:
  explicit GPSTimeState(const GPSTimeCodes& codes)
    : Codes(codes)
    , Multiple(codes.MultiSymbols)
    , ZeroDifference(codes.ZeroSymbols)
  {
  }

  void Start(std::int64_t first) { this->LastTime[0] = first; }

protected:
  GPSTimeCodes Codes;
  unsigned Current = 0;
  unsigned Newest = 0;
  std::int64_t LastTime[4] = {};
  std::int32_t LastDifference[4] = {};
  std::int32_t ExtremeCounter[4] = {};
  SymbolModel Multiple;
  SymbolModel ZeroDifference;
  IntegerCoder Differences{ 32, 9 };
};

/**
 * The GPS time (a double, coded as its 64-bit pattern) decoded: a time is coded as a multiple of
 * its sequence's last difference plus a correction, or as a jump to another sequence, or in full.
 */
class GPSTimeSequences : public GPSTimeState<IntegerDecoder>
{
public:
  using GPSTimeState::GPSTimeState;

  /// Decodes the next time and returns its bit pattern.
  std::int64_t Decode(ArithmeticDecoder& decoder);

private:
  bool DecodeTime(ArithmeticDecoder& decoder);
  bool DecodeAfterZero(ArithmeticDecoder& decoder);
  std::int32_t DecodeMultiple(ArithmeticDecoder& decoder, std::uint32_t multi);
  void DecodeFullTime(ArithmeticDecoder& decoder);
};

} // namespace laz
} // namespace pcbilateral

#endif

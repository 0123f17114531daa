// The GPS time encoder of LASzip, the mirror of GPSTimeSequences (LAZGPSTime.h). Private to the
// LAZ codec.
#ifndef pcbilateral_LAZGPSTimeEncoder_h
#define pcbilateral_LAZGPSTimeEncoder_h

#include "LAZEntropyEncoder.h"
#include "LAZGPSTime.h"

#include <cstdint>

namespace pcbilateral
{
namespace laz
{

class GPSTimeEncoder
{
public:
  explicit GPSTimeEncoder(const GPSTimeCodes& codes);

  void Start(std::int64_t first);
  /// Codes the time `bits` (a double's pattern). With version 3's codes it must differ from the
  /// last one (the point14 item says whether it changed).
  void Encode(ArithmeticEncoder& encoder, std::int64_t bits);

private:
  void EncodeAfterZero(ArithmeticEncoder& encoder, std::int64_t bits);
  void EncodeMultiple(ArithmeticEncoder& encoder, std::int32_t difference);
  /// Codes a jump to a sequence the time is close to; false when there is none.
  bool EncodeJump(ArithmeticEncoder& encoder,
    SymbolModel& model,
    std::uint32_t code,
    std::int64_t bits);
  void EncodeFullTime(ArithmeticEncoder& encoder,
    SymbolModel& model,
    std::uint32_t code,
    std::int64_t bits);

  GPSTimeCodes Codes;
  unsigned Current = 0;
  unsigned Newest = 0;
  std::int64_t LastTime[4] = {};
  std::int32_t LastDifference[4] = {};
  std::int32_t ExtremeCounter[4] = {};
  SymbolModel Multiple;
  SymbolModel ZeroDifference;
  IntegerEncoder Differences{ 32, 9 };
};

} // namespace laz
} // namespace pcbilateral

#endif

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

/// The GPS time encoded, the mirror of GPSTimeSequences.
class GPSTimeEncoder : public GPSTimeState<IntegerEncoder>
{
public:
  using GPSTimeState::GPSTimeState;

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
};

} // namespace laz
} // namespace pcbilateral

#endif

#include "LAZGPSTimeEncoder.h"

#include <cmath>

namespace pcbilateral
{
namespace laz
{

namespace
{
/// Version 2's code after the multiples: the time did not change.
constexpr std::uint32_t GPSMultiUnchanged = GPSMulti - GPSMultiMinus + 1;

bool Fits32(std::int64_t value)
{
  return value == static_cast<std::int32_t>(value);
}
} // namespace

void GPSTimeEncoder::Encode(ArithmeticEncoder& encoder, std::int64_t bits)
{
  const unsigned last = this->Current;
  if (this->LastDifference[last] == 0)
  {
    this->EncodeAfterZero(encoder, bits);
    return;
  }
  // Version 2 has a code for an unchanged time; version 3 codes it as a multiple 0.
  if (bits == this->LastTime[last] && this->Codes.FullCode > GPSMultiUnchanged)
  {
    encoder.EncodeSymbol(this->Multiple, GPSMultiUnchanged);
    return;
  }
  const std::int64_t difference = static_cast<std::int64_t>(
    static_cast<std::uint64_t>(bits) - static_cast<std::uint64_t>(this->LastTime[last]));
  if (Fits32(difference))
  {
    this->EncodeMultiple(encoder, static_cast<std::int32_t>(difference));
    this->LastTime[last] = bits;
    return;
  }
  if (!this->EncodeJump(encoder, this->Multiple, this->Codes.FullCode, bits))
  {
    this->EncodeFullTime(encoder, this->Multiple, this->Codes.FullCode, bits);
  }
}

void GPSTimeEncoder::EncodeAfterZero(ArithmeticEncoder& encoder, std::int64_t bits)
{
  const unsigned last = this->Current;
  if (bits == this->LastTime[last] && this->Codes.ZeroOffset > 0)
  {
    encoder.EncodeSymbol(this->ZeroDifference, 0);
    return;
  }
  const std::int64_t difference = static_cast<std::int64_t>(
    static_cast<std::uint64_t>(bits) - static_cast<std::uint64_t>(this->LastTime[last]));
  if (Fits32(difference))
  {
    encoder.EncodeSymbol(this->ZeroDifference, this->Codes.ZeroOffset);
    this->Differences.Encode(encoder, 0, static_cast<std::int32_t>(difference), 0);
    this->LastDifference[last] = static_cast<std::int32_t>(difference);
    this->ExtremeCounter[last] = 0;
    this->LastTime[last] = bits;
    return;
  }
  if (!this->EncodeJump(encoder, this->ZeroDifference, this->Codes.ZeroOffset + 1, bits))
  {
    this->EncodeFullTime(encoder, this->ZeroDifference, this->Codes.ZeroOffset + 1, bits);
  }
}

void GPSTimeEncoder::EncodeMultiple(ArithmeticEncoder& encoder, std::int32_t difference)
{
  const unsigned last = this->Current;
  const std::int32_t previous = this->LastDifference[last];
  // The multiple of the last difference nearest to this one (bounded: only its code matters).
  const double ratio = std::max(-1e6, std::min(1e6, double(difference) / double(previous)));
  const auto multi = static_cast<std::int32_t>(std::lround(ratio));
  bool extreme = false;
  if (multi == 1)
  {
    encoder.EncodeSymbol(this->Multiple, 1);
    this->Differences.Encode(encoder, previous, difference, 1);
    this->ExtremeCounter[last] = 0;
  }
  else if (multi > 1 && multi < GPSMulti)
  {
    encoder.EncodeSymbol(this->Multiple, static_cast<std::uint32_t>(multi));
    this->Differences.Encode(encoder, GPSMultiply(multi, previous), difference, multi < 10 ? 2 : 3);
  }
  else if (multi >= GPSMulti)
  {
    encoder.EncodeSymbol(this->Multiple, GPSMulti);
    this->Differences.Encode(encoder, GPSMultiply(GPSMulti, previous), difference, 4);
    extreme = true;
  }
  else if (multi < 0 && multi > GPSMultiMinus)
  {
    encoder.EncodeSymbol(this->Multiple, static_cast<std::uint32_t>(GPSMulti - multi));
    this->Differences.Encode(encoder, GPSMultiply(multi, previous), difference, 5);
  }
  else if (multi < 0)
  {
    encoder.EncodeSymbol(this->Multiple, static_cast<std::uint32_t>(GPSMulti - GPSMultiMinus));
    this->Differences.Encode(encoder, GPSMultiply(GPSMultiMinus, previous), difference, 6);
    extreme = true;
  }
  else
  {
    encoder.EncodeSymbol(this->Multiple, 0);
    this->Differences.Encode(encoder, 0, difference, 7);
    extreme = true;
  }
  if (extreme && ++this->ExtremeCounter[last] > 3)
  {
    this->LastDifference[last] = difference;
    this->ExtremeCounter[last] = 0;
  }
}

bool GPSTimeEncoder::EncodeJump(ArithmeticEncoder& encoder,
  SymbolModel& model,
  std::uint32_t code,
  std::int64_t bits)
{
  for (unsigned i = 1; i < 4; ++i)
  {
    const unsigned other = (this->Current + i) & 3;
    const std::int64_t difference = static_cast<std::int64_t>(
      static_cast<std::uint64_t>(bits) - static_cast<std::uint64_t>(this->LastTime[other]));
    if (Fits32(difference))
    {
      encoder.EncodeSymbol(model, code + i);
      this->Current = other;
      this->Encode(encoder, bits);
      return true;
    }
  }
  return false;
}

void GPSTimeEncoder::EncodeFullTime(ArithmeticEncoder& encoder,
  SymbolModel& model,
  std::uint32_t code,
  std::int64_t bits)
{
  encoder.EncodeSymbol(model, code);
  const auto lastHigh =
    static_cast<std::int32_t>(static_cast<std::uint64_t>(this->LastTime[this->Current]) >> 32);
  const auto high = static_cast<std::int32_t>(static_cast<std::uint64_t>(bits) >> 32);
  this->Differences.Encode(encoder, lastHigh, high, 8);
  encoder.WriteInt(static_cast<std::uint32_t>(static_cast<std::uint64_t>(bits)));
  this->Newest = (this->Newest + 1) & 3;
  this->Current = this->Newest;
  this->LastDifference[this->Current] = 0;
  this->ExtremeCounter[this->Current] = 0;
  this->LastTime[this->Current] = bits;
}

} // namespace laz
} // namespace pcbilateral

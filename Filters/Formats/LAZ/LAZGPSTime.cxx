#include "LAZGPSTime.h"

namespace pcbilateral
{
namespace laz
{

namespace
{
constexpr std::uint32_t GPSMultiEnd = GPSMulti - GPSMultiMinus + 1;

/// The time's bits moved by a difference, wrapping as the encoder's do: a damaged stream may
/// give any difference, and a signed overflow would be undefined.
void Advance(std::int64_t& time, std::int32_t difference)
{
  time = static_cast<std::int64_t>(
    static_cast<std::uint64_t>(time) + static_cast<std::uint64_t>(std::int64_t(difference)));
}
} // namespace

std::int64_t GPSTimeSequences::Decode(ArithmeticDecoder& decoder)
{
  // A jump to another sequence is followed by the time itself; more than three jumps in a row
  // make no sense, which bounds the loop on damaged data.
  for (int jumps = 0; jumps < 4 && !this->DecodeTime(decoder); ++jumps)
  {
  }
  return this->LastTime[this->Current];
}

bool GPSTimeSequences::DecodeAfterZero(ArithmeticDecoder& decoder)
{
  const unsigned last = this->Current;
  const std::uint32_t symbol = decoder.DecodeSymbol(this->ZeroDifference);
  if (symbol < this->Codes.ZeroOffset)
  {
    return true;
  }
  const std::uint32_t code = symbol - this->Codes.ZeroOffset;
  if (code == 0)
  {
    this->LastDifference[last] = this->Differences.Decode(decoder, 0, 0);
    Advance(this->LastTime[last], this->LastDifference[last]);
    this->ExtremeCounter[last] = 0;
  }
  else if (code == 1)
  {
    this->DecodeFullTime(decoder);
  }
  else
  {
    this->Current = (last + code - 1) & 3;
    return false;
  }
  return true;
}

/// Decodes the time, or returns false after a jump to another sequence.
bool GPSTimeSequences::DecodeTime(ArithmeticDecoder& decoder)
{
  const unsigned last = this->Current;
  if (this->LastDifference[last] == 0)
  {
    return this->DecodeAfterZero(decoder);
  }
  const std::uint32_t multi = decoder.DecodeSymbol(this->Multiple);
  if (multi == 1)
  {
    Advance(this->LastTime[last], this->Differences.Decode(decoder, this->LastDifference[last], 1));
    this->ExtremeCounter[last] = 0;
  }
  else if (multi < GPSMultiEnd)
  {
    Advance(this->LastTime[last], this->DecodeMultiple(decoder, multi));
  }
  else if (multi == this->Codes.FullCode)
  {
    this->DecodeFullTime(decoder);
  }
  else if (multi > this->Codes.FullCode)
  {
    this->Current = (last + multi - this->Codes.FullCode) & 3;
    return false;
  }
  return true;
}

std::int32_t GPSTimeSequences::DecodeMultiple(ArithmeticDecoder& decoder, std::uint32_t multi)
{
  const unsigned last = this->Current;
  const std::int32_t previous = this->LastDifference[last];
  std::int32_t difference;
  bool extreme = false;
  if (multi == 0)
  {
    difference = this->Differences.Decode(decoder, 0, 7);
    extreme = true;
  }
  else if (multi < static_cast<std::uint32_t>(GPSMulti))
  {
    difference =
      this->Differences.Decode(decoder, GPSMultiply(multi, previous), multi < 10 ? 2 : 3);
  }
  else if (multi == static_cast<std::uint32_t>(GPSMulti))
  {
    difference = this->Differences.Decode(decoder, GPSMultiply(GPSMulti, previous), 4);
    extreme = true;
  }
  else
  {
    const std::int32_t negative = GPSMulti - static_cast<std::int32_t>(multi);
    if (negative > GPSMultiMinus)
    {
      difference = this->Differences.Decode(decoder, GPSMultiply(negative, previous), 5);
    }
    else
    {
      difference = this->Differences.Decode(decoder, GPSMultiply(GPSMultiMinus, previous), 6);
      extreme = true;
    }
  }
  // A run of differences far from the last one makes the latest the new reference.
  if (extreme && ++this->ExtremeCounter[last] > 3)
  {
    this->LastDifference[last] = difference;
    this->ExtremeCounter[last] = 0;
  }
  return difference;
}

/// A time in full, which starts a new sequence.
void GPSTimeSequences::DecodeFullTime(ArithmeticDecoder& decoder)
{
  const unsigned last = this->Current;
  const unsigned next = (this->Newest + 1) & 3;
  this->Newest = next;
  const auto highPredicted =
    static_cast<std::int32_t>(static_cast<std::uint64_t>(this->LastTime[last]) >> 32);
  const auto high = static_cast<std::uint32_t>(this->Differences.Decode(decoder, highPredicted, 8));
  const std::uint64_t bits = (static_cast<std::uint64_t>(high) << 32) | decoder.ReadInt();
  this->LastTime[next] = static_cast<std::int64_t>(bits);
  this->Current = next;
  this->LastDifference[next] = 0;
  this->ExtremeCounter[next] = 0;
}

} // namespace laz
} // namespace pcbilateral

#include "LAZEntropyEncoder.h"

namespace pcbilateral
{
namespace laz
{

void ArithmeticEncoder::Finish()
{
  // One more byte settles a long interval, two a short one.
  bool anotherByte = true;
  if (this->Length > 2 * MinimumLength)
  {
    this->Add(MinimumLength);
    this->Length = MinimumLength >> 1;
  }
  else
  {
    this->Add(MinimumLength >> 1);
    this->Length = MinimumLength >> 9;
    anotherByte = false;
  }
  this->Renormalise();
  this->Out.push_back(0);
  this->Out.push_back(0);
  if (anotherByte)
  {
    this->Out.push_back(0);
  }
}

IntegerEncoder::IntegerEncoder(unsigned bits, unsigned contexts, unsigned highBits)
  : CorrectionBits(bits > 0 && bits < 32 ? bits : 32)
  , HighBits(highBits)
  , CorrectionRange(std::int64_t(1) << (bits > 0 && bits < 32 ? bits : 32))
{
  for (unsigned c = 0; c < contexts; ++c)
  {
    this->BitLengths.emplace_back(this->CorrectionBits + 1);
  }
  this->Corrections.emplace_back(2);
  for (unsigned k = 1; k <= this->CorrectionBits; ++k)
  {
    this->Corrections.emplace_back(1u << (k <= highBits ? k : highBits));
  }
}

void IntegerEncoder::Encode(ArithmeticEncoder& encoder,
  std::int32_t predicted,
  std::int32_t real,
  unsigned context)
{
  // The correction, folded into [-range/2, range/2 - 1].
  std::int64_t correction = static_cast<std::int64_t>(real) - predicted;
  const std::int64_t half = this->CorrectionRange / 2;
  if (correction < -half)
  {
    correction += this->CorrectionRange;
  }
  else if (correction > half - 1)
  {
    correction -= this->CorrectionRange;
  }
  // k: the bits of the magnitude (of c - 1 for positive c, so that 1 needs none).
  std::uint64_t magnitude = correction <= 0 ? static_cast<std::uint64_t>(-correction)
                                            : static_cast<std::uint64_t>(correction - 1);
  unsigned k = 0;
  while (magnitude)
  {
    magnitude >>= 1;
    ++k;
  }
  this->LastK = k;
  encoder.EncodeSymbol(this->BitLengths[context], k);
  if (k == 0)
  {
    encoder.EncodeBit(this->ZeroOrOne, static_cast<std::uint32_t>(correction));
    return;
  }
  if (k >= 32)
  {
    return; // the smallest correction, which the length alone says
  }
  const std::uint32_t code = static_cast<std::uint32_t>(
    correction < 0 ? correction + ((std::int64_t(1) << k) - 1) : correction - 1);
  if (k <= this->HighBits)
  {
    encoder.EncodeSymbol(this->Corrections[k], code);
  }
  else
  {
    const unsigned lowBits = k - this->HighBits;
    encoder.EncodeSymbol(this->Corrections[k], code >> lowBits);
    encoder.WriteBits(lowBits, code & ((1u << lowBits) - 1));
  }
}

} // namespace laz
} // namespace pcbilateral

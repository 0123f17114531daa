#include "LAZEntropyDecoder.h"

namespace pcbilateral
{
namespace laz
{

SymbolModel::SymbolModel(std::uint32_t symbols)
  : Symbols(symbols)
  , LastSymbol(symbols - 1)
  , UpdateCycle(symbols)
  , UntilUpdate(symbols)
  , Distribution(symbols)
  , Counts(symbols, 1)
{
  if (symbols > 16)
  {
    unsigned tableBits = 3;
    while (symbols > (1u << (tableBits + 2)))
    {
      ++tableBits;
    }
    this->TableSize = 1u << tableBits;
    this->TableShift = SymbolPrecisionBits - tableBits;
    this->Table.assign(this->TableSize + 2, 0);
  }
  // The first update sees every symbol once, then the cycle starts at half the alphabet.
  this->Update();
  this->UpdateCycle = (symbols + 6) >> 1;
  this->UntilUpdate = this->UpdateCycle;
}

void SymbolModel::Update()
{
  this->TotalCount += this->UpdateCycle;
  if (this->TotalCount > SymbolMaximumCount)
  {
    // Halving the counts keeps them within the distribution's precision and lets old symbols
    // fade.
    this->TotalCount = 0;
    for (std::uint32_t& count : this->Counts)
    {
      count = (count + 1) >> 1;
      this->TotalCount += count;
    }
  }
  const std::uint32_t scale = 0x80000000u / this->TotalCount;
  std::uint32_t sum = 0;
  std::uint32_t slot = 0;
  for (std::uint32_t k = 0; k < this->Symbols; ++k)
  {
    this->Distribution[k] = (scale * sum) >> (31 - SymbolPrecisionBits);
    sum += this->Counts[k];
    if (this->TableSize > 0)
    {
      const std::uint32_t reached = this->Distribution[k] >> this->TableShift;
      while (slot < reached)
      {
        this->Table[++slot] = k - 1;
      }
    }
  }
  if (this->TableSize > 0)
  {
    this->Table[0] = 0;
    while (slot <= this->TableSize)
    {
      this->Table[++slot] = this->Symbols - 1;
    }
  }
  this->UpdateCycle = (5 * this->UpdateCycle) >> 2;
  const std::uint32_t longestCycle = (this->Symbols + 6) << 3;
  if (this->UpdateCycle > longestCycle)
  {
    this->UpdateCycle = longestCycle;
  }
  this->UntilUpdate = this->UpdateCycle;
}

void BitModel::Update()
{
  this->BitCount += this->UpdateCycle;
  if (this->BitCount > BitMaximumCount)
  {
    this->BitCount = (this->BitCount + 1) >> 1;
    this->ZeroCount = (this->ZeroCount + 1) >> 1;
    if (this->ZeroCount == this->BitCount)
    {
      ++this->BitCount;
    }
  }
  const std::uint32_t scale = 0x80000000u / this->BitCount;
  this->ZeroProbability = (this->ZeroCount * scale) >> (31 - BitPrecisionBits);
  this->UpdateCycle = (5 * this->UpdateCycle) >> 2;
  if (this->UpdateCycle > 64)
  {
    this->UpdateCycle = 64;
  }
  this->UntilUpdate = this->UpdateCycle;
}

IntegerDecoder::IntegerDecoder(unsigned bits, unsigned contexts, unsigned highBits)
  : CorrectionBits(bits > 0 && bits < 32 ? bits : 32)
  , HighBits(highBits)
  , CorrectionRange(std::uint64_t(1) << (bits > 0 && bits < 32 ? bits : 32))
  , CorrectionMinimum(static_cast<std::int32_t>(-static_cast<std::int64_t>(CorrectionRange / 2)))
{
  this->BitLengths.reserve(contexts);
  for (unsigned c = 0; c < contexts; ++c)
  {
    this->BitLengths.emplace_back(this->CorrectionBits + 1);
  }
  // Corrections[k] models the top bits of a correction of k bits; Corrections[0] is unused
  // (k = 0 is coded by ZeroOrOne).
  this->Corrections.reserve(this->CorrectionBits + 1);
  this->Corrections.emplace_back(2);
  for (unsigned k = 1; k <= this->CorrectionBits; ++k)
  {
    this->Corrections.emplace_back(1u << (k <= highBits ? k : highBits));
  }
}

std::int32_t IntegerDecoder::Correction(ArithmeticDecoder& decoder, unsigned context)
{
  const unsigned k = decoder.DecodeSymbol(this->BitLengths[context]);
  this->LastK = k;
  if (k == 0)
  {
    return static_cast<std::int32_t>(decoder.DecodeBit(this->ZeroOrOne));
  }
  if (k >= 32)
  {
    return this->CorrectionMinimum;
  }
  std::uint32_t code;
  if (k <= this->HighBits)
  {
    code = decoder.DecodeSymbol(this->Corrections[k]);
  }
  else
  {
    const unsigned lowBits = k - this->HighBits;
    code = decoder.DecodeSymbol(this->Corrections[k]);
    code = (code << lowBits) | decoder.ReadBits(lowBits);
  }
  // Codes of k bits stand for the corrections whose magnitude needs k bits: the upper half
  // for positive ones (from 2^(k-1)), the lower half for negative ones.
  const std::int64_t value = code;
  if (code >= (std::uint32_t(1) << (k - 1)))
  {
    return static_cast<std::int32_t>(value + 1);
  }
  return static_cast<std::int32_t>(value - ((std::int64_t(1) << k) - 1));
}

} // namespace laz
} // namespace pcbilateral

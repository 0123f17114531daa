// The entropy encoder of LASzip, the mirror of LAZEntropyDecoder.h: a range (arithmetic) encoder
// with 32-bit registers and carry propagation into the bytes already written, over the same
// adaptive models, and the integer corrector's encoder. Private to the LAZ codec.
#ifndef pcbilateral_LAZEntropyEncoder_h
#define pcbilateral_LAZEntropyEncoder_h

#include "LAZEntropyDecoder.h"

#include <cstdint>
#include <vector>

namespace pcbilateral
{
namespace laz
{

/// Encodes symbols, bits and raw values, appending the bytes to Bytes().
class ArithmeticEncoder
{
public:
  void EncodeBit(BitModel& model, std::uint32_t bit)
  {
    const std::uint32_t split = model.ZeroProbability * (this->Length >> BitPrecisionBits);
    if (bit == 0)
    {
      this->Length = split;
      ++model.ZeroCount;
    }
    else
    {
      this->Add(split);
      this->Length -= split;
    }
    this->Renormalise();
    if (--model.UntilUpdate == 0)
    {
      model.Update();
    }
  }

  void EncodeSymbol(SymbolModel& model, std::uint32_t symbol)
  {
    std::uint32_t low;
    if (symbol == model.LastSymbol)
    {
      low = model.Distribution[symbol] * (this->Length >> SymbolPrecisionBits);
      this->Add(low);
      this->Length -= low;
    }
    else
    {
      this->Length >>= SymbolPrecisionBits;
      low = model.Distribution[symbol] * this->Length;
      this->Add(low);
      this->Length = model.Distribution[symbol + 1] * this->Length - low;
    }
    this->Renormalise();
    ++model.Counts[symbol];
    if (--model.UntilUpdate == 0)
    {
      model.Update();
    }
  }

  /// The low `bits` bits of `value` (at most 32), uniformly coded.
  void WriteBits(unsigned bits, std::uint32_t value)
  {
    if (bits > 19)
    {
      this->WriteUniform(16, value & 0xFFFF);
      this->WriteBits(bits - 16, value >> 16);
      return;
    }
    this->WriteUniform(bits, value);
  }

  void WriteInt(std::uint32_t value)
  {
    this->WriteUniform(16, value & 0xFFFF);
    this->WriteUniform(16, value >> 16);
  }

  /// Ends the stream: the bytes that settle the interval, then the zero bytes the decoder reads
  /// ahead.
  void Finish();

  std::vector<std::uint8_t>& Bytes() { return this->Out; }

private:
  void WriteUniform(unsigned bits, std::uint32_t value)
  {
    this->Length >>= bits;
    this->Add(value * this->Length);
    this->Renormalise();
  }

  /// Adds to the interval's base, carrying into the bytes written when it overflows.
  void Add(std::uint32_t value)
  {
    const std::uint32_t before = this->Base;
    this->Base += value;
    if (this->Base < before)
    {
      for (std::size_t k = this->Out.size(); k-- > 0;)
      {
        if (++this->Out[k] != 0)
        {
          break;
        }
      }
    }
  }

  void Renormalise()
  {
    while (this->Length < MinimumLength)
    {
      this->Out.push_back(static_cast<std::uint8_t>(this->Base >> 24));
      this->Base <<= 8;
      this->Length <<= 8;
    }
  }

  std::uint32_t Base = 0;
  std::uint32_t Length = 0xFFFFFFFFu;
  std::vector<std::uint8_t> Out;
};

/// Encodes integers as corrections of predictions, the mirror of IntegerDecoder.
class IntegerEncoder
{
public:
  IntegerEncoder(unsigned bits = 16, unsigned contexts = 1, unsigned highBits = 8);

  void Encode(ArithmeticEncoder& encoder,
    std::int32_t predicted,
    std::int32_t real,
    unsigned context = 0);
  unsigned K() const { return this->LastK; }

private:
  unsigned CorrectionBits;
  unsigned HighBits;
  std::int64_t CorrectionRange;
  unsigned LastK = 0;
  std::vector<SymbolModel> BitLengths;
  BitModel ZeroOrOne;
  std::vector<SymbolModel> Corrections;
};

} // namespace laz
} // namespace pcbilateral

#endif

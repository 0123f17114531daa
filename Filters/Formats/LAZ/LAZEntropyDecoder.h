// The entropy decoder of LASzip: a range (arithmetic) decoder with 32-bit registers, adaptive
// models of symbols and of bits, raw bits, and the integer corrector that codes the difference
// between a predicted and an actual integer by its bit length and then its bits. Written from the
// LASzip paper (Isenburg 2013, "LASzip: lossless compression of LiDAR data") and its
// specification; every rounding rule here is part of the format, as the encoder's model must
// stay in step with the decoder's bit for bit. Private to the LAZ codec.
#ifndef pcbilateral_LAZEntropyDecoder_h
#define pcbilateral_LAZEntropyDecoder_h

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcbilateral
{
namespace laz
{

/// Below this, the coder's interval is widened by a byte (renormalisation).
constexpr std::uint32_t MinimumLength = 0x01000000u;
/// Bits of precision of a symbol model's cumulative distribution.
constexpr unsigned SymbolPrecisionBits = 15;
constexpr std::uint32_t SymbolMaximumCount = 1u << SymbolPrecisionBits;
/// Bits of precision of a bit model's probability of a zero.
constexpr unsigned BitPrecisionBits = 13;
constexpr std::uint32_t BitMaximumCount = 1u << 13;

/**
 * An adaptive model of `symbols` symbols: counts of the symbols seen, turned into a
 * cumulative distribution after a number of symbols that grows by 5/4 each time (capped), so
 * the model adapts fast at first and cheaply later. Larger alphabets get a lookup table from the
 * distribution's top bits to a symbol range, which the decoder then bisects.
 */
class SymbolModel
{
public:
  explicit SymbolModel(std::uint32_t symbols = 2);
  /// Recomputes the distribution (and the decoder's table) from the counts.
  void Update();

  std::uint32_t Symbols;
  std::uint32_t LastSymbol;
  std::uint32_t TableShift = 0;
  std::uint32_t TableSize = 0;
  std::uint32_t TotalCount = 0;
  std::uint32_t UpdateCycle;
  std::uint32_t UntilUpdate;
  std::vector<std::uint32_t> Distribution;
  std::vector<std::uint32_t> Counts;
  std::vector<std::uint32_t> Table;
};

/// An adaptive model of one bit: the probability of a zero, updated like SymbolModel's counts.
class BitModel
{
public:
  void Update();

  std::uint32_t ZeroCount = 1;
  std::uint32_t BitCount = 2;
  std::uint32_t ZeroProbability = 1u << (BitPrecisionBits - 1);
  std::uint32_t UpdateCycle = 4;
  std::uint32_t UntilUpdate = 4;
};

/**
 * Decodes symbols, bits and raw values from bytes [begin, end). Reading past the end yields
 * zero bytes and sets Overrun(): a damaged or truncated stream decodes to some values but is
 * then reported, and never reads outside its bytes.
 */
class ArithmeticDecoder
{
public:
  ArithmeticDecoder() = default;
  ArithmeticDecoder(const std::uint8_t* begin, const std::uint8_t* end) { this->Start(begin, end); }

  /// Starts decoding at `begin`: the first four bytes fill the value register.
  void Start(const std::uint8_t* begin, const std::uint8_t* end)
  {
    this->Next = begin;
    this->End = end;
    this->Length = 0xFFFFFFFFu;
    this->Value = 0;
    this->Overran = false;
    for (int k = 0; k < 4; ++k)
    {
      this->Value = (this->Value << 8) | this->NextByte();
    }
  }

  bool Overrun() const { return this->Overran; }
  /// Where the next byte would be read (after the last byte the decoder needed so far).
  const std::uint8_t* Position() const { return this->Next; }

  std::uint32_t DecodeBit(BitModel& model)
  {
    const std::uint32_t split = model.ZeroProbability * (this->Length >> BitPrecisionBits);
    std::uint32_t bit;
    if (this->Value < split)
    {
      bit = 0;
      this->Length = split;
      ++model.ZeroCount;
    }
    else
    {
      bit = 1;
      this->Value -= split;
      this->Length -= split;
    }
    this->Renormalise();
    if (--model.UntilUpdate == 0)
    {
      model.Update();
    }
    return bit;
  }

  std::uint32_t DecodeSymbol(SymbolModel& model)
  {
    std::uint32_t symbol;
    std::uint32_t low;
    std::uint32_t high = this->Length;
    this->Length >>= SymbolPrecisionBits;
    if (model.TableSize > 0)
    {
      const std::uint32_t target = this->Value / this->Length;
      std::uint32_t slot = target >> model.TableShift;
      // Only a damaged stream has its value beyond its interval; the table must not be
      // overrun then.
      slot = slot > model.TableSize ? model.TableSize : slot;
      symbol = model.Table[slot];
      std::uint32_t after = model.Table[slot + 1] + 1;
      while (after > symbol + 1)
      {
        const std::uint32_t middle = (symbol + after) >> 1;
        if (model.Distribution[middle] > target)
        {
          after = middle;
        }
        else
        {
          symbol = middle;
        }
      }
      low = model.Distribution[symbol] * this->Length;
      if (symbol != model.LastSymbol)
      {
        high = model.Distribution[symbol + 1] * this->Length;
      }
    }
    else
    {
      symbol = 0;
      low = 0;
      std::uint32_t after = model.Symbols;
      std::uint32_t middle = after >> 1;
      do
      {
        const std::uint32_t bound = this->Length * model.Distribution[middle];
        if (bound > this->Value)
        {
          after = middle;
          high = bound;
        }
        else
        {
          symbol = middle;
          low = bound;
        }
        middle = (symbol + after) >> 1;
      } while (middle != symbol);
    }
    this->Value -= low;
    this->Length = high - low;
    this->Renormalise();
    ++model.Counts[symbol];
    if (--model.UntilUpdate == 0)
    {
      model.Update();
    }
    return symbol;
  }

  /// `bits` raw bits (at most 32), uniformly coded.
  std::uint32_t ReadBits(unsigned bits)
  {
    if (bits > 19)
    {
      const std::uint32_t low = this->ReadUniform(16);
      return (this->ReadBits(bits - 16) << 16) | low;
    }
    return this->ReadUniform(bits);
  }

  std::uint32_t ReadInt()
  {
    const std::uint32_t low = this->ReadUniform(16);
    return (this->ReadUniform(16) << 16) | low;
  }

private:
  std::uint32_t ReadUniform(unsigned bits)
  {
    this->Length >>= bits;
    const std::uint32_t value = this->Value / this->Length;
    this->Value -= this->Length * value;
    this->Renormalise();
    return value;
  }

  std::uint32_t NextByte()
  {
    if (this->Next < this->End)
    {
      return *this->Next++;
    }
    this->Overran = true;
    return 0;
  }

  void Renormalise()
  {
    while (this->Length < MinimumLength)
    {
      this->Value = (this->Value << 8) | this->NextByte();
      this->Length <<= 8;
    }
  }

  const std::uint8_t* Next = nullptr;
  const std::uint8_t* End = nullptr;
  std::uint32_t Value = 0;
  std::uint32_t Length = 0xFFFFFFFFu;
  bool Overran = false;
};

/**
 * Decodes integers coded as a correction of a prediction: the number k of bits of the correction
 * (a symbol, in one of `contexts` models), then its k bits, the top ones (at most `highBits`) with
 * an adaptive model per k and the rest raw. K() is the last k, which other fields use as a
 * context. `bits` is the width of the integers (32 for coordinates); corrections wrap modulo
 * 2^bits.
 */
class IntegerDecoder
{
public:
  IntegerDecoder(unsigned bits = 16, unsigned contexts = 1, unsigned highBits = 8);

  std::int32_t Decode(ArithmeticDecoder& decoder, std::int32_t predicted, unsigned context = 0)
  {
    std::int64_t real = static_cast<std::int64_t>(predicted) + this->Correction(decoder, context);
    if (real < 0)
    {
      real += this->CorrectionRange;
    }
    else if (real >= static_cast<std::int64_t>(this->CorrectionRange))
    {
      real -= this->CorrectionRange;
    }
    return static_cast<std::int32_t>(static_cast<std::uint32_t>(real));
  }

  unsigned K() const { return this->LastK; }

private:
  std::int32_t Correction(ArithmeticDecoder& decoder, unsigned context);

  unsigned CorrectionBits;
  unsigned HighBits;
  std::uint64_t CorrectionRange;
  std::int32_t CorrectionMinimum;
  unsigned LastK = 0;
  std::vector<SymbolModel> BitLengths;
  BitModel ZeroOrOne;
  std::vector<SymbolModel> Corrections;
};

} // namespace laz
} // namespace pcbilateral

#endif

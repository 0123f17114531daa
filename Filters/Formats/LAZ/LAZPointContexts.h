// What the LAZ item decoders and encoders share: the contexts derived from a point's return
// number r and number of returns n, the running median of five differences that predicts x and
// y, the point10 item's models and the coding of colours. Private to the LAZ codec.
#ifndef pcbilateral_LAZPointContexts_h
#define pcbilateral_LAZPointContexts_h

#include "LAZEntropyDecoder.h"
#include "LAZEntropyEncoder.h"
#include "LAZItemDecoders.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

namespace pcbilateral
{
namespace laz
{

/**
 * The return map of point formats 0 to 5: the valid (n, r) pairs numbered 0 to 14 (n = 1: 0;
 * n = 2: 1, 2; n = 3: 3, 4, 5; n = 4: 6 to 9; n = 5: 10 to 14), and the invalid ones (r or n 0,
 * r > n, n > 5) given contexts of their own, as in the LASzip specification's table.
 */
inline unsigned ReturnMap(unsigned n, unsigned r)
{
  static const std::uint8_t map[8][8] = {
    { 15, 14, 13, 12, 11, 10, 9, 8 },
    { 14, 0, 1, 3, 6, 10, 10, 9 },
    { 13, 1, 2, 4, 7, 11, 11, 10 },
    { 12, 3, 4, 5, 8, 12, 12, 11 },
    { 11, 6, 7, 8, 9, 13, 13, 12 },
    { 10, 10, 11, 12, 13, 14, 14, 13 },
    { 9, 10, 11, 12, 13, 14, 15, 14 },
    { 8, 9, 10, 11, 12, 13, 14, 15 },
  };
  return map[n & 7][r & 7];
}

/// The return level of formats 0 to 5: how far r is from n.
inline unsigned ReturnLevel(unsigned n, unsigned r)
{
  return n > r ? n - r : r - n;
}

/// The median of the last five values added (all start at 0), updated in a few comparisons.
class StreamingMedian5
{
public:
  std::int32_t Get() const { return this->Values[2]; }

  void Add(std::int32_t v)
  {
    std::int32_t* s = this->Values;
    if (this->High)
    {
      if (v < s[2])
      {
        s[4] = s[3];
        s[3] = s[2];
        if (v < s[0])
        {
          s[2] = s[1];
          s[1] = s[0];
          s[0] = v;
        }
        else if (v < s[1])
        {
          s[2] = s[1];
          s[1] = v;
        }
        else
        {
          s[2] = v;
        }
      }
      else
      {
        if (v < s[3])
        {
          s[4] = s[3];
          s[3] = v;
        }
        else
        {
          s[4] = v;
        }
        this->High = false;
      }
    }
    else
    {
      if (s[2] < v)
      {
        s[0] = s[1];
        s[1] = s[2];
        if (s[4] < v)
        {
          s[2] = s[3];
          s[3] = s[4];
          s[4] = v;
        }
        else if (s[3] < v)
        {
          s[2] = s[3];
          s[3] = v;
        }
        else
        {
          s[2] = v;
        }
      }
      else
      {
        if (s[1] < v)
        {
          s[0] = s[1];
          s[1] = v;
        }
        else
        {
          s[0] = v;
        }
        this->High = true;
      }
    }
  }

private:
  std::int32_t Values[5] = {};
  bool High = true;
};

/// Models chosen by a previous value, each made when first needed (most never are).
class LazyModels
{
public:
  LazyModels(std::size_t count, std::uint32_t symbols)
    : Models(count)
    , Symbols(symbols)
  {
  }

  SymbolModel& operator[](std::size_t index)
  {
    std::unique_ptr<SymbolModel>& model = this->Models[index];
    if (!model)
    {
      model = std::make_unique<SymbolModel>(this->Symbols);
    }
    return *model;
  }

private:
  std::vector<std::unique_ptr<SymbolModel>> Models;
  std::uint32_t Symbols;
};

/**
 * What the point10 item (formats 0 to 5) predicts from: the last point's 20 bytes, the last
 * intensities, differences and heights by return context, and the models, the same on both
 * sides of the coder (IntegerCoder: IntegerDecoder or IntegerEncoder).
 */
template<typename IntegerCoder>
struct Point10Models
{
  /// Starts from the chunk's first point, stored raw.
  void StartFrom(const std::uint8_t* item)
  {
    std::memcpy(this->Last, item, 20);
    // The first point's intensity is not a prediction of the next ones'.
    std::memset(this->Last + 12, 0, 2);
  }

  std::uint8_t Last[20] = {};
  std::uint16_t LastIntensity[16] = {};
  StreamingMedian5 XDifferences[16];
  StreamingMedian5 YDifferences[16];
  std::int32_t LastHeight[8] = {};
  SymbolModel ChangedValues{ 64 };
  IntegerCoder Intensity{ 16, 4 };
  SymbolModel ScanAngle[2] = { SymbolModel(256), SymbolModel(256) };
  IntegerCoder PointSource{ 16 };
  LazyModels BitByte{ 256, 256 };
  LazyModels Classification{ 256, 256 };
  LazyModels UserData{ 256, 256 };
  IntegerCoder DX{ 32, 2 };
  IntegerCoder DY{ 32, 22 };
  IntegerCoder Z{ 32, 20 };
};

/// The models of one colour coder: which of the six bytes changed, and each byte's change.
struct RGBModels
{
  SymbolModel ByteUsed{ 128 };
  SymbolModel Differences[6] = { SymbolModel(256),
    SymbolModel(256),
    SymbolModel(256),
    SymbolModel(256),
    SymbolModel(256),
    SymbolModel(256) };
};

/// The models of the layered items' colour (rgb14, rgbnir14): the colour's, and the near
/// infrared's, which bytes changed and each byte's change.
struct ColourLayerModels
{
  RGBModels Colour;
  SymbolModel NIRBytesUsed{ 4 };
  SymbolModel NIRDifferences[2] = { SymbolModel(256), SymbolModel(256) };
};

/**
 * Decodes a colour from the previous one `last` into `rgb` (16-bit values): a symbol says which
 * bytes changed and whether the colour is grey (bit 6 clear: green and blue equal red); the
 * change of green's and blue's bytes is predicted from red's.
 */
inline void DecodeRGBDifferences(ArithmeticDecoder& decoder,
  RGBModels& models,
  const std::uint32_t last[3],
  std::uint32_t rgb[3])
{
  const std::uint32_t used = decoder.DecodeSymbol(models.ByteUsed);
  auto byteOf = [](std::uint32_t value, int high) -> std::int32_t
  { return static_cast<std::int32_t>(high ? (value >> 8) : (value & 0xFF)); };
  auto decodeByte = [&](int bit, std::int32_t predicted, std::uint32_t unchanged) -> std::uint32_t
  {
    if (used & (1u << bit))
    {
      return FoldByte(
        static_cast<std::int32_t>(decoder.DecodeSymbol(models.Differences[bit])) + predicted);
    }
    return unchanged;
  };
  std::uint32_t out[3][2];
  for (int high = 0; high < 2; ++high)
  {
    out[0][high] = decodeByte(high, byteOf(last[0], high), byteOf(last[0], high));
  }
  if (used & (1u << 6))
  {
    for (int high = 0; high < 2; ++high)
    {
      const std::int32_t redStep = static_cast<std::int32_t>(out[0][high]) - byteOf(last[0], high);
      out[1][high] =
        decodeByte(2 + high, ClampByte(redStep + byteOf(last[1], high)), byteOf(last[1], high));
      const std::int32_t step =
        (redStep + (static_cast<std::int32_t>(out[1][high]) - byteOf(last[1], high))) / 2;
      out[2][high] =
        decodeByte(4 + high, ClampByte(step + byteOf(last[2], high)), byteOf(last[2], high));
    }
  }
  else
  {
    for (int high = 0; high < 2; ++high)
    {
      out[1][high] = out[2][high] = out[0][high];
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = out[c][0] | (out[c][1] << 8);
  }
}

/// The mirror of DecodeRGBDifferences: codes the colour `rgb` after `last`.
inline void EncodeRGBDifferences(ArithmeticEncoder& encoder,
  RGBModels& models,
  const std::uint32_t last[3],
  const std::uint32_t rgb[3])
{
  auto byteOf = [](std::uint32_t value, int high) -> std::int32_t
  { return static_cast<std::int32_t>(high ? (value >> 8) : (value & 0xFF)); };
  std::uint32_t used = 0;
  for (int c = 0; c < 3; ++c)
  {
    for (int high = 0; high < 2; ++high)
    {
      used |= byteOf(rgb[c], high) != byteOf(last[c], high) ? 1u << (2 * c + high) : 0u;
    }
  }
  const bool grey = rgb[1] == rgb[0] && rgb[2] == rgb[0];
  used |= grey ? 0u : 1u << 6;
  encoder.EncodeSymbol(models.ByteUsed, used);
  for (int high = 0; high < 2; ++high)
  {
    if (used & (1u << high))
    {
      encoder.EncodeSymbol(
        models.Differences[high], FoldByte(byteOf(rgb[0], high) - byteOf(last[0], high)));
    }
  }
  if (grey)
  {
    return;
  }
  for (int high = 0; high < 2; ++high)
  {
    const std::int32_t redStep = byteOf(rgb[0], high) - byteOf(last[0], high);
    if (used & (1u << (2 + high)))
    {
      const std::int32_t predicted = ClampByte(redStep + byteOf(last[1], high));
      encoder.EncodeSymbol(
        models.Differences[2 + high], FoldByte(byteOf(rgb[1], high) - predicted));
    }
    const std::int32_t step = (redStep + (byteOf(rgb[1], high) - byteOf(last[1], high))) / 2;
    if (used & (1u << (4 + high)))
    {
      const std::int32_t predicted = ClampByte(step + byteOf(last[2], high));
      encoder.EncodeSymbol(
        models.Differences[4 + high], FoldByte(byteOf(rgb[2], high) - predicted));
    }
  }
}

} // namespace laz
} // namespace pcbilateral

#endif

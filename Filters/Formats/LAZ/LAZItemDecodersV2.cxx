// Version 2 of the items of point formats 0 to 5 (LASzip 2.0 and later): point10, gpstime11,
// rgb12 and the extra bytes.
#include "LAZGPSTime.h"
#include "LAZItemDecoders.h"
#include "LAZPointContexts.h"

#include "LASBinary.h"

#include <array>
#include <cstring>
#include <vector>

namespace pcbilateral
{
namespace laz
{

namespace
{
using las::Load;
using las::Store;

/// The 20 bytes of x, y, z, intensity, the return bits, classification, scan angle, user data
/// and point source of formats 0 to 5.
class Point10Decoder final
  : public ItemDecoder
  , private Point10Models<IntegerDecoder>
{
public:
  void Start(const std::uint8_t* item) override { this->StartFrom(item); }

  void Decode(ArithmeticDecoder& decoder, std::uint8_t* item) override
  {
    const std::uint32_t changed = decoder.DecodeSymbol(this->ChangedValues);
    if (changed & 32)
    {
      this->Last[14] =
        static_cast<std::uint8_t>(decoder.DecodeSymbol(this->BitByte[this->Last[14]]));
    }
    const unsigned r = this->Last[14] & 7;
    const unsigned n = (this->Last[14] >> 3) & 7;
    const unsigned m = ReturnMap(n, r);
    const unsigned l = ReturnLevel(n, r);
    if (changed)
    {
      this->DecodeChangedAttributes(decoder, changed, m);
    }
    const std::int32_t dx =
      this->DecodeDifference(decoder, this->XDifferences[m], this->DX, n == 1);
    Store<std::int32_t>(
      this->Last, static_cast<std::int32_t>(Load<std::uint32_t>(this->Last) + dx));
    const unsigned kx = this->DX.K();
    const std::int32_t dy = this->DecodeDifference(
      decoder, this->YDifferences[m], this->DY, (n == 1) + (kx < 20 ? (kx & ~1u) : 20));
    Store<std::int32_t>(
      this->Last + 4, static_cast<std::int32_t>(Load<std::uint32_t>(this->Last + 4) + dy));
    const unsigned kxy = (this->DX.K() + this->DY.K()) / 2;
    const std::int32_t z =
      this->Z.Decode(decoder, this->LastHeight[l], (n == 1) + (kxy < 18 ? (kxy & ~1u) : 18));
    Store<std::int32_t>(this->Last + 8, z);
    this->LastHeight[l] = z;
    std::memcpy(item, this->Last, 20);
  }

private:
  std::int32_t DecodeDifference(ArithmeticDecoder& decoder,
    StreamingMedian5& recent,
    IntegerDecoder& integers,
    unsigned context)
  {
    const std::int32_t difference = integers.Decode(decoder, recent.Get(), context);
    recent.Add(difference);
    return difference;
  }

  void DecodeChangedAttributes(ArithmeticDecoder& decoder, std::uint32_t changed, unsigned m)
  {
    if (changed & 16)
    {
      const auto intensity = static_cast<std::uint16_t>(
        this->Intensity.Decode(decoder, this->LastIntensity[m], m < 3 ? m : 3));
      Store<std::uint16_t>(this->Last + 12, intensity);
      this->LastIntensity[m] = intensity;
    }
    else
    {
      // "Unchanged" is relative to the last intensity of the same return map.
      Store<std::uint16_t>(this->Last + 12, this->LastIntensity[m]);
    }
    if (changed & 8)
    {
      this->Last[15] =
        static_cast<std::uint8_t>(decoder.DecodeSymbol(this->Classification[this->Last[15]]));
    }
    if (changed & 4)
    {
      const unsigned direction = (this->Last[14] >> 6) & 1;
      const std::int32_t step =
        static_cast<std::int32_t>(decoder.DecodeSymbol(this->ScanAngle[direction]));
      this->Last[16] = FoldByte(step + this->Last[16]);
    }
    if (changed & 2)
    {
      this->Last[17] =
        static_cast<std::uint8_t>(decoder.DecodeSymbol(this->UserData[this->Last[17]]));
    }
    if (changed & 1)
    {
      Store<std::uint16_t>(this->Last + 18,
        static_cast<std::uint16_t>(
          this->PointSource.Decode(decoder, Load<std::uint16_t>(this->Last + 18))));
    }
  }
};

/// The GPS time of formats 1 and 3.
class GPSTimeDecoder final : public ItemDecoder
{
public:
  void Start(const std::uint8_t* item) override { this->Times.Start(Load<std::int64_t>(item)); }

  void Decode(ArithmeticDecoder& decoder, std::uint8_t* item) override
  {
    Store<std::int64_t>(item, this->Times.Decode(decoder));
  }

private:
  GPSTimeSequences Times{ GPSTimeCodesV2 };
};

/// Red, green and blue: which bytes changed, then each changed byte; green and blue are
/// predicted from red's change.
class RGBDecoder final : public ItemDecoder
{
public:
  void Start(const std::uint8_t* item) override
  {
    for (int c = 0; c < 3; ++c)
    {
      this->Last[c] = Load<std::uint16_t>(item + 2 * c);
    }
  }

  void Decode(ArithmeticDecoder& decoder, std::uint8_t* item) override
  {
    std::uint32_t rgb[3];
    DecodeRGBDifferences(decoder, this->Models, this->Last, rgb);
    for (int c = 0; c < 3; ++c)
    {
      this->Last[c] = rgb[c];
      Store<std::uint16_t>(item + 2 * c, static_cast<std::uint16_t>(rgb[c]));
    }
  }

private:
  std::uint32_t Last[3] = {};
  RGBModels Models;
};

/// The extra bytes: each byte as a difference with the previous point's.
class ExtraBytesDecoder final : public ItemDecoder
{
public:
  explicit ExtraBytesDecoder(std::size_t size)
    : Last(size)
    , Models(size, SymbolModel(256))
  {
  }

  void Start(const std::uint8_t* item) override
  {
    std::memcpy(this->Last.data(), item, this->Last.size());
  }

  void Decode(ArithmeticDecoder& decoder, std::uint8_t* item) override
  {
    for (std::size_t i = 0; i < this->Last.size(); ++i)
    {
      const auto step = static_cast<std::int32_t>(decoder.DecodeSymbol(this->Models[i]));
      this->Last[i] = FoldByte(step + this->Last[i]);
    }
    std::memcpy(item, this->Last.data(), this->Last.size());
  }

private:
  std::vector<std::uint8_t> Last;
  std::vector<SymbolModel> Models;
};
} // namespace

std::unique_ptr<ItemDecoder> MakeItemDecoderV1(const LAZItem& item);

std::unique_ptr<ItemDecoder> MakeItemDecoder(const LAZItem& item)
{
  if (item.Version == 1)
  {
    return MakeItemDecoderV1(item);
  }
  if (item.Version != 2)
  {
    return nullptr;
  }
  switch (static_cast<LAZItemType>(item.Type))
  {
    case LAZItemType::Point10:
      return std::make_unique<Point10Decoder>();
    case LAZItemType::GPSTime11:
      return std::make_unique<GPSTimeDecoder>();
    case LAZItemType::RGB12:
      return std::make_unique<RGBDecoder>();
    case LAZItemType::Byte:
      return std::make_unique<ExtraBytesDecoder>(item.Size);
    default:
      return nullptr;
  }
}

} // namespace laz
} // namespace pcbilateral

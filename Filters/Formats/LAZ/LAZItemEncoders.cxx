#include "LAZItemEncoders.h"

#include "LAZGPSTimeEncoder.h"
#include "LAZPointContexts.h"

#include "LASBinary.h"

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

std::uint32_t Step(std::int32_t to, std::int32_t from)
{
  return FoldByte(to - from);
}

/// point10: the mirror of the decoder in LAZItemDecodersV2.cxx.
class Point10Encoder final
  : public ItemEncoder
  , private Point10Models<IntegerEncoder>
{
public:
  void Start(const std::uint8_t* item) override { this->StartFrom(item); }

  void Encode(ArithmeticEncoder& encoder, const std::uint8_t* item) override
  {
    const unsigned r = item[14] & 7;
    const unsigned n = (item[14] >> 3) & 7;
    const unsigned m = ReturnMap(n, r);
    const unsigned l = ReturnLevel(n, r);
    const std::uint16_t intensity = Load<std::uint16_t>(item + 12);
    const std::uint32_t changed =
      (this->Last[14] != item[14] ? 32u : 0u) | (this->LastIntensity[m] != intensity ? 16u : 0u) |
      (this->Last[15] != item[15] ? 8u : 0u) | (this->Last[16] != item[16] ? 4u : 0u) |
      (this->Last[17] != item[17] ? 2u : 0u) |
      (std::memcmp(this->Last + 18, item + 18, 2) != 0 ? 1u : 0u);
    encoder.EncodeSymbol(this->ChangedValues, changed);
    this->EncodeChangedAttributes(encoder, changed, item, m);
    const std::int32_t dx =
      static_cast<std::int32_t>(Load<std::uint32_t>(item) - Load<std::uint32_t>(this->Last));
    this->DX.Encode(encoder, this->XDifferences[m].Get(), dx, n == 1);
    this->XDifferences[m].Add(dx);
    const unsigned kx = this->DX.K();
    const std::int32_t dy = static_cast<std::int32_t>(
      Load<std::uint32_t>(item + 4) - Load<std::uint32_t>(this->Last + 4));
    this->DY.Encode(
      encoder, this->YDifferences[m].Get(), dy, (n == 1) + (kx < 20 ? (kx & ~1u) : 20));
    this->YDifferences[m].Add(dy);
    const unsigned kxy = (this->DX.K() + this->DY.K()) / 2;
    const std::int32_t z = Load<std::int32_t>(item + 8);
    this->Z.Encode(encoder, this->LastHeight[l], z, (n == 1) + (kxy < 18 ? (kxy & ~1u) : 18));
    this->LastHeight[l] = z;
    std::memcpy(this->Last, item, 20);
  }

private:
  void EncodeChangedAttributes(ArithmeticEncoder& encoder,
    std::uint32_t changed,
    const std::uint8_t* item,
    unsigned m)
  {
    if (changed & 32)
    {
      encoder.EncodeSymbol(this->BitByte[this->Last[14]], item[14]);
    }
    if (changed & 16)
    {
      const std::uint16_t intensity = Load<std::uint16_t>(item + 12);
      this->Intensity.Encode(encoder, this->LastIntensity[m], intensity, m < 3 ? m : 3);
      this->LastIntensity[m] = intensity;
    }
    if (changed & 8)
    {
      encoder.EncodeSymbol(this->Classification[this->Last[15]], item[15]);
    }
    if (changed & 4)
    {
      encoder.EncodeSymbol(this->ScanAngle[(item[14] >> 6) & 1], Step(item[16], this->Last[16]));
    }
    if (changed & 2)
    {
      encoder.EncodeSymbol(this->UserData[this->Last[17]], item[17]);
    }
    if (changed & 1)
    {
      this->PointSource.Encode(
        encoder, Load<std::uint16_t>(this->Last + 18), Load<std::uint16_t>(item + 18));
    }
  }
};

class GPSTimeItemEncoder final : public ItemEncoder
{
public:
  void Start(const std::uint8_t* item) override { this->Times.Start(Load<std::int64_t>(item)); }
  void Encode(ArithmeticEncoder& encoder, const std::uint8_t* item) override
  {
    this->Times.Encode(encoder, Load<std::int64_t>(item));
  }

private:
  GPSTimeEncoder Times{ GPSTimeCodesV2 };
};

class RGBEncoder final : public ItemEncoder
{
public:
  void Start(const std::uint8_t* item) override
  {
    for (int c = 0; c < 3; ++c)
    {
      this->Last[c] = Load<std::uint16_t>(item + 2 * c);
    }
  }

  void Encode(ArithmeticEncoder& encoder, const std::uint8_t* item) override
  {
    std::uint32_t rgb[3];
    for (int c = 0; c < 3; ++c)
    {
      rgb[c] = Load<std::uint16_t>(item + 2 * c);
    }
    EncodeRGBDifferences(encoder, this->Models, this->Last, rgb);
    std::memcpy(this->Last, rgb, sizeof(rgb));
  }

private:
  std::uint32_t Last[3] = {};
  RGBModels Models;
};

class ExtraBytesEncoder final : public ItemEncoder
{
public:
  explicit ExtraBytesEncoder(std::size_t size)
    : Last(size)
    , Models(size, SymbolModel(256))
  {
  }

  void Start(const std::uint8_t* item) override
  {
    std::memcpy(this->Last.data(), item, this->Last.size());
  }

  void Encode(ArithmeticEncoder& encoder, const std::uint8_t* item) override
  {
    for (std::size_t i = 0; i < this->Last.size(); ++i)
    {
      encoder.EncodeSymbol(this->Models[i], Step(item[i], this->Last[i]));
    }
    std::memcpy(this->Last.data(), item, this->Last.size());
  }

private:
  std::vector<std::uint8_t> Last;
  std::vector<SymbolModel> Models;
};
} // namespace

std::unique_ptr<ItemEncoder> MakeItemEncoder(const LAZItem& item)
{
  if (item.Version != 2)
  {
    return nullptr;
  }
  switch (static_cast<LAZItemType>(item.Type))
  {
    case LAZItemType::Point10:
      return std::make_unique<Point10Encoder>();
    case LAZItemType::GPSTime11:
      return std::make_unique<GPSTimeItemEncoder>();
    case LAZItemType::RGB12:
      return std::make_unique<RGBEncoder>();
    case LAZItemType::Byte:
      return std::make_unique<ExtraBytesEncoder>(item.Size);
    default:
      return nullptr;
  }
}

} // namespace laz
} // namespace pcbilateral

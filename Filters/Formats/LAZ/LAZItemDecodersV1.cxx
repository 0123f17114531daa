// Version 1 of the items of point formats 0 to 3 (LASzip 1.x, 2011 and before; the pointwise
// compressor): point10, gpstime11 and rgb12 predicted more simply than in version 2.
#include "LAZItemDecoders.h"

#include "LASBinary.h"

#include <cstring>
#include <memory>

namespace pcbilateral
{
namespace laz
{

namespace
{
using las::Load;
using las::Store;

/// The median of three values.
std::int32_t Median3(const std::int32_t v[3])
{
  if (v[0] < v[1])
  {
    return v[1] < v[2] ? v[1] : (v[0] < v[2] ? v[2] : v[0]);
  }
  return v[0] < v[2] ? v[0] : (v[1] < v[2] ? v[2] : v[1]);
}

SymbolModel& Lazy(std::unique_ptr<SymbolModel>& model)
{
  if (!model)
  {
    model = std::make_unique<SymbolModel>(256);
  }
  return *model;
}

/// point10 version 1: x and y predicted by the median of the last three differences, then the
/// other fields, each only when it changed.
class Point10DecoderV1 final : public ItemDecoder
{
public:
  void Start(const std::uint8_t* item) override { std::memcpy(this->Last, item, 20); }

  void Decode(ArithmeticDecoder& decoder, std::uint8_t* item) override
  {
    std::uint8_t* last = this->Last;
    const std::int32_t dx = this->DX.Decode(decoder, Median3(this->XDifferences));
    Store<std::uint32_t>(last, Load<std::uint32_t>(last) + static_cast<std::uint32_t>(dx));
    unsigned k = this->DX.K();
    const std::int32_t dy = this->DY.Decode(decoder, Median3(this->YDifferences), k < 19 ? k : 19);
    Store<std::uint32_t>(last + 4, Load<std::uint32_t>(last + 4) + static_cast<std::uint32_t>(dy));
    k = (k + this->DY.K()) / 2;
    Store<std::int32_t>(
      last + 8, this->Z.Decode(decoder, Load<std::int32_t>(last + 8), k < 19 ? k : 19));
    const std::uint32_t changed = decoder.DecodeSymbol(this->ChangedValues);
    if (changed & 32)
    {
      Store<std::uint16_t>(last + 12,
        static_cast<std::uint16_t>(
          this->Intensity.Decode(decoder, Load<std::uint16_t>(last + 12))));
    }
    if (changed & 16)
    {
      last[14] = static_cast<std::uint8_t>(decoder.DecodeSymbol(Lazy(this->BitByte[last[14]])));
    }
    if (changed & 8)
    {
      last[15] =
        static_cast<std::uint8_t>(decoder.DecodeSymbol(Lazy(this->Classification[last[15]])));
    }
    if (changed & 4)
    {
      last[16] = static_cast<std::uint8_t>(this->ScanAngle.Decode(decoder, last[16], k < 3));
    }
    if (changed & 2)
    {
      last[17] = static_cast<std::uint8_t>(decoder.DecodeSymbol(Lazy(this->UserData[last[17]])));
    }
    if (changed & 1)
    {
      Store<std::uint16_t>(last + 18,
        static_cast<std::uint16_t>(
          this->PointSource.Decode(decoder, Load<std::uint16_t>(last + 18))));
    }
    this->XDifferences[this->Next] = dx;
    this->YDifferences[this->Next] = dy;
    this->Next = (this->Next + 1) % 3;
    std::memcpy(item, last, 20);
  }

private:
  std::uint8_t Last[20] = {};
  std::int32_t XDifferences[3] = {};
  std::int32_t YDifferences[3] = {};
  unsigned Next = 0;
  IntegerDecoder DX{ 32, 1 };
  IntegerDecoder DY{ 32, 20 };
  IntegerDecoder Z{ 32, 20 };
  IntegerDecoder Intensity{ 16 };
  IntegerDecoder ScanAngle{ 8, 2 };
  IntegerDecoder PointSource{ 16 };
  SymbolModel ChangedValues{ 64 };
  std::unique_ptr<SymbolModel> BitByte[256];
  std::unique_ptr<SymbolModel> Classification[256];
  std::unique_ptr<SymbolModel> UserData[256];
};

/// gpstime11 version 1: one sequence of times, a difference predicted from the last one or a
/// multiple of it, or the time in full.
class GPSTimeDecoderV1 final : public ItemDecoder
{
public:
  void Start(const std::uint8_t* item) override { this->Time = Load<std::int64_t>(item); }

  void Decode(ArithmeticDecoder& decoder, std::uint8_t* item) override
  {
    if (this->LastDifference == 0)
    {
      const std::uint32_t code = decoder.DecodeSymbol(this->ZeroDifference);
      if (code == 1)
      {
        this->LastDifference = this->Differences.Decode(decoder, 0, 0);
        this->Time += this->LastDifference;
      }
      else if (code == 2)
      {
        this->Time = static_cast<std::int64_t>(ReadInt64(decoder));
      }
    }
    else
    {
      const std::uint32_t multi = decoder.DecodeSymbol(this->Multiple);
      if (multi < MultiMax - 2)
      {
        this->Time += this->DecodeMultiple(decoder, multi);
      }
      else if (multi < MultiMax - 1)
      {
        this->Time = static_cast<std::int64_t>(ReadInt64(decoder));
      }
    }
    Store<std::int64_t>(item, this->Time);
  }

private:
  static constexpr std::uint32_t MultiMax = 512;

  static std::uint64_t ReadInt64(ArithmeticDecoder& decoder)
  {
    const std::uint64_t low = decoder.ReadInt();
    return (static_cast<std::uint64_t>(decoder.ReadInt()) << 32) | low;
  }

  std::int32_t DecodeMultiple(ArithmeticDecoder& decoder, std::uint32_t multi)
  {
    const std::int32_t last = this->LastDifference;
    const auto times = [&](std::uint32_t m)
    { return static_cast<std::int32_t>(m * static_cast<std::uint32_t>(last)); };
    if (multi == 1)
    {
      this->LastDifference = this->Differences.Decode(decoder, last, 1);
      this->ExtremeCounter = 0;
      return this->LastDifference;
    }
    std::int32_t difference;
    bool extreme = false;
    if (multi == 0)
    {
      difference = this->Differences.Decode(decoder, last / 4, 2);
      extreme = true;
    }
    else
    {
      difference =
        this->Differences.Decode(decoder, times(multi), multi < 10 ? 3 : (multi < 50 ? 4 : 5));
      extreme = multi == MultiMax - 3;
    }
    if (extreme && ++this->ExtremeCounter > 3)
    {
      this->LastDifference = difference;
      this->ExtremeCounter = 0;
    }
    return difference;
  }

  std::int64_t Time = 0;
  std::int32_t LastDifference = 0;
  std::int32_t ExtremeCounter = 0;
  SymbolModel Multiple{ MultiMax };
  SymbolModel ZeroDifference{ 3 };
  IntegerDecoder Differences{ 32, 6 };
};

/// rgb12 version 1: which bytes changed, then each changed byte from the last one.
class RGBDecoderV1 final : public ItemDecoder
{
public:
  void Start(const std::uint8_t* item) override { std::memcpy(this->Last, item, 6); }

  void Decode(ArithmeticDecoder& decoder, std::uint8_t* item) override
  {
    const std::uint32_t used = decoder.DecodeSymbol(this->ByteUsed);
    for (unsigned b = 0; b < 6; ++b)
    {
      // Byte b is the low (even b) or high byte of colour b / 2: the same order as in memory.
      if (used & (1u << b))
      {
        this->Last[b] = static_cast<std::uint8_t>(this->Bytes.Decode(decoder, this->Last[b], b));
      }
    }
    std::memcpy(item, this->Last, 6);
  }

private:
  std::uint8_t Last[6] = {};
  SymbolModel ByteUsed{ 64 };
  IntegerDecoder Bytes{ 8, 6 };
};
} // namespace

std::unique_ptr<ItemDecoder> MakeItemDecoderV1(const LAZItem& item)
{
  switch (static_cast<LAZItemType>(item.Type))
  {
    case LAZItemType::Point10:
      return std::make_unique<Point10DecoderV1>();
    case LAZItemType::GPSTime11:
      return std::make_unique<GPSTimeDecoderV1>();
    case LAZItemType::RGB12:
      return std::make_unique<RGBDecoderV1>();
    default:
      return nullptr;
  }
}

} // namespace laz
} // namespace pcbilateral

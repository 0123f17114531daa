// What the point14 item's decoder (LAZPoint14Decoder.cxx) and encoder (LAZPoint14Encoder.cxx)
// keep per scanner channel. Private to the LAZ codec.
#ifndef pcbilateral_LAZPoint14Channel_h
#define pcbilateral_LAZPoint14Channel_h

#include "LAZGPSTime.h"
#include "LAZPoint14Decoder.h"
#include "LAZPointContexts.h"

#include <cstdint>

namespace pcbilateral
{
namespace laz
{

/**
 * What the point14 item predicts per scanner channel: the channel's last point and the models,
 * the same on both sides of the coder (IntegerCoder and TimeCoder: IntegerDecoder and
 * GPSTimeSequences when decoding, IntegerEncoder and GPSTimeEncoder when encoding).
 */
template<typename IntegerCoder, typename TimeCoder>
struct Point14ChannelModels
{
  explicit Point14ChannelModels(const Point14& from)
    : Last(from)
  {
    this->Last.GPSTimeChanged = false;
    for (std::int32_t& z : this->LastZ)
    {
      z = from.Z;
    }
    for (std::uint16_t& intensity : this->LastIntensity)
    {
      intensity = from.Intensity;
    }
    this->Times.Start(from.GPSTime);
  }

  Point14 Last;
  SymbolModel ChangedValues[8] = { SymbolModel(128),
    SymbolModel(128),
    SymbolModel(128),
    SymbolModel(128),
    SymbolModel(128),
    SymbolModel(128),
    SymbolModel(128),
    SymbolModel(128) };
  SymbolModel ScannerChannel{ 3 };
  LazyModels NumberOfReturns{ 16, 16 };
  LazyModels ReturnNumber{ 16, 16 };
  SymbolModel ReturnNumberSameTime{ 13 };
  IntegerCoder DX{ 32, 2 };
  IntegerCoder DY{ 32, 22 };
  IntegerCoder Z{ 32, 20 };
  StreamingMedian5 XDifferences[12];
  StreamingMedian5 YDifferences[12];
  std::int32_t LastZ[8];
  LazyModels Classification{ 64, 256 };
  LazyModels Flags{ 64, 64 };
  LazyModels UserData{ 64, 256 };
  IntegerCoder Intensity{ 16, 4 };
  std::uint16_t LastIntensity[8];
  IntegerCoder ScanAngle{ 16, 2 };
  IntegerCoder PointSource{ 16 };
  TimeCoder Times{ GPSTimeCodesV3 };
};

} // namespace laz
} // namespace pcbilateral

#endif

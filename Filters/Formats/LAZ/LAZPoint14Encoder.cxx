#include "LAZPoint14Encoder.h"

#include "LAZGPSTimeEncoder.h"
#include "LAZPoint14Channel.h"
#include "LAZPointContexts.h"

namespace pcbilateral
{
namespace laz
{

/// What is predicted per scanner channel when encoding.
struct Point14EncoderContext : Point14ChannelModels<IntegerEncoder, GPSTimeEncoder>
{
  using Point14ChannelModels::Point14ChannelModels;
};

Point14Encoder::Point14Encoder() = default;
Point14Encoder::~Point14Encoder() = default;

void Point14Encoder::Start(const std::uint8_t* item)
{
  const Point14 first = ParsePoint14(item);
  this->Current = first.Channel;
  this->Contexts[this->Current] = std::make_unique<Point14EncoderContext>(first);
}

void Point14Encoder::Encode(const std::uint8_t* item)
{
  const Point14 point = ParsePoint14(item);
  Point14EncoderContext* old = this->Contexts[this->Current].get();
  const Point14& previous = old->Last;
  const unsigned lastReturnContext = (previous.Return == 1 ? 1u : 0u) +
                                     (previous.Return >= previous.Returns ? 2u : 0u) +
                                     (previous.GPSTimeChanged ? 4u : 0u);
  Point14EncoderContext* c = old;
  const unsigned channel = point.Channel;
  if (channel != this->Current)
  {
    if (!this->Contexts[channel])
    {
      this->Contexts[channel] = std::make_unique<Point14EncoderContext>(old->Last);
    }
    c = this->Contexts[channel].get();
    c->Last.Channel = channel;
  }
  const Point14& last = c->Last;
  const bool gpsChanged = point.GPSTime != last.GPSTime;
  std::uint32_t returnCode = 3;
  if (point.Return == last.Return)
  {
    returnCode = 0;
  }
  else if (point.Return == ((last.Return + 1) & 15))
  {
    returnCode = 1;
  }
  else if (point.Return == ((last.Return + 15) & 15))
  {
    returnCode = 2;
  }
  const std::uint32_t changed = (channel != this->Current ? 1u << 6 : 0u) |
                                (point.PointSource != last.PointSource ? 1u << 5 : 0u) |
                                (gpsChanged ? 1u << 4 : 0u) |
                                (point.ScanAngle != last.ScanAngle ? 1u << 3 : 0u) |
                                (point.Returns != last.Returns ? 1u << 2 : 0u) | returnCode;
  ArithmeticEncoder& encoder = this->Encoders[ReturnsXYLayer];
  encoder.EncodeSymbol(old->ChangedValues[lastReturnContext], changed);
  if (channel != this->Current)
  {
    encoder.EncodeSymbol(old->ScannerChannel, (channel - this->Current - 1) & 3);
    this->Current = channel;
  }
  this->EncodeReturns(*c, point, changed, gpsChanged);
  this->EncodeCoordinates(*c, point, gpsChanged);
  this->EncodeAttributes(*c, point, changed, gpsChanged);
  c->Last = point;
  c->Last.GPSTimeChanged = gpsChanged;
}

void Point14Encoder::EncodeReturns(Point14EncoderContext& c,
  const Point14& point,
  std::uint32_t changed,
  bool gpsChanged)
{
  ArithmeticEncoder& encoder = this->Encoders[ReturnsXYLayer];
  const Point14& last = c.Last;
  if (changed & (1u << 2))
  {
    encoder.EncodeSymbol(c.NumberOfReturns[last.Returns], point.Returns);
  }
  if ((changed & 3) == 3)
  {
    if (gpsChanged)
    {
      encoder.EncodeSymbol(c.ReturnNumber[last.Return], point.Return);
    }
    else
    {
      encoder.EncodeSymbol(c.ReturnNumberSameTime, (point.Return - last.Return - 2) & 15);
    }
  }
}

void Point14Encoder::EncodeCoordinates(Point14EncoderContext& c,
  const Point14& point,
  bool gpsChanged)
{
  ArithmeticEncoder& encoder = this->Encoders[ReturnsXYLayer];
  const unsigned n = point.Returns;
  const unsigned r = point.Return;
  const unsigned m = (ReturnMap6(n, r) << 1) | (gpsChanged ? 1u : 0u);
  const auto dx = static_cast<std::int32_t>(
    static_cast<std::uint32_t>(point.X) - static_cast<std::uint32_t>(c.Last.X));
  c.DX.Encode(encoder, c.XDifferences[m].Get(), dx, n == 1);
  c.XDifferences[m].Add(dx);
  const unsigned kx = c.DX.K();
  const auto dy = static_cast<std::int32_t>(
    static_cast<std::uint32_t>(point.Y) - static_cast<std::uint32_t>(c.Last.Y));
  c.DY.Encode(encoder, c.YDifferences[m].Get(), dy, (n == 1) + (kx < 20 ? (kx & ~1u) : 20));
  c.YDifferences[m].Add(dy);
  const unsigned kxy = (c.DX.K() + c.DY.K()) / 2;
  const unsigned l = ReturnLevel8(n, r);
  this->Changed[ZLayer] = this->Changed[ZLayer] || point.Z != c.Last.Z;
  c.Z.Encode(this->Encoders[ZLayer], c.LastZ[l], point.Z, (n == 1) + (kxy < 18 ? (kxy & ~1u) : 18));
  c.LastZ[l] = point.Z;
}

void Point14Encoder::EncodeAttributes(Point14EncoderContext& c,
  const Point14& point,
  std::uint32_t changed,
  bool gpsChanged)
{
  const Point14& last = c.Last;
  const unsigned n = point.Returns;
  const unsigned r = point.Return;
  const unsigned returnContext = (r == 1 ? 1u : 0u) + (r >= n ? 2u : 0u);
  bool* layer = this->Changed;
  layer[ClassificationLayer] |= point.Classification != last.Classification;
  const unsigned classContext = ((last.Classification & 0x1Fu) << 1) + (returnContext == 3);
  this->Encoders[ClassificationLayer].EncodeSymbol(
    c.Classification[classContext], point.Classification);
  const unsigned previousFlags =
    (last.EdgeOfFlightLine << 5) | (last.ScanDirection << 4) | last.ClassificationFlags;
  const unsigned flags =
    (point.EdgeOfFlightLine << 5) | (point.ScanDirection << 4) | point.ClassificationFlags;
  layer[FlagsLayer] |= flags != previousFlags;
  this->Encoders[FlagsLayer].EncodeSymbol(c.Flags[previousFlags], flags);
  const unsigned slot = (returnContext << 1) | (gpsChanged ? 1u : 0u);
  layer[IntensityLayer] |= point.Intensity != last.Intensity;
  c.Intensity.Encode(
    this->Encoders[IntensityLayer], c.LastIntensity[slot], point.Intensity, returnContext);
  c.LastIntensity[slot] = point.Intensity;
  if (changed & (1u << 3))
  {
    layer[ScanAngleLayer] = true;
    c.ScanAngle.Encode(
      this->Encoders[ScanAngleLayer], last.ScanAngle, point.ScanAngle, gpsChanged ? 1 : 0);
  }
  layer[UserDataLayer] |= point.UserData != last.UserData;
  this->Encoders[UserDataLayer].EncodeSymbol(c.UserData[last.UserData / 4], point.UserData);
  if (changed & (1u << 5))
  {
    layer[PointSourceLayer] = true;
    c.PointSource.Encode(this->Encoders[PointSourceLayer], last.PointSource, point.PointSource);
  }
  if (gpsChanged)
  {
    layer[GPSTimeLayer] = true;
    c.Times.Encode(this->Encoders[GPSTimeLayer], point.GPSTime);
  }
}

std::vector<std::uint8_t> Point14Encoder::Finish(int layer)
{
  this->Encoders[layer].Finish();
  // A field that never changed in the chunk needs no layer: the decoder keeps its value.
  if (layer != ReturnsXYLayer && !this->Changed[layer])
  {
    return {};
  }
  return std::move(this->Encoders[layer].Bytes());
}

} // namespace laz
} // namespace pcbilateral

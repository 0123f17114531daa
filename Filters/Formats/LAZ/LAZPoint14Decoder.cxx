#include "LAZPoint14Decoder.h"

#include "LASBinary.h"
#include "LAZGPSTime.h"
#include "LAZPoint14Channel.h"
#include "LAZPointContexts.h"

namespace pcbilateral
{
namespace laz
{

using las::Load;
using las::Store;

/**
 * The return map of formats 6 to 10 (4-bit r and n), reduced to six contexts, as in the LASzip
 * specification's table: single returns, first of two, second of two, then first, last and
 * intermediate returns of more.
 */
unsigned ReturnMap6(unsigned n, unsigned r)
{
  static const std::uint8_t map[16][16] = {
    { 0, 1, 2, 3, 4, 5, 3, 4, 4, 5, 5, 5, 5, 5, 5, 5 },
    { 1, 0, 1, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3 },
    { 2, 1, 2, 4, 4, 4, 4, 4, 4, 4, 4, 3, 3, 3, 3, 3 },
    { 3, 3, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4 },
    { 4, 3, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4 },
    { 5, 3, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4 },
    { 3, 3, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4 },
    { 4, 3, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4 },
    { 4, 3, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4 },
    { 5, 3, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4 },
    { 5, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4 },
    { 5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 4, 4, 4 },
    { 5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4, 4 },
    { 5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4 },
    { 5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5 },
    { 5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5 },
  };
  return map[n & 15][r & 15];
}

/// The return level of formats 6 to 10: how far r is from n, at most 7.
unsigned ReturnLevel8(unsigned n, unsigned r)
{
  const unsigned level = n > r ? n - r : r - n;
  return level < 7 ? level : 7;
}

Point14 ParsePoint14(const std::uint8_t* item)
{
  Point14 p;
  p.X = Load<std::int32_t>(item);
  p.Y = Load<std::int32_t>(item + 4);
  p.Z = Load<std::int32_t>(item + 8);
  p.Intensity = Load<std::uint16_t>(item + 12);
  p.Return = item[14] & 15;
  p.Returns = item[14] >> 4;
  p.ClassificationFlags = item[15] & 15;
  p.Channel = (item[15] >> 4) & 3;
  p.ScanDirection = (item[15] >> 6) & 1;
  p.EdgeOfFlightLine = item[15] >> 7;
  p.Classification = item[16];
  p.UserData = item[17];
  p.ScanAngle = Load<std::int16_t>(item + 18);
  p.PointSource = Load<std::uint16_t>(item + 20);
  p.GPSTime = Load<std::int64_t>(item + 22);
  return p;
}

void StorePoint14(const Point14& p, std::uint8_t* item)
{
  Store<std::int32_t>(item, p.X);
  Store<std::int32_t>(item + 4, p.Y);
  Store<std::int32_t>(item + 8, p.Z);
  Store<std::uint16_t>(item + 12, p.Intensity);
  item[14] = static_cast<std::uint8_t>(p.Return | (p.Returns << 4));
  item[15] = static_cast<std::uint8_t>(
    p.ClassificationFlags | (p.Channel << 4) | (p.ScanDirection << 6) | (p.EdgeOfFlightLine << 7));
  item[16] = p.Classification;
  item[17] = p.UserData;
  Store<std::int16_t>(item + 18, p.ScanAngle);
  Store<std::uint16_t>(item + 20, p.PointSource);
  Store<std::int64_t>(item + 22, p.GPSTime);
}

/// What is predicted per scanner channel when decoding.
struct Point14Context : Point14ChannelModels<IntegerDecoder, GPSTimeSequences>
{
  using Point14ChannelModels::Point14ChannelModels;
};

Point14Decoder::Point14Decoder() = default;
Point14Decoder::~Point14Decoder() = default;

void Point14Decoder::Start(const std::uint8_t* item, const Layer* layers)
{
  for (int k = 0; k < Layers; ++k)
  {
    // A layer without bytes is a field that does not change in the chunk.
    this->Changed[k] = !layers[k].Empty();
    if (this->Changed[k] || k == ReturnsXYLayer)
    {
      this->Decoders[k].Start(layers[k].Begin, layers[k].End);
    }
  }
  const Point14 first = ParsePoint14(item);
  this->Current = first.Channel;
  this->Context(this->Current, first);
}

bool Point14Decoder::Overrun() const
{
  for (int k = 0; k < Layers; ++k)
  {
    if ((this->Changed[k] || k == ReturnsXYLayer) && this->Decoders[k].Overrun())
    {
      return true;
    }
  }
  return false;
}

/// The context of a channel, made from the point `from` when the channel is first seen.
Point14Context& Point14Decoder::Context(unsigned channel, const Point14& from)
{
  if (!this->Contexts[channel])
  {
    this->Contexts[channel] = std::make_unique<Point14Context>(from);
  }
  return *this->Contexts[channel];
}

void Point14Decoder::Decode(std::uint8_t* item, unsigned& channel)
{
  ArithmeticDecoder& decoder = this->Decoders[ReturnsXYLayer];
  Point14Context* c = this->Contexts[this->Current].get();
  {
    const Point14& last = c->Last;
    const unsigned lastReturnContext = (last.Return == 1 ? 1u : 0u) +
                                       (last.Return >= last.Returns ? 2u : 0u) +
                                       (last.GPSTimeChanged ? 4u : 0u);
    const std::uint32_t changed = decoder.DecodeSymbol(c->ChangedValues[lastReturnContext]);
    if (changed & (1u << 6))
    {
      const unsigned step = decoder.DecodeSymbol(c->ScannerChannel);
      const unsigned next = (this->Current + step + 1) & 3;
      c = &this->Context(next, c->Last);
      this->Current = next;
      c->Last.Channel = next;
    }
    const bool gpsChanged = (changed & (1u << 4)) != 0;
    const unsigned r = this->DecodeReturns(*c, changed, gpsChanged);
    const unsigned n = c->Last.Returns;
    this->DecodeCoordinates(*c, n, r, gpsChanged);
    this->DecodeAttributes(*c, changed, n, r);
    StorePoint14(c->Last, item);
    c->Last.GPSTimeChanged = gpsChanged;
  }
  channel = this->Current;
}

/// The number of returns and the return number; returns the latter.
unsigned Point14Decoder::DecodeReturns(Point14Context& c, std::uint32_t changed, bool gpsChanged)
{
  ArithmeticDecoder& decoder = this->Decoders[ReturnsXYLayer];
  Point14& last = c.Last;
  if (changed & (1u << 2))
  {
    last.Returns = decoder.DecodeSymbol(c.NumberOfReturns[last.Returns]);
  }
  switch (changed & 3)
  {
    case 0:
      break;
    case 1:
      last.Return = (last.Return + 1) & 15;
      break;
    case 2:
      last.Return = (last.Return + 15) & 15;
      break;
    default:
      // A bigger step: the return itself when the time changed (a new pulse), else the step.
      if (gpsChanged)
      {
        last.Return = decoder.DecodeSymbol(c.ReturnNumber[last.Return]);
      }
      else
      {
        last.Return = (last.Return + decoder.DecodeSymbol(c.ReturnNumberSameTime) + 2) & 15;
      }
  }
  return last.Return;
}

void Point14Decoder::DecodeCoordinates(Point14Context& c, unsigned n, unsigned r, bool gpsChanged)
{
  ArithmeticDecoder& decoder = this->Decoders[ReturnsXYLayer];
  const unsigned m = (ReturnMap6(n, r) << 1) | (gpsChanged ? 1u : 0u);
  const std::int32_t dx = c.DX.Decode(decoder, c.XDifferences[m].Get(), n == 1);
  c.XDifferences[m].Add(dx);
  c.Last.X = static_cast<std::int32_t>(static_cast<std::uint32_t>(c.Last.X) + dx);
  const unsigned kx = c.DX.K();
  const std::int32_t dy =
    c.DY.Decode(decoder, c.YDifferences[m].Get(), (n == 1) + (kx < 20 ? (kx & ~1u) : 20));
  c.YDifferences[m].Add(dy);
  c.Last.Y = static_cast<std::int32_t>(static_cast<std::uint32_t>(c.Last.Y) + dy);
  if (this->Changed[ZLayer])
  {
    const unsigned kxy = (c.DX.K() + c.DY.K()) / 2;
    const unsigned l = ReturnLevel8(n, r);
    c.Last.Z =
      c.Z.Decode(this->Decoders[ZLayer], c.LastZ[l], (n == 1) + (kxy < 18 ? (kxy & ~1u) : 18));
    c.LastZ[l] = c.Last.Z;
  }
}

void Point14Decoder::DecodeAttributes(Point14Context& c,
  std::uint32_t changed,
  unsigned n,
  unsigned r)
{
  Point14& last = c.Last;
  const bool gpsChanged = (changed & (1u << 4)) != 0;
  const unsigned returnContext = (r == 1 ? 1u : 0u) + (r >= n ? 2u : 0u);
  if (this->Changed[ClassificationLayer])
  {
    const unsigned context = ((last.Classification & 0x1Fu) << 1) + (returnContext == 3 ? 1 : 0);
    last.Classification = static_cast<std::uint8_t>(
      this->Decoders[ClassificationLayer].DecodeSymbol(c.Classification[context]));
  }
  if (this->Changed[FlagsLayer])
  {
    const unsigned previous =
      (last.EdgeOfFlightLine << 5) | (last.ScanDirection << 4) | last.ClassificationFlags;
    const unsigned flags = this->Decoders[FlagsLayer].DecodeSymbol(c.Flags[previous]);
    last.EdgeOfFlightLine = (flags >> 5) & 1;
    last.ScanDirection = (flags >> 4) & 1;
    last.ClassificationFlags = flags & 15;
  }
  if (this->Changed[IntensityLayer])
  {
    const unsigned slot = (returnContext << 1) | (gpsChanged ? 1u : 0u);
    last.Intensity = static_cast<std::uint16_t>(
      c.Intensity.Decode(this->Decoders[IntensityLayer], c.LastIntensity[slot], returnContext));
    c.LastIntensity[slot] = last.Intensity;
  }
  if (this->Changed[ScanAngleLayer] && (changed & (1u << 3)))
  {
    last.ScanAngle = static_cast<std::int16_t>(
      c.ScanAngle.Decode(this->Decoders[ScanAngleLayer], last.ScanAngle, gpsChanged ? 1 : 0));
  }
  if (this->Changed[UserDataLayer])
  {
    last.UserData = static_cast<std::uint8_t>(
      this->Decoders[UserDataLayer].DecodeSymbol(c.UserData[last.UserData / 4]));
  }
  if (this->Changed[PointSourceLayer] && (changed & (1u << 5)))
  {
    last.PointSource = static_cast<std::uint16_t>(
      c.PointSource.Decode(this->Decoders[PointSourceLayer], last.PointSource));
  }
  if (this->Changed[GPSTimeLayer] && gpsChanged)
  {
    last.GPSTime = c.Times.Decode(this->Decoders[GPSTimeLayer]);
  }
}

} // namespace laz
} // namespace pcbilateral

// The point14 item of LASzip's layered compressor (point formats 6 to 10, item version 3): the
// 30 bytes of a LAS 1.4 point, each group of fields in a layer of its own, predicted from the
// previous point of the same scanner channel (four contexts). Private to the LAZ codec.
#ifndef pcbilateral_LAZPoint14Decoder_h
#define pcbilateral_LAZPoint14Decoder_h

#include "LAZEntropyDecoder.h"

#include <cstdint>
#include <memory>

namespace pcbilateral
{
namespace laz
{

/// The bytes of one layer of a chunk.
struct Layer
{
  const std::uint8_t* Begin = nullptr;
  const std::uint8_t* End = nullptr;
  bool Empty() const { return this->Begin == this->End; }
};

/// The fields of a point of formats 6 to 10 that point14 codes.
struct Point14
{
  std::int32_t X = 0;
  std::int32_t Y = 0;
  std::int32_t Z = 0;
  std::uint16_t Intensity = 0;
  unsigned Return = 0;
  unsigned Returns = 0;
  unsigned ClassificationFlags = 0;
  unsigned Channel = 0;
  unsigned ScanDirection = 0;
  unsigned EdgeOfFlightLine = 0;
  std::uint8_t Classification = 0;
  std::uint8_t UserData = 0;
  std::int16_t ScanAngle = 0;
  std::uint16_t PointSource = 0;
  std::int64_t GPSTime = 0;
  /// Whether this point's GPS time differed from the previous one's (a context of the next).
  bool GPSTimeChanged = false;
};

/// The fields of a raw 30-byte record of formats 6 to 10, and back.
Point14 ParsePoint14(const std::uint8_t* item);
void StorePoint14(const Point14& point, std::uint8_t* item);
/// The return map of formats 6 to 10, reduced to six contexts (the specification's table).
unsigned ReturnMap6(unsigned n, unsigned r);
/// The return level of formats 6 to 10: how far r is from n, at most 7.
unsigned ReturnLevel8(unsigned n, unsigned r);

/// The layers of point14, in the order of their byte counts in a chunk.
enum Point14Layer
{
  ReturnsXYLayer,
  ZLayer,
  ClassificationLayer,
  FlagsLayer,
  IntensityLayer,
  ScanAngleLayer,
  UserDataLayer,
  PointSourceLayer,
  GPSTimeLayer
};

struct Point14Context;

/// Decodes the point14 items of a layered chunk.
class Point14Decoder
{
public:
  static constexpr int Layers = 9;

  Point14Decoder();
  ~Point14Decoder();
  Point14Decoder(const Point14Decoder&) = delete;
  Point14Decoder& operator=(const Point14Decoder&) = delete;

  /// The chunk's first point, raw, and the bytes of the nine layers.
  void Start(const std::uint8_t* item, const Layer* layers);
  /// Decodes the next point into `item` (30 bytes); `channel` is its scanner channel, the
  /// context of the other items.
  void Decode(std::uint8_t* item, unsigned& channel);
  bool Overrun() const;
  unsigned Channel() const { return this->Current; }

private:
  Point14Context& Context(unsigned channel, const Point14& from);
  unsigned DecodeReturns(Point14Context& c, std::uint32_t changed, bool gpsChanged);
  void DecodeCoordinates(Point14Context& c, unsigned n, unsigned r, bool gpsChanged);
  void DecodeAttributes(Point14Context& c, std::uint32_t changed, unsigned n, unsigned r);

  ArithmeticDecoder Decoders[Layers];
  bool Changed[Layers] = {};
  std::unique_ptr<Point14Context> Contexts[4];
  unsigned Current = 0;
};

} // namespace laz
} // namespace pcbilateral

#endif

// The point14 item's encoder (point formats 6 to 10, item version 3), the mirror of
// Point14Decoder: each group of fields into a layer of its own. Private to the LAZ codec.
#ifndef pcbilateral_LAZPoint14Encoder_h
#define pcbilateral_LAZPoint14Encoder_h

#include "LAZEntropyEncoder.h"
#include "LAZPoint14Decoder.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace pcbilateral
{
namespace laz
{

struct Point14EncoderContext;

class Point14Encoder
{
public:
  Point14Encoder();
  ~Point14Encoder();
  Point14Encoder(const Point14Encoder&) = delete;
  Point14Encoder& operator=(const Point14Encoder&) = delete;

  /// The chunk's first point, which is stored raw.
  void Start(const std::uint8_t* item);
  void Encode(const std::uint8_t* item);
  /// The scanner channel of the last point: the context of the other items.
  unsigned Channel() const { return this->Current; }
  /// Ends layer `layer` (a Point14Layer) and returns its bytes.
  std::vector<std::uint8_t> Finish(int layer);

private:
  void EncodeReturns(Point14EncoderContext& c,
    const Point14& point,
    std::uint32_t changed,
    bool gpsChanged);
  void EncodeCoordinates(Point14EncoderContext& c, const Point14& point, bool gpsChanged);
  void EncodeAttributes(Point14EncoderContext& c,
    const Point14& point,
    std::uint32_t changed,
    bool gpsChanged);

  ArithmeticEncoder Encoders[Point14Decoder::Layers];
  bool Changed[Point14Decoder::Layers] = {};
  std::unique_ptr<Point14EncoderContext> Contexts[4];
  unsigned Current = 0;
};

} // namespace laz
} // namespace pcbilateral

#endif

#include "LAZLayeredDecoder.h"

#include "LASBinary.h"
#include "LAZPoint14Decoder.h"
#include "LAZPointContexts.h"

#include <cstring>
#include <memory>
#include <vector>

namespace pcbilateral
{
namespace laz
{

namespace
{
using las::Load;
using las::Store;
using las::Str;

/**
 * An item after point14 (colours, near infrared, extra bytes): values per scanner channel, each
 * a layer of its own. A channel seen for the first time starts from the values of the channel
 * before. As in LASzip (and so in every file it wrote), returning to a channel seen before keeps
 * predicting from, and updating, the previous channel's values with the new channel's models.
 */
class LayeredItem
{
public:
  explicit LayeredItem(std::size_t size)
    : Size(size)
  {
  }
  virtual ~LayeredItem() = default;
  virtual std::size_t LayerCount() const = 0;

  void Start(const std::uint8_t* item, const Layer* layers, unsigned channel)
  {
    this->Decoders.resize(this->LayerCount());
    this->Changed.resize(this->LayerCount());
    for (std::size_t k = 0; k < this->LayerCount(); ++k)
    {
      this->Changed[k] = !layers[k].Empty();
      if (this->Changed[k])
      {
        this->Decoders[k].Start(layers[k].Begin, layers[k].End);
      }
    }
    this->Current = channel;
    this->Used[channel] = true;
    this->Last[channel].assign(item, item + this->Size);
    this->MakeModels(channel);
  }

  void Decode(std::uint8_t* item, unsigned channel)
  {
    unsigned lastSlot = this->Current;
    if (channel != this->Current)
    {
      this->Current = channel;
      if (!this->Used[channel])
      {
        this->Used[channel] = true;
        this->Last[channel] = this->Last[lastSlot];
        this->MakeModels(channel);
        lastSlot = channel;
      }
    }
    this->DecodeValues(this->Current, this->Last[lastSlot].data());
    std::memcpy(item, this->Last[lastSlot].data(), this->Size);
  }

  bool Overrun() const
  {
    for (std::size_t k = 0; k < this->Decoders.size(); ++k)
    {
      if (this->Changed[k] && this->Decoders[k].Overrun())
      {
        return true;
      }
    }
    return false;
  }

protected:
  virtual void MakeModels(unsigned channel) = 0;
  /// Decodes the values of a point with the models of `channel`, from and into `last`.
  virtual void DecodeValues(unsigned channel, std::uint8_t* last) = 0;

  std::vector<ArithmeticDecoder> Decoders;
  std::vector<char> Changed;

private:
  std::size_t Size;
  unsigned Current = 0;
  bool Used[4] = {};
  std::vector<std::uint8_t> Last[4];
};

/// RGB14 (one layer) and RGBNIR14 (a layer for the colour, one for near infrared).
class ColourItem final : public LayeredItem
{
public:
  explicit ColourItem(bool nearInfrared)
    : LayeredItem(nearInfrared ? 8 : 6)
    , NearInfrared(nearInfrared)
  {
  }

  std::size_t LayerCount() const override { return this->NearInfrared ? 2 : 1; }

private:
  using Models = ColourLayerModels;

  void MakeModels(unsigned channel) override
  {
    this->ChannelModels[channel] = std::make_unique<Models>();
  }

  void DecodeValues(unsigned channel, std::uint8_t* last) override
  {
    Models& models = *this->ChannelModels[channel];
    if (this->Changed[0])
    {
      std::uint32_t previous[3];
      std::uint32_t rgb[3];
      for (int c = 0; c < 3; ++c)
      {
        previous[c] = Load<std::uint16_t>(last + 2 * c);
      }
      DecodeRGBDifferences(this->Decoders[0], models.Colour, previous, rgb);
      for (int c = 0; c < 3; ++c)
      {
        Store<std::uint16_t>(last + 2 * c, static_cast<std::uint16_t>(rgb[c]));
      }
    }
    if (this->NearInfrared && this->Changed[1])
    {
      ArithmeticDecoder& decoder = this->Decoders[1];
      const std::uint32_t used = decoder.DecodeSymbol(models.NIRBytesUsed);
      std::uint8_t* nir = last + 6;
      for (int high = 0; high < 2; ++high)
      {
        if (used & (1u << high))
        {
          const auto step =
            static_cast<std::int32_t>(decoder.DecodeSymbol(models.NIRDifferences[high]));
          nir[high] = FoldByte(step + nir[high]);
        }
      }
    }
  }

  bool NearInfrared;
  std::unique_ptr<Models> ChannelModels[4];
};

/// BYTE14: the extra bytes, a layer per byte.
class ExtraBytesItem final : public LayeredItem
{
public:
  explicit ExtraBytesItem(std::size_t count)
    : LayeredItem(count)
    , Count(count)
  {
  }

  std::size_t LayerCount() const override { return this->Count; }

private:
  void MakeModels(unsigned channel) override
  {
    this->ChannelModels[channel].assign(this->Count, SymbolModel(256));
  }

  void DecodeValues(unsigned channel, std::uint8_t* last) override
  {
    std::vector<SymbolModel>& models = this->ChannelModels[channel];
    for (std::size_t i = 0; i < this->Count; ++i)
    {
      if (this->Changed[i])
      {
        const auto step = static_cast<std::int32_t>(this->Decoders[i].DecodeSymbol(models[i]));
        last[i] = FoldByte(step + last[i]);
      }
    }
  }

  std::size_t Count;
  std::vector<SymbolModel> ChannelModels[4];
};

/// Cuts the chunk after its first point into layers: the point count, the byte count of each
/// layer of each item, then the layers in that order.
std::string CutLayers(const std::uint8_t* at,
  const std::uint8_t* end,
  std::size_t layerCount,
  std::vector<Layer>& layers)
{
  const std::size_t header = 4 + 4 * layerCount;
  if (static_cast<std::size_t>(end - at) < header)
  {
    return "truncated: the chunk ends in its table of layers";
  }
  const std::uint8_t* data = at + header;
  layers.resize(layerCount);
  for (std::size_t k = 0; k < layerCount; ++k)
  {
    const std::uint32_t bytes = Load<std::uint32_t>(at + 4 + 4 * k);
    if (bytes > static_cast<std::size_t>(end - data))
    {
      return "truncated or damaged: layer " + Str(k + 1) + " of " + Str(layerCount) + " (" +
             Str(bytes) + " bytes) runs past the chunk";
    }
    layers[k] = { data, data + bytes };
    data += bytes;
  }
  return std::string();
}

std::vector<std::unique_ptr<LayeredItem>> MakeLayeredItems(const LAZParameters& parameters)
{
  std::vector<std::unique_ptr<LayeredItem>> items;
  for (std::size_t i = 1; i < parameters.Items.size(); ++i)
  {
    const LAZItem& item = parameters.Items[i];
    switch (static_cast<LAZItemType>(item.Type))
    {
      case LAZItemType::RGB14:
        items.push_back(std::make_unique<ColourItem>(false));
        break;
      case LAZItemType::RGBNIR14:
        items.push_back(std::make_unique<ColourItem>(true));
        break;
      case LAZItemType::Byte14:
        items.push_back(std::make_unique<ExtraBytesItem>(item.Size));
        break;
      default:
        return {};
    }
  }
  return items;
}
} // namespace

std::string DecodeLayeredChunk(const std::uint8_t* begin,
  const std::uint8_t* end,
  const LAZParameters& parameters,
  std::size_t recordLength,
  std::uint64_t points,
  std::uint8_t* out)
{
  if (static_cast<std::size_t>(end - begin) < recordLength)
  {
    return "truncated: the chunk is shorter than its first point";
  }
  std::memcpy(out, begin, recordLength);
  if (points < 2)
  {
    return std::string();
  }
  std::vector<std::unique_ptr<LayeredItem>> items = MakeLayeredItems(parameters);
  if (items.size() + 1 != parameters.Items.size())
  {
    return "an item after point14 is not one of rgb14, rgbnir14 and byte14";
  }
  std::size_t layerCount = Point14Decoder::Layers;
  for (const auto& item : items)
  {
    layerCount += item->LayerCount();
  }
  std::vector<Layer> layers;
  std::string problem = CutLayers(begin + recordLength, end, layerCount, layers);
  if (!problem.empty())
  {
    return problem;
  }
  Point14Decoder point;
  point.Start(out, layers.data());
  std::size_t layer = Point14Decoder::Layers;
  std::size_t offset = 30;
  std::vector<std::size_t> offsets;
  for (const auto& item : items)
  {
    item->Start(out + offset, layers.data() + layer, point.Channel());
    offsets.push_back(offset);
    layer += item->LayerCount();
    offset += parameters.Items[offsets.size()].Size;
  }
  for (std::uint64_t p = 1; p < points; ++p)
  {
    if ((p & 4095) == 0 && point.Overrun())
    {
      break; // damaged: reported below, without decoding the rest
    }
    std::uint8_t* record = out + p * recordLength;
    unsigned channel = 0;
    point.Decode(record, channel);
    for (std::size_t i = 0; i < items.size(); ++i)
    {
      items[i]->Decode(record + offsets[i], channel);
    }
  }
  bool overrun = point.Overrun();
  for (const auto& item : items)
  {
    overrun = overrun || item->Overrun();
  }
  return overrun ? "truncated or damaged: a layer ends before the chunk's last point"
                 : std::string();
}

} // namespace laz
} // namespace pcbilateral

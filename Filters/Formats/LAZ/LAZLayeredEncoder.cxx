#include "LAZLayeredEncoder.h"

#include "LASBinary.h"
#include "LAZPoint14Encoder.h"
#include "LAZPointContexts.h"

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

/// The mirror of LayeredItem (LAZLayeredDecoder.cxx): values per scanner channel, with
/// LASzip's way of predicting from the previous channel's values on a return to a channel.
class LayeredItemEncoder
{
public:
  LayeredItemEncoder(std::size_t size, std::size_t layers)
    : Size(size)
    , Encoders(layers)
    , Changed(layers, 0)
  {
  }
  virtual ~LayeredItemEncoder() = default;

  std::size_t LayerCount() const { return this->Encoders.size(); }

  void Start(const std::uint8_t* item, unsigned channel)
  {
    this->Current = channel;
    this->Used[channel] = true;
    this->Last[channel].assign(item, item + this->Size);
    this->MakeModels(channel);
  }

  void Encode(const std::uint8_t* item, unsigned channel)
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
    std::uint8_t* last = this->Last[lastSlot].data();
    this->EncodeValues(this->Current, last, item);
    std::memcpy(last, item, this->Size);
  }

  /// Ends layer `k`; a layer whose values never changed is left empty.
  std::vector<std::uint8_t> Finish(std::size_t k)
  {
    this->Encoders[k].Finish();
    return this->Changed[k] ? std::move(this->Encoders[k].Bytes()) : std::vector<std::uint8_t>();
  }

protected:
  virtual void MakeModels(unsigned channel) = 0;
  virtual void EncodeValues(unsigned channel,
    const std::uint8_t* last,
    const std::uint8_t* item) = 0;

  std::size_t Size;
  std::vector<ArithmeticEncoder> Encoders;
  std::vector<char> Changed;

private:
  unsigned Current = 0;
  bool Used[4] = {};
  std::vector<std::uint8_t> Last[4];
};

class ColourItemEncoder final : public LayeredItemEncoder
{
public:
  explicit ColourItemEncoder(bool nearInfrared)
    : LayeredItemEncoder(nearInfrared ? 8 : 6, nearInfrared ? 2 : 1)
    , NearInfrared(nearInfrared)
  {
  }

private:
  using Models = ColourLayerModels;

  void MakeModels(unsigned channel) override
  {
    this->ChannelModels[channel] = std::make_unique<Models>();
  }

  void EncodeValues(unsigned channel, const std::uint8_t* last, const std::uint8_t* item) override
  {
    Models& models = *this->ChannelModels[channel];
    std::uint32_t previous[3];
    std::uint32_t rgb[3];
    for (int c = 0; c < 3; ++c)
    {
      previous[c] = Load<std::uint16_t>(last + 2 * c);
      rgb[c] = Load<std::uint16_t>(item + 2 * c);
    }
    this->Changed[0] |= std::memcmp(last, item, 6) != 0;
    EncodeRGBDifferences(this->Encoders[0], models.Colour, previous, rgb);
    if (!this->NearInfrared)
    {
      return;
    }
    const std::uint32_t used = (last[6] != item[6] ? 1u : 0u) | (last[7] != item[7] ? 2u : 0u);
    this->Changed[1] |= used != 0;
    this->Encoders[1].EncodeSymbol(models.NIRBytesUsed, used);
    for (int high = 0; high < 2; ++high)
    {
      if (used & (1u << high))
      {
        this->Encoders[1].EncodeSymbol(
          models.NIRDifferences[high], FoldByte(item[6 + high] - last[6 + high]));
      }
    }
  }

  bool NearInfrared;
  std::unique_ptr<Models> ChannelModels[4];
};

class ExtraBytesItemEncoder final : public LayeredItemEncoder
{
public:
  explicit ExtraBytesItemEncoder(std::size_t count)
    : LayeredItemEncoder(count, count)
  {
  }

private:
  void MakeModels(unsigned channel) override
  {
    this->ChannelModels[channel].assign(this->Size, SymbolModel(256));
  }

  void EncodeValues(unsigned channel, const std::uint8_t* last, const std::uint8_t* item) override
  {
    for (std::size_t i = 0; i < this->Size; ++i)
    {
      this->Changed[i] |= last[i] != item[i];
      this->Encoders[i].EncodeSymbol(this->ChannelModels[channel][i], FoldByte(item[i] - last[i]));
    }
  }

  std::vector<SymbolModel> ChannelModels[4];
};

std::unique_ptr<LayeredItemEncoder> MakeLayeredItemEncoder(const LAZItem& item)
{
  switch (static_cast<LAZItemType>(item.Type))
  {
    case LAZItemType::RGB14:
      return std::make_unique<ColourItemEncoder>(false);
    case LAZItemType::RGBNIR14:
      return std::make_unique<ColourItemEncoder>(true);
    case LAZItemType::Byte14:
      return std::make_unique<ExtraBytesItemEncoder>(item.Size);
    default:
      return nullptr;
  }
}
} // namespace

std::vector<std::uint8_t> CompressLayeredChunk(const std::uint8_t* records,
  std::size_t count,
  std::size_t recordLength,
  const LAZParameters& parameters)
{
  std::vector<std::uint8_t> out(records, records + recordLength);
  if (count < 2)
  {
    return out;
  }
  Point14Encoder point;
  point.Start(records);
  std::vector<std::unique_ptr<LayeredItemEncoder>> items;
  std::vector<std::size_t> offsets;
  std::size_t offset = 30;
  for (std::size_t i = 1; i < parameters.Items.size(); ++i)
  {
    items.push_back(MakeLayeredItemEncoder(parameters.Items[i]));
    items.back()->Start(records + offset, point.Channel());
    offsets.push_back(offset);
    offset += parameters.Items[i].Size;
  }
  for (std::size_t p = 1; p < count; ++p)
  {
    const std::uint8_t* record = records + p * recordLength;
    point.Encode(record);
    for (std::size_t i = 0; i < items.size(); ++i)
    {
      items[i]->Encode(record + offsets[i], point.Channel());
    }
  }
  std::vector<std::vector<std::uint8_t>> layers;
  for (int k = 0; k < Point14Decoder::Layers; ++k)
  {
    layers.push_back(point.Finish(k));
  }
  for (const auto& item : items)
  {
    for (std::size_t k = 0; k < item->LayerCount(); ++k)
    {
      layers.push_back(item->Finish(k));
    }
  }
  std::uint8_t word[4];
  Store<std::uint32_t>(word, static_cast<std::uint32_t>(count));
  out.insert(out.end(), word, word + 4);
  for (const auto& layer : layers)
  {
    Store<std::uint32_t>(word, static_cast<std::uint32_t>(layer.size()));
    out.insert(out.end(), word, word + 4);
  }
  for (const auto& layer : layers)
  {
    out.insert(out.end(), layer.begin(), layer.end());
  }
  return out;
}

} // namespace laz
} // namespace pcbilateral

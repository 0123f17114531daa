// Writing a PCD file in one of its three encodings, and PCL's packed colours both ways.
#include "FileBytes.h"
#include "PCDFile.h"
#include "PCDValues.h"

#include "ReplacingFile.h"

#include <lzf.h>

#include <charconv>
#include <cstdio>
#include <limits>

namespace pcbilateral
{
namespace
{
/// The header's text for `count` points.
std::string FormatHeader(const PCDHeader& header, std::size_t count, PCDEncoding encoding)
{
  std::string names, sizes, types, counts;
  for (const PCDField& field : header.Fields)
  {
    names += " " + field.Name;
    sizes += " " + std::to_string(field.Size);
    types += std::string(" ") + field.Type;
    counts += " " + std::to_string(field.Count);
  }
  const bool organised = header.Width * header.Height == count;
  std::string viewpoint;
  for (const double value : header.Viewpoint)
  {
    char buffer[32];
    viewpoint += " " + std::string(buffer, std::to_chars(buffer, buffer + 32, value).ptr);
  }
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS" + names + "\nSIZE" +
         sizes + "\nTYPE" + types + "\nCOUNT" + counts + "\nWIDTH " +
         std::to_string(organised ? header.Width : count) + "\nHEIGHT " +
         std::to_string(organised ? header.Height : 1) + "\nVIEWPOINT" + viewpoint + "\nPOINTS " +
         std::to_string(count) + "\nDATA " + PCDEncodingName(encoding) + "\n";
}

/// Every field's values (x y z converted from the positions, padding as zeros), one column each.
std::string GatherColumns(const PCDCloud& cloud, std::vector<PCDColumn>& columns)
{
  const std::size_t count = cloud.NumberOfPoints;
  std::size_t next = 0;
  for (const PCDField& field : cloud.Header.Fields)
  {
    PCDColumn column{ field, {} };
    if (field.IsCoordinate())
    {
      column.Bytes.resize(count * field.Size);
      const int axis = field.Name[0] - 'x';
      for (std::size_t i = 0; i < count; ++i)
      {
        StorePCDValue(field, cloud.Positions[3 * i + axis], column.Bytes.data() + i * field.Size);
      }
    }
    else if (field.IsPadding())
    {
      column.Bytes.assign(count * field.Bytes(), 0);
    }
    else
    {
      if (next >= cloud.Columns.size() || cloud.Columns[next].Bytes.size() != count * field.Bytes())
      {
        return "field '" + field.Name + "' has no values for every point";
      }
      column.Bytes = cloud.Columns[next++].Bytes;
    }
    columns.push_back(std::move(column));
  }
  return std::string();
}

std::vector<std::uint8_t> Interleave(const std::vector<PCDColumn>& columns, std::size_t count)
{
  std::size_t stride = 0;
  for (const PCDColumn& column : columns)
  {
    stride += column.Field.Bytes();
  }
  std::vector<std::uint8_t> records(stride * count);
  std::size_t offset = 0;
  for (std::size_t c = 0; c < columns.size(); ++c)
  {
    const std::size_t bytes = columns[c].Field.Bytes();
    for (std::size_t i = 0; i < count; ++i)
    {
      if (i % PointsPerProgressPoint == 0 && ProgressPoint(c * count + i, columns.size() * count))
      {
        return records; // (the caller asks too, and writes nothing)
      }
      std::copy_n(columns[c].Bytes.data() + i * bytes, bytes, records.data() + i * stride + offset);
    }
    offset += bytes;
  }
  return records;
}

std::string FormatASCII(const std::vector<PCDColumn>& columns, std::size_t count)
{
  std::string text;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (i % PointsPerProgressPoint == 0 && ProgressPoint(i, count))
    {
      return std::string(); // (the caller asks too, and writes nothing)
    }
    bool first = true;
    for (const PCDColumn& column : columns)
    {
      const PCDField& field = column.Field;
      for (unsigned c = 0; c < field.Count; ++c)
      {
        text += first ? "" : " ";
        first = false;
        AppendPCDText(field, column.Bytes.data() + (i * field.Count + c) * field.Size, text);
      }
    }
    text += '\n';
  }
  return text;
}

/// The two sizes and the LZF data of `size` bytes of fields; an error when too large.
std::string CompressFields(const std::uint8_t* fields,
  std::size_t size,
  std::vector<std::uint8_t>& block)
{
  if (size > std::numeric_limits<std::uint32_t>::max() / 2)
  {
    return "too large for binary_compressed (over 2 GB of fields): write binary";
  }
  // LZF never grows data by more than about 1/32: the room given covers it.
  block.resize(8 + size + size / 16 + 64);
  const auto uncompressed = static_cast<std::uint32_t>(size);
  std::uint32_t compressed = 0;
  if (uncompressed > 0)
  {
    compressed =
      lzf_compress(fields, uncompressed, block.data() + 8, static_cast<unsigned>(block.size() - 8));
    if (compressed == 0)
    {
      return "LZF compression failed";
    }
  }
  std::memcpy(block.data(), &compressed, 4);
  std::memcpy(block.data() + 4, &uncompressed, 4);
  block.resize(8 + compressed);
  return std::string();
}

/// The fields one after another, compressed.
std::string Compress(const std::vector<PCDColumn>& columns, std::vector<std::uint8_t>& block)
{
  std::vector<std::uint8_t> fields;
  for (const PCDColumn& column : columns)
  {
    fields.insert(fields.end(), column.Bytes.begin(), column.Bytes.end());
  }
  return CompressFields(fields.data(), fields.size(), block);
}

std::string EncodeData(const std::vector<PCDColumn>& columns,
  std::size_t count,
  PCDEncoding encoding,
  std::vector<std::uint8_t>& data)
{
  switch (encoding)
  {
    case PCDEncoding::ASCII:
    {
      const std::string text = FormatASCII(columns, count);
      data.assign(text.begin(), text.end());
      return std::string();
    }
    case PCDEncoding::Binary:
      data = Interleave(columns, count);
      return std::string();
    case PCDEncoding::BinaryCompressed:
      return Compress(columns, data);
  }
  return std::string();
}
} // namespace

bool IsPCDPackedColour(const PCDField& field)
{
  return (field.Name == "rgb" || field.Name == "rgba") && field.Size == 4 && field.Count == 1;
}

std::vector<std::uint8_t> UnpackPCDColours(const PCDColumn& column)
{
  const int channels = column.Field.Name == "rgba" ? 4 : 3;
  const std::size_t count = column.Bytes.size() / 4;
  std::vector<std::uint8_t> colours(channels * count);
  for (std::size_t i = 0; i < count; ++i)
  {
    const auto packed = LoadPCDValue<std::uint32_t>(column.Bytes.data() + 4 * i);
    std::uint8_t* colour = colours.data() + channels * i;
    colour[0] = static_cast<std::uint8_t>(packed >> 16);
    colour[1] = static_cast<std::uint8_t>(packed >> 8);
    colour[2] = static_cast<std::uint8_t>(packed);
    if (channels == 4)
    {
      colour[3] = static_cast<std::uint8_t>(packed >> 24);
    }
  }
  return colours;
}

PCDColumn PackPCDColours(const PCDField& field,
  const std::uint8_t* colours,
  int channels,
  std::size_t numberOfPoints)
{
  PCDColumn column{ field, std::vector<std::uint8_t>(4 * numberOfPoints) };
  for (std::size_t i = 0; i < numberOfPoints; ++i)
  {
    const std::uint8_t* colour = colours + channels * i;
    const std::uint32_t alpha = channels == 4 ? colour[3] : 255u;
    const std::uint32_t packed =
      alpha << 24 | std::uint32_t{ colour[0] } << 16 | std::uint32_t{ colour[1] } << 8 | colour[2];
    std::memcpy(column.Bytes.data() + 4 * i, &packed, 4);
  }
  return column;
}

std::string WritePCD(const std::string& path, const PCDCloud& cloud, PCDEncoding encoding)
{
  std::vector<PCDColumn> columns;
  std::vector<std::uint8_t> data;
  std::string problem = GatherColumns(cloud, columns);
  SetProgressStage(0.0, 0.6);
  if (problem.empty())
  {
    problem = EncodeData(columns, cloud.NumberOfPoints, encoding, data);
  }
  if (ProgressStopAsked())
  {
    return AbortedMessage;
  }
  SetProgressStage(0.6, 1.0);
  if (!problem.empty())
  {
    return path + ": " + problem;
  }
  columns.clear();
  const std::string header = FormatHeader(cloud.Header, cloud.NumberOfPoints, encoding);
  ReplacingFile file(path);
  if (!file.Get())
  {
    return file.OpenError();
  }
  bool written = std::fwrite(header.data(), 1, header.size(), file.Get()) == header.size();
  written = written && WriteInBlocks(file.Get(), data.data(), data.size());
  const std::string committed = file.Commit(written);
  return ProgressStopAsked() ? AbortedMessage : committed; // (no file then)
}

std::string WritePCDCompressedFields(const std::string& path,
  const PCDHeader& header,
  std::size_t count,
  const std::uint8_t* fields)
{
  std::vector<std::uint8_t> data;
  const std::string problem = CompressFields(fields, count * header.PointBytes(), data);
  if (!problem.empty())
  {
    return path + ": " + problem;
  }
  const std::string text = FormatHeader(header, count, PCDEncoding::BinaryCompressed);
  ReplacingFile file(path);
  if (!file.Get())
  {
    return file.OpenError();
  }
  bool written = std::fwrite(text.data(), 1, text.size(), file.Get()) == text.size();
  written = written && std::fwrite(data.data(), 1, data.size(), file.Get()) == data.size();
  return file.Commit(written);
}

struct PCDBinaryStreamWriter::Internals
{
  std::string Path;
  PCDHeader Header;
  std::size_t Expected = 0;
  std::size_t Appended = 0;
  std::unique_ptr<ReplacingFile> Output;
  PCDEncoding Encoding = PCDEncoding::Binary;
  bool Ok = false;
};

PCDBinaryStreamWriter::PCDBinaryStreamWriter()
  : Impl(std::make_unique<Internals>())
{
}

PCDBinaryStreamWriter::~PCDBinaryStreamWriter() = default;

std::string PCDBinaryStreamWriter::Open(const std::string& path,
  const PCDHeader& header,
  std::size_t count,
  PCDEncoding encoding)
{
  Internals& w = *this->Impl;
  if (encoding == PCDEncoding::BinaryCompressed)
  {
    return path + ": binary_compressed is one block, not written a range at a time";
  }
  w.Encoding = encoding;
  w.Path = path;
  w.Header = header;
  w.Expected = count;
  w.Output = std::make_unique<ReplacingFile>(path);
  if (!w.Output->Get())
  {
    return w.Output->OpenError();
  }
  const std::string text = FormatHeader(header, count, encoding);
  w.Ok = std::fwrite(text.data(), 1, text.size(), w.Output->Get()) == text.size();
  return std::string();
}

std::string PCDBinaryStreamWriter::Append(const PCDCloud& range)
{
  Internals& w = *this->Impl;
  if (!w.Output || !w.Output->Get() || w.Appended + range.NumberOfPoints > w.Expected)
  {
    w.Ok = false;
    return w.Path + ": more points written than announced, or the file was not opened";
  }
  if (range.Header.Fields.size() != w.Header.Fields.size())
  {
    w.Ok = false;
    return w.Path + ": a range with other fields than the header's";
  }
  std::vector<PCDColumn> columns;
  const std::string problem = GatherColumns(range, columns);
  if (!problem.empty())
  {
    w.Ok = false;
    return w.Path + ": " + problem;
  }
  std::vector<std::uint8_t> records;
  EncodeData(columns, range.NumberOfPoints, w.Encoding, records);
  w.Ok = w.Ok && std::fwrite(records.data(), 1, records.size(), w.Output->Get()) == records.size();
  w.Appended += range.NumberOfPoints;
  return std::string();
}

std::string PCDBinaryStreamWriter::Close()
{
  Internals& w = *this->Impl;
  if (!w.Output || !w.Output->Get())
  {
    return w.Path + ": the file was not opened";
  }
  if (w.Appended != w.Expected)
  {
    w.Ok = false;
  }
  const std::string problem = w.Output->Commit(w.Ok);
  return problem.empty() && w.Appended != w.Expected
           ? w.Path + ": fewer points written than announced"
           : problem;
}

} // namespace pcbilateral

// Decoding a PCD file's data: every field into a column, then x y z as doubles and, unless
// asked to keep them, the points without coordinates (NaN) left out.
#include "FileBytes.h"
#include "LASReader.h"
#include "PCDFile.h"
#include "PCDValues.h"
#include "PointPieces.h"

#include <lzf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

namespace pcbilateral
{
namespace
{
/// LZF turns at most 3 bytes into 264 (a long back-reference): data that announces more than
/// this many times its compressed size lies.
constexpr std::uint64_t LZFMaximumRatio = 88;
} // namespace

std::string DecompressPCDFields(const std::uint8_t* data,
  std::size_t size,
  const PCDHeader& header,
  std::size_t count,
  std::vector<std::uint8_t>& fields)
{
  if (size < 8)
  {
    return "the compressed data has no sizes";
  }
  std::uint32_t compressed = 0, uncompressed = 0;
  std::memcpy(&compressed, data, 4);
  std::memcpy(&uncompressed, data + 4, 4);
  const std::size_t stride = header.PointBytes();
  if (stride != 0 && count > std::numeric_limits<std::uint32_t>::max() / stride)
  {
    return "the header announces more points than compressed data can hold";
  }
  if (uncompressed != count * stride)
  {
    return "the compressed data announces " + std::to_string(uncompressed) +
           " bytes, the header's points take " + std::to_string(count * stride);
  }
  if (compressed > size - 8 || uncompressed > LZFMaximumRatio * compressed + 8)
  {
    return "the compressed data's sizes (" + std::to_string(compressed) + " bytes to " +
           std::to_string(uncompressed) + ") do not match the file";
  }
  fields.assign(uncompressed, 0);
  if (uncompressed != 0 &&
      lzf_decompress(data + 8, compressed, fields.data(), uncompressed) != uncompressed)
  {
    return "the compressed data is damaged (it does not decompress to its announced size)";
  }
  return std::string();
}

namespace
{

/// The columns of every field (padding too), sized for `count` points.
std::vector<PCDColumn> EmptyColumns(const PCDHeader& header, std::size_t count)
{
  std::vector<PCDColumn> columns;
  for (const PCDField& field : header.Fields)
  {
    columns.push_back(PCDColumn{ field, std::vector<std::uint8_t>(count * field.Bytes()) });
  }
  return columns;
}

/// The binary block: the points' records one after another.
std::string DecodeBinary(const std::uint8_t* data,
  std::size_t size,
  const PCDHeader& header,
  std::size_t count,
  const PointRange& share,
  std::vector<PCDColumn>& columns)
{
  const std::size_t stride = header.PointBytes();
  if (stride != 0 && count > size / stride)
  {
    return "the binary data holds " + std::to_string(stride ? size / stride : 0) +
           " points, the header announces " + std::to_string(count);
  }
  columns = EmptyColumns(header, share.Count);
  const std::uint8_t* records = data + share.First * stride;
  std::size_t offset = 0;
  std::size_t done = 0;
  for (PCDColumn& column : columns)
  {
    const std::size_t bytes = column.Field.Bytes();
    for (std::size_t i = 0; i < share.Count; ++i)
    {
      if (i % PointsPerProgressPoint == 0 &&
          ProgressPoint(done + i, columns.size() * static_cast<std::uint64_t>(share.Count)))
      {
        return AbortedMessage;
      }
      std::memcpy(column.Bytes.data() + i * bytes, records + i * stride + offset, bytes);
    }
    offset += bytes;
    done += share.Count;
  }
  return std::string();
}

/// The compressed block: two 32-bit sizes, then the LZF data of the fields one after another.
std::string DecodeCompressed(const std::uint8_t* data,
  std::size_t size,
  const PCDHeader& header,
  std::size_t count,
  const PointRange& share,
  std::vector<PCDColumn>& columns)
{
  std::vector<std::uint8_t> fields;
  const std::string problem = DecompressPCDFields(data, size, header, count, fields);
  if (!problem.empty())
  {
    return problem;
  }
  // One LZF block: decompressed whole, then only the share's values kept.
  columns = EmptyColumns(header, share.Count);
  std::size_t offset = 0;
  for (PCDColumn& column : columns)
  {
    const std::size_t bytes = column.Field.Bytes();
    std::copy_n(
      fields.data() + offset + share.First * bytes, column.Bytes.size(), column.Bytes.data());
    offset += count * bytes;
  }
  return std::string();
}

/// The ascii block: one line per point, its fields' values in order.
std::string DecodeASCII(const char* data,
  std::size_t size,
  std::size_t firstLine,
  const PCDHeader& header,
  std::size_t count,
  const PointRange& share,
  std::vector<PCDColumn>& columns)
{
  std::size_t valuesPerPoint = 0;
  for (const PCDField& field : header.Fields)
  {
    valuesPerPoint += field.Count;
  }
  // Each value takes at least a character and a separator: a header announcing far more
  // points than that is refused before their columns are made.
  if (count > 0 && count > (size + 1) / valuesPerPoint)
  {
    return "the ascii data holds fewer than the " + std::to_string(count) +
           " points the header announces";
  }
  columns = EmptyColumns(header, share.Count);
  PCDTextCursor cursor{ data, data + size, firstLine };
  // Every line is found (the count is the whole file's), only the share's are parsed.
  for (std::size_t line = 0; line < count; ++line)
  {
    if (line % PointsPerProgressPoint == 0 && ProgressPoint(line, count))
    {
      return AbortedMessage;
    }
    if (!cursor.NextLine())
    {
      return "the ascii data holds " + std::to_string(line) + " points, the header announces " +
             std::to_string(count);
    }
    if (line < share.First || line >= share.First + share.Count)
    {
      cursor.At = cursor.LineEnd;
      continue;
    }
    const std::size_t i = line - share.First;
    for (PCDColumn& column : columns)
    {
      const PCDField& field = column.Field;
      for (unsigned c = 0; c < field.Count; ++c)
      {
        std::uint8_t* value = column.Bytes.data() + (i * field.Count + c) * field.Size;
        std::string problem = cursor.ParseValue(field, value);
        if (!problem.empty())
        {
          return problem;
        }
      }
    }
    if (!cursor.AtLineEnd())
    {
      return "line " + std::to_string(cursor.Line) + ": more values than the fields take";
    }
  }
  if (cursor.NextLine())
  {
    return "line " + std::to_string(cursor.Line) + ": more points than the header announces (" +
           std::to_string(count) + ")";
  }
  return std::string();
}

/// x y z as doubles, the other fields as columns, NaN points left out unless kept.
void Assemble(std::vector<PCDColumn>& columns, const PCDReadOptions& options, PCDCloud& cloud)
{
  const std::size_t count = cloud.NumberOfPoints;
  std::vector<double> positions(3 * count);
  for (const PCDColumn& column : columns)
  {
    if (column.Field.IsCoordinate())
    {
      const int axis = column.Field.Name[0] - 'x';
      for (std::size_t i = 0; i < count; ++i)
      {
        positions[3 * i + axis] =
          PCDValueAsDouble(column.Field, column.Bytes.data() + i * column.Field.Size);
      }
    }
  }
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < count; ++i)
  {
    const double* p = positions.data() + 3 * i;
    if (options.KeepNaNPoints ||
        (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
    {
      kept.push_back(i);
    }
  }
  cloud.NumberOfDroppedPoints = count - kept.size();
  cloud.NumberOfPoints = kept.size();
  cloud.Positions.resize(3 * kept.size());
  for (std::size_t k = 0; k < kept.size(); ++k)
  {
    std::copy_n(positions.data() + 3 * kept[k], 3, cloud.Positions.data() + 3 * k);
  }
  for (PCDColumn& column : columns)
  {
    if (column.Field.IsCoordinate() || column.Field.IsPadding())
    {
      continue;
    }
    if (kept.size() != count)
    {
      const std::size_t bytes = column.Field.Bytes();
      for (std::size_t k = 0; k < kept.size(); ++k)
      {
        std::memmove(column.Bytes.data() + k * bytes, column.Bytes.data() + kept[k] * bytes, bytes);
      }
      column.Bytes.resize(kept.size() * bytes);
    }
    cloud.Columns.push_back(std::move(column));
  }
}
} // namespace

std::string DecodePCD(const char* data,
  std::size_t size,
  const std::string& source,
  const PCDReadOptions& options,
  PCDCloud& cloud)
{
  cloud = PCDCloud();
  std::string problem = ParsePCDHeader(data, size, source, cloud.Header);
  if (!problem.empty())
  {
    return problem;
  }
  const PCDHeader& header = cloud.Header;
  if (header.NumberOfPoints > std::numeric_limits<std::size_t>::max() / 64)
  {
    return source + ": the header announces more points than the file can hold";
  }
  const auto count = static_cast<std::size_t>(header.NumberOfPoints);
  const PointRange share = PieceOfPoints(count, options.Piece, options.NumberOfPieces);
  const char* block = data + header.DataOffset;
  const std::size_t blockSize = size - header.DataOffset;
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(block);
  std::vector<PCDColumn> columns;
  switch (header.Encoding)
  {
    case PCDEncoding::ASCII:
      problem = DecodeASCII(block,
        blockSize,
        1 + static_cast<std::size_t>(std::count(data, block, '\n')),
        header,
        count,
        share,
        columns);
      break;
    case PCDEncoding::Binary:
      problem = DecodeBinary(bytes, blockSize, header, count, share, columns);
      break;
    case PCDEncoding::BinaryCompressed:
      problem = DecodeCompressed(bytes, blockSize, header, count, share, columns);
      break;
  }
  if (!problem.empty())
  {
    cloud = PCDCloud();
    return source + ": " + problem;
  }
  cloud.NumberOfPoints = static_cast<std::size_t>(share.Count);
  Assemble(columns, options, cloud);
  return std::string();
}

std::string ReadPCD(const std::string& path, const PCDReadOptions& options, PCDCloud& cloud)
{
  // A piece maps the file rather than holding a copy of it: it reads only its share's pages
  // of binary data. When the file cannot be mapped, the read below says why.
  LASFileBytes mapped;
  if (options.NumberOfPieces > 1 && mapped.Open(path).empty())
  {
    return DecodePCD(
      reinterpret_cast<const char*>(mapped.Data()), mapped.Size(), path, options, cloud);
  }
  std::string bytes;
  SetProgressStage(0.0, 0.3);
  const std::string problem = ReadFileInBlocks(path, bytes);
  if (!problem.empty())
  {
    return problem;
  }
  SetProgressStage(0.3, 1.0);
  return DecodePCD(bytes.data(), bytes.size(), path, options, cloud);
}

} // namespace pcbilateral

// The PCD header: keyword lines up to DATA, checked against each other.
#include "PCDFile.h"

#include <charconv>
#include <cstring>
#include <limits>
#include <set>
#include <string_view>

namespace pcbilateral
{
namespace
{
/// More fields or values per field than any real file has: a header beyond them is damaged.
constexpr std::size_t MaximumFields = 4096;
constexpr unsigned MaximumCount = 1u << 20;

std::vector<std::string_view> Words(std::string_view line)
{
  std::vector<std::string_view> words;
  std::size_t at = 0;
  while (at < line.size())
  {
    const std::size_t start = line.find_first_not_of(" \t", at);
    if (start == std::string_view::npos)
    {
      break;
    }
    const std::size_t end = std::min(line.find_first_of(" \t", start), line.size());
    words.push_back(line.substr(start, end - start));
    at = end;
  }
  return words;
}

template<typename Number>
bool ParseWord(std::string_view word, Number& value)
{
  const char* end = word.data() + word.size();
  const auto result = std::from_chars(word.data(), end, value);
  return result.ec == std::errc() && result.ptr == end;
}

/// The header's lines as they are met, then checked together (Check).
struct HeaderParser
{
  std::string Source;
  PCDHeader& Header;
  std::vector<std::string_view> Names, Sizes, Types, Counts;
  bool HasWidth = false, HasHeight = false, HasPoints = false, HasData = false;

  std::string Fail(const std::string& problem) const { return this->Source + ": " + problem; }

  std::string Line(const std::vector<std::string_view>& words);
  std::string Data(std::string_view encoding);
  std::string Fields();
  std::string Check();
};

std::string HeaderParser::Line(const std::vector<std::string_view>& words)
{
  const std::string_view key = words[0];
  const std::vector<std::string_view> values(words.begin() + 1, words.end());
  auto number = [&](std::uint64_t& value, bool& seen) -> std::string
  {
    seen = true;
    return values.size() == 1 && ParseWord(values[0], value)
             ? std::string()
             : this->Fail(std::string(key) + " is not a whole number");
  };
  if (key == "VERSION")
  {
    return std::string();
  }
  if (key == "FIELDS" || key == "COLUMNS")
  {
    this->Names = values;
    return std::string();
  }
  if (key == "SIZE" || key == "TYPE" || key == "COUNT")
  {
    (key == "SIZE" ? this->Sizes : key == "TYPE" ? this->Types : this->Counts) = values;
    return std::string();
  }
  if (key == "WIDTH")
  {
    return number(this->Header.Width, this->HasWidth);
  }
  if (key == "HEIGHT")
  {
    return number(this->Header.Height, this->HasHeight);
  }
  if (key == "POINTS")
  {
    return number(this->Header.NumberOfPoints, this->HasPoints);
  }
  if (key == "VIEWPOINT")
  {
    bool good = values.size() == 7;
    for (std::size_t k = 0; good && k < 7; ++k)
    {
      good = ParseWord(values[k], this->Header.Viewpoint[k]);
    }
    return good ? std::string() : this->Fail("VIEWPOINT is not 7 numbers");
  }
  if (key == "DATA")
  {
    return values.size() == 1 ? this->Data(values[0]) : this->Fail("DATA names no encoding");
  }
  return this->Fail(
    "not a PCD file (unknown header line '" + std::string(key.substr(0, 40)) + "')");
}

std::string HeaderParser::Data(std::string_view encoding)
{
  this->HasData = true;
  if (encoding == "ascii")
  {
    this->Header.Encoding = PCDEncoding::ASCII;
  }
  else if (encoding == "binary")
  {
    this->Header.Encoding = PCDEncoding::Binary;
  }
  else if (encoding == "binary_compressed")
  {
    this->Header.Encoding = PCDEncoding::BinaryCompressed;
  }
  else
  {
    return this->Fail("unknown DATA encoding '" + std::string(encoding.substr(0, 40)) + "'");
  }
  return std::string();
}

std::string HeaderParser::Fields()
{
  const std::size_t count = this->Names.size();
  if (count == 0 || count > MaximumFields)
  {
    return this->Fail(count == 0 ? "FIELDS names no field" : "too many fields");
  }
  if (this->Sizes.size() != count || this->Types.size() != count ||
      (!this->Counts.empty() && this->Counts.size() != count))
  {
    return this->Fail("FIELDS, SIZE, TYPE and COUNT do not have one value per field each");
  }
  std::set<std::string_view> seen;
  for (std::size_t f = 0; f < count; ++f)
  {
    PCDField field;
    field.Name = std::string(this->Names[f]);
    const std::string quoted = "field '" + field.Name.substr(0, 40) + "'";
    if (!ParseWord(this->Sizes[f], field.Size) ||
        (!this->Counts.empty() && !ParseWord(this->Counts[f], field.Count)) || field.Count == 0 ||
        field.Count > MaximumCount)
    {
      return this->Fail(quoted + " has a SIZE or COUNT that is not a whole number from 1");
    }
    field.Type = this->Types[f].size() == 1 ? this->Types[f][0] : '?';
    const bool validSize = field.Size == 1 || field.Size == 2 || field.Size == 4 || field.Size == 8;
    if ((field.Type != 'I' && field.Type != 'U' && field.Type != 'F') || !validSize ||
        (field.Type == 'F' && field.Size < 4))
    {
      return this->Fail(quoted + " has an unknown type '" +
                        std::string(this->Types[f].substr(0, 8)) + "' of " +
                        std::to_string(field.Size) + " bytes");
    }
    if (!field.IsPadding() && !seen.insert(this->Names[f]).second)
    {
      return this->Fail(quoted + " is named twice");
    }
    if (field.IsCoordinate() && field.Count != 1)
    {
      return this->Fail(quoted + " has COUNT " + std::to_string(field.Count) + ", not 1");
    }
    this->Header.Fields.push_back(field);
  }
  if (!seen.count("x") || !seen.count("y") || !seen.count("z"))
  {
    return this->Fail("no x y z fields: not a point cloud");
  }
  return std::string();
}

std::string HeaderParser::Check()
{
  if (!this->HasData)
  {
    return this->Fail("not a PCD file (no DATA line)");
  }
  if (!this->HasWidth)
  {
    return this->Fail("the header has no WIDTH");
  }
  std::string problem = this->Fields();
  if (!problem.empty())
  {
    return problem;
  }
  PCDHeader& header = this->Header;
  const std::uint64_t limit = std::numeric_limits<std::uint64_t>::max();
  if (header.Height != 0 && header.Width > limit / header.Height)
  {
    return this->Fail("WIDTH x HEIGHT is too large");
  }
  const std::uint64_t frame = header.Width * header.Height;
  if (!this->HasPoints)
  {
    header.NumberOfPoints = frame;
  }
  if (header.NumberOfPoints != frame)
  {
    return this->Fail("POINTS " + std::to_string(header.NumberOfPoints) +
                      " is not WIDTH x HEIGHT (" + std::to_string(header.Width) + " x " +
                      std::to_string(header.Height) + ")");
  }
  return std::string();
}
} // namespace

const char* PCDEncodingName(PCDEncoding encoding)
{
  switch (encoding)
  {
    case PCDEncoding::ASCII:
      return "ascii";
    case PCDEncoding::Binary:
      return "binary";
    case PCDEncoding::BinaryCompressed:
      return "binary_compressed";
  }
  return "binary";
}

std::size_t PCDHeader::PointBytes() const
{
  std::size_t bytes = 0;
  for (const PCDField& field : this->Fields)
  {
    bytes += field.Bytes();
  }
  return bytes;
}

std::string ParsePCDHeader(const char* data,
  std::size_t size,
  const std::string& source,
  PCDHeader& header)
{
  header = PCDHeader();
  HeaderParser parser{ source, header, {}, {}, {}, {} };
  std::size_t at = 0;
  while (!parser.HasData)
  {
    if (at >= size)
    {
      return parser.Fail(at == 0 ? "the file is empty" : "not a PCD file (no DATA line)");
    }
    const char* end = static_cast<const char*>(std::memchr(data + at, '\n', size - at));
    const std::size_t next = end ? static_cast<std::size_t>(end - data) + 1 : size;
    std::string_view line(data + at, (end ? next - 1 : next) - at);
    at = next;
    if (!line.empty() && line.back() == '\r')
    {
      line.remove_suffix(1);
    }
    const std::vector<std::string_view> words = Words(line);
    if (words.empty() || words[0][0] == '#')
    {
      continue;
    }
    const std::string problem = parser.Line(words);
    if (!problem.empty())
    {
      return problem;
    }
  }
  header.DataOffset = at;
  return parser.Check();
}

} // namespace pcbilateral

#include "PLYFileCheck.h"

#include "TextFields.h"

#include "FileBytes.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

namespace pcbilateral
{
namespace
{
struct PLYElement
{
  std::string Name;
  unsigned long long Count = 0;
  std::size_t FixedBytes = 0; // scalar properties, and the count of each list
  std::size_t Properties = 0; // values on an ASCII line at least
  std::vector<std::string> Names;
};

struct PLYHeader
{
  std::string Format;
  std::vector<PLYElement> Elements;
  std::size_t Bytes = 0; // up to and with the end_header line
};

std::size_t PLYTypeSize(const std::string& type)
{
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8")
  {
    return 1;
  }
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16")
  {
    return 2;
  }
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
      type == "float32")
  {
    return 4;
  }
  if (type == "double" || type == "float64")
  {
    return 8;
  }
  return 0;
}

/// "element NAME COUNT", the words after the keyword.
std::string ReadElement(std::istringstream& words, std::vector<PLYElement>& elements)
{
  PLYElement element;
  std::string count;
  words >> element.Name >> count;
  const auto parsed = std::from_chars(count.data(), count.data() + count.size(), element.Count);
  if (parsed.ec != std::errc() || parsed.ptr != count.data() + count.size())
  {
    return "the PLY header gives element '" + element.Name + "' the count '" + count +
           "', not a whole number";
  }
  elements.push_back(element);
  return std::string();
}

/// "property TYPE NAME" or "property list COUNT_TYPE ITEM_TYPE NAME", the words after the
/// keyword: a property of the last element.
std::string ReadProperty(std::istringstream& words, std::vector<PLYElement>& elements)
{
  if (elements.empty())
  {
    return "the PLY header has a property before any element";
  }
  std::string type, name;
  words >> type;
  if (type == "list")
  {
    std::string countType, itemType;
    words >> countType >> itemType >> name;
    type = countType;
    if (PLYTypeSize(itemType) == 0)
    {
      type = itemType;
    }
  }
  else
  {
    words >> name;
  }
  if (PLYTypeSize(type) == 0)
  {
    return "the PLY header has a property of unknown type '" + type + "'";
  }
  elements.back().FixedBytes += PLYTypeSize(type);
  elements.back().Properties += 1;
  elements.back().Names.push_back(name);
  return std::string();
}

/// The header's lines up to end_header, within the file's first 64 KB.
std::string ReadHeader(const std::string& head, PLYHeader& header)
{
  const std::string noEnd = "the PLY header has no end_header line in its first 64 KB";
  std::istringstream lines(head);
  std::string line;
  while (std::getline(lines, line))
  {
    header.Bytes += line.size() + 1;
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "end_header")
    {
      return lines.eof() ? noEnd : std::string();
    }
    std::string problem;
    if (keyword == "format")
    {
      words >> header.Format;
    }
    else if (keyword == "element")
    {
      problem = ReadElement(words, header.Elements);
    }
    else if (keyword == "property")
    {
      problem = ReadProperty(words, header.Elements);
    }
    if (!problem.empty())
    {
      return problem;
    }
  }
  return noEnd;
}

/// A known format, and vertices with x, y and z.
std::string CheckFormatAndVertices(const PLYHeader& header)
{
  const std::string& format = header.Format;
  if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
  {
    return "the PLY header gives an unknown format '" + format + "'";
  }
  const PLYElement* vertices = nullptr;
  for (const PLYElement& element : header.Elements)
  {
    vertices = element.Name == "vertex" ? &element : vertices;
  }
  if (!vertices)
  {
    return "the PLY file has no vertex element";
  }
  std::string missing;
  for (const char* axis : { "x", "y", "z" })
  {
    if (std::find(vertices->Names.begin(), vertices->Names.end(), axis) == vertices->Names.end())
    {
      missing += missing.empty() ? axis : std::string(", ") + axis;
    }
  }
  if (!missing.empty())
  {
    return "the PLY vertices have no " + missing + " property (x, y and z are needed)";
  }
  return std::string();
}

/// Binary data: lists hold at least their count, which gives the smallest size the announced
/// elements can take.
std::string CheckBinarySize(const PLYHeader& header, std::uintmax_t size)
{
  const std::uintmax_t dataBytes = size - std::min<std::uintmax_t>(size, header.Bytes);
  std::uintmax_t needed = 0;
  for (const PLYElement& element : header.Elements)
  {
    if (element.FixedBytes > 0 && element.Count > (dataBytes - needed) / element.FixedBytes)
    {
      return "truncated: the PLY header announces " + std::to_string(element.Count) + " " +
             element.Name + " records of at least " + std::to_string(element.FixedBytes) +
             " bytes, the file holds " + std::to_string(dataBytes) + " bytes after its header";
    }
    needed += element.Count * element.FixedBytes;
  }
  return std::string();
}

/// ASCII data: one line per record (blank lines skipped), each with at least as many values
/// as the element's properties.
std::string CheckASCIILines(const std::string& path, const PLYHeader& header)
{
  std::ifstream file(path, std::ios::binary);
  file.seekg(static_cast<std::streamoff>(header.Bytes));
  std::string line;
  for (const PLYElement& element : header.Elements)
  {
    for (unsigned long long k = 0; k < element.Count; ++k)
    {
      do
      {
        if (!std::getline(file, line))
        {
          return "truncated: the PLY header announces " + std::to_string(element.Count) + " " +
                 element.Name + " lines, the file holds " + std::to_string(k);
        }
      } while (line.find_first_not_of(" \t\r") == std::string::npos);
      const std::size_t values = CountFields(line.data(), line.data() + line.size());
      if (values < element.Properties)
      {
        return element.Name + " " + std::to_string(k + 1) + " has " + std::to_string(values) +
               " values, the PLY header announces " + std::to_string(element.Properties);
      }
    }
  }
  return std::string();
}

/// The problem of a PLY file, without its path.
std::string FindPLYProblem(const std::string& path, std::uintmax_t size)
{
  constexpr std::size_t MaximumHeader = 1 << 16;
  const std::string head = ReadFileBytes(path, 0, MaximumHeader);
  if (head.compare(0, 3, "ply") != 0 || head.size() < 4 || (head[3] != '\n' && head[3] != '\r'))
  {
    return "not a PLY file (it does not start with 'ply')";
  }
  PLYHeader header;
  std::string problem = ReadHeader(head, header);
  if (problem.empty())
  {
    problem = CheckFormatAndVertices(header);
  }
  if (problem.empty())
  {
    problem =
      header.Format == "ascii" ? CheckASCIILines(path, header) : CheckBinarySize(header, size);
  }
  return problem;
}
} // namespace

std::string CheckPLYFile(const std::string& path)
{
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error)
  {
    return path + ": " + error.message();
  }
  const std::string problem = FindPLYProblem(path, size);
  return problem.empty() ? problem : path + ": " + problem;
}

} // namespace pcbilateral

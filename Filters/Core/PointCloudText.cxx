#include "PointCloudText.h"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <sys/stat.h>

namespace pcbilateral
{

namespace
{
bool IsSpace(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/// Splits one line into fields separated by blanks.
void SplitFields(const char* begin,
  const char* end,
  std::vector<std::pair<const char*, const char*>>& fields)
{
  fields.clear();
  const char* c = begin;
  while (c < end)
  {
    while (c < end && IsSpace(*c))
    {
      ++c;
    }
    const char* start = c;
    while (c < end && !IsSpace(*c))
    {
      ++c;
    }
    if (c > start)
    {
      fields.emplace_back(start, c);
    }
  }
}

bool ParseNumber(const char* begin, const char* end, double& value)
{
  if (begin < end && *begin == '+')
  {
    ++begin; // from_chars does not take a leading '+', which other programs write
  }
  const auto parsed = std::from_chars(begin, end, value);
  return parsed.ec == std::errc() && parsed.ptr == end;
}

std::string Located(const std::string& source, std::size_t line, const std::string& what)
{
  std::ostringstream message;
  message << source << ":" << line << ": " << what;
  return message.str();
}
} // namespace

std::string ParsePointCloudText(const char* text,
  std::size_t length,
  bool hasNormals,
  const std::string& sourceName,
  PointCloudTable& table)
{
  table = PointCloudTable();
  const std::size_t leadingColumns = hasNormals ? 6 : 3;
  std::size_t columns = 0;
  std::vector<std::string> headerNames;
  std::vector<std::pair<const char*, const char*>> fields;
  const char* end = text + length;
  std::size_t lineNumber = 0;
  bool firstContentLine = true;
  for (const char* line = text; line < end;)
  {
    const char* lineEnd = static_cast<const char*>(std::memchr(line, '\n', end - line));
    if (lineEnd == nullptr)
    {
      lineEnd = end;
    }
    ++lineNumber;
    SplitFields(line, lineEnd, fields);
    line = lineEnd + 1;
    if (fields.empty() || *fields[0].first == '#')
    {
      continue;
    }

    double value = 0.0;
    if (firstContentLine && !ParseNumber(fields[0].first, fields[0].second, value))
    {
      // A header naming the columns.
      for (const auto& field : fields)
      {
        headerNames.emplace_back(field.first, field.second);
      }
      firstContentLine = false;
      continue;
    }
    firstContentLine = false;

    if (columns == 0)
    {
      columns = fields.size();
      if (columns < leadingColumns)
      {
        return Located(sourceName,
          lineNumber,
          "expected at least " + std::to_string(leadingColumns) + " numbers (x y z" +
            (hasNormals ? " nx ny nz" : "") + "), found " + std::to_string(columns));
      }
      if (!headerNames.empty() && headerNames.size() != columns)
      {
        return Located(sourceName,
          lineNumber,
          "the header names " + std::to_string(headerNames.size()) + " columns but this line has " +
            std::to_string(columns));
      }
      table.ExtraColumns.resize(columns - leadingColumns);
      for (std::size_t c = leadingColumns; c < columns; ++c)
      {
        table.ExtraColumnNames.push_back(
          headerNames.empty() ? "column" + std::to_string(c + 1) : headerNames[c]);
      }
    }
    else if (fields.size() != columns)
    {
      return Located(sourceName,
        lineNumber,
        "expected " + std::to_string(columns) + " columns like the first point, found " +
          std::to_string(fields.size()));
    }

    for (std::size_t c = 0; c < columns; ++c)
    {
      if (!ParseNumber(fields[c].first, fields[c].second, value))
      {
        return Located(sourceName,
          lineNumber,
          "'" + std::string(fields[c].first, fields[c].second) + "' is not a number");
      }
      if (c < 3)
      {
        table.Positions.push_back(value);
      }
      else if (c < leadingColumns)
      {
        table.Normals.push_back(value);
      }
      else
      {
        table.ExtraColumns[c - leadingColumns].push_back(value);
      }
    }
    ++table.NumberOfPoints;
  }
  return std::string();
}

std::string ReadPointCloudText(const std::string& path, bool hasNormals, PointCloudTable& table)
{
  struct stat status;
  if (stat(path.c_str(), &status) != 0)
  {
    return path + ": " + std::strerror(errno);
  }
  if (S_ISDIR(status.st_mode))
  {
    return path + ": is a directory, not a point file";
  }
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    return path + ": cannot be opened for reading";
  }
  std::string text;
  text.resize(static_cast<std::size_t>(status.st_size));
  if (!text.empty() && !file.read(&text[0], static_cast<std::streamsize>(text.size())))
  {
    return path + ": read error";
  }
  return ParsePointCloudText(text.data(), text.size(), hasNormals, path, table);
}

std::string WritePointCloudText(const std::string& path, const PointCloudTable& table)
{
  const std::string temporary = path + ".partial";
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (file == nullptr)
  {
    return path + ": cannot be written (" + std::strerror(errno) + ")";
  }
  const bool withNormals =
    table.Normals.size() == 3 * table.NumberOfPoints && !table.Normals.empty();
  std::string line;
  char number[64];
  auto append = [&](double value)
  {
    const auto written = std::to_chars(number, number + sizeof(number), value);
    if (!line.empty())
    {
      line.push_back('\t');
    }
    line.append(number, written.ptr);
  };
  bool ok = true;
  for (std::size_t i = 0; i < table.NumberOfPoints && ok; ++i)
  {
    line.clear();
    for (int axis = 0; axis < 3; ++axis)
    {
      append(table.Positions[3 * i + axis]);
    }
    if (withNormals)
    {
      for (int axis = 0; axis < 3; ++axis)
      {
        append(table.Normals[3 * i + axis]);
      }
    }
    for (const auto& column : table.ExtraColumns)
    {
      append(column[i]);
    }
    line.push_back('\n');
    ok = std::fwrite(line.data(), 1, line.size(), file) == line.size();
  }
  ok = (std::fclose(file) == 0) && ok;
  if (!ok || std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    const std::string reason = std::strerror(errno);
    std::remove(temporary.c_str());
    return path + ": write failed (" + reason + ")";
  }
  return std::string();
}

} // namespace pcbilateral

#include "PointCloudText.h"

#include "ReplacingFile.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <sstream>
#include <system_error>

namespace pcbilateral
{

namespace
{
bool IsSpace(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

const char* SkipSpaces(const char* c, const char* end)
{
  while (c < end && IsSpace(*c))
  {
    ++c;
  }
  return c;
}

const char* SkipField(const char* c, const char* end)
{
  while (c < end && !IsSpace(*c))
  {
    ++c;
  }
  return c;
}

const char* LineEnd(const char* line, const char* end)
{
  const char* found = static_cast<const char*>(std::memchr(line, '\n', end - line));
  return found ? found : end;
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

/// Lines that carry no point: empty, blank, or a comment.
bool IsSkipped(const char* line, const char* lineEnd)
{
  const char* first = SkipSpaces(line, lineEnd);
  return first == lineEnd || *first == '#';
}

std::size_t CountFields(const char* line, const char* lineEnd)
{
  std::size_t count = 0;
  for (const char* c = SkipSpaces(line, lineEnd); c < lineEnd; c = SkipSpaces(c, lineEnd))
  {
    c = SkipField(c, lineEnd);
    ++count;
  }
  return count;
}

/// The points of one piece of the text, which starts at a line start and ends after a line end.
struct ParsedPiece
{
  std::vector<double> Positions, Normals;
  std::vector<std::vector<double>> ExtraColumns;
  std::size_t NumberOfPoints = 0;
  std::size_t NumberOfLines = 0;
  /// The first problem: its line within the piece (from 1) and what it is.
  std::size_t ErrorLine = 0;
  std::string Error;
};

void ParsePiece(const char* begin,
  const char* end,
  std::size_t columns,
  std::size_t leadingColumns,
  ParsedPiece& piece)
{
  // Sized once: a piece's lines are at most its points.
  const std::size_t lines = static_cast<std::size_t>(std::count(begin, end, '\n')) + 1;
  piece.Positions.reserve(3 * lines);
  piece.Normals.reserve((leadingColumns - 3) * lines);
  piece.ExtraColumns.resize(columns - leadingColumns);
  for (auto& column : piece.ExtraColumns)
  {
    column.reserve(lines);
  }
  double values[3];
  for (const char* line = begin; line < end; ++piece.NumberOfLines)
  {
    const char* lineEnd = LineEnd(line, end);
    const char* c = SkipSpaces(line, lineEnd);
    const char* next = lineEnd + 1;
    if (c == lineEnd || *c == '#')
    {
      line = next;
      continue;
    }
    std::size_t column = 0;
    for (; c < lineEnd; c = SkipSpaces(c, lineEnd), ++column)
    {
      const char* fieldEnd = SkipField(c, lineEnd);
      double value;
      if (column < columns && !ParseNumber(c, fieldEnd, value))
      {
        piece.ErrorLine = piece.NumberOfLines + 1;
        piece.Error = "'" + std::string(c, fieldEnd) + "' is not a number";
        return;
      }
      if (column < 3)
      {
        values[column] = value;
      }
      else if (column < leadingColumns)
      {
        piece.Normals.push_back(value);
      }
      else if (column < columns)
      {
        piece.ExtraColumns[column - leadingColumns].push_back(value);
      }
      c = fieldEnd;
    }
    if (column != columns)
    {
      piece.ErrorLine = piece.NumberOfLines + 1;
      piece.Error = "expected " + std::to_string(columns) +
                    " columns like the first point, found " + std::to_string(column);
      return;
    }
    piece.Positions.insert(piece.Positions.end(), values, values + 3);
    ++piece.NumberOfPoints;
    line = next;
  }
}

template<typename T>
void Append(std::vector<T>& to, const std::vector<T>& from)
{
  to.insert(to.end(), from.begin(), from.end());
}
} // namespace

std::string ParsePointCloudText(const char* text,
  std::size_t length,
  bool hasNormals,
  const std::string& sourceName,
  PointCloudTable& table,
  std::size_t minimumPieceBytes)
{
  table = PointCloudTable();
  const std::size_t leadingColumns = hasNormals ? 6 : 3;
  const char* end = text + length;

  // The first line with content: a header naming the columns, or the first point, which sets
  // the number of columns.
  std::size_t lineNumber = 0;
  const char* line = text;
  std::vector<std::string> headerNames;
  std::size_t columns = 0;
  while (line < end && columns == 0)
  {
    const char* lineEnd = LineEnd(line, end);
    ++lineNumber;
    if (!IsSkipped(line, lineEnd))
    {
      const char* first = SkipSpaces(line, lineEnd);
      double value;
      if (headerNames.empty() && !ParseNumber(first, SkipField(first, lineEnd), value))
      {
        for (const char* c = first; c < lineEnd; c = SkipSpaces(c, lineEnd))
        {
          const char* fieldEnd = SkipField(c, lineEnd);
          headerNames.emplace_back(c, fieldEnd);
          c = fieldEnd;
        }
        line = lineEnd + 1;
        continue;
      }
      columns = CountFields(line, lineEnd);
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
      --lineNumber; // the point's line is parsed again below
      break;
    }
    line = lineEnd + 1;
  }
  if (columns == 0)
  {
    return std::string(); // no points
  }
  for (std::size_t c = leadingColumns; c < columns; ++c)
  {
    table.ExtraColumnNames.push_back(
      headerNames.empty() ? "column" + std::to_string(c + 1) : headerNames[c]);
  }

  // The points, in pieces of whole lines parsed in parallel, then joined in order.
  const std::size_t bytes = static_cast<std::size_t>(end - line);
  const int pieceCount = static_cast<int>(
    std::min<std::size_t>(64, bytes / std::max<std::size_t>(1, minimumPieceBytes) + 1));
  std::vector<const char*> bounds{ line };
  for (int k = 1; k < pieceCount; ++k)
  {
    const char* cut = std::max(bounds.back(), line + bytes * k / pieceCount);
    bounds.push_back(cut < end ? LineEnd(cut, end) + 1 : end);
  }
  bounds.push_back(end);
  std::vector<ParsedPiece> pieces(static_cast<std::size_t>(pieceCount));
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < pieceCount; ++k)
  {
    ParsePiece(
      std::min(bounds[k], end), std::min(bounds[k + 1], end), columns, leadingColumns, pieces[k]);
  }
  for (const ParsedPiece& piece : pieces)
  {
    if (!piece.Error.empty())
    {
      return Located(sourceName, lineNumber + piece.ErrorLine, piece.Error);
    }
    lineNumber += piece.NumberOfLines;
  }

  table.Positions = std::move(pieces[0].Positions);
  table.Normals = std::move(pieces[0].Normals);
  table.ExtraColumns = std::move(pieces[0].ExtraColumns);
  table.NumberOfPoints = pieces[0].NumberOfPoints;
  for (std::size_t k = 1; k < pieces.size(); ++k)
  {
    Append(table.Positions, pieces[k].Positions);
    Append(table.Normals, pieces[k].Normals);
    for (std::size_t c = 0; c < table.ExtraColumns.size(); ++c)
    {
      Append(table.ExtraColumns[c], pieces[k].ExtraColumns[c]);
    }
    table.NumberOfPoints += pieces[k].NumberOfPoints;
  }
  return std::string();
}

std::string ReadPointCloudText(const std::string& path, bool hasNormals, PointCloudTable& table)
{
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
  {
    return path + ": is a directory, not a point file";
  }
  const std::uintmax_t fileSize = std::filesystem::file_size(path, error);
  if (error)
  {
    return path + ": " + error.message();
  }
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr)
  {
    return path + ": cannot be opened for reading (" + std::strerror(errno) + ")";
  }
  // Not zero-filled first: the read fills it.
  const auto size = static_cast<std::size_t>(fileSize);
  const std::unique_ptr<char[]> text(new char[size + 1]);
  const std::size_t read = std::fread(text.get(), 1, size, file);
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed || read != size)
  {
    return path + ": read error";
  }
  return ParsePointCloudText(text.get(), size, hasNormals, path, table);
}

std::string WritePointCloudText(const std::string& path, const PointCloudTable& table)
{
  ReplacingFile output(path);
  std::FILE* file = output.Get();
  if (file == nullptr)
  {
    return output.OpenError();
  }
  const bool withNormals =
    table.Normals.size() == 3 * table.NumberOfPoints && !table.Normals.empty();
  const std::size_t columns = 3 + (withNormals ? 3 : 0) + table.ExtraColumns.size();

  // A header line names the extra columns, so that reading the file back keeps their names. A
  // file of x y z [nx ny nz] alone needs none, and stays in the authors' format, which their
  // program reads.
  std::string header = table.ExtraColumns.empty() ? ""
                       : withNormals              ? "x\ty\tz\tnx\tny\tnz"
                                                  : "x\ty\tz";
  for (std::size_t c = 0; c < table.ExtraColumns.size(); ++c)
  {
    std::string name = c < table.ExtraColumnNames.size() ? table.ExtraColumnNames[c] : "";
    // A name is one field of the line: no spaces, and never empty.
    std::replace_if(
      name.begin(), name.end(), [](char ch) { return IsSpace(ch) || ch == '\n'; }, '_');
    header +=
      "\t" + (name.empty() ? "column" + std::to_string(4 + (withNormals ? 3 : 0) + c) : name);
  }
  header += header.empty() ? "" : "\n";
  bool ok = std::fwrite(header.data(), 1, header.size(), file) == header.size();

  // Blocks of lines formatted in parallel, written in order.
  constexpr std::size_t PointsPerBlock = 1 << 13;
  const std::size_t blockCount = (table.NumberOfPoints + PointsPerBlock - 1) / PointsPerBlock;
  constexpr std::size_t BlocksAtOnce = 16; // about 10 MB of text at a time
  std::vector<std::string> blocks(std::min(blockCount, BlocksAtOnce));
  for (std::size_t first = 0; first < blockCount && ok; first += BlocksAtOnce)
  {
    const auto count = static_cast<std::int64_t>(std::min(BlocksAtOnce, blockCount - first));
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t b = 0; b < count; ++b)
    {
      std::string& block = blocks[b];
      block.clear();
      const std::size_t begin = (first + b) * PointsPerBlock;
      const std::size_t blockEnd = std::min(table.NumberOfPoints, begin + PointsPerBlock);
      // The longest shortest round-trip form of a double takes 24 characters.
      block.resize((blockEnd - begin) * columns * 25);
      char* out = &block[0];
      for (std::size_t i = begin; i < blockEnd; ++i)
      {
        auto put = [&](double value)
        {
          out = std::to_chars(out, out + 25, value).ptr;
          *out++ = '\t';
        };
        for (int axis = 0; axis < 3; ++axis)
        {
          put(table.Positions[3 * i + axis]);
        }
        if (withNormals)
        {
          for (int axis = 0; axis < 3; ++axis)
          {
            put(table.Normals[3 * i + axis]);
          }
        }
        for (const auto& column : table.ExtraColumns)
        {
          put(column[i]);
        }
        out[-1] = '\n';
      }
      block.resize(static_cast<std::size_t>(out - block.data()));
    }
    for (std::int64_t b = 0; b < count && ok; ++b)
    {
      ok = std::fwrite(blocks[b].data(), 1, blocks[b].size(), file) == blocks[b].size();
    }
  }
  return output.Commit(ok);
}

} // namespace pcbilateral

#include "PointCloudText.h"
#include "PointPieces.h"

#include "TextFields.h"

#include "ProgressCheck.h"
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

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pcbilateral
{

namespace
{
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

/// The delimiter of a line: the blank after its first field, a tab or else a space.
char DelimiterOf(const char* line, const char* lineEnd)
{
  const char* gap = SkipField(SkipSpaces(line, lineEnd), lineEnd);
  return gap < lineEnd && *gap == '\t' ? '\t' : ' ';
}

/// What the lines before the points say.
struct TextStart
{
  /// The header's fields, if there is a header line.
  std::vector<std::string> HeaderNames;
  /// The columns of the first point (0: no point), where its line starts and its number less one.
  std::size_t Columns = 0;
  const char* FirstPoint = nullptr;
  std::size_t LineNumber = 0;
  char Delimiter = '\t';
};

/**
 * Reads up to the first point: the header line, if the first line with content does not start
 * with a number, and the number of columns of the first point, which every point must have.
 * Returns an empty string, or a message naming the line.
 */
std::string ReadTextStart(const char* text,
  const char* end,
  std::size_t leadingColumns,
  const std::string& sourceName,
  TextStart& start)
{
  for (const char* line = text; line < end; line = LineEnd(line, end) + 1)
  {
    const char* lineEnd = LineEnd(line, end);
    ++start.LineNumber;
    if (IsSkipped(line, lineEnd))
    {
      continue;
    }
    start.Delimiter = DelimiterOf(line, lineEnd);
    const char* first = SkipSpaces(line, lineEnd);
    double value;
    if (start.HeaderNames.empty() && !ParseNumber(first, SkipField(first, lineEnd), value))
    {
      for (const char* c = first; c < lineEnd; c = SkipSpaces(c, lineEnd))
      {
        const char* fieldEnd = SkipField(c, lineEnd);
        start.HeaderNames.emplace_back(c, fieldEnd);
        c = fieldEnd;
      }
      continue;
    }
    start.Columns = CountFields(line, lineEnd);
    if (start.Columns < leadingColumns)
    {
      return Located(sourceName,
        start.LineNumber,
        "expected at least " + std::to_string(leadingColumns) + " numbers (x y z" +
          (leadingColumns == 6 ? " nx ny nz" : "") + "), found " + std::to_string(start.Columns));
    }
    if (!start.HeaderNames.empty() && start.HeaderNames.size() != start.Columns)
    {
      return Located(sourceName,
        start.LineNumber,
        "the header names " + std::to_string(start.HeaderNames.size()) +
          " columns but this line has " + std::to_string(start.Columns));
    }
    start.FirstPoint = line;
    --start.LineNumber; // the point's line is parsed again with the others
    break;
  }
  return std::string();
}

/// Where the pieces of [begin, end) start: at least minimumPieceBytes each (at most 64 pieces),
/// cut after a line end; the last bound is end.
std::vector<const char*> PieceBounds(const char* begin,
  const char* end,
  std::size_t minimumPieceBytes)
{
  const std::size_t bytes = static_cast<std::size_t>(end - begin);
  const int pieceCount = static_cast<int>(
    std::min<std::size_t>(64, bytes / std::max<std::size_t>(1, minimumPieceBytes) + 1));
  std::vector<const char*> bounds{ begin };
  for (int k = 1; k < pieceCount; ++k)
  {
    const char* cut = std::max(bounds.back(), begin + bytes * k / pieceCount);
    bounds.push_back(cut < end ? LineEnd(cut, end) + 1 : end);
  }
  bounds.push_back(end);
  return bounds;
}

/// The pieces' points appended to the table's, in order.
void JoinPieces(std::vector<ParsedPiece>& pieces, PointCloudTable& table)
{
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
}

/// The points from the text start on, in pieces of whole lines parsed in parallel, then joined
/// in order. Returns an empty string, or a message naming the first bad line.
std::string ParsePoints(const TextStart& start,
  const char* end,
  std::size_t leadingColumns,
  const std::string& sourceName,
  std::size_t minimumPieceBytes,
  PointCloudTable& table)
{
  const std::vector<const char*> bounds = PieceBounds(start.FirstPoint, end, minimumPieceBytes);
  const int pieceCount = static_cast<int>(bounds.size()) - 1;
  std::vector<ParsedPiece> pieces(static_cast<std::size_t>(pieceCount));
  ParallelProgress progress(static_cast<std::uint64_t>(end - start.FirstPoint));
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < pieceCount; ++k)
  {
    if (progress.StopAsked())
    {
      continue;
    }
    const char* first = std::min(bounds[k], end);
    const char* last = std::min(bounds[k + 1], end);
    ParsePiece(first, last, start.Columns, leadingColumns, pieces[k]);
    progress.Done(static_cast<std::uint64_t>(last - first));
  }
  if (progress.StopAsked())
  {
    return AbortedMessage;
  }
  std::size_t lineNumber = start.LineNumber;
  for (const ParsedPiece& piece : pieces)
  {
    if (!piece.Error.empty())
    {
      return Located(sourceName, lineNumber + piece.ErrorLine, piece.Error);
    }
    lineNumber += piece.NumberOfLines;
  }
  JoinPieces(pieces, table);
  return std::string();
}
/**
 * Narrows `start` (from the first point on) to the lines of piece `piece` of `pieces` of the
 * points: moves FirstPoint and LineNumber to its first line, returns where its lines end.
 */
const char* ShareOfLines(TextStart& start, const char* end, int piece, int pieces)
{
  // Two passes over the lines, keeping nothing per line: count the points, then find the
  // share's first line and the line after its last.
  std::uint64_t points = 0;
  for (const char* line = start.FirstPoint; line < end; line = LineEnd(line, end) + 1)
  {
    points += IsSkipped(line, LineEnd(line, end)) ? 0 : 1;
  }
  const PointRange share = PieceOfPoints(points, piece, pieces);
  std::uint64_t point = 0;
  std::size_t number = start.LineNumber;
  const char* line = start.FirstPoint;
  for (; line < end; line = LineEnd(line, end) + 1)
  {
    ++number;
    if (IsSkipped(line, LineEnd(line, end)))
    {
      continue;
    }
    if (point == share.First)
    {
      start.FirstPoint = line;
      start.LineNumber = number - 1;
    }
    if (point == share.First + share.Count)
    {
      return line;
    }
    ++point;
  }
  if (share.Count == 0)
  {
    start.FirstPoint = end;
  }
  return end;
}

std::string ParseTextPiece(const char* text,
  std::size_t length,
  bool hasNormals,
  const std::string& sourceName,
  int piece,
  int pieces,
  PointCloudTable& table,
  std::size_t minimumPieceBytes);
} // namespace

std::string ParsePointCloudText(const char* text,
  std::size_t length,
  bool hasNormals,
  const std::string& sourceName,
  PointCloudTable& table,
  std::size_t minimumPieceBytes)
{
  return ParseTextPiece(text, length, hasNormals, sourceName, 0, 1, table, minimumPieceBytes);
}

std::string ParsePointCloudTextPiece(const char* text,
  std::size_t length,
  bool hasNormals,
  const std::string& sourceName,
  int piece,
  int pieces,
  PointCloudTable& table)
{
  return ParseTextPiece(
    text, length, hasNormals, sourceName, piece, pieces, table, std::size_t{ 1 } << 20);
}

namespace
{
std::string ParseTextPiece(const char* text,
  std::size_t length,
  bool hasNormals,
  const std::string& sourceName,
  int piece,
  int pieces,
  PointCloudTable& table,
  std::size_t minimumPieceBytes)
{
  table = PointCloudTable();
  const std::size_t leadingColumns = hasNormals ? 6 : 3;
  const char* end = text + length;
  TextStart start;
  const std::string error = ReadTextStart(text, end, leadingColumns, sourceName, start);
  if (!error.empty())
  {
    return error;
  }
  PointCloudTextLayout& layout = table.Layout;
  const std::vector<std::string>& header = start.HeaderNames;
  layout.Header = header.empty() ? PointCloudTextLayout::HeaderLine::Never
                                 : PointCloudTextLayout::HeaderLine::Always;
  layout.LeadingColumnNames.assign(
    header.begin(), header.begin() + std::min(leadingColumns, header.size()));
  layout.Delimiter = start.Delimiter;
  if (start.Columns == 0)
  {
    return std::string(); // no points
  }
  for (std::size_t c = leadingColumns; c < start.Columns; ++c)
  {
    table.ExtraColumnNames.push_back(header.empty() ? "column" + std::to_string(c + 1) : header[c]);
  }
  if (pieces > 1)
  {
    end = ShareOfLines(start, end, piece, pieces);
  }
  return ParsePoints(start, end, leadingColumns, sourceName, minimumPieceBytes, table);
}
} // namespace

std::string ReadPointCloudText(const std::string& path,
  bool hasNormals,
  PointCloudTable& table,
  int piece,
  int pieces)
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
  // Not zero-filled first: the read fills it. In blocks, for progress and abort.
  const auto size = static_cast<std::size_t>(fileSize);
  const std::unique_ptr<char[]> text(new char[size + 1]);
  constexpr std::size_t BlockBytes = std::size_t(8) << 20;
  SetProgressStage(0.0, 0.3);
  std::size_t read = 0;
  while (read < size && !ProgressPoint(read, size))
  {
    const std::size_t count =
      std::fread(text.get() + read, 1, std::min(BlockBytes, size - read), file);
    read += count;
    if (count == 0)
    {
      break;
    }
  }
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (ProgressStopAsked())
  {
    return AbortedMessage;
  }
  if (failed || read != size)
  {
    return path + ": read error";
  }
  SetProgressStage(0.3, 1.0);
  return ParsePointCloudTextPiece(text.get(), size, hasNormals, path, piece, pieces, table);
}

namespace
{
/// A column's name as one field of the header line: no blanks, and never empty.
std::string HeaderField(std::string name, std::size_t column)
{
  std::replace_if(
    name.begin(), name.end(), [](char ch) { return IsSpace(ch) || ch == '\n'; }, '_');
  return name.empty() ? "column" + std::to_string(column + 1) : name;
}

/// The header line the table's layout asks for, with its line end, or "" for none.
std::string MakeHeaderLine(const PointCloudTable& table, bool withNormals)
{
  using HeaderLine = PointCloudTextLayout::HeaderLine;
  const PointCloudTextLayout& layout = table.Layout;
  if (layout.Header == HeaderLine::Never ||
      (layout.Header == HeaderLine::WhenExtraColumns && table.ExtraColumns.empty()))
  {
    return std::string();
  }
  static const char* const leadingNames[] = { "x", "y", "z", "nx", "ny", "nz" };
  const std::size_t leading = withNormals ? 6 : 3;
  std::string header;
  for (std::size_t c = 0; c < leading + table.ExtraColumns.size(); ++c)
  {
    const std::vector<std::string>& names =
      c < leading ? layout.LeadingColumnNames : table.ExtraColumnNames;
    const std::size_t k = c < leading ? c : c - leading;
    std::string name = k < names.size() ? names[k] : "";
    if (name.empty() && c < leading)
    {
      name = leadingNames[c];
    }
    header += (c == 0 ? "" : std::string(1, layout.Delimiter)) + HeaderField(name, c);
  }
  return header + "\n";
}

/// The lines of points [begin, end), values separated by the layout's delimiter.
void FormatLines(const PointCloudTable& table,
  bool withNormals,
  std::size_t begin,
  std::size_t end,
  std::string& block)
{
  const std::size_t columns = 3 + (withNormals ? 3 : 0) + table.ExtraColumns.size();
  const char delimiter = table.Layout.Delimiter;
  // The longest shortest round-trip form of a double takes 24 characters.
  block.resize((end - begin) * columns * 25);
  char* out = &block[0];
  auto put = [&](double value)
  {
    out = std::to_chars(out, out + 25, value).ptr;
    *out++ = delimiter;
  };
  for (std::size_t i = begin; i < end; ++i)
  {
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
/// The lines of every point of the table, in blocks formatted in parallel, written in order;
/// false when a write failed.
bool WriteLines(std::FILE* file, const PointCloudTable& table, bool withNormals)
{
  constexpr std::size_t PointsPerBlock = 1 << 13;
  const std::size_t blockCount = (table.NumberOfPoints + PointsPerBlock - 1) / PointsPerBlock;
  constexpr std::size_t BlocksAtOnce = 16; // about 10 MB of text at a time
  std::vector<std::string> blocks(std::min(blockCount, BlocksAtOnce));
  bool ok = true;
  for (std::size_t first = 0; first < blockCount && ok; first += BlocksAtOnce)
  {
    if (ProgressPoint(first, blockCount))
    {
      return false;
    }
    const auto count = static_cast<std::int64_t>(std::min(BlocksAtOnce, blockCount - first));
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t b = 0; b < count; ++b)
    {
      const std::size_t begin = (first + b) * PointsPerBlock;
      FormatLines(table,
        withNormals,
        begin,
        std::min(table.NumberOfPoints, begin + PointsPerBlock),
        blocks[b]);
    }
    for (std::int64_t b = 0; b < count && ok; ++b)
    {
      ok = std::fwrite(blocks[b].data(), 1, blocks[b].size(), file) == blocks[b].size();
    }
  }
  return ok;
}
} // namespace

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
  const std::string header = MakeHeaderLine(table, withNormals);
  bool ok = std::fwrite(header.data(), 1, header.size(), file) == header.size();
  ok = ok && WriteLines(file, table, withNormals);
  const std::string problem = output.Commit(ok);
  return ProgressStopAsked() ? AbortedMessage : problem; // (the file is not written then)
}

struct PointCloudTextStream::Internals
{
  std::string Path;
  const char* Text = nullptr;
  std::size_t Size = 0;
  std::size_t LeadingColumns = 3;
  TextStart Start;
  PointCloudTable Header;
  std::uint64_t Points = 0;
  /// Where the next range starts: its first line, that line's number less one, its point.
  const char* Next = nullptr;
  std::size_t NextLineNumber = 0;
  std::uint64_t NextPoint = 0;

  void Release() const { this->Release(this->Text, this->Text + this->Size); }
  /// Gives back the whole pages of the mapping in [from, to).
  void Release(const char* from, const char* to) const
  {
    if (this->Text == nullptr)
    {
      return;
    }
    const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
    const std::uintptr_t first = reinterpret_cast<std::uintptr_t>(from) / page * page;
    const std::uintptr_t last = reinterpret_cast<std::uintptr_t>(to) / page * page;
    if (last > first)
    {
      ::madvise(reinterpret_cast<void*>(first), last - first, MADV_DONTNEED);
    }
  }
};

PointCloudTextStream::PointCloudTextStream()
  : Impl(std::make_unique<Internals>())
{
}

PointCloudTextStream::~PointCloudTextStream()
{
  if (this->Impl->Text != nullptr)
  {
    ::munmap(const_cast<char*>(this->Impl->Text), this->Impl->Size);
  }
}

std::string PointCloudTextStream::Open(const std::string& path, bool hasNormals)
{
  Internals& s = *this->Impl;
  s.Path = path;
  s.LeadingColumns = hasNormals ? 6 : 3;
  const int descriptor = ::open(path.c_str(), O_RDONLY);
  struct stat status;
  if (descriptor < 0 || ::fstat(descriptor, &status) != 0 || S_ISDIR(status.st_mode))
  {
    const bool directory = descriptor >= 0 && S_ISDIR(status.st_mode);
    // (ReadPointCloudText's messages: a missing file is said as the system says it.)
    const int failure = errno;
    const std::string problem =
      path + ": " +
      (directory ? std::string("is a directory, not a point file")
        : failure == ENOENT
          ? std::string(std::strerror(failure))
          : "cannot be opened for reading (" + std::string(std::strerror(failure)) + ")");
    if (descriptor >= 0)
    {
      ::close(descriptor);
    }
    return problem;
  }
  s.Size = static_cast<std::size_t>(status.st_size);
  void* mapped =
    s.Size > 0 ? ::mmap(nullptr, s.Size, PROT_READ, MAP_PRIVATE, descriptor, 0) : MAP_FAILED;
  ::close(descriptor);
  if (mapped == MAP_FAILED)
  {
    return path + (s.Size == 0 ? ": contains no points" : ": cannot be mapped for reading");
  }
  s.Text = static_cast<const char*>(mapped);
  const char* end = s.Text + s.Size;
  const std::string error = ReadTextStart(s.Text, end, s.LeadingColumns, path, s.Start);
  if (!error.empty())
  {
    return error;
  }
  PointCloudTextLayout& layout = s.Header.Layout;
  const std::vector<std::string>& names = s.Start.HeaderNames;
  layout.Header = names.empty() ? PointCloudTextLayout::HeaderLine::Never
                                : PointCloudTextLayout::HeaderLine::Always;
  layout.LeadingColumnNames.assign(
    names.begin(), names.begin() + std::min(s.LeadingColumns, names.size()));
  layout.Delimiter = s.Start.Delimiter;
  for (std::size_t c = s.LeadingColumns; c < s.Start.Columns; ++c)
  {
    s.Header.ExtraColumnNames.push_back(
      names.empty() ? "column" + std::to_string(c + 1) : names[c]);
  }
  s.Header.ExtraColumns.resize(s.Header.ExtraColumnNames.size());
  // Counted a block at a time, each block's pages given back after it: the mapped file's pages
  // count in the process's memory while they are held.
  const char* released = s.Text;
  for (const char* line = s.Start.FirstPoint; line != nullptr && line < end;
       line = LineEnd(line, end) + 1)
  {
    s.Points += IsSkipped(line, LineEnd(line, end)) ? 0 : 1;
    if (line - released > (std::ptrdiff_t{ 1 } << 26))
    {
      s.Release(released, line);
      released = line;
    }
  }
  s.Release();
  return std::string();
}

std::uint64_t PointCloudTextStream::GetNumberOfPoints() const
{
  return this->Impl->Points;
}

const PointCloudTable& PointCloudTextStream::GetHeader() const
{
  return this->Impl->Header;
}

std::string PointCloudTextStream::Read(std::uint64_t first,
  std::size_t count,
  PointCloudTable& table)
{
  Internals& s = *this->Impl;
  if (first == 0)
  {
    s.Next = s.Start.FirstPoint;
    s.NextLineNumber = s.Start.LineNumber;
    s.NextPoint = 0;
  }
  if (first != s.NextPoint || first + count > s.Points)
  {
    return s.Path + ": points read out of order";
  }
  // The range's lines end after its count-th point's line.
  const char* end = s.Text + s.Size;
  const char* line = s.Next;
  std::size_t lines = 0;
  for (std::size_t points = 0; points < count && line < end; line = LineEnd(line, end) + 1)
  {
    ++lines;
    points += IsSkipped(line, LineEnd(line, end)) ? 0 : 1;
  }
  TextStart start = s.Start;
  start.FirstPoint = s.Next;
  start.LineNumber = s.NextLineNumber;
  table = PointCloudTable();
  table.Layout = s.Header.Layout;
  table.ExtraColumnNames = s.Header.ExtraColumnNames;
  const std::string error = ParsePoints(
    start, std::min(line, end), s.LeadingColumns, s.Path, std::size_t{ 1 } << 20, table);
  s.Release();
  s.Next = line;
  s.NextLineNumber += lines;
  s.NextPoint += count;
  return error;
}

struct PointCloudTextStreamWriter::Internals
{
  std::unique_ptr<ReplacingFile> Output;
  bool WithNormals = false;
  bool Ok = false;
};

PointCloudTextStreamWriter::PointCloudTextStreamWriter()
  : Impl(std::make_unique<Internals>())
{
}

PointCloudTextStreamWriter::~PointCloudTextStreamWriter() = default;

std::string PointCloudTextStreamWriter::Open(const std::string& path,
  const PointCloudTable& header,
  bool withNormals)
{
  Internals& w = *this->Impl;
  w.Output = std::make_unique<ReplacingFile>(path);
  w.WithNormals = withNormals;
  if (w.Output->Get() == nullptr)
  {
    return w.Output->OpenError();
  }
  const std::string line = MakeHeaderLine(header, withNormals);
  w.Ok = std::fwrite(line.data(), 1, line.size(), w.Output->Get()) == line.size();
  return std::string();
}

std::string PointCloudTextStreamWriter::Append(const PointCloudTable& points)
{
  Internals& w = *this->Impl;
  if (!w.Output || w.Output->Get() == nullptr)
  {
    return "the text file was not opened";
  }
  w.Ok = w.Ok && WriteLines(w.Output->Get(), points, w.WithNormals);
  return std::string();
}

std::string PointCloudTextStreamWriter::Close()
{
  Internals& w = *this->Impl;
  if (!w.Output || w.Output->Get() == nullptr)
  {
    return "the text file was not opened";
  }
  return w.Output->Commit(w.Ok);
}

} // namespace pcbilateral

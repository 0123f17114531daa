// Reading and writing the ASCII point format of the authors' program: one point per line,
// "x y z", then "nx ny nz" when the file carries normals, then any further columns.
// Plain C++17, no VTK types.
#ifndef pcbilateral_PointCloudText_h
#define pcbilateral_PointCloudText_h

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pcbilateral
{

/**
 * How a text file lays out its lines: what the reader found, which the writer follows, so that a
 * cloud read from a text file is written back as its file was (and a tool that reads one reads
 * the other).
 */
struct PointCloudTextLayout
{
  enum class HeaderLine
  {
    /// A header line only when there are extra columns, to keep their names: for a cloud that
    /// did not come from a text file. A file of x y z [nx ny nz] alone then stays in the
    /// authors' format, which their program reads.
    WhenExtraColumns,
    Always,
    Never
  };
  HeaderLine Header = HeaderLine::WhenExtraColumns;
  /// The header's names of the leading columns (x y z, then nx ny nz when read with normals);
  /// missing ones are written "x", "y", "z", "nx", "ny", "nz".
  std::vector<std::string> LeadingColumnNames;
  /// Between two values of a line: '\t' or ' '.
  char Delimiter = '\t';
};

/// A point cloud as columns of numbers.
struct PointCloudTable
{
  std::size_t NumberOfPoints = 0;
  /// x y z interleaved.
  std::vector<double> Positions;
  /// nx ny nz interleaved, or empty.
  std::vector<double> Normals;
  /// Further columns, in file order, each with one value per point.
  std::vector<std::string> ExtraColumnNames;
  std::vector<std::vector<double>> ExtraColumns;
  /// The file's layout (ParsePointCloudText), or the one to write (WritePointCloudText).
  PointCloudTextLayout Layout;
};

/**
 * Parses the text of a point file. Columns are separated by spaces or tabs; lines may end in
 * CR LF; empty lines and lines starting with '#' are skipped. A first line that does not start
 * with a number names the columns (the names of the extra columns are kept); otherwise they are
 * named "column4", "column5", ... by position. Every data line must have the same number of
 * columns: at least 3, or 6 when hasNormals. The table's Layout says whether there was a header
 * line, its names of the leading columns, and the delimiter: a tab if the first point's first
 * value is followed by one, else a space.
 *
 * Returns an empty string on success, else a one-line message naming `sourceName`, the line
 * and the problem.
 *
 * The text is parsed in parallel, in pieces of whole lines of at least `minimumPieceBytes`
 * (tests make them tiny, to check that the pieces join seamlessly).
 */
std::string ParsePointCloudText(const char* text,
  std::size_t length,
  bool hasNormals,
  const std::string& sourceName,
  PointCloudTable& table,
  std::size_t minimumPieceBytes = std::size_t{ 1 } << 20);

/**
 * ParsePointCloudText for piece `piece` of `pieces` (a process's share of a distributed read,
 * PointPieces.h): the header and the first point are read as there, every line of the text is
 * found to count the N points, and only the lines of points [floor(piece N / pieces),
 * floor((piece + 1) N / pieces)) are parsed (and checked: a malformed line outside the share is
 * not seen by this piece). Errors name the file's own line numbers. One piece is
 * ParsePointCloudText.
 */
std::string ParsePointCloudTextPiece(const char* text,
  std::size_t length,
  bool hasNormals,
  const std::string& sourceName,
  int piece,
  int pieces,
  PointCloudTable& table);

/// Reads and parses a file, or its piece `piece` of `pieces` (see ParsePointCloudTextPiece).
std::string ReadPointCloudText(const std::string& path,
  bool hasNormals,
  PointCloudTable& table,
  int piece = 0,
  int pieces = 1);

/**
 * Writes a table as text, in its Layout: a header line naming the columns when the layout has
 * one ("x y z", "nx ny nz" when there are normals, or the layout's names of them, then the
 * extra columns' names, with spaces replaced by '_'), then one line per point, values
 * separated by the layout's delimiter, printed with the shortest digits that read back to the
 * same double. Writes to a temporary file beside `path` and renames it, so that a failed write
 * leaves no partial file. Returns an empty string on success, else a one-line message.
 */
std::string WritePointCloudText(const std::string& path, const PointCloudTable& table);

/**
 * A text point file read a range of points at a time, for a cloud that is never in memory whole
 * (pcbilateral --memory-limit): the same points, values and errors as ReadPointCloudText. The
 * file is mapped, and each range's pages are given back after it.
 */
class PointCloudTextStream
{
public:
  PointCloudTextStream();
  ~PointCloudTextStream();
  PointCloudTextStream(const PointCloudTextStream&) = delete;
  PointCloudTextStream& operator=(const PointCloudTextStream&) = delete;

  /// Maps the file, reads its header and first point and counts its points; an empty string or
  /// a one-line message.
  std::string Open(const std::string& path, bool hasNormals);
  std::uint64_t GetNumberOfPoints() const;
  /// The file's layout and extra columns' names (no points).
  const PointCloudTable& GetHeader() const;
  /// Points [first, first + count) into `table`: read in order, each range starting where the
  /// last ended, or at 0 again. Errors name the file's line.
  std::string Read(std::uint64_t first, std::size_t count, PointCloudTable& table);

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

/// WritePointCloudText a range of points at a time (PointCloudTextStream's counterpart): the
/// same bytes as WritePointCloudText given all the points at once.
class PointCloudTextStreamWriter
{
public:
  PointCloudTextStreamWriter();
  ~PointCloudTextStreamWriter();
  PointCloudTextStreamWriter(const PointCloudTextStreamWriter&) = delete;
  PointCloudTextStreamWriter& operator=(const PointCloudTextStreamWriter&) = delete;

  /// Writes the header line `header` (its layout, extra columns' names) asks for.
  std::string Open(const std::string& path, const PointCloudTable& header, bool withNormals);
  /// The next points, with the header's columns.
  std::string Append(const PointCloudTable& points);
  /// Moves the file onto the path (no file is left if any write failed).
  std::string Close();

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

} // namespace pcbilateral

#endif

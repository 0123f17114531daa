// Reading and writing the ASCII point format of the authors' program: one point per line,
// "x y z", then "nx ny nz" when the file carries normals, then any further columns.
// Plain C++17, no VTK types.
#ifndef pcbilateral_PointCloudText_h
#define pcbilateral_PointCloudText_h

#include <cstddef>
#include <string>
#include <vector>

namespace pcbilateral
{

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
};

/**
 * Parses the text of a point file. Columns are separated by spaces or tabs; lines may end in
 * CR LF; empty lines and lines starting with '#' are skipped. A first line that does not start
 * with a number names the columns (the names of the extra columns are kept); otherwise they are
 * named "column4", "column5", ... by position. Every data line must have the same number of
 * columns: at least 3, or 6 when hasNormals.
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

/// Reads and parses a file (see ParsePointCloudText).
std::string ReadPointCloudText(const std::string& path, bool hasNormals, PointCloudTable& table);

/**
 * Writes a table as text: a header line naming the columns ("x y z", "nx ny nz" when there
 * are normals, then the extra columns' names, with spaces replaced by '_'), then one line per
 * point, values separated by tabs, printed with the shortest digits that read back to the
 * same double. Writes to a temporary file beside `path`
 * and renames it, so that a failed write leaves no partial file. Returns an empty string on
 * success, else a one-line message.
 */
std::string WritePointCloudText(const std::string& path, const PointCloudTable& table);

} // namespace pcbilateral

#endif

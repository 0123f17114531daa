// A range of points as the point arrays the run in memory's reader makes of its file (names,
// value types, components), and the filtered cloud written from them into another format as the
// run in memory's VTK writers write those arrays: PCD or text input into LAS, LAZ, text or PCD.
// Plain C++17 over Formats.
#ifndef pcbilateral_StreamedArrays_h
#define pcbilateral_StreamedArrays_h

#include "PCDFile.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace pcbilateral
{

class OutOfCoreRun;
class StreamedFile;

/// One point array of a range: what a VTK array of the run in memory holds.
struct StreamedArray
{
  std::string Name;
  /// The values' type and size ('F' 4 or 8, 'I' or 'U' 1 to 8) and components (Count); the
  /// field's name is unused.
  PCDField Type;
  /// The point data's normals (vtkPointData::SetNormals), not only an array named so.
  bool IsNormals = false;
  /// Count values per point, point after point.
  std::vector<std::uint8_t> Bytes;

  /// Component `component` of point `point`, as vtkDataArray::GetComponent gives it.
  double Value(std::size_t point, unsigned component) const;
};

/// A range of points: positions (x y z interleaved) and the reader's arrays, in the order the
/// run in memory's point data holds them.
struct StreamedArrays
{
  std::size_t NumberOfPoints = 0;
  std::vector<double> Positions;
  std::vector<StreamedArray> Arrays;

  /// Keeps the points whose `removed` is 0, in order.
  void LeaveOutRemoved(const std::vector<std::uint8_t>& removed);
};

/**
 * Calls `range(first, count)` for the ranges of `pointsPerRange` points of `total`, in order,
 * until one returns a problem (returned), with the progress after each (0 to 1).
 */
std::string ForEachRange(std::uint64_t total,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress,
  const std::function<std::string(std::uint64_t first, std::size_t count)>& range);

/// Whether `path` ends in `suffix` (lower case), in any case.
bool HasExtension(const std::string& path, const char* suffix);

/// Whether `path` names a LAS or LAZ file (.las, .laz), or a text file (.txt, .xyz).
bool IsLASPath(const std::string& path);
bool IsTextPath(const std::string& path);

/// Whether `path` is written through WriteStreamedArrays (.las, .laz, .txt, .xyz, .pcd).
bool IsArraysOutput(const std::string& path);

/**
 * Writes the filtered cloud of `run` into `path` (LAS, LAZ, text or PCD, by its extension) as
 * pcbilateral's run in memory writes the reader's arrays of a file that is not of that format:
 * LAS and LAZ with vtkLASPointCloudWriter's default header (its scale and offset from the
 * filtered cloud's bounds, the smallest point format holding GpsTime and RGB) and the arrays
 * named as its dimensions; text with vtkPointCloudTextWriter's columns (`withNormals`, -R: the
 * normals as columns 4-6); binary PCD with vtkPCDPointCloudWriter's fields for a cloud without a
 * PCD layout. `input` gives its ranges by ReadArrays. Progress from 0 to 1; an empty string or
 * a one-line message (no file is left then).
 */
std::string WriteStreamedArrays(StreamedFile& input,
  OutOfCoreRun& run,
  const std::string& path,
  bool withNormals,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress);

/// The warning the run in memory says writing arrays like `layout`'s into `path` (LAS: the
/// arrays no dimension of the point format takes), or empty.
std::string StreamedArraysWarning(const StreamedArrays& layout, const std::string& path);

} // namespace pcbilateral

#endif

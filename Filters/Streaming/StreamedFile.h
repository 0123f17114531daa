// The files the out-of-core run reads and writes: an input read a range of points at a time, and
// the filtered cloud written in the output's format a range at a time. Plain C++17 over Formats.
#ifndef pcbilateral_StreamedFile_h
#define pcbilateral_StreamedFile_h

#include "COPC.h"
#include "OutOfCoreRun.h"
#include "StreamedArrays.h"

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pcbilateral
{

/// An input file for OutOfCoreRun, which also writes the filtered cloud in its own format.
class StreamedFile : public StreamedPoints
{
public:
  /**
   * Writes the file's records again, a range of `pointsPerRange` points at a time, each point
   * at its filtered position (run.ReadFiltered): the same bytes as pcbilateral's run in memory
   * writes. Progress from 0 to 1. Returns an empty string or a one-line message (no file is
   * left then).
   */
  virtual std::string WriteFiltered(OutOfCoreRun& run,
    const std::string& path,
    std::size_t pointsPerRange,
    const std::function<void(double)>& progress) = 0;

  /// The warning the run in memory says when it writes this input's cloud into `path` (e.g.
  /// what the output's format cannot hold), or empty.
  virtual std::string WriteWarning(const std::string& path) const
  {
    (void)path;
    return std::string();
  }

  /// Points [first, first + count) as the run in memory's reader's point arrays (the same
  /// arrays, in the same order, for every range; count 0 gives them without values), for the
  /// writers into another format (WriteStreamedArrays). An empty string or a one-line message.
  virtual std::string ReadArrays(std::uint64_t first, std::size_t count, StreamedArrays& range)
  {
    (void)first;
    (void)count;
    (void)range;
    return "--memory-limit: this input is not streamed into another format";
  }

  /// The run in memory's warning on reading this input (--copc options on a file that is not
  /// COPC), or empty.
  const std::string& GetReadWarning() const { return this->ReadWarning; }
  void SetReadWarning(const std::string& warning) { this->ReadWarning = warning; }

  /// Points without coordinates the run in memory's reader leaves out (PCD input), said as it
  /// says them.
  virtual std::uint64_t GetNumberOfDroppedPoints() const { return 0; }

  /// --classes: filter only the points whose integer dimension `name` holds one of `classes`,
  /// the others left alone (GetNumberOfPointsLeftAlone). An empty string, or the run in
  /// memory's one-line error; a file that has no such dimensions says it is not streamed.
  virtual std::string ChooseClasses(const std::string& name, const std::vector<long long>& classes)
  {
    (void)name;
    (void)classes;
    return "--memory-limit: --classes is streamed for LAS, LAZ and PCD input only";
  }

private:
  std::string ReadWarning;
};

/// Whether a class array's value (an integer, read as a double) is one of `classes`: compared as
/// doubles, as the filter in memory compares them (exact below 2^53).
bool IsChosenClass(const std::vector<long long>& classes, double value);

/// The one-line error of the filter in memory for a class array that is not one integer per
/// point: `components` of the type VTK names `typeName` ("float", "unsigned short"...).
std::string ClassArrayTypeProblem(const std::string& name,
  unsigned components,
  const std::string& typeName);

/// The same for a class array the input does not have.
std::string MissingClassArrayProblem(const std::string& name);

/// Why `input` cannot be streamed into `output` (by their extensions), or empty: LAS, LAZ, text
/// (.txt, .xyz) or PCD into any of them.
std::string StreamingFormatsProblem(const std::string& input, const std::string& output);

/// The points of a range read and written at a time: 2^18, or PCB_STREAMING_RANGE_POINTS from
/// the environment (tests).
std::size_t StreamedRangePoints();

/// The input opened for streaming into `output`'s format, or null with `problem` set;
/// `orientedNormals` (pcbilateral -R): a text file's columns 4-6 are normals, and normals are
/// written as a text output's columns 4-6; `keepNaN` (--keep-nan): a PCD file's points without
/// coordinates are kept in place (passed through, never neighbours), not left out; `copcPart`
/// (--copc-level, --copc-bounds, or null): a COPC file's points are those it asks for (any
/// other file's are all read, with the run in memory's warning, GetReadWarning).
std::unique_ptr<StreamedFile> OpenStreamedFile(const std::string& input,
  const std::string& output,
  bool orientedNormals,
  bool keepNaN,
  const COPCQuery* copcPart,
  std::string& problem);

} // namespace pcbilateral

#endif

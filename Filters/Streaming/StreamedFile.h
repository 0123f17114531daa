// The files the out-of-core run reads and writes: an input read a range of points at a time, and
// the filtered cloud written in the output's format a range at a time. Plain C++17 over Formats.
#ifndef pcbilateral_StreamedFile_h
#define pcbilateral_StreamedFile_h

#include "OutOfCoreRun.h"

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
    return "--memory-limit: --classes is streamed for LAS and LAZ input only";
  }
};

/// Why `input` cannot be streamed into `output` (by their extensions), or empty: LAS or LAZ into
/// LAS or LAZ, text (.txt, .xyz) into text.
std::string StreamingFormatsProblem(const std::string& input, const std::string& output);

/// Why pcbilateral's options cannot be streamed with these files, or empty: the --copc options
/// (`copc`), --classes (`classes`) with text input or PCD output, --keep-nan (`keepNaN`) with
/// PCD input, then StreamingFormatsProblem.
std::string StreamingProblem(const std::string& input,
  const std::string& output,
  bool copc,
  bool classes,
  bool keepNaN);

/// The points of a range read and written at a time: 2^18, or PCB_STREAMING_RANGE_POINTS from
/// the environment (tests).
std::size_t StreamedRangePoints();

/// The input opened for streaming into `output`'s format, or null with `problem` set;
/// `orientedNormals` (pcbilateral -R): a text file's columns 4-6 are normals, written back.
std::unique_ptr<StreamedFile> OpenStreamedFile(const std::string& input,
  const std::string& output,
  bool orientedNormals,
  std::string& problem);

} // namespace pcbilateral

#endif

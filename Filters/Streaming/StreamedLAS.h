// LAS and LAZ files read a range of points at a time, and the filtered cloud written as LAS a
// range at a time, for the out-of-core run (OutOfCoreRun.h). Plain C++17 over Formats.
#ifndef pcbilateral_StreamedLAS_h
#define pcbilateral_StreamedLAS_h

#include "COPC.h"
#include "LASHeader.h"
#include "MappedInput.h"
#include "OutOfCoreRun.h"
#include "StreamedFile.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace pcbilateral
{

/**
 * A LAS or LAZ file, mapped without being read in: each range of points is decoded from its own
 * pages (or LAZ chunks), which are given back to the system after it, so that the memory taken
 * is that of a range, not of the file.
 */
class LASPointSource : public StreamedFile
{
public:
  LASPointSource() = default;
  LASPointSource(const LASPointSource&) = delete;
  LASPointSource& operator=(const LASPointSource&) = delete;

  /// Maps the file and checks its header; an empty string or a one-line message. With `part`
  /// (--copc-level, --copc-bounds) and a COPC file, the points are only those `part` asks for,
  /// in file order, as the run in memory's reader reads them (ReadCOPCPoints): the chosen
  /// nodes' chunks, and with a box the points inside it (counted here, a node at a time).
  std::string Open(const std::string& path, const COPCQuery* part = nullptr);
  const LASFileInfo& GetInfo() const { return this->Info; }
  /// Whether the points are a part of a COPC file (Open's `part` on a COPC file).
  bool IsCOPCPart() const { return this->Part; }
  std::uint64_t GetNumberOfPoints() const override
  {
    return this->Part ? this->PartFirst.back() : this->Info.Header.NumberOfPoints;
  }
  std::string ReadPositions(std::uint64_t first, std::size_t count, double* positions) override;
  /// Positions and every dimension's column (laid out as DecodeLASPoints lays them out).
  std::string ReadPoints(std::uint64_t first,
    std::size_t count,
    double* positions,
    void* const* columns);
  std::string WriteFiltered(OutOfCoreRun& run,
    const std::string& path,
    std::size_t pointsPerRange,
    const std::function<void(double)>& progress) override;
  std::string ChooseClasses(const std::string& name,
    const std::vector<long long>& classes) override;
  std::string WriteWarning(const std::string& path) const override;
  /// Whether every RGB value of the file is at most 255 (true without RGB): the run in memory's
  /// display colours are then the values, else their high bytes.
  std::string ColoursFitEightBits(bool& fit);
  std::string GetClassArrayName() const override { return this->ClassName; }

private:
  void Release();
  std::string OpenCOPCPart(const COPCQuery& part);
  /// The records of node `node` of the part (the points inside the box only, with one) into
  /// `records`.
  std::string ReadPartNode(std::size_t node, std::vector<std::uint8_t>& records);
  /// The records of the part's points [first, first + count) into Decompressed.
  std::string ReadPartRecords(std::uint64_t first, std::size_t count);
  std::string Path;
  LASFileInfo Info;
  MappedInput Mapped;
  std::vector<std::uint8_t> Decompressed;
  /// --classes: the class dimension's index (or none) and the classes.
  std::size_t ClassDimension = static_cast<std::size_t>(-1);
  std::vector<long long> Classes;
  std::string ClassName;
  /// --copc-level, --copc-bounds on a COPC file: the query, the chosen nodes' chunks in file
  /// order, the part's points before each (and their total, last), and the node read last.
  bool Part = false;
  COPCQuery Query;
  std::vector<LAZChunk> PartChunks;
  std::vector<std::uint64_t> PartFirst{ 0 };
  std::size_t CachedNode = static_cast<std::size_t>(-1);
  std::vector<std::uint8_t> CachedRecords;
};

/// The header a LAS file written from `info` has after pcbilateral's in-memory run (the
/// reader's field data and the writer's reading of it): the same fields, the dimensions of its
/// point format and extra bytes, no LASzip record.
LASFileInfo LASInfoAsWritten(const LASFileInfo& info);

/**
 * Writes the filtered cloud of `run` as a LAS file, or a LAZ file when `path` ends in .laz: the
 * input's records, a range at a time, with the filtered positions (LASStreamWriter,
 * LAZStreamWriter). Progress from 0 to 1. Returns an empty string or a
 * one-line message (no file is left then).
 */
std::string WriteStreamedLAS(LASPointSource& input,
  OutOfCoreRun& run,
  const std::string& path,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress);

/**
 * Writes the filtered cloud of `run` as a text file (.txt, .xyz), as pcbilateral's run in memory
 * writes a LAS or LAZ file's cloud: a header line, tabs, x y z then every dimension's values
 * and, with RGB, the 8-bit display colours (whether the file's colours fit 8 bits is read from
 * the whole file first). Progress from 0 to 1; an empty string or a one-line message.
 */
std::string WriteStreamedLASAsText(LASPointSource& input,
  OutOfCoreRun& run,
  const std::string& path,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress);

/**
 * Writes the filtered cloud of `run` as a binary PCD file, as pcbilateral's run in memory writes
 * a LAS or LAZ file's cloud (vtkPCDPointCloudWriter): x y z as F4 when every filtered position is
 * a float, else F8; with RGB a packed `rgb` of the 8-bit display colours; then every dimension,
 * its components as the field's COUNT. Progress from 0 to 1; an empty string or a one-line
 * message.
 */
std::string WriteStreamedLASAsPCD(LASPointSource& input,
  OutOfCoreRun& run,
  const std::string& path,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress);

} // namespace pcbilateral

#endif

// PCD files (ascii and binary) read a range of points at a time, and the filtered cloud written
// back as PCD a range at a time, for the out-of-core run (OutOfCoreRun.h). Plain C++17 over
// Formats.
#ifndef pcbilateral_StreamedPCD_h
#define pcbilateral_StreamedPCD_h

#include "MappedInput.h"
#include "PCDFile.h"
#include "StreamedFile.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace pcbilateral
{

/**
 * A PCD file, mapped without being read in (binary_compressed: its one LZF block decompressed
 * whole). Open checks the whole file as
 * the run in memory's reader does (the same one-line errors, in the same order) and counts its
 * points with coordinates; the points without (NaN) are left out, as the run in memory leaves
 * them out by default, so the points are numbered as in memory. A checkpoint every 4096
 * records (the record, its place in the file, the points kept before it) lets a range of kept
 * points be found without reading the file from its start.
 */
class PCDPointSource : public StreamedFile
{
public:
  PCDPointSource() = default;
  PCDPointSource(const PCDPointSource&) = delete;
  PCDPointSource& operator=(const PCDPointSource&) = delete;

  /// Maps and checks the file; an empty string or the run in memory's one-line message.
  /// `withNormals` (-R): the normals are written as a text output's columns 4-6; `keepNaN`
  /// (--keep-nan): the points without coordinates are kept in place, not left out.
  std::string Open(const std::string& path, bool withNormals = false, bool keepNaN = false);
  std::uint64_t GetNumberOfPoints() const override { return this->Kept; }
  std::uint64_t GetNumberOfDroppedPoints() const override
  {
    return this->Header.NumberOfPoints - this->Kept;
  }
  std::string ReadPositions(std::uint64_t first, std::size_t count, double* positions) override;
  /// As pcbilateral's run in memory writes a PCD file's cloud into PCD (vtkPCDPointCloudReader
  /// then vtkPCDPointCloudWriter): the input's fields, WIDTH, HEIGHT and VIEWPOINT, its
  /// encoding, packed `rgb` unpacked and packed again (alpha 255), normals gathered and
  /// scattered, padding as zeros.
  std::string WriteFiltered(OutOfCoreRun& run,
    const std::string& path,
    std::size_t pointsPerRange,
    const std::function<void(double)>& progress) override;
  /// vtkPCDPointCloudReader's arrays: the normals gathered from normal_x/y/z, then every other
  /// field but x y z and padding, packed colours as 8-bit RGB or RGBA.
  std::string ReadArrays(std::uint64_t first, std::size_t count, StreamedArrays& range) override;
  std::string WriteWarning(const std::string& path) const override;
  /// --classes: `name` is one of vtkPCDPointCloudReader's arrays, a field of one integer.
  std::string ChooseClasses(const std::string& name,
    const std::vector<long long>& classes) override;
  std::string GetClassArrayName() const override { return this->ClassName; }

private:
  struct Checkpoint
  {
    std::uint64_t Record = 0;
    std::uint64_t KeptBefore = 0;
    /// ascii: where the record's line may start (after the previous record's line), and the
    /// line number there.
    std::size_t Offset = 0;
    std::size_t Line = 0;
  };
  void FindCoordinates();
  /// The data's size against the header's points, as DecodePCD checks it first; then the
  /// binary_compressed block decompressed.
  std::string CheckSize();
  std::string CheckData();
  /// binary_compressed: the block checked and decompressed into Fields.
  std::string Decompress();
  /// Record `record` (binary layout) into `out`, from the mapped file or, binary_compressed,
  /// from the decompressed fields.
  void CopyRecord(std::uint64_t record, std::uint8_t* out) const;
  /// binary_compressed: the filtered values written into the decompressed fields in place,
  /// the points kept moved to the front field by field, then compressed as one block.
  std::string WriteCompressed(OutOfCoreRun& run,
    const std::string& path,
    std::size_t pointsPerRange,
    const std::function<void(double)>& progress);
  /// binary_compressed: the points `written` moved to the front of the decompressed fields;
  /// their number.
  std::size_t MoveToFront(const std::vector<bool>& written);
  /// The records (binary layout, `Stride` bytes each) of the kept points [first, first + count).
  std::string ReadRecords(std::uint64_t first,
    std::size_t count,
    std::vector<std::uint8_t>& records);
  bool IsKept(const std::uint8_t* record) const;
  /// The record's x y z as doubles.
  void RecordPosition(const std::uint8_t* record, double* position) const;
  void Release();

  std::string Path;
  MappedInput Mapped;
  PCDHeader Header;
  std::size_t Stride = 0;
  std::size_t FirstLine = 1;
  std::size_t CoordinateOffsets[3] = { 0, 0, 0 };
  PCDField CoordinateFields[3];
  std::vector<Checkpoint> Checkpoints;
  /// binary_compressed: every field's values, one field after another (one LZF block,
  /// decompressed whole when opened; counted in the memory the run holds before its slabs),
  /// and where each field starts.
  std::vector<std::uint8_t> Fields;
  std::vector<std::size_t> FieldStarts;
  std::uint64_t Kept = 0;
  /// --classes: the class field, where it lies in a record, and the classes.
  PCDField ClassField;
  std::size_t ClassOffset = 0;
  std::string ClassName;
  std::vector<long long> Classes;
  bool WithNormals = false;
  bool KeepNaN = false;
};

/// Why a PCD file's layout is not streamed into PCD (fields whose names the run in memory's VTK
/// arrays would mix up: RGB, RGBA, Colors, Normals, vtkOriginalPointIds), or empty.
std::string PCDLayoutProblem(const PCDHeader& header);

} // namespace pcbilateral

#endif

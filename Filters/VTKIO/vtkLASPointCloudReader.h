/**
 * @class   vtkLASPointCloudReader
 * @brief   read LAS and LAZ files (LiDAR point clouds, LAS 1.0 to 1.4, point formats 0-10)
 *
 * LAZ files (LASzip-compressed LAS: point formats 0-3 and 6-8, including COPC files read as
 * LAZ, in file order) are decompressed to the same point records first, chunks in parallel.
 * The output has the points in double precision (the file's integer coordinates times its
 * scale plus its offset), one vertex cell per point, and every field of the point records as
 * a point array of the record's own type: Intensity, ReturnNumber, NumberOfReturns,
 * ScanDirectionFlag, EdgeOfFlightLine, Classification, Synthetic, KeyPoint, Withheld,
 * Overlap and ScannerChannel (formats 6-10), ScanAngleRank (formats 0-5, degrees) or ScanAngle
 * (formats 6-10, degrees as floats: the stored integer times 0.006), UserData, PointSourceId,
 * GpsTime, RGB (3 unsigned shorts, the file's 16-bit values), NIR, the wave packet fields, and
 * the extra bytes named by the file's extra-bytes record (as doubles, stored value times scale
 * plus offset, when the record gives a scale or an offset for an integer type of up to 32 bits,
 * NaN for its no-data value; else the stored values). The writer stores these values back
 * rounded to the nearest step, so a file read and written unchanged keeps its point records.
 * Files with colours also get "Colors", the colours as 3 unsigned chars
 * (the 16-bit values divided by 256, or as they are when no value exceeds 255) that ParaView
 * shows as they are when "Map Scalars" is off.
 *
 * The header and the variable-length records are kept in the field data ("LAS Version",
 * "LAS Point Format", "LAS Point Record Length", "LAS Scale", "LAS Offset", "LAS VLRs",
 * "LAS EVLRs", ...; "LAS CRS WKT" when the file has a WKT coordinate system) so that
 * vtkLASPointCloudWriter writes a file like the one read.
 *
 * A damaged or unsupported file (truncated, counts or offsets beyond the file, not LAS, a
 * point format beyond 10, a LAZ variant not supported such as waveforms, a damaged chunk) gives one
 * error naming the file and the problem (also from GetErrorMessage()) and an empty output. Nothing
 * is read outside the file.
 *
 * Decoding is parallel (OpenMP) over a memory-mapped file.
 *
 * The reader honours streaming pieces (UPDATE_PIECE_NUMBER and UPDATE_NUMBER_OF_PIECES, one
 * piece per process under `mpirun pvbatch` or pvserver): piece p of n reads only the points
 * [floor(p N / n), floor((p + 1) N / n)) of the file's N, in file order; of a LAZ file only
 * the chunks that hold them are decompressed. The field data is the same on every piece;
 * "Colors" too follows the whole file (a piece whose colours all fit 8 bits looks at the
 * others' until one does not). One piece is the whole file.
 *
 * COPC files (LAZ whose chunks are the nodes of an octree) can be read in part: COPCMaxLevel
 * (default -1, every level) keeps the nodes of that level and above (a level of detail), and
 * with COPCUseBounds (default off) only the points inside COPCBounds (xmin, xmax, ymin, ymax,
 * zmin, zmax, real coordinates, faces included) are read. Only the chosen nodes' chunks are
 * decompressed; the points come in file order. Piece p of n gets whole nodes, its share of the
 * chosen nodes' points (COPCPieceOfNodes), and decompresses only those. The octree is checked first
 * (COPC.h): a damaged hierarchy is one error and an empty output. With the defaults a COPC file is
 * read as LAZ and its octree is not looked at. Set on a file that is not COPC, these options give
 * one warning (they apply to COPC files only) and every point is read.
 *
 * @sa
 * vtkLASPointCloudWriter vtkPointCloudFileIO
 */
#ifndef vtkLASPointCloudReader_h
#define vtkLASPointCloudReader_h

#include "vtkIOPointCloudBilateralModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <cstdint> // For the record bytes
#include <string>  // For the error message
#include <vector>  // For the decompressed records

namespace pcbilateral
{
class LASFileBytes;
struct LASFileInfo;
struct PointRange;
}
class vtkPolyData;

class VTKIOPOINTCLOUDBILATERAL_EXPORT vtkLASPointCloudReader : public vtkPolyDataAlgorithm
{
public:
  static vtkLASPointCloudReader* New();
  vtkTypeMacro(vtkLASPointCloudReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// COPC files only: the deepest octree level read; -1 (the default) for every level.
  vtkSetClampMacro(COPCMaxLevel, int, -1, VTK_INT_MAX);
  vtkGetMacro(COPCMaxLevel, int);
  ///@}

  ///@{
  /// COPC files only: whether only the points inside COPCBounds are read (default off).
  vtkSetMacro(COPCUseBounds, bool);
  vtkGetMacro(COPCUseBounds, bool);
  vtkBooleanMacro(COPCUseBounds, bool);
  ///@}

  ///@{
  /// COPC files only: the box read with COPCUseBounds: xmin, xmax, ymin, ymax, zmin, zmax.
  vtkSetVector6Macro(COPCBounds, double);
  vtkGetVector6Macro(COPCBounds, double);
  ///@}

  /// Why the last read failed; empty after a successful read.
  const char* GetErrorMessage() const { return this->ErrorMessage.c_str(); }

protected:
  vtkLASPointCloudReader();
  ~vtkLASPointCloudReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  std::string ErrorMessage;
  int COPCMaxLevel = -1;
  bool COPCUseBounds = false;
  double COPCBounds[6] = { 0, 0, 0, 0, 0, 0 };

private:
  /// The records of piece `piece` of `pieces` into `records` and their `count`: a share of the
  /// file's points, or of those the COPC options choose. `colourShare` is the range of the
  /// file's points AddDisplayColours looks beyond (none for COPC: the whole file).
  std::string ReadShare(const pcbilateral::LASFileBytes& file,
    const pcbilateral::LASFileInfo& info,
    int piece,
    int pieces,
    std::vector<std::uint8_t>& decompressed,
    const std::uint8_t*& records,
    std::uint64_t& count,
    pcbilateral::PointRange& colourShare);
  std::string DecodePoints(const pcbilateral::LASFileInfo& info,
    const std::uint8_t* records,
    std::uint64_t numberOfPoints,
    vtkPolyData* output);
  std::string AddDisplayColours(const std::uint8_t* data,
    std::size_t size,
    const pcbilateral::LASFileInfo& info,
    const pcbilateral::PointRange& share,
    vtkPolyData* output);

  vtkLASPointCloudReader(const vtkLASPointCloudReader&) = delete;
  void operator=(const vtkLASPointCloudReader&) = delete;
};

#endif

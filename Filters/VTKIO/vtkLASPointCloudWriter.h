/**
 * @class   vtkLASPointCloudWriter
 * @brief   write a point cloud as a LAS file, or a LAZ file when its name ends in .laz
 *
 * LAZ (LASzip-compressed LAS, chunks of 50,000 points compressed in parallel) is written for
 * point formats 0 to 3 and 6 to 8; a waveform format asked for as .laz is a one-line error
 * (write .las). The LASzip record is added to the VLRs.
 *
 * When the input carries the field data of vtkLASPointCloudReader (a LAS file read, then
 * filtered), the file gets the version, point format, record length, scales, offsets, header
 * identifiers and variable-length records of the file read, so that it stays valid for the
 * tools that made it; each record field is filled from the point array of the same name (see
 * vtkLASPointCloudReader), converted to the field's type when it has another. A file read and
 * written without a change has the same point records, byte for byte.
 *
 * Otherwise it writes LAS 1.2 (1.4 beyond 2^32 - 1 points), point format 0, or 1, 2 or 3 when
 * the input has a "GpsTime" array and/or a 3-component "RGB" array (8-bit colours are scaled
 * to 16 bits), offsets at the lower corner of the bounds and the finest power-of-ten scales
 * that keep the extent within the 32-bit records. Other arrays are not written.
 *
 * The bounds, point counts and counts by return of the header are computed from the points.
 * The file is written under a temporary name and renamed, so a failed write leaves none.
 * Errors (coordinates that do not fit the records, an unwritable file) are one line, also
 * from GetErrorMessage().
 *
 * @sa
 * vtkLASPointCloudReader vtkPointCloudFileIO
 */
#ifndef vtkLASPointCloudWriter_h
#define vtkLASPointCloudWriter_h

#include "vtkIOPointCloudBilateralModule.h" // For export macro
#include "vtkWriter.h"

class vtkPointSet;

#include <cstddef> // For std::size_t
#include <string>  // For the error message

namespace pcbilateral
{
struct LASFileInfo;
}

class VTKIOPOINTCLOUDBILATERAL_EXPORT vtkLASPointCloudWriter : public vtkWriter
{
public:
  static vtkLASPointCloudWriter* New();
  vtkTypeMacro(vtkLASPointCloudWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to write.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  /// Why the last write failed; empty after a successful write.
  const char* GetErrorMessage() const { return this->ErrorMessage.c_str(); }

  /// What the header of a cloud without a LAS file's field data is made from.
  struct CloudSummary
  {
    vtkIdType NumberOfPoints = 0;
    /// min x, min y, min z, max x, max y, max z; zeros without points
    double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
    bool HasGpsTime = false;
    bool HasRGB = false;
  };

protected:
  vtkLASPointCloudWriter();
  ~vtkLASPointCloudWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  /// The cloud to write, for a default header (`input` null when it cannot be written): here
  /// the input's; vtkPLASPointCloudWriter's is the whole cloud over the processes.
  virtual CloudSummary MeasureCloud(vtkPointSet* input);

  /**
   * Writes the points prepared by WriteData, or fails with `problem` when it is not empty:
   * here with WriteLAS or WriteLAZ; vtkPLASPointCloudWriter writes this process's part of one
   * file. Returns an empty string or one line.
   */
  virtual std::string WritePoints(const std::string& problem,
    const std::string& fileName,
    const pcbilateral::LASFileInfo& info,
    std::size_t count,
    const double* positions,
    const void* const* columns,
    bool compressed);

  char* FileName = nullptr;
  std::string ErrorMessage;

private:
  vtkLASPointCloudWriter(const vtkLASPointCloudWriter&) = delete;
  void operator=(const vtkLASPointCloudWriter&) = delete;
};

#endif

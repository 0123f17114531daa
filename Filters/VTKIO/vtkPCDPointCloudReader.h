/**
 * @class   vtkPCDPointCloudReader
 * @brief   read PCD files, the point cloud format of the Point Cloud Library (PCL)
 *
 * Reads PCD 0.7 (and older files with COLUMNS) in its three encodings: ascii, binary and
 * binary_compressed (LZF). The output has the points in double precision from the x y z
 * fields (of any type), one vertex cell per point, and every other field as a point array of
 * the field's own type (F4 float, F8 double, I1 to I8 signed and U1 to U8 unsigned integers),
 * with COUNT components. Padding fields (`_`) are skipped. PCL's packed colours become
 * unsigned-char arrays: "RGB" (3 components) from an `rgb` field, "RGBA" (4) from `rgba` (the
 * bits of the 32-bit value, 0xAARRGGBB, a float's bits for type F), or "Colors" when another
 * field has that name. `normal_x`, `normal_y` and `normal_z` become the point normals
 * ("Normals").
 *
 * Organised frames (HEIGHT > 1, a depth camera's) mark pixels without a depth by NaN points.
 * By default those points are left out (GetNumberOfDroppedPoints() says how many); with
 * KeepNaNPoints on they stay, so that the frame keeps its WIDTH x HEIGHT layout: the bilateral
 * filter passes them through unchanged and never uses them as neighbours, and
 * vtkPCDPointCloudWriter writes the frame back with its WIDTH, HEIGHT and VIEWPOINT.
 *
 * The file's layout is kept in the field data ("PCD Fields": "name TYPE SIZE COUNT" per field,
 * padding and x y z included; "PCD Width", "PCD Height", "PCD Viewpoint", "PCD Data": the
 * encoding) for vtkPCDPointCloudWriter.
 *
 * A damaged file (data shorter than the header announces, a header that disagrees with itself
 * or with the data, compressed data that does not decompress to its size, an unknown type)
 * gives one error naming the file and the problem (also from GetErrorMessage()) and an empty
 * output. Nothing is read outside the file.
 *
 * The reader honours streaming pieces (UPDATE_PIECE_NUMBER and UPDATE_NUMBER_OF_PIECES, one
 * piece per process under `mpirun pvbatch` or pvserver): piece p of n keeps only the file's
 * points [floor(p N / n), floor((p + 1) N / n)), in file order (NaN points among them dropped
 * unless kept, GetNumberOfDroppedPoints() counting the piece's). Binary data is read only at
 * the piece's records (the file is memory-mapped); ascii data is scanned whole for its lines
 * but only the piece's are parsed; binary_compressed data is one LZF block, decompressed whole
 * by every piece, which keeps its share. The field data is the same on every piece.
 *
 * @sa
 * vtkPCDPointCloudWriter vtkPointCloudFileIO
 */
#ifndef vtkPCDPointCloudReader_h
#define vtkPCDPointCloudReader_h

#include "vtkIOPointCloudBilateralModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For the error message

class VTKIOPOINTCLOUDBILATERAL_EXPORT vtkPCDPointCloudReader : public vtkPolyDataAlgorithm
{
public:
  static vtkPCDPointCloudReader* New();
  vtkTypeMacro(vtkPCDPointCloudReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// Keep the points without coordinates (NaN) in place (default off: they are left out).
  vtkSetMacro(KeepNaNPoints, bool);
  vtkGetMacro(KeepNaNPoints, bool);
  vtkBooleanMacro(KeepNaNPoints, bool);
  ///@}

  /// The points without coordinates (NaN) the last read left out.
  vtkGetMacro(NumberOfDroppedPoints, vtkIdType);

  /// Why the last read failed; empty after a successful read.
  const char* GetErrorMessage() const { return this->ErrorMessage.c_str(); }

protected:
  vtkPCDPointCloudReader();
  ~vtkPCDPointCloudReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  bool KeepNaNPoints = false;
  vtkIdType NumberOfDroppedPoints = 0;
  std::string ErrorMessage;

private:
  vtkPCDPointCloudReader(const vtkPCDPointCloudReader&) = delete;
  void operator=(const vtkPCDPointCloudReader&) = delete;
};

#endif

/**
 * @class   vtkPCDPointCloudWriter
 * @brief   write a point cloud as a PCD file, the format of the Point Cloud Library (PCL)
 *
 * When the input carries the field data of vtkPCDPointCloudReader (a PCD file read, then
 * filtered), the file gets the fields of the file read, in their order and with their types,
 * sizes and counts (padding as zeros), its VIEWPOINT, and its WIDTH and HEIGHT when the cloud
 * still has WIDTH x HEIGHT points (an organised frame read with KeepNaNPoints; otherwise the
 * number of points and 1). A field whose array is gone is left out. So a PCD file read and
 * written back holds the same arrays, and float x y z stay float (PCL's point types want
 * them so).
 *
 * Otherwise: x y z as F4 when every coordinate is exactly a float, else F8 (doubles, so that
 * coordinates stay exact); the point normals as normal_x normal_y normal_z; 8-bit colours
 * ("RGB" or "Colors", 3 unsigned chars) as PCL's packed `rgb` float (alpha 255), "RGBA" (4) as
 * `rgba` (U4). Every other numeric point array follows as a field of its type and number of
 * components (spaces in names written as '_'), except vtkOriginalPointIds.
 *
 * A PCD file has no place for a LAS file's scale, offset and coordinate system: writing a cloud
 * read from LAS says so in one warning (a WarningEvent), once per write.
 *
 * DataEncoding: the encoding of the file read (binary for a cloud from elsewhere) by default,
 * or ascii, binary or binary_compressed (LZF). The file is written under a temporary name and
 * renamed when complete, so a failed write leaves no file. Errors are one line, also from
 * GetErrorMessage().
 *
 * @sa
 * vtkPCDPointCloudReader vtkPointCloudFileIO
 */
#ifndef vtkPCDPointCloudWriter_h
#define vtkPCDPointCloudWriter_h

#include "vtkIOPointCloudBilateralModule.h" // For export macro
#include "vtkWriter.h"

#include <string> // For the error message

class VTKIOPOINTCLOUDBILATERAL_EXPORT vtkPCDPointCloudWriter : public vtkWriter
{
public:
  static vtkPCDPointCloudWriter* New();
  vtkTypeMacro(vtkPCDPointCloudWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to write.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  /// The values of DataEncoding.
  enum Encoding
  {
    AS_READ = -1,
    ASCII = 0,
    BINARY = 1,
    BINARY_COMPRESSED = 2
  };

  ///@{
  /// How the points are stored (default AS_READ: the encoding of the PCD file read, else
  /// binary).
  vtkSetClampMacro(DataEncoding, int, AS_READ, BINARY_COMPRESSED);
  vtkGetMacro(DataEncoding, int);
  ///@}

  /// Why the last write failed; empty after a successful write.
  const char* GetErrorMessage() const { return this->ErrorMessage.c_str(); }

protected:
  vtkPCDPointCloudWriter();
  ~vtkPCDPointCloudWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  char* FileName = nullptr;
  int DataEncoding = AS_READ;
  std::string ErrorMessage;

private:
  vtkPCDPointCloudWriter(const vtkPCDPointCloudWriter&) = delete;
  void operator=(const vtkPCDPointCloudWriter&) = delete;
};

#endif

/**
 * @class   vtkPointCloudTextWriter
 * @brief   write a point cloud in the ASCII point format of the bilateral filter's authors
 *
 * A cloud read from a text file by vtkPointCloudTextReader is written in its file's layout,
 * which the reader keeps in field data ("Text Delimiter", "Text Header"): a header line or not,
 * the header's names of x y z [nx ny nz], and the delimiter, tab or space. A cloud from
 * elsewhere gets a header line when it has point arrays besides the normals, and only then (as
 * in the authors' files), and tabs.
 *
 * The header line names the columns: x y z [nx ny nz], then the arrays' names ("name:0",
 * "name:1", ... for the components of an array, which vtkPointCloudTextReader makes one array
 * again). Then one line per point: "x y z", then the point normals when WriteNormals is on and
 * the input has them, then every other point-data array in order, one column per component.
 * Numbers are written with the shortest digits that read back to the same double. The file is
 * written under a temporary name and renamed when complete, so a failed write leaves no
 * partial file.
 *
 * @sa
 * vtkPointCloudTextReader
 */

#ifndef vtkPointCloudTextWriter_h
#define vtkPointCloudTextWriter_h

#include "vtkIOPointCloudBilateralModule.h" // For export macro
#include "vtkWriter.h"

#include <string> // For the error message

class vtkPolyData;

class VTKIOPOINTCLOUDBILATERAL_EXPORT vtkPointCloudTextWriter : public vtkWriter
{
public:
  static vtkPointCloudTextWriter* New();
  vtkTypeMacro(vtkPointCloudTextWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to write.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// Write the point normals as columns 4 to 6 (default on).
  vtkSetMacro(WriteNormals, bool);
  vtkGetMacro(WriteNormals, bool);
  vtkBooleanMacro(WriteNormals, bool);
  ///@}

  /// Why the last write failed; empty after a successful write.
  const char* GetErrorMessage() const { return this->ErrorMessage.c_str(); }

protected:
  vtkPointCloudTextWriter();
  ~vtkPointCloudTextWriter() override;

  void WriteData() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;

  char* FileName = nullptr;
  bool WriteNormals = true;
  std::string ErrorMessage;

private:
  vtkPointCloudTextWriter(const vtkPointCloudTextWriter&) = delete;
  void operator=(const vtkPointCloudTextWriter&) = delete;
};

#endif

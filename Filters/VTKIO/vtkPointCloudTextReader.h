/**
 * @class   vtkPointCloudTextReader
 * @brief   read the ASCII point format of the bilateral filter's authors
 *
 * One point per line: "x y z", then "nx ny nz" when HasNormals is on (the authors' `-R`),
 * then any further columns. Columns are separated by spaces or tabs; CR LF line ends, empty
 * lines and lines starting with '#' are accepted. A first line that does not start with a
 * number names the columns. Every data line must have the same number of columns.
 *
 * The output has the points (double), one vertex cell per point, the normals as the point
 * normals ("Normals"), and each further column as a double point array, named by the header
 * or "column4", "column5", ... by its position in the line. Columns named "name:0",
 * "name:1", ... (as vtkPointCloudTextWriter names the components of an array) make one
 * array "name" of as many components.
 *
 * The file's layout is kept in the output's field data, for vtkPointCloudTextWriter to write
 * the cloud back the same way (the filters pass field data on): "Text Delimiter", a string
 * array with the delimiter of the lines, "tab" (when the first point's first value is followed
 * by one) or "space", and, when the file has a header line, "Text Header", a string array with
 * the header's names of the leading columns (x y z, then nx ny nz with HasNormals).
 *
 * Errors (missing file, a directory, a malformed line) name the file and the line; the
 * message of the last one is also available from GetErrorMessage().
 *
 * The reader honours streaming pieces (UPDATE_PIECE_NUMBER and UPDATE_NUMBER_OF_PIECES, one
 * piece per process under `mpirun pvbatch` or pvserver): piece p of n keeps only the points
 * [floor(p N / n), floor((p + 1) N / n)) of the file's N, in file order. A line can end
 * anywhere, so every piece reads the whole text and finds every line, but parses only its
 * share's lines (a malformed line is reported by the piece that holds it).
 *
 * @sa
 * vtkPointCloudTextWriter vtkPointCloudBilateralFilter
 */

#ifndef vtkPointCloudTextReader_h
#define vtkPointCloudTextReader_h

#include "vtkIOPointCloudBilateralModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For the error message

class VTKIOPOINTCLOUDBILATERAL_EXPORT vtkPointCloudTextReader : public vtkPolyDataAlgorithm
{
public:
  static vtkPointCloudTextReader* New();
  vtkTypeMacro(vtkPointCloudTextReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// Columns 4 to 6 are normals (default off).
  vtkSetMacro(HasNormals, bool);
  vtkGetMacro(HasNormals, bool);
  vtkBooleanMacro(HasNormals, bool);
  ///@}

  /// Why the last read failed; empty after a successful read.
  const char* GetErrorMessage() const { return this->ErrorMessage.c_str(); }

  ///@{
  /// The names of the field data arrays that keep the file's layout (see above).
  static const char* GetDelimiterArrayName() { return "Text Delimiter"; }
  static const char* GetHeaderArrayName() { return "Text Header"; }
  ///@}

  /// How "Text Delimiter" names a delimiter: "tab" for '\t', "space" for ' '.
  static const char* GetDelimiterName(char delimiter)
  {
    return delimiter == '\t' ? "tab" : "space";
  }

protected:
  vtkPointCloudTextReader();
  ~vtkPointCloudTextReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  bool HasNormals = false;
  std::string ErrorMessage;

private:
  vtkPointCloudTextReader(const vtkPointCloudTextReader&) = delete;
  void operator=(const vtkPointCloudTextReader&) = delete;
};

#endif

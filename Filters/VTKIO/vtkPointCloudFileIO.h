/**
 * @class   vtkPointCloudFileIO
 * @brief   the one place that picks a reader or a writer by a file's extension
 *
 * Used by pcbilateral, pcbilateral_picture and Python scripts. Extensions (any case):
 * .txt and .xyz (the authors' text format, vtkPointCloudTextReader/Writer), .las and .laz
 * (LASzip-compressed LAS; vtkLASPointCloudReader/Writer), .pcd (PCL's format,
 * vtkPCDPointCloudReader/Writer), .ply (vtkPLYReader/Writer, binary) and .vtp
 * (vtkXMLPolyDataReader/Writer).
 *
 * Read() checks PLY and VTP files before VTK's readers see them, since those readers do not
 * stop at damaged files (a PLY file cut short reads as made-up points with thousands of
 * warnings; one announcing more vertices than it holds aborts the program): the PLY header
 * must name x, y and z vertex properties and the data after it must hold as many vertices as
 * it announces (bytes for binary files, lines and values for ASCII ones); a VTP file must be a
 * VTK XML file that ends with its closing tag (pcbilateral::CheckPLYFile and CheckVTPFile, in
 * the formats library). Every failure is one line naming the file and the problem, from
 * GetErrorMessage(); nothing is printed.
 *
 * Write() writes under a temporary name and renames (pcbilateral::ReplacingPath), so a failed
 * write leaves no file.
 *
 * Read() and Write() pass their reader's and writer's ProgressEvents on as this object's own
 * (the call data is the fraction done), for a program that shows the progress of each phase.
 *
 * @sa
 * vtkLASPointCloudReader vtkPointCloudTextReader
 */
#ifndef vtkPointCloudFileIO_h
#define vtkPointCloudFileIO_h

#include "vtkIOPointCloudBilateralModule.h" // For export macro
#include "vtkObject.h"
#include "vtkWrappingHints.h" // For VTK_NEWINSTANCE

#include <string> // For the messages
#include <vector> // For the warnings

class vtkAlgorithm;
class vtkPolyData;

class VTKIOPOINTCLOUDBILATERAL_EXPORT vtkPointCloudFileIO : public vtkObject
{
public:
  static vtkPointCloudFileIO* New();
  vtkTypeMacro(vtkPointCloudFileIO, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Text files: columns 4 to 6 are normals when read, and the normals are written (the
  /// authors' -R). Default off.
  vtkSetMacro(OrientedNormals, bool);
  vtkGetMacro(OrientedNormals, bool);
  vtkBooleanMacro(OrientedNormals, bool);
  ///@}

  ///@{
  /// PCD files: keep the points without coordinates (NaN) of an organised frame in place,
  /// so that it is written back with its WIDTH and HEIGHT (vtkPCDPointCloudReader). Default
  /// off: they are left out, and GetNumberOfDroppedPoints() says how many.
  vtkSetMacro(KeepNaNPoints, bool);
  vtkGetMacro(KeepNaNPoints, bool);
  vtkBooleanMacro(KeepNaNPoints, bool);
  ///@}

  ///@{
  /// COPC files: the deepest octree level read (-1, the default: every level), and whether
  /// only the points inside COPCBounds (xmin, xmax, ymin, ymax, zmin, zmax) are read
  /// (vtkLASPointCloudReader). Set for any other file: a warning, and every point is read.
  vtkSetClampMacro(COPCMaxLevel, int, -1, VTK_INT_MAX);
  vtkGetMacro(COPCMaxLevel, int);
  vtkSetMacro(COPCUseBounds, bool);
  vtkGetMacro(COPCUseBounds, bool);
  vtkSetVector6Macro(COPCBounds, double);
  vtkGetVector6Macro(COPCBounds, double);
  ///@}

  /// The points without coordinates (NaN) the last Read() left out (PCD files).
  vtkGetMacro(NumberOfDroppedPoints, vtkIdType);

  /// The warnings of the last Read() or Write(), one line each: what the target file cannot
  /// hold (a LAS file's coordinate system, scale and offset written to PCD), COPC options
  /// given for a file that is not COPC, say.
  int GetNumberOfWarnings() const { return static_cast<int>(this->Warnings.size()); }
  const char* GetWarning(int index) const { return this->Warnings.at(index).c_str(); }

  /// The extensions read and written, for messages: ".txt, .xyz, .las, .laz, .pcd, .ply or
  /// .vtp".
  static const char* GetSupportedExtensions();

  /// Whether the path's extension is one of them.
  static bool IsSupported(const char* path);

  /**
   * Whether a file of this name can be read (`forWriting` false) or written (true), judged by
   * its extension alone: an empty string, or one line naming the file and the problem (an
   * unsupported extension).
   */
  static std::string CheckFileName(const char* path, bool forWriting);

  /**
   * Whether `output` can take the result of filtering `input`, judged before the input is
   * read (a large cloud then filters for minutes): an empty string, or one line naming the
   * output and the problem, a folder that does not exist or the input file itself (which the
   * run would replace with its result).
   */
  static std::string CheckOutputPath(const char* output, const char* input);

  /// Whether the path names a file of the authors' text format (.txt, .xyz).
  static bool IsTextFormat(const char* path);

  /**
   * A new reader for the path's extension with its file name set, or nullptr for an unknown
   * extension. It is not run and the file is not checked (see CheckInputFile()). The caller
   * owns it.
   */
  VTK_NEWINSTANCE static vtkAlgorithm* NewReader(const char* path);

  /// A new writer for the path's extension with its file name set, or nullptr; the caller
  /// owns it. PLY writers write binary files.
  VTK_NEWINSTANCE static vtkAlgorithm* NewWriter(const char* path);

  /**
   * Checks a file before it is read: it exists and is not a folder; PLY and VTP files as said
   * above. Returns an empty string or a one-line message naming the file.
   */
  static std::string CheckInputFile(const char* path);

  /**
   * Reads a file into `output`: CheckInputFile(), then the reader of NewReader(). Returns
   * false with one line in GetErrorMessage() on failure (and `output` empty).
   */
  bool Read(const char* path, vtkPolyData* output);

  /// Writes `data` to `path` with the writer of NewWriter(). Returns false with one line in
  /// GetErrorMessage() on failure (a full disk too), leaving no file, or the file that was
  /// there as it was.
  bool Write(vtkPolyData* data, const char* path);

  /**
   * The message of a VTK ErrorEvent or WarningEvent (its call data) without what VTK's
   * macros add around it ("ERROR: In file.cxx, line N", "vtkClass (0x...): "): one line.
   */
  static std::string EventMessage(const char* callData);

  /// Why the last Read() or Write() failed; empty after a success.
  const char* GetErrorMessage() const { return this->ErrorMessage.c_str(); }

protected:
  vtkPointCloudFileIO();
  ~vtkPointCloudFileIO() override;

  bool OrientedNormals = false;
  bool KeepNaNPoints = false;
  int COPCMaxLevel = -1;
  bool COPCUseBounds = false;
  double COPCBounds[6] = { 0, 0, 0, 0, 0, 0 };
  vtkIdType NumberOfDroppedPoints = 0;
  std::vector<std::string> Warnings;
  std::string ErrorMessage;

private:
  vtkPointCloudFileIO(const vtkPointCloudFileIO&) = delete;
  void operator=(const vtkPointCloudFileIO&) = delete;
};

#endif

// A destination written under a temporary name beside it and moved onto it only once every
// write went well, so that a failed or interrupted write leaves no partial file. Writers that
// open the temporary file by name themselves (VTK's PLY and XML writers) use this class;
// ReplacingFile (ReplacingFile.h) opens it as a FILE* for the text and LAS writers.
#ifndef pcbilateral_ReplacingPath_h
#define pcbilateral_ReplacingPath_h

#include <string>

namespace pcbilateral
{

class ReplacingPath
{
public:
  /// How the temporary file is named after the destination.
  enum class TemporaryName
  {
    /// PATH.partial.
    Appended,
    /// NAME.partial.ext, the extension last and in lower case: vtkPLYWriter appends ".ply" to
    /// a name that does not end with it (case-sensitively). PATH.partial without an extension.
    ExtensionLast
  };

  explicit ReplacingPath(const std::string& path, TemporaryName naming = TemporaryName::Appended);

  /// Removes the temporary file unless Commit() ran.
  ~ReplacingPath();

  ReplacingPath(const ReplacingPath&) = delete;
  ReplacingPath& operator=(const ReplacingPath&) = delete;

  /// Where the writer writes until Commit().
  const std::string& GetTemporaryPath() const { return this->Temporary; }

  /// "PATH: cannot be written (reason)": the temporary file could not be created, for the
  /// reason of the errno value `error`.
  std::string OpenError(int error) const;

  /**
   * When `ok` (every write succeeded, the file is closed), moves the temporary file onto the
   * path; otherwise, or when the move fails, removes it. Returns an empty string or one line
   * naming the path: "PATH: write failed (reason)" when the temporary file was there,
   * OpenError() when the writer never created it. The reason is that of the failed move, else
   * of `failure` (an errno value) when given, else of errno.
   */
  std::string Commit(bool ok, int failure = 0);

private:
  std::string Path;
  std::string Temporary;
  bool Committed = false;
};

} // namespace pcbilateral

#endif

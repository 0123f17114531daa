// A file written beside its destination and moved onto it only once every write went well, so
// that a failed or interrupted write leaves no partial file (the text and LAS writers, which
// write through a FILE*; see ReplacingPath for writers that open the file themselves).
#ifndef pcbilateral_ReplacingFile_h
#define pcbilateral_ReplacingFile_h

#include "ReplacingPath.h"

#include <cerrno>
#include <cstdio>
#include <string>

namespace pcbilateral
{

class ReplacingFile
{
public:
  /// Opens `path` + ".partial" for writing (empty, and readable too: the LAS writer maps it,
  /// which needs a descriptor open for reading); Get() is null when that failed (see
  /// OpenError()).
  explicit ReplacingFile(const std::string& path)
    : Destination(path)
    , File(std::fopen(this->Destination.GetTemporaryPath().c_str(), "w+b"))
    , OpenErrno(errno)
  {
  }

  /// Closes the file; the temporary file is removed unless Commit() moved it.
  ~ReplacingFile()
  {
    if (this->File)
    {
      std::fclose(this->File);
    }
  }

  ReplacingFile(const ReplacingFile&) = delete;
  ReplacingFile& operator=(const ReplacingFile&) = delete;

  std::FILE* Get() const { return this->File; }

  /// "PATH: cannot be written (reason)", for a file that could not be opened.
  std::string OpenError() const { return this->Destination.OpenError(this->OpenErrno); }

  /// Closes the file and, when `ok` (every write succeeded), moves it onto the path; otherwise
  /// removes it. Returns an empty string or "PATH: write failed (reason)", the reason that of
  /// `failure` (an errno value) when given, else of errno.
  std::string Commit(bool ok, int failure = 0)
  {
    ok = (std::fclose(this->File) == 0) && ok;
    this->File = nullptr;
    return this->Destination.Commit(ok, failure);
  }

private:
  // Declared first: destroyed last, after the destructor closed the file.
  ReplacingPath Destination;
  std::FILE* File;
  int OpenErrno;
};

} // namespace pcbilateral

#endif

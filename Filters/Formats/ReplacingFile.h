// A file written beside its destination and moved onto it only once every write went well, so
// that a failed or interrupted write leaves no partial file (the text and LAS writers).
#ifndef pcbilateral_ReplacingFile_h
#define pcbilateral_ReplacingFile_h

#include <cerrno>
#include <cstdio>
#include <cstring>
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
    : Path(path)
    , Temporary(path + ".partial")
    , File(std::fopen(this->Temporary.c_str(), "w+b"))
    , OpenErrno(errno)
  {
  }

  /// Closes and removes the temporary file unless Commit() moved it.
  ~ReplacingFile()
  {
    if (this->File)
    {
      std::fclose(this->File);
      std::remove(this->Temporary.c_str());
    }
  }

  ReplacingFile(const ReplacingFile&) = delete;
  ReplacingFile& operator=(const ReplacingFile&) = delete;

  std::FILE* Get() const { return this->File; }

  /// "PATH: cannot be written (reason)", for a file that could not be opened.
  std::string OpenError() const
  {
    return this->Path + ": cannot be written (" + std::strerror(this->OpenErrno) + ")";
  }

  /// Closes the file and, when `ok` (every write succeeded), moves it onto the path; otherwise
  /// removes it. Returns an empty string or "PATH: write failed (reason)", the reason that of
  /// `failure` (an errno value) when given, else of errno.
  std::string Commit(bool ok, int failure = 0)
  {
    ok = (std::fclose(this->File) == 0) && ok;
    this->File = nullptr;
    if (!ok || std::rename(this->Temporary.c_str(), this->Path.c_str()) != 0)
    {
      const std::string reason = std::strerror(failure ? failure : errno);
      std::remove(this->Temporary.c_str());
      return this->Path + ": write failed (" + reason + ")";
    }
    return std::string();
  }

private:
  std::string Path;
  std::string Temporary;
  std::FILE* File;
  int OpenErrno;
};

} // namespace pcbilateral

#endif

// The fuzz targets' scratch file (one per process, at a path of the same length everywhere) and
// the checks every format's target makes of errors and refused writes.
#ifndef pcbilateral_FuzzScratchFile_h
#define pcbilateral_FuzzScratchFile_h

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <unistd.h>

/// P_tmpdir "/<stem>-<process id on 10 digits><extension>" (P_tmpdir is /tmp with glibc). The
/// path must not vary in length, or the coverage varies with it (string code inlined into the
/// instrumented code), and so the inputs that a reproducible run goes on to try: measured, a
/// 4-digit process id or a long TMPDIR gave other corpora. Hence the C library's fixed-width
/// formatting (std::to_string is instrumented code too) and no TMPDIR.
inline std::string FuzzScratchPath(const char* stem, const char* extension)
{
  char path[256];
  std::snprintf(
    path, sizeof path, "%s/%s-%010ld%s", P_tmpdir, stem, static_cast<long>(getpid()), extension);
  return path;
}

/// Aborts unless `error` is one line that starts by naming its source ("<source>: ...").
inline void CheckOneLine(const std::string& error, const std::string& source)
{
  if (error.compare(0, source.size() + 2, source + ": ") != 0 ||
      error.find('\n') != std::string::npos)
  {
    std::abort(); // an error must be one line naming the source
  }
}

/// After a write of `path` that returned `error`: whether it was refused, in which case its
/// message must be one line naming the file and no file may be left (else it aborts).
inline bool RefusedWithoutFile(const std::string& error, const std::string& path)
{
  if (error.empty())
  {
    return false;
  }
  CheckOneLine(error, path);
  std::error_code ignored;
  if (std::filesystem::exists(path, ignored))
  {
    std::abort(); // a refused write left a file
  }
  return true;
}

#endif

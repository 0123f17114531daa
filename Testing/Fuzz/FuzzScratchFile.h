// The fuzz targets' scratch file: one per process, at a path of the same length everywhere.
#ifndef pcbilateral_FuzzScratchFile_h
#define pcbilateral_FuzzScratchFile_h

#include <cstdio>
#include <string>
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

#endif

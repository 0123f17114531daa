// The bytes of a part of a file, for the checks that look at a file before a reader does, and of
// a whole file, for the readers that parse it from memory.
#ifndef pcbilateral_FileBytes_h
#define pcbilateral_FileBytes_h

#include "ProgressCheck.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

namespace pcbilateral
{

/// Up to `count` bytes of a file from `offset`: fewer at its end, none when it cannot be read.
inline std::string ReadFileBytes(const std::string& path, std::uintmax_t offset, std::size_t count)
{
  std::ifstream file(path, std::ios::binary);
  file.seekg(static_cast<std::streamoff>(offset));
  std::string bytes(count, '\0');
  file.read(&bytes[0], static_cast<std::streamsize>(count));
  bytes.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, file.gcount())));
  return bytes;
}

/// Points (or lines) between two ProgressPoint calls in a reader's or writer's loop over points.
constexpr std::size_t PointsPerProgressPoint = 16384;

/**
 * A whole file's bytes into `bytes`, read in blocks so that the read of a large file reports
 * progress and stops when asked (ProgressPoint). Returns an empty string, a one-line message
 * naming the file, or AbortedMessage.
 */
inline std::string ReadFileInBlocks(const std::string& path, std::string& bytes)
{
  constexpr std::size_t BlockBytes = std::size_t(8) << 20;
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file)
  {
    return path + ": cannot be opened";
  }
  const std::streamoff size = file.tellg();
  file.seekg(0);
  if (size < 0 || !file)
  {
    return path + ": cannot be read";
  }
  bytes.resize(static_cast<std::size_t>(size));
  const auto total = static_cast<std::size_t>(size);
  for (std::size_t offset = 0; offset < total; offset += BlockBytes)
  {
    if (ProgressPoint(offset, total))
    {
      bytes.clear();
      return AbortedMessage;
    }
    const std::size_t count = std::min(BlockBytes, total - offset);
    file.read(&bytes[offset], static_cast<std::streamsize>(count));
    if (static_cast<std::size_t>(file.gcount()) != count)
    {
      return path + ": cannot be read";
    }
  }
  return std::string();
}

/// Writes `count` bytes to `file` in blocks, so that a large write reports progress and stops
/// when asked (ProgressPoint). Returns whether every byte was written (false once stopped too).
inline bool WriteInBlocks(std::FILE* file, const std::uint8_t* bytes, std::size_t count)
{
  constexpr std::size_t BlockBytes = std::size_t(8) << 20;
  for (std::size_t offset = 0; offset < count; offset += BlockBytes)
  {
    const std::size_t block = std::min(BlockBytes, count - offset);
    if (ProgressPoint(offset, count) || std::fwrite(bytes + offset, 1, block, file) != block)
    {
      return false;
    }
  }
  return true;
}

} // namespace pcbilateral

#endif

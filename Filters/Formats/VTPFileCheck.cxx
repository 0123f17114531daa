#include "VTPFileCheck.h"

#include "FileBytes.h"

#include <cctype>
#include <filesystem>
#include <system_error>

namespace pcbilateral
{

std::string CheckVTPFile(const std::string& path)
{
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error)
  {
    return path + ": " + error.message();
  }
  const std::string head = ReadFileBytes(path, 0, 512);
  if (head.find("<VTKFile") == std::string::npos)
  {
    return path + ": not a VTK XML file (no <VTKFile> element at its start)";
  }
  std::string tail = ReadFileBytes(path, size > 64 ? size - 64 : 0, 64);
  while (!tail.empty() && std::isspace(static_cast<unsigned char>(tail.back())))
  {
    tail.pop_back();
  }
  const std::string closing = "</VTKFile>";
  if (tail.size() < closing.size() ||
      tail.compare(tail.size() - closing.size(), closing.size(), closing) != 0)
  {
    return path + ": truncated: the VTK XML file does not end with </VTKFile>";
  }
  return std::string();
}

} // namespace pcbilateral

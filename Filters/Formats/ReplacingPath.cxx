#include "ReplacingPath.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace pcbilateral
{
namespace
{
std::string TemporaryPathFor(const std::string& path, ReplacingPath::TemporaryName naming)
{
  std::string extension = std::filesystem::path(path).extension().string();
  if (naming == ReplacingPath::TemporaryName::Appended || extension.empty())
  {
    return path + ".partial";
  }
  std::transform(extension.begin(),
    extension.end(),
    extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return path.substr(0, path.size() - extension.size()) + ".partial" + extension;
}

/// The text of an errno value; 0 when a writer failed without setting errno.
std::string Reason(int error)
{
  return error ? std::strerror(error) : "the writer failed";
}
} // namespace

ReplacingPath::ReplacingPath(const std::string& path, TemporaryName naming)
  : Path(path)
  , Temporary(TemporaryPathFor(path, naming))
{
}

ReplacingPath::~ReplacingPath()
{
  if (!this->Committed)
  {
    std::remove(this->Temporary.c_str());
  }
}

std::string ReplacingPath::OpenError(int error) const
{
  return this->Path + ": cannot be written (" + Reason(error) + ")";
}

std::string ReplacingPath::Commit(bool ok, int failure)
{
  this->Committed = true;
  int error = failure ? failure : errno;
  if (ok)
  {
    if (std::rename(this->Temporary.c_str(), this->Path.c_str()) == 0)
    {
      return std::string();
    }
    error = errno;
  }
  const bool created = std::remove(this->Temporary.c_str()) == 0;
  return created ? this->Path + ": write failed (" + Reason(error) + ")" : this->OpenError(error);
}

} // namespace pcbilateral

#include "TemporaryFiles.h"

#include "OutOfCoreRun.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unistd.h>
#include <vector>

namespace pcbilateral
{

namespace
{
constexpr std::size_t PathBytes = 1024;
// What a signal handler may read: plain arrays, written before the files exist.
char RegisteredFolder[PathBytes];
char RegisteredFiles[TemporaryFiles::MaximumFiles][PathBytes];
char ExtraPath[PathBytes];
volatile std::sig_atomic_t FolderRegistered = 0;

void RemoveRegistered()
{
  if (FolderRegistered)
  {
    for (std::size_t f = 0; f < TemporaryFiles::MaximumFiles; ++f)
    {
      if (RegisteredFiles[f][0] != '\0')
      {
        ::unlink(RegisteredFiles[f]);
      }
    }
    ::rmdir(RegisteredFolder);
  }
  if (ExtraPath[0] != '\0')
  {
    ::unlink(ExtraPath);
  }
}

extern "C" void RemoveAtExit()
{
  RemoveRegistered();
}

extern "C" void RemoveAndExit(int signal)
{
  RemoveRegistered();
  ::_exit(128 + signal);
}
} // namespace

TemporaryFiles::~TemporaryFiles()
{
  this->RemoveAll();
}

std::string TemporaryFiles::Create(const std::string& parent)
{
  std::string pattern = (parent.empty() ? std::string(".") : parent) + "/pcbilateral-XXXXXX";
  if (pattern.size() + 16 >= PathBytes)
  {
    return parent + ": the path of the temporary folder is too long";
  }
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  if (::mkdtemp(name.data()) == nullptr)
  {
    return "cannot make a temporary folder in " + parent + " (" + std::strerror(errno) +
           "): set TMPDIR to a folder with room";
  }
  this->Folder = name.data();
  std::memset(RegisteredFiles, 0, sizeof RegisteredFiles);
  std::snprintf(RegisteredFolder, sizeof RegisteredFolder, "%s", this->Folder.c_str());
  FolderRegistered = 1;
  return std::string();
}

std::string TemporaryFiles::PathOf(std::size_t number)
{
  char path[PathBytes];
  std::snprintf(path, sizeof path, "%s/%04zu.bin", this->Folder.c_str(), number);
  if (number < MaximumFiles && FolderRegistered)
  {
    std::memcpy(RegisteredFiles[number], path, sizeof path);
  }
  return path;
}

void TemporaryFiles::RemoveAll()
{
  if (this->Folder.empty())
  {
    return;
  }
  for (std::size_t f = 0; f < MaximumFiles; ++f)
  {
    if (RegisteredFiles[f][0] != '\0')
    {
      ::unlink(RegisteredFiles[f]);
      RegisteredFiles[f][0] = '\0';
    }
  }
  ::rmdir(this->Folder.c_str());
  FolderRegistered = 0;
  this->Folder.clear();
}

void RemoveTemporaryFilesOnSignals(const std::string& extraPath)
{
  std::snprintf(ExtraPath, sizeof ExtraPath, "%s", extraPath.c_str());
  // Also at exit(): an error reported with exit() runs no destructor.
  std::atexit(RemoveAtExit);
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = RemoveAndExit;
  sigemptyset(&action.sa_mask);
  for (int signal : { SIGINT, SIGTERM, SIGHUP })
  {
    sigaction(signal, &action, nullptr);
  }
}

} // namespace pcbilateral

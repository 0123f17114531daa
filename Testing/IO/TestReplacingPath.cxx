// The replace-the-file helpers (ReplacingPath.h, ReplacingFile.h): the temporary names, the
// move onto the destination only after a success, the old file kept and nothing left behind
// after a failure, and the messages.
#include "CoreTesting.h"

#include "ReplacingFile.h"
#include "ReplacingPath.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/stat.h>

namespace
{
using pcbilateral::ReplacingFile;
using pcbilateral::ReplacingPath;

bool Exists(const std::string& path)
{
  struct stat status;
  return stat(path.c_str(), &status) == 0;
}

using pcbilateral_testing::FileContents;
using pcbilateral_testing::WriteFileContents;

void ExpectTemporary(const std::string& path,
  ReplacingPath::TemporaryName naming,
  const std::string& expected)
{
  const ReplacingPath destination(path, naming);
  PCB_CHECK(destination.GetTemporaryPath() == expected,
    "%s: %s instead of %s",
    path.c_str(),
    destination.GetTemporaryPath().c_str(),
    expected.c_str());
}

void TemporaryNames()
{
  using Name = ReplacingPath::TemporaryName;
  ExpectTemporary("dir/out.xyz", Name::Appended, "dir/out.xyz.partial");
  ExpectTemporary("dir/out.ply", Name::ExtensionLast, "dir/out.partial.ply");
  // vtkPLYWriter appends ".ply" to a name that does not end with it, case-sensitively.
  ExpectTemporary("dir/OUT.PLY", Name::ExtensionLast, "dir/OUT.partial.ply");
  ExpectTemporary("dir.d/out", Name::ExtensionLast, "dir.d/out.partial");
  ExpectTemporary("a.b.vtp", Name::ExtensionLast, "a.b.partial.vtp");
  ExpectTemporary("dir/.ply", Name::ExtensionLast, "dir/.ply.partial");
}

void CommitAndFailures()
{
  const std::string path = "replaced.ply";
  WriteFileContents(path, "old");
  {
    ReplacingPath destination(path, ReplacingPath::TemporaryName::ExtensionLast);
    WriteFileContents(destination.GetTemporaryPath(), "new");
    PCB_CHECK(FileContents(path) == "old", "the file changed before the commit");
    const std::string problem = destination.Commit(true);
    PCB_CHECK(problem.empty(), "%s", problem.c_str());
  }
  PCB_CHECK(
    FileContents(path) == "new" && !Exists("replaced.partial.ply"), "not moved onto the path");
  {
    ReplacingPath destination(path, ReplacingPath::TemporaryName::ExtensionLast);
    WriteFileContents(destination.GetTemporaryPath(), "cut");
    const std::string problem = destination.Commit(false, EIO);
    const std::string expected = path + ": write failed (" + std::strerror(EIO) + ")";
    PCB_CHECK(problem == expected, "\"%s\" instead of \"%s\"", problem.c_str(), expected.c_str());
  }
  PCB_CHECK(FileContents(path) == "new" && !Exists("replaced.partial.ply"),
    "a failed write changed the file or left its temporary file");
  {
    ReplacingPath destination(path, ReplacingPath::TemporaryName::ExtensionLast);
    const std::string problem = destination.Commit(false, ENOENT);
    const std::string expected = path + ": cannot be written (" + std::strerror(ENOENT) + ")";
    PCB_CHECK(problem == expected, "\"%s\" instead of \"%s\"", problem.c_str(), expected.c_str());
  }
  {
    ReplacingPath destination(path);
    WriteFileContents(destination.GetTemporaryPath(), "abandoned");
  }
  PCB_CHECK(!Exists(path + ".partial") && FileContents(path) == "new",
    "a temporary file outlived its ReplacingPath");
  std::remove(path.c_str());
}

void FailedMove()
{
  // A folder that is not empty cannot be replaced by a file.
  const std::string folder = "replaced-folder.xyz";
  mkdir(folder.c_str(), 0755);
  WriteFileContents(folder + "/inside", "x");
  ReplacingPath destination(folder);
  WriteFileContents(destination.GetTemporaryPath(), "new");
  const std::string problem = destination.Commit(true);
  PCB_CHECK(problem.rfind(folder + ": write failed (", 0) == 0 && !Exists(folder + ".partial"),
    "%s",
    problem.c_str());
  std::remove((folder + "/inside").c_str());
  std::remove(folder.c_str());
}

void ReplacingFiles()
{
  const std::string path = "replacing-file.xyz";
  {
    ReplacingFile output(path);
    PCB_CHECK(
      output.Get() != nullptr && Exists(path + ".partial"), "%s", output.OpenError().c_str());
    std::fputs("0 0 0\n", output.Get());
    const std::string problem = output.Commit(true);
    PCB_CHECK(problem.empty(), "%s", problem.c_str());
  }
  PCB_CHECK(FileContents(path) == "0 0 0\n" && !Exists(path + ".partial"), "not written");
  {
    ReplacingFile output(path);
    std::fputs("1 1 1\n", output.Get()); // never committed
  }
  PCB_CHECK(
    FileContents(path) == "0 0 0\n" && !Exists(path + ".partial"), "an abandoned write stayed");
  std::remove(path.c_str());
  const ReplacingFile nowhere("no/such/folder/out.xyz");
  const std::string expected =
    "no/such/folder/out.xyz: cannot be written (" + std::string(std::strerror(ENOENT)) + ")";
  PCB_CHECK(!nowhere.Get() && nowhere.OpenError() == expected, "%s", nowhere.OpenError().c_str());
}
} // namespace

int main(int argc, char* argv[])
{
  return RunNamedCase(argc,
    argv,
    { { "temporary-names", TemporaryNames },
      { "commit", CommitAndFailures },
      { "failed-move", FailedMove },
      { "replacing-file", ReplacingFiles } });
}

// vtkPointCloudFileIO::Write in every format: extensions in any case give the file asked for,
// and a write that fails part-way (a file larger than the process may write, as on a full
// disk) says so in one line and leaves the old file as it was, with no temporary file beside.
#include "CoreTesting.h"
#include "FileSizeLimit.h"
#include "VTKTesting.h"

#include "vtkLASPointCloudWriter.h"
#include "vtkPointCloudFileIO.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace
{
const char* const Names[] = { "OUT.PLY", "Out.Vtp", "OUT.XYZ", "Out.Las" };

/// A cloud of `count` points on a slanted plane.
vtkSmartPointer<vtkPolyData> MakePlane(int count)
{
  std::vector<double> xyz;
  for (int i = 0; i < count; ++i)
  {
    xyz.insert(xyz.end(), { 0.001 * (i % 1000), 0.001 * (i / 1000), 0.0002 * i });
  }
  return pcbilateral_testing::MakeCloud(xyz);
}

/// The names of the files in the working folder.
std::set<std::string> Files()
{
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator("."))
  {
    names.insert(entry.path().filename().string());
  }
  return names;
}

void RemoveFiles()
{
  for (const std::string& name : Files())
  {
    std::filesystem::remove(name);
  }
}

void UpperCaseExtensions()
{
  RemoveFiles();
  vtkSmartPointer<vtkPolyData> cloud = MakePlane(100);
  vtkNew<vtkPointCloudFileIO> io;
  for (const char* name : Names)
  {
    PCB_CHECK(io->Write(cloud, name), "%s", io->GetErrorMessage());
    vtkNew<vtkPolyData> back;
    PCB_CHECK(io->Read(name, back) && back->GetNumberOfPoints() == 100,
      "%s: %s",
      name,
      io->GetErrorMessage());
  }
  const std::set<std::string> expected(std::begin(Names), std::end(Names));
  PCB_CHECK(Files() == expected, "other files than those asked for were written");
}

/// Writes `cloud` to `name` allowed files of `limit` bytes at most; the error message.
std::string WriteLimited(vtkPolyData* cloud, const std::string& name, rlim_t limit)
{
  vtkNew<vtkPointCloudFileIO> io;
  bool written = false;
  {
    const pcbilateral_testing::FileSizeLimit sizeLimit(limit);
    written = io->Write(cloud, name.c_str());
  }
  return written ? std::string() : io->GetErrorMessage();
}

void WriteBeyondLimit()
{
  RemoveFiles();
  vtkSmartPointer<vtkPolyData> cloud = MakePlane(200000); // about 2.4 MB in PLY, the least
  for (const char* name : Names)
  {
    std::ofstream(name, std::ios::binary) << "the old file";
  }
  for (const char* name : Names)
  {
    const std::string message = WriteLimited(cloud, name, 1000000);
    const std::string expected = std::string(name) + ": write failed (";
    PCB_CHECK(
      message.compare(0, expected.size(), expected) == 0 && message.find('\n') == std::string::npos,
      "%s: \"%s\" instead of \"%s...)\"",
      name,
      message.c_str(),
      expected.c_str());
    PCB_CHECK(pcbilateral_testing::FileContents(name) == "the old file",
      "%s: a failed write changed the file",
      name);
  }
  const std::set<std::string> expected(std::begin(Names), std::end(Names));
  PCB_CHECK(Files() == expected, "a failed write left a file behind");
}

/// The LAS writer without a file name, null or empty: one message, no file.
void NoFileName()
{
  RemoveFiles();
  vtkSmartPointer<vtkPolyData> cloud = MakePlane(10);
  vtkNew<vtkCallbackCommand> quiet; // the message is read from the writer, not printed
  for (const char* name : { static_cast<const char*>(nullptr), "" })
  {
    vtkNew<vtkLASPointCloudWriter> writer;
    writer->AddObserver(vtkCommand::ErrorEvent, quiet);
    writer->SetFileName(name);
    writer->SetInputData(cloud);
    writer->Write();
    PCB_CHECK(std::string(writer->GetErrorMessage()) == "no file name was given",
      "\"%s\" instead of \"no file name was given\"",
      writer->GetErrorMessage());
  }
  PCB_CHECK(Files().empty(), "a file was written");
}
} // namespace

int main(int argc, char* argv[])
{
  return RunNamedCase(argc,
    argv,
    { { "upper-case-extensions", UpperCaseExtensions },
      { "beyond-size-limit", WriteBeyondLimit },
      { "no-file-name", NoFileName } });
}

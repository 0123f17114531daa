// pcbilateral: denoise a point cloud file with the bilateral filter of Digne & de Franchis
// (IPOL 2017), with the option letters of the authors' program.
//
//   pcbilateral INPUT OUTPUT [-r R] [-n RN] [-N ITER] [-R] [-t THREADS] [--remove-isolated]
//
// Formats by extension: .txt and .xyz (the authors' ASCII format), .ply, .vtp. Errors print
// one line and exit with status 1. Run with -h for the options.
#include "BilateralFilter.h"
#include "vtkPointCloudBilateralFilter.h"
#include "vtkPointCloudTextReader.h"
#include "vtkPointCloudTextWriter.h"

#include "vtkAlgorithm.h"
#include "vtkFloatArray.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPLYReader.h"
#include "vtkPLYWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace
{
const char* const Usage =
  "usage: pcbilateral INPUT OUTPUT [-r R] [-n RN] [-N ITER] [-R] [-t THREADS] [--remove-isolated]\n"
  "\n"
  "Denoises a point cloud with the bilateral filter (Digne & de Franchis, IPOL 2017).\n"
  "INPUT and OUTPUT: .txt or .xyz (x y z [nx ny nz] [more columns]), .ply or .vtp.\n"
  "\n"
  "  -r R               neighbourhood radius (default: sqrt(20 / points) x largest extent)\n"
  "  -n RN              normal radius, the tolerance to the tangent plane (default: R)\n"
  "  -N ITER            number of iterations (default 1)\n"
  "  -R                 text files carry oriented normals in columns 4-6; the estimated\n"
  "                     normals are oriented by them and they are written back\n"
  "  -t THREADS         threads (default 0: all cores); the result does not depend on it\n"
  "  --remove-isolated  remove points with fewer than 5 neighbours, as the authors' program\n"
  "                     does (default: they stay where they are)\n"
  "  -p                 accepted for compatibility and ignored: the filter always runs in "
  "parallel\n"
  "  -h, --help         this text\n";

/// Prints VTK's errors and warnings as one line each, without the source location.
class OneLineOutputWindow : public vtkOutputWindow
{
public:
  static OneLineOutputWindow* New();
  vtkTypeMacro(OneLineOutputWindow, vtkOutputWindow);

  void DisplayText(const char* text) override
  {
    std::string message = text ? text : "";
    // "ERROR: In file.cxx, line N\nvtkClass (0x...): the message\n\n"
    const std::size_t lineEnd = message.find('\n');
    if (lineEnd != std::string::npos && message.compare(0, 3, "In ") != 0)
    {
      const std::size_t objectEnd = message.find("): ", lineEnd);
      if (objectEnd != std::string::npos)
      {
        message = message.substr(objectEnd + 3);
      }
    }
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
    {
      message.pop_back();
    }
    const bool isError = this->GetCurrentMessageType() == vtkOutputWindow::MESSAGE_TYPE_ERROR;
    if (isError && this->ErrorSeen)
    {
      return; // the pipeline's own report of the same failure
    }
    std::fprintf(stderr, "pcbilateral: %s%s\n", isError ? "error: " : "warning: ", message.c_str());
    this->ErrorSeen = this->ErrorSeen || isError;
  }
  bool ErrorSeen = false;
};
vtkStandardNewMacro(OneLineOutputWindow);

[[noreturn]] void Fail(const std::string& message)
{
  std::fprintf(stderr, "pcbilateral: error: %s\n", message.c_str());
  std::exit(EXIT_FAILURE);
}

std::string Extension(const std::string& path)
{
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return std::string();
  }
  std::string extension = path.substr(dot);
  std::transform(extension.begin(),
    extension.end(),
    extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

bool IsText(const std::string& extension)
{
  return extension == ".txt" || extension == ".xyz";
}

void CheckFormat(const std::string& path)
{
  const std::string extension = Extension(path);
  if (!IsText(extension) && extension != ".ply" && extension != ".vtp")
  {
    Fail(path + ": unsupported file type '" + extension + "' (use .txt, .xyz, .ply or .vtp)");
  }
}

/// A number; whether it is an acceptable radius is the core's to say (CheckParameters).
double ParseNumber(const char* option, const char* text)
{
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0')
  {
    Fail(std::string(option) + ": '" + text + "' is not a number");
  }
  return value;
}

/// A whole number; its limits are the core's (CheckParameters).
int ParseCount(const char* option, const char* text)
{
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || errno == ERANGE || value < INT_MIN || value > INT_MAX)
  {
    Fail(std::string(option) + ": '" + text + "' is not a whole number");
  }
  return static_cast<int>(value);
}

struct Options
{
  std::string Input, Output;
  // The core's defaults.
  double Radius = pcbilateral::BilateralParameters().Radius;
  double NormalRadius = pcbilateral::BilateralParameters().NormalRadius;
  int Iterations = pcbilateral::BilateralParameters().NumberOfIterations;
  bool OrientedNormals = false;
  int Threads = pcbilateral::BilateralParameters().NumberOfThreads;
  bool RemoveIsolated = pcbilateral::BilateralParameters().RemoveIsolatedPoints;
};

Options ParseArguments(int argc, char* argv[])
{
  Options options;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    auto value = [&]() -> const char*
    {
      if (i + 1 >= argc)
      {
        Fail(argument + " needs a value");
      }
      return argv[++i];
    };
    if (argument == "-h" || argument == "--help")
    {
      std::fputs(Usage, stdout);
      std::exit(EXIT_SUCCESS);
    }
    else if (argument == "-r")
    {
      options.Radius = ParseNumber("-r", value());
    }
    else if (argument == "-n")
    {
      options.NormalRadius = ParseNumber("-n", value());
    }
    else if (argument == "-N")
    {
      options.Iterations = ParseCount("-N", value());
    }
    else if (argument == "-t")
    {
      options.Threads = ParseCount("-t", value());
    }
    else if (argument == "-R")
    {
      options.OrientedNormals = true;
    }
    else if (argument == "-p")
    {
      // The authors' "parallel" switch: always on here.
    }
    else if (argument == "--remove-isolated")
    {
      options.RemoveIsolated = true;
    }
    else if (argument.size() > 1 && argument[0] == '-')
    {
      Fail("unknown option '" + argument + "' (see pcbilateral -h)");
    }
    else
    {
      positional.push_back(argument);
    }
  }
  if (positional.size() != 2)
  {
    std::fputs(Usage, stderr);
    std::exit(EXIT_FAILURE);
  }
  options.Input = positional[0];
  options.Output = positional[1];
  // The core's checks and messages, before any file is read.
  pcbilateral::BilateralParameters parameters;
  parameters.Radius = options.Radius;
  parameters.NormalRadius = options.NormalRadius;
  parameters.NumberOfIterations = options.Iterations;
  parameters.NumberOfThreads = options.Threads;
  const std::string problem = pcbilateral::CheckParameters(parameters);
  if (!problem.empty())
  {
    Fail(problem);
  }
  CheckFormat(options.Input);
  CheckFormat(options.Output);
  return options;
}

vtkSmartPointer<vtkAlgorithm> MakeReader(const Options& options)
{
  struct stat status;
  if (stat(options.Input.c_str(), &status) != 0)
  {
    Fail(options.Input + ": " + std::strerror(errno));
  }
  if (S_ISDIR(status.st_mode))
  {
    Fail(options.Input + ": is a directory, not a point file");
  }
  const std::string extension = Extension(options.Input);
  if (IsText(extension))
  {
    auto reader = vtkSmartPointer<vtkPointCloudTextReader>::New();
    reader->SetFileName(options.Input.c_str());
    reader->SetHasNormals(options.OrientedNormals);
    return reader;
  }
  if (extension == ".ply")
  {
    auto reader = vtkSmartPointer<vtkPLYReader>::New();
    reader->SetFileName(options.Input.c_str());
    return reader;
  }
  auto reader = vtkSmartPointer<vtkXMLPolyDataReader>::New();
  reader->SetFileName(options.Input.c_str());
  return reader;
}

/// Writes PLY and VTP under a temporary name, then renames, so no partial file is left.
bool WriteOutput(const Options& options, vtkPolyData* cloud)
{
  const std::string extension = Extension(options.Output);
  if (IsText(extension))
  {
    // The authors' layout: the input's columns in order, no columns of the filter's own.
    cloud->GetPointData()->RemoveArray("vtkOriginalPointIds");
    vtkNew<vtkPointCloudTextWriter> writer;
    writer->SetFileName(options.Output.c_str());
    writer->SetWriteNormals(options.OrientedNormals);
    writer->SetInputData(cloud);
    return writer->Write() == 1 && writer->GetErrorMessage()[0] == '\0';
  }
  // The PLY writer appends ".ply" to a name without it: keep the extension last.
  const std::string temporary =
    options.Output.substr(0, options.Output.size() - extension.size()) + ".partial" + extension;
  // The writers' own messages do not name the file: this program's one line below does.
  vtkObject::GlobalWarningDisplayOff();
  int written = 0;
  if (extension == ".ply")
  {
    vtkNew<vtkPLYWriter> writer;
    writer->SetFileName(temporary.c_str());
    writer->SetFileTypeToBinary();
    // PLY stores float normals only.
    vtkDataArray* normals = cloud->GetPointData()->GetNormals();
    if (normals && normals->GetDataType() != VTK_FLOAT)
    {
      vtkNew<vtkFloatArray> floatNormals;
      floatNormals->DeepCopy(normals);
      cloud->GetPointData()->SetNormals(floatNormals);
    }
    for (const char* colours : { "RGB", "RGBA" })
    {
      if (cloud->GetPointData()->GetArray(colours))
      {
        writer->SetArrayName(colours);
      }
    }
    writer->SetInputData(cloud);
    written = writer->Write();
  }
  else
  {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetFileName(temporary.c_str());
    writer->SetInputData(cloud);
    written = writer->Write();
  }
  vtkObject::GlobalWarningDisplayOn();
  if (written != 1 || std::rename(temporary.c_str(), options.Output.c_str()) != 0)
  {
    const std::string reason = std::strerror(errno);
    std::remove(temporary.c_str());
    Fail(options.Output + ": cannot be written (" + reason + ")");
  }
  return true;
}
} // namespace

/**
 * Runs the program again with glibc's malloc asked to back its memory with transparent huge
 * pages, unless the user set glibc's tunables already. A cloud of millions of points takes
 * hundreds of megabytes, touched once each: with 4 KB pages that is a page fault every 4 KB,
 * which costs more than reading and writing the text (measured on a virtual machine: 0.78 s
 * against 0.28 s for reading and writing 600,000 points). The tunable can only be given at
 * start-up, hence the new start; if it fails, the program goes on as it is.
 */
void RestartWithHugePages(char* argv[])
{
  if (std::getenv("GLIBC_TUNABLES") != nullptr)
  {
    return;
  }
  if (setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 0) == 0)
  {
    execv("/proc/self/exe", argv);
  }
}

int main(int argc, char* argv[])
{
  RestartWithHugePages(argv);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  vtkNew<OneLineOutputWindow> messages;
  vtkOutputWindow::SetInstance(messages);
  const Options options = ParseArguments(argc, argv);

  vtkSmartPointer<vtkAlgorithm> reader = MakeReader(options);
  reader->Update();
  vtkPolyData* input = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (messages->ErrorSeen || !input)
  {
    return EXIT_FAILURE;
  }
  if (input->GetNumberOfPoints() == 0)
  {
    Fail(options.Input + ": contains no points");
  }

  vtkNew<vtkPointCloudBilateralFilter> filter;
  filter->SetInputData(input);
  filter->SetRadius(options.Radius);
  filter->SetNormalRadius(options.NormalRadius);
  filter->SetNumberOfIterations(options.Iterations);
  filter->SetNumberOfThreads(options.Threads);
  filter->SetRemoveIsolatedPoints(options.RemoveIsolated);
  const auto start = std::chrono::steady_clock::now();
  filter->Update();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (messages->ErrorSeen)
  {
    return EXIT_FAILURE;
  }

  vtkNew<vtkPolyData> output;
  output->ShallowCopy(filter->GetOutput());
  std::printf("input:         %s, %lld points\n",
    options.Input.c_str(),
    static_cast<long long>(input->GetNumberOfPoints()));
  std::printf("radius:        %.9g%s\n",
    filter->GetRadiusUsed(),
    options.Radius > 0.0 ? "" : " (automatic: sqrt(20 / points) x largest extent)");
  std::printf("normal radius: %.9g%s\n",
    filter->GetNormalRadiusUsed(),
    options.NormalRadius > 0.0 ? "" : " (same as the radius)");
  std::printf("iterations:    %d\n", options.Iterations);
  if (options.RemoveIsolated)
  {
    std::printf("removed:       %lld isolated points\n",
      static_cast<long long>(filter->GetNumberOfRemovedPoints()));
  }
  std::printf("filtering:     %.3f s\n", seconds);
  if (!WriteOutput(options, output))
  {
    return EXIT_FAILURE;
  }
  std::printf("output:        %s, %lld points\n",
    options.Output.c_str(),
    static_cast<long long>(output->GetNumberOfPoints()));
  return EXIT_SUCCESS;
}

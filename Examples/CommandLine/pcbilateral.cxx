// pcbilateral: denoise a point cloud file with the bilateral filter of Digne & de Franchis
// (IPOL 2017), with the option letters of the authors' program.
//
//   pcbilateral INPUT OUTPUT [-r R] [-n RN] [-N ITER] [--paper] [-R] [-t THREADS]
//               [--remove-isolated] [--edge-aware] [--keep-nan] [-q]
//               [--classes LIST [--class-array NAME]]
//               [--copc-level N] [--copc-bounds xmin,xmax,ymin,ymax,zmin,zmax]
//               [--memory-limit SIZE]
//
// Formats by extension: .txt and .xyz (the authors' ASCII format), .las, .laz, .pcd, .ply,
// .vtp. Errors print one line and exit with status 1; a damaged input file is an error, never
// a cloud. Run with -h for the options.
#include "BilateralFilter.h"
#include "OutOfCoreRun.h"
#include "StreamedArrays.h"
#include "StreamedFile.h"
#include "StreamedLAS.h"
#include "Threads.h"
#include "pcbilateral_checks.h"
#include "pcbilateral_help.h"
#include "pcbilateral_progress.h"
#include "vtkPointCloudBilateralFilter.h"
#include "vtkPointCloudFileIO.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{
using pcbilateral_cli::HelpText;
using pcbilateral_cli::Say;
using pcbilateral_cli::Screen;
/// Swallows what VTK prints by itself: the messages that matter come from the observers of
/// the reader, the filter and the writer (see ReportMessages); the rest repeat them (the
/// pipeline's "returned failure" reports) or are internals of VTK's readers.
class QuietOutputWindow : public vtkOutputWindow
{
public:
  static QuietOutputWindow* New();
  vtkTypeMacro(QuietOutputWindow, vtkOutputWindow);
  void DisplayText(const char*) override {}
};
vtkStandardNewMacro(QuietOutputWindow);

/// The "input:" line of the points without coordinates a PCD reader left out.
void SayDropped(unsigned long long dropped)
{
  if (dropped > 0)
  {
    Say("input:         dropped %llu points without coordinates (NaN)\n", dropped);
  }
}

/// Prints the filter's errors and warnings as one line each, as they arise.
struct ReportMessages
{
  bool ErrorSeen = false;
  vtkNew<vtkCallbackCommand> Command;

  void Observe(vtkObject* object)
  {
    this->Command->SetClientData(this);
    this->Command->SetCallback(
      [](vtkObject*, unsigned long event, void* clientData, void* callData)
      {
        auto* self = static_cast<ReportMessages*>(clientData);
        const std::string message =
          vtkPointCloudFileIO::EventMessage(static_cast<const char*>(callData));
        const bool isError = event == vtkCommand::ErrorEvent;
        if (!(isError && self->ErrorSeen))
        {
          Screen().ClearBar();
          std::fprintf(
            stderr, "pcbilateral: %s%s\n", isError ? "error: " : "warning: ", message.c_str());
        }
        self->ErrorSeen = self->ErrorSeen || isError;
      });
    object->AddObserver(vtkCommand::ErrorEvent, this->Command);
    object->AddObserver(vtkCommand::WarningEvent, this->Command);
  }
};

[[noreturn]] void Fail(const std::string& message)
{
  Screen().ClearBar();
  std::fprintf(stderr, "pcbilateral: error: %s\n", message.c_str());
  std::exit(EXIT_FAILURE);
}

void CheckFileName(const std::string& path, bool output)
{
  const std::string problem = vtkPointCloudFileIO::CheckFileName(path.c_str(), output);
  if (!problem.empty())
  {
    Fail(problem);
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
  if (end == text || *end != '\0')
  {
    Fail(std::string(option) + ": '" + text + "' is not a whole number");
  }
  if (errno == ERANGE || value < INT_MIN || value > INT_MAX)
  {
    Fail(std::string(option) + ": '" + text + "' is out of range");
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
  pcbilateral::AutomaticParameters Automatic = pcbilateral::BilateralParameters().Automatic;
  bool OrientedNormals = false;
  int Threads = pcbilateral::BilateralParameters().NumberOfThreads;
  bool RemoveIsolated = pcbilateral::BilateralParameters().RemoveIsolatedPoints;
  bool EdgeAware = pcbilateral::BilateralParameters().EdgeAware;
  std::vector<long long> Classes;
  std::string ClassArray = "Classification";
  bool KeepNaNPoints = false;
  int COPCLevel = -1;
  bool COPCUseBounds = false;
  double COPCBounds[6] = { 0, 0, 0, 0, 0, 0 };
  bool Quiet = false;
  /// --memory-limit in bytes (0: none given).
  std::uint64_t MemoryLimit = 0;
};

/// --copc-level N (N >= -1) and --copc-bounds xmin,xmax,ymin,ymax,zmin,zmax at argv[i] (and
/// its value, advancing i); false when argv[i] is neither.
bool ParseCOPCOption(int argc, char* argv[], int& i, Options& options)
{
  const std::string option = argv[i];
  if (option != "--copc-level" && option != "--copc-bounds")
  {
    return false;
  }
  if (++i >= argc)
  {
    Fail(option + " needs a value");
  }
  const char* text = argv[i];
  if (option == "--copc-level")
  {
    options.COPCLevel = ParseCount("--copc-level", text);
    if (options.COPCLevel < -1)
    {
      Fail(std::string("--copc-level: '") + text + "' is not a level (0 or more, -1: all)");
    }
    return true;
  }
  const char* at = text;
  for (int i = 0; i < 6; ++i)
  {
    char* end = nullptr;
    options.COPCBounds[i] = std::strtod(at, &end);
    const bool last = i == 5;
    if (end == at || *end != (last ? '\0' : ',') || !std::isfinite(options.COPCBounds[i]) ||
        (i % 2 == 1 && options.COPCBounds[i] < options.COPCBounds[i - 1]))
    {
      Fail(std::string("--copc-bounds: '") + text +
           "' is not six numbers xmin,xmax,ymin,ymax,zmin,zmax with each min <= max");
    }
    at = end + 1;
  }
  options.COPCUseBounds = true;
  return true;
}

/// --memory-limit SIZE at argv[i] (and its value, advancing i); false when argv[i] is not it.
bool ParseMemoryOption(int argc, char* argv[], int& i, Options& options)
{
  if (std::string(argv[i]) != "--memory-limit")
  {
    return false;
  }
  if (++i >= argc)
  {
    Fail("--memory-limit needs a value");
  }
  options.MemoryLimit = pcbilateral::ParseMemorySize(argv[i]);
  if (options.MemoryLimit == 0)
  {
    Fail(std::string("--memory-limit: '") + argv[i] + "' is not a size (e.g. 512M, 2G)");
  }
  return true;
}

/// --classes LIST: integers separated by commas.
std::vector<long long> ParseClasses(const char* text)
{
  std::vector<long long> classes;
  const char* at = text;
  while (true)
  {
    char* end = nullptr;
    errno = 0;
    const long long value = std::strtoll(at, &end, 10);
    if (end == at || errno == ERANGE || (*end != ',' && *end != '\0'))
    {
      Fail(std::string("--classes: '") + text +
           "' is not a list of whole numbers separated by commas (e.g. 2,6)");
    }
    classes.push_back(value);
    if (*end == '\0')
    {
      return classes;
    }
    at = end + 1;
  }
}

/// Reads the option at argv[i] (and its value, advancing i) into options; false when argv[i] is
/// not an option.
bool ParseOption(int argc, char* argv[], int& i, Options& options)
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
    std::fputs(HelpText().c_str(), stdout);
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
  else if (argument == "--paper")
  {
    options.Automatic = pcbilateral::AutomaticParameters::Paper;
  }
  else if (argument == "--remove-isolated")
  {
    options.RemoveIsolated = true;
  }
  else if (argument == "--edge-aware")
  {
    options.EdgeAware = true;
  }
  else if (argument == "--classes")
  {
    options.Classes = ParseClasses(value());
  }
  else if (argument == "--class-array")
  {
    options.ClassArray = value();
  }
  else if (argument == "--keep-nan")
  {
    options.KeepNaNPoints = true;
  }
  else if (argument == "--quiet" || argument == "-q")
  {
    options.Quiet = true;
  }
  else if (argument.size() > 1 && argument[0] == '-')
  {
    Fail("unknown option '" + argument + "' (see pcbilateral -h)");
  }
  else
  {
    return false;
  }
  return true;
}

/// The core's parameters the options give.
pcbilateral::BilateralParameters CoreParameters(const Options& options)
{
  pcbilateral::BilateralParameters parameters;
  parameters.Radius = options.Radius;
  parameters.NormalRadius = options.NormalRadius;
  parameters.NumberOfIterations = options.Iterations;
  parameters.Automatic = options.Automatic;
  parameters.NumberOfThreads = options.Threads;
  parameters.EdgeAware = options.EdgeAware;
  parameters.RemoveIsolatedPoints = options.RemoveIsolated;
  return parameters;
}

/// The core's checks and messages, before any file is read.
void CheckOptions(const Options& options)
{
  const std::string problem = pcbilateral::CheckParameters(CoreParameters(options));
  if (!problem.empty())
  {
    Fail(problem);
  }
  CheckFileName(options.Input, false);
  CheckFileName(options.Output, true);
  const std::string keepNaNProblem =
    pcbilateral_cli::KeepNaNOutputProblem(options.Input, options.Output, options.KeepNaNPoints);
  if (!keepNaNProblem.empty())
  {
    Fail(keepNaNProblem);
  }
  const std::string outputProblem =
    vtkPointCloudFileIO::CheckOutputPath(options.Output.c_str(), options.Input.c_str());
  if (!outputProblem.empty())
  {
    Fail(outputProblem);
  }
}

Options ParseArguments(int argc, char* argv[])
{
  Options options;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i)
  {
    if (!ParseCOPCOption(argc, argv, i, options) && !ParseMemoryOption(argc, argv, i, options) &&
        !ParseOption(argc, argv, i, options))
    {
      positional.push_back(argv[i]);
    }
  }
  if (positional.size() != 2)
  {
    std::fputs(HelpText().c_str(), stderr);
    std::exit(EXIT_FAILURE);
  }
  options.Input = positional[0];
  options.Output = positional[1];
  CheckOptions(options);
  return options;
}

/// The warnings about options that cannot do what they ask here, once the input could be read
/// (an input that cannot be read is one line, its error).
void WarnAboutOptions(const Options& options)
{
  std::vector<std::string> warnings = pcbilateral_cli::NoEffectWarnings(
    options.Input, options.Output, options.OrientedNormals, options.KeepNaNPoints);
  const std::string threads =
    pcbilateral_cli::ThreadsWarning(options.Threads, pcbilateral::HardwareThreadCount());
  if (!threads.empty())
  {
    warnings.insert(warnings.begin(), threads);
  }
  for (const std::string& warning : warnings)
  {
    std::fprintf(stderr, "pcbilateral: warning: %s\n", warning.c_str());
  }
}

/// The points of `cloud` without finite coordinates.
unsigned long long CountNonFinitePoints(vtkPolyData* cloud)
{
  vtkDataArray* xyz = cloud->GetPoints() ? cloud->GetPoints()->GetData() : nullptr;
  unsigned long long count = 0;
  for (vtkIdType i = 0; xyz && i < xyz->GetNumberOfTuples(); ++i)
  {
    double p[3];
    xyz->GetTuple(i, p);
    count += std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]) ? 0 : 1;
  }
  return count;
}

/// The input cloud; a file that cannot be read or holds no points is an error.
void ReadInput(vtkPointCloudFileIO* files, const Options& options, vtkPolyData* input)
{
  const bool read = files->Read(options.Input.c_str(), input);
  Screen().EndPhase(read);
  if (!read)
  {
    Fail(files->GetErrorMessage());
  }
  for (int w = 0; w < files->GetNumberOfWarnings(); ++w)
  {
    std::fprintf(stderr, "pcbilateral: warning: %s\n", files->GetWarning(w));
  }
  if (input->GetNumberOfPoints() == 0)
  {
    Fail(options.Input + ": contains no points");
  }
  if (pcbilateral::IsLASPath(options.Output))
  {
    // Said before the filter runs, not when its result cannot be written.
    const std::string problem =
      pcbilateral_cli::NonFiniteOutputProblem(options.Output, CountNonFinitePoints(input));
    if (!problem.empty())
    {
      Fail(problem);
    }
  }
  SayDropped(static_cast<unsigned long long>(files->GetNumberOfDroppedPoints()));
}

void ConfigureFilter(vtkPointCloudBilateralFilter* filter, const Options& options)
{
  filter->SetRadius(options.Radius);
  filter->SetNormalRadius(options.NormalRadius);
  filter->SetNumberOfIterations(options.Iterations);
  filter->SetAutomaticParameters(static_cast<int>(options.Automatic));
  filter->SetNumberOfThreads(options.Threads);
  filter->SetRemoveIsolatedPoints(options.RemoveIsolated);
  filter->SetEdgeAware(options.EdgeAware);
  filter->SetClassArrayName(options.ClassArray.c_str());
  for (long long value : options.Classes)
  {
    filter->AddClass(value);
  }
}

/// "low to high", or one value when they are equal.
std::string Range(double low, double high)
{
  char text[64];
  if (low == high)
  {
    std::snprintf(text, sizeof text, "%.9g", low);
  }
  else
  {
    std::snprintf(text, sizeof text, "%.9g to %.9g", low, high);
  }
  return text;
}

/// With --classes: which points were filtered.
void PrintClasses(long long filtered, const Options& options)
{
  if (options.Classes.empty())
  {
    return;
  }
  std::string list;
  for (long long value : options.Classes)
  {
    list += (list.empty() ? "" : ", ") + std::to_string(value);
  }
  Say("classes:       %s in '%s': %lld points filtered, the others unchanged\n",
    list.c_str(),
    options.ClassArray.c_str(),
    filtered);
}

/// The parameters the filter used (`used`: as the core reports them), and for those the user
/// left automatic, from what.
void PrintParameters(const pcbilateral::BilateralResult& used, const Options& options)
{
  const bool measured = used.PointSpacing > 0.0;
  if (measured)
  {
    Say(
      "measured:      point spacing %.6g, noise sigma %.6g\n", used.PointSpacing, used.NoiseSigma);
    const double* distances = used.NearestNeighbourDistance;
    Say("sampling:      nearest-neighbour distance %.6g (5%%), %.6g (median), %.6g "
        "(95%%); local spacing varies %.3g times\n",
      distances[0],
      distances[1],
      distances[2],
      used.SpacingSpread);
  }
  const char* automatic =
    measured ? " (automatic, from the measured spacing and noise)" : " (automatic: the paper's)";
  if (!used.RadiusFollowsDensity && !(used.RadiusUsed > 0.0))
  {
    // (A cloud without extent: the core's warning says why; no parameter was used.)
    Say("radius:        none could be chosen automatically: the points are written unchanged\n");
    return;
  }
  if (used.RadiusFollowsDensity)
  {
    Say("radius:        %s, following the density (automatic, each point's from its "
        "local spacing)\n",
      Range(used.RadiusRange[0], used.RadiusRange[1]).c_str());
    Say("normal radius: %s%s\n",
      Range(used.NormalRadiusRange[0], used.NormalRadiusRange[1]).c_str(),
      options.NormalRadius > 0.0 ? "" : automatic);
  }
  else
  {
    Say("radius:        %.9g%s\n", used.RadiusUsed, options.Radius > 0.0 ? "" : automatic);
    Say("normal radius: %.9g%s\n",
      used.NormalRadiusUsed,
      options.NormalRadius > 0.0 ? "" : automatic);
  }
  Say(
    "iterations:    %d%s\n", used.NumberOfIterationsUsed, options.Iterations > 0 ? "" : automatic);
  Say("mode:          %s\n",
    options.EdgeAware ? "edge-aware (normals filtered bilaterally, beyond the paper)"
                      : "the paper's filter");
}

/// PrintParameters for the VTK filter's run.
void PrintParametersUsed(vtkPointCloudBilateralFilter* filter, const Options& options)
{
  PrintClasses(static_cast<long long>(filter->GetNumberOfFilteredPoints()), options);
  if (filter->GetNumberOfFilteredPoints() == 0)
  {
    return; // (no parameter was used)
  }
  pcbilateral::BilateralResult used;
  used.PointSpacing = filter->GetPointSpacing();
  used.NoiseSigma = filter->GetNoiseSigma();
  std::copy_n(filter->GetNearestNeighbourDistances(), 3, used.NearestNeighbourDistance);
  used.SpacingSpread = filter->GetSpacingSpread();
  used.RadiusFollowsDensity = filter->GetRadiusFollowsDensity();
  std::copy_n(filter->GetRadiusRange(), 2, used.RadiusRange);
  std::copy_n(filter->GetNormalRadiusRange(), 2, used.NormalRadiusRange);
  used.RadiusUsed = filter->GetRadiusUsed();
  used.NormalRadiusUsed = filter->GetNormalRadiusUsed();
  used.NumberOfIterationsUsed = filter->GetNumberOfIterationsUsed();
  PrintParameters(used, options);
}

void WriteOutput(vtkPointCloudFileIO* files, const Options& options, vtkPolyData* output)
{
  if (vtkPointCloudFileIO::IsTextFormat(options.Output.c_str()))
  {
    // The authors' layout: the input's columns in order, no columns of the filter's own.
    output->GetPointData()->RemoveArray("vtkOriginalPointIds");
  }
  const bool written = files->Write(output, options.Output.c_str());
  Screen().EndPhase(written);
  if (!written)
  {
    Fail(files->GetErrorMessage());
  }
  for (int w = 0; w < files->GetNumberOfWarnings(); ++w)
  {
    std::fprintf(stderr, "pcbilateral: warning: %s\n", files->GetWarning(w));
  }
  Say("output:        %s, %lld points\n",
    options.Output.c_str(),
    static_cast<long long>(output->GetNumberOfPoints()));
}

/// Why the streamed run (--memory-limit) cannot run with these files and options, or empty.
std::string StreamingUnsupported(const Options& options)
{
  return pcbilateral::StreamingFormatsProblem(options.Input, options.Output);
}

/// The streamed run's progress: a bar per phase on a terminal, a line per slab otherwise.
void StreamProgress(const std::string& phase, double fraction)
{
  static std::chrono::steady_clock::time_point start;
  static std::string current;
  const bool slab = phase.compare(0, 5, "slab ") == 0 || phase == "filtered";
  const std::string label = slab ? "slabs" : phase;
  const auto now = std::chrono::steady_clock::now();
  if (label != current)
  {
    current = label;
    start = now;
  }
  if (!slab || Screen().ShowsBar())
  {
    Screen().Phase(label, fraction);
    return;
  }
  Screen().EndPhase();
  const double elapsed = std::chrono::duration<double>(now - start).count();
  unsigned long done = 0, total = 0;
  if (fraction > 0.0 &&
      (phase == "filtered" || std::sscanf(phase.c_str(), "slab %lu of %lu", &done, &total) == 2))
  {
    const double left = elapsed * (1.0 - fraction) / fraction;
    Say(phase == "filtered" ? "slabs:         all done\n"
                            : "slabs:         %lu of %lu done, %.0f s left\n",
      done - 1,
      total,
      left);
  }
}

/// The settings of a streamed run within `limit` bytes.
pcbilateral::OutOfCoreSettings StreamSettings(const Options& options, std::uint64_t limit)
{
  pcbilateral::OutOfCoreSettings settings =
    pcbilateral::StreamingSettings(limit, options.Output, options.Threads);
  settings.Progress = StreamProgress;
  return settings;
}

void SayWarnings(const std::vector<std::string>& warnings, std::size_t& said)
{
  for (; said < warnings.size(); ++said)
  {
    Screen().ClearBar();
    std::fprintf(stderr, "pcbilateral: warning: %s\n", warnings[said].c_str());
  }
}

/// The input of the streamed run, its COPC part and classes chosen (with the run in memory's
/// warning on a file that is not COPC), or null with `problem` set.
std::unique_ptr<pcbilateral::StreamedFile> OpenStreamedInput(const Options& options,
  std::string& problem)
{
  pcbilateral::COPCQuery part;
  part.MaxLevel = options.COPCLevel;
  part.UseBounds = options.COPCUseBounds;
  std::copy_n(options.COPCBounds, 6, part.Bounds);
  const bool partAsked = part.MaxLevel != -1 || part.UseBounds;
  std::unique_ptr<pcbilateral::StreamedFile> file = pcbilateral::OpenStreamedFile(options.Input,
    options.Output,
    options.OrientedNormals,
    options.KeepNaNPoints,
    partAsked ? &part : nullptr,
    problem);
  if (file && !file->GetReadWarning().empty())
  {
    std::fprintf(stderr, "pcbilateral: warning: %s\n", file->GetReadWarning().c_str());
  }
  if (problem.empty() && file->GetNumberOfPoints() == 0)
  {
    problem = options.Input + ": contains no points";
  }
  if (problem.empty() && !options.Classes.empty())
  {
    problem = file->ChooseClasses(options.ClassArray, options.Classes);
  }
  return problem.empty() ? std::move(file) : nullptr;
}

/// The streamed run's parameters and slabs, once it has planned them.
void SayPlan(const pcbilateral::OutOfCoreRun& run,
  const pcbilateral::StreamedFile& input,
  const Options& options)
{
  const pcbilateral::OutOfCorePlan& plan = run.GetPlan();
  if (plan.NumberOfSlabs == 0)
  {
    Screen().EndPhase(); // measuring (no bucketing follows it: nothing to filter)
  }
  PrintClasses(
    static_cast<long long>(input.GetNumberOfPoints() - input.GetNumberOfPointsLeftAlone()),
    options);
  PrintParameters(run.GetSummary(), options);
  if (plan.NumberOfSlabs > 0)
  {
    Say("slabs:         %zu along %c, a halo of %.6g, at most %llu points with it\n",
      plan.NumberOfSlabs,
      "xyz"[plan.Axis],
      plan.Halo,
      static_cast<unsigned long long>(plan.LargestSlabPoints));
  }
}

/// The out-of-core run: the file in slabs within `limit` bytes, the same output file as the
/// run in memory. Returns an empty string or the one-line error.
std::string RunStreamed(const Options& options, std::uint64_t limit)
{
  const pcbilateral::OutOfCoreSettings settings = StreamSettings(options, limit);
  std::string problem = pcbilateral::MemoryLimitProblem(settings, options.EdgeAware);
  if (!problem.empty())
  {
    return "--memory-limit: " + problem;
  }
  const std::unique_ptr<pcbilateral::StreamedFile> file = OpenStreamedInput(options, problem);
  if (!problem.empty())
  {
    return problem;
  }
  WarnAboutOptions(options);
  pcbilateral::StreamedFile& input = *file;
  SayDropped(input.GetNumberOfDroppedPoints());
  Say("input:         %s, %llu points, streamed within %s of memory\n",
    options.Input.c_str(),
    static_cast<unsigned long long>(input.GetNumberOfPoints()),
    pcbilateral::MemorySizeText(limit).c_str());
  pcbilateral::RemoveTemporaryFilesOnSignals(options.Output + ".partial");
  pcbilateral::OutOfCoreRun run(input, CoreParameters(options), settings);
  std::size_t warned = 0;
  problem = run.Measure();
  // (Before the warnings, which this makes moot: the one line of a run that stops.)
  const std::string unwritable = problem.empty()
                                   ? pcbilateral_cli::NonFiniteOutputProblem(
                                       options.Output, run.GetSummary().NumberOfNonFinitePoints)
                                   : std::string();
  if (!unwritable.empty())
  {
    return unwritable;
  }
  SayWarnings(run.GetSummary().Warnings, warned);
  if (problem.empty())
  {
    Say("temporary:     %s on disk in %s (removed at the end)\n",
      pcbilateral::MemorySizeText(run.GetDiskBytesNeeded()).c_str(),
      settings.TemporaryDirectory.c_str());
    problem = run.Bucket();
  }
  if (!problem.empty())
  {
    return problem;
  }
  SayPlan(run, input, options);
  const auto start = std::chrono::steady_clock::now();
  problem = run.Filter();
  SayWarnings(run.GetSummary().Warnings, warned);
  if (!problem.empty())
  {
    return problem;
  }
  if (options.RemoveIsolated)
  {
    Say("removed:       %llu isolated points\n",
      static_cast<unsigned long long>(run.GetNumberOfRemovedPoints()));
  }
  Say("filtering:     %.3f s\n",
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  problem = input.WriteFiltered(run,
    options.Output,
    pcbilateral::StreamedRangePoints(),
    [](double fraction) { StreamProgress("writing", fraction); });
  if (problem.empty() && !input.WriteWarning(options.Output).empty())
  {
    std::fprintf(stderr, "pcbilateral: warning: %s\n", input.WriteWarning(options.Output).c_str());
  }
  if (problem.empty())
  {
    Say("output:        %s, %llu points\n",
      options.Output.c_str(),
      static_cast<unsigned long long>(input.GetNumberOfPoints() - run.GetNumberOfRemovedPoints()));
  }
  return problem;
}

/// The memory limit of the run: --memory-limit, or, for a cloud that would not fit in 80% of
/// the available memory, that much (said); 0 to run in memory.
std::uint64_t ChooseMemoryLimit(const Options& options)
{
  if (options.MemoryLimit > 0)
  {
    const std::string problem = StreamingUnsupported(options);
    if (!problem.empty())
    {
      Fail("--memory-limit: " + problem);
    }
    return options.MemoryLimit;
  }
  // The points: a LAS file's header says; a text file's are estimated from its size (a line
  // of x y z takes 20 bytes and more), without reading it.
  std::uint64_t points = 0;
  pcbilateral::LASPointSource las;
  std::error_code error;
  if (!StreamingUnsupported(options).empty())
  {
    return 0;
  }
  if (vtkPointCloudFileIO::IsTextFormat(options.Input.c_str()))
  {
    const std::uintmax_t bytes = std::filesystem::file_size(options.Input, error);
    points = error ? 0 : bytes / 20;
  }
  else if (las.Open(options.Input).empty())
  {
    points = las.GetNumberOfPoints();
  }
  const std::uint64_t available = pcbilateral::AvailableMemory();
  const std::uint64_t limit = pcbilateral::AutomaticMemoryLimit(points, available);
  if (limit == 0)
  {
    return 0;
  }
  Say("memory:        about %s needed in memory, %s available: streamed within %s "
      "(automatic; --memory-limit sets it)\n",
    pcbilateral::MemorySizeText(pcbilateral::InMemoryBytesPerPoint * points).c_str(),
    pcbilateral::MemorySizeText(available).c_str(),
    pcbilateral::MemorySizeText(limit).c_str());
  return limit;
}

/// Shows the progress events of `object` as the phase `phase`; the filter's (null `phase`) as
/// its own phases (measuring, each iteration). Returns the observer's tag.
unsigned long ShowProgress(vtkObject* object, const char* phase)
{
  vtkNew<vtkCallbackCommand> show;
  show->SetClientData(const_cast<char*>(phase));
  show->SetCallback(
    [](vtkObject* caller, unsigned long, void* client, void* callData)
    {
      if (auto* filter = vtkPointCloudBilateralFilter::SafeDownCast(caller))
      {
        if (*filter->GetProgressPhase()) // (not before the run has a phase)
        {
          Screen().Phase(filter->GetProgressPhase(), filter->GetPhaseProgress());
        }
        return;
      }
      Screen().Phase(static_cast<const char*>(client), *static_cast<double*>(callData));
    });
  return object->AddObserver(vtkCommand::ProgressEvent, show);
}

/// With a memory limit (given, or needed: ChooseMemoryLimit), the streamed run, then exit.
void StreamIfLimited(const Options& options)
{
  const std::uint64_t memoryLimit = ChooseMemoryLimit(options);
  if (memoryLimit == 0)
  {
    return;
  }
  const std::string problem = RunStreamed(options, memoryLimit);
  Screen().ClearBar();
  if (!problem.empty())
  {
    Fail(problem);
  }
  std::exit(EXIT_SUCCESS);
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
  vtkNew<QuietOutputWindow> quiet;
  vtkOutputWindow::SetInstance(quiet);
  const Options options = ParseArguments(argc, argv);
  Screen().Configure(options.Quiet, isatty(fileno(stdout)));
  StreamIfLimited(options);

  // One place picks the reader and writer by extension and checks the file first.
  vtkNew<vtkPointCloudFileIO> files;
  files->SetOrientedNormals(options.OrientedNormals);
  files->SetKeepNaNPoints(options.KeepNaNPoints);
  files->SetCOPCMaxLevel(options.COPCLevel);
  files->SetCOPCUseBounds(options.COPCUseBounds);
  files->SetCOPCBounds(options.COPCBounds);
  vtkNew<vtkPolyData> input;
  const unsigned long reading = ShowProgress(files, "reading");
  ReadInput(files, options, input);
  files->RemoveObserver(reading);
  WarnAboutOptions(options);

  Say("input:         %s, %lld points\n",
    options.Input.c_str(),
    static_cast<long long>(input->GetNumberOfPoints()));

  ReportMessages messages;
  vtkNew<vtkPointCloudBilateralFilter> filter;
  messages.Observe(filter);
  filter->SetInputData(input);
  ConfigureFilter(filter, options);
  // What was measured and chosen, as soon as it is (a large cloud then filters for minutes),
  // and the progress bar.
  struct Watch
  {
    vtkPointCloudBilateralFilter* Filter;
    const Options* Chosen;
    bool ParametersSaid = false;
  } watch{ filter, &options };
  vtkNew<vtkCallbackCommand> watcher;
  watcher->SetClientData(&watch);
  watcher->SetCallback(
    [](vtkObject*, unsigned long, void* client, void*)
    {
      auto* self = static_cast<Watch*>(client);
      Screen().EndPhase(); // measuring
      PrintParametersUsed(self->Filter, *self->Chosen);
      self->ParametersSaid = true;
    });
  filter->AddObserver(vtkPointCloudBilateralFilter::ParametersChosenEvent, watcher);
  ShowProgress(filter, nullptr);
  const auto start = std::chrono::steady_clock::now();
  filter->Update();
  Screen().EndPhase(!messages.ErrorSeen);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (messages.ErrorSeen)
  {
    return EXIT_FAILURE;
  }

  vtkNew<vtkPolyData> output;
  output->ShallowCopy(filter->GetOutput());
  if (!watch.ParametersSaid)
  {
    PrintParametersUsed(filter, options); // (no iteration ran: nothing to filter)
  }
  if (options.RemoveIsolated)
  {
    Say("removed:       %lld isolated points\n",
      static_cast<long long>(filter->GetNumberOfRemovedPoints()));
  }
  Say("filtering:     %.3f s\n", seconds);
  ShowProgress(files, "writing");
  WriteOutput(files, options, output);
  return EXIT_SUCCESS;
}

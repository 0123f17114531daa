// pcbilateral: denoise a point cloud file with the bilateral filter of Digne & de Franchis
// (IPOL 2017), with the option letters of the authors' program.
//
//   pcbilateral INPUT OUTPUT [-r R] [-n RN] [-N ITER] [--paper] [-R] [-t THREADS]
//               [--remove-isolated] [--edge-aware] [--keep-nan] [-q]
//               [--classes LIST [--class-array NAME]]
//
// Formats by extension: .txt and .xyz (the authors' ASCII format), .las, .laz, .pcd, .ply,
// .vtp. Errors print one line and exit with status 1; a damaged input file is an error, never
// a cloud. Run with -h for the options.
#include "AutomaticRule.h"
#include "BilateralFilter.h"
#include "EdgeAwareRule.h"
#include "vtkPointCloudBilateralFilter.h"
#include "vtkPointCloudFileIO.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <cerrno>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{
// The help's fixed text; the automatic rule and the paper's heuristic are the core's own words
// (AutomaticRule.h), inserted by HelpText.
const char* const UsageHead =
  "usage: pcbilateral INPUT OUTPUT [-r R] [-n RN] [-N ITER] [--paper] [-R] [-t THREADS]\n"
  "                   [--remove-isolated] [--edge-aware] [--keep-nan] [-q]\n"
  "                   [--classes LIST [--class-array NAME]]\n"
  "\n"
  "Denoises a point cloud with the bilateral filter (Digne & de Franchis, IPOL 2017).\n"
  "INPUT and OUTPUT: .txt or .xyz (x y z [nx ny nz] [more columns]), .las (LiDAR),\n"
  ".laz (compressed LiDAR), .pcd (PCL's), .ply or .vtp. A text file is written as the\n"
  "text input was: the same columns in the same order, a header line only if it had\n"
  "one, spaces or tabs.\n"
  "\n"
  "  -r R               neighbourhood radius\n"
  "  -n RN              normal radius, the tolerance to the tangent plane\n"
  "  -N ITER            number of iterations\n";
const char* const AutomaticLead =
  "Each is automatic when not given (or 0): chosen from the cloud's measured point spacing "
  "and noise sigma";
const char* const PaperLead =
  "parameters not given follow the paper's heuristic instead, as the authors' program:";
const char* const UsageTail =
  "  -R                 text files carry oriented normals in columns 4-6; the estimated\n"
  "                     normals are oriented by them and they are written back\n"
  "  -t THREADS         threads (default 0: all cores); the result does not depend on it\n"
  "  --remove-isolated  remove points with fewer than 5 neighbours, as the authors' program\n"
  "                     does (default: they stay where they are)\n"
  "  --edge-aware       edge-aware mode, beyond the paper: normals filtered bilaterally\n"
  "                     before the displacement, for sharp edges under strong noise\n"
  "                     (default: the paper's filter)\n"
  "  --classes LIST     filter only the points of these classes (integers, comma-separated,\n"
  "                     e.g. 2,6 for LAS ground and buildings); the others keep their exact\n"
  "                     coordinates and are no one's neighbours (default: every point)\n"
  "  --class-array NAME the integer point array that holds the class (default\n"
  "                     Classification, as LAS files name it)\n"
  "  --keep-nan         PCD input: keep the points without coordinates (NaN) of an\n"
  "                     organised frame in place, never as neighbours, so that a .pcd\n"
  "                     output keeps the frame's WIDTH and HEIGHT (default: left out)\n"
  "  -q, --quiet        print nothing but warnings and errors (default: what was read,\n"
  "                     measured, chosen and written, each line as soon as it is known, and\n"
  "                     on a terminal a progress bar with the time left)\n"
  "  -p                 accepted for compatibility and ignored: the filter always runs in "
  "parallel\n"
  "  -h, --help         this text\n";

/// The help's option descriptions start in this column and wrap before this width.
constexpr std::size_t DescriptionColumn = 21;
constexpr std::size_t HelpWidth = 86;

/// `label` padded to the description column, then `text` wrapped at word boundaries, each
/// continuation line indented to that column.
std::string OptionParagraph(const std::string& label, const std::string& text)
{
  std::string paragraph = label + std::string(DescriptionColumn - label.size(), ' ');
  std::size_t lineLength = DescriptionColumn;
  std::istringstream words(text);
  std::string word;
  while (words >> word)
  {
    const bool lineStarted = lineLength > DescriptionColumn;
    if (lineStarted && lineLength + 1 + word.size() > HelpWidth)
    {
      paragraph += "\n" + std::string(DescriptionColumn, ' ');
      lineLength = DescriptionColumn;
    }
    else if (lineStarted)
    {
      paragraph += ' ';
      ++lineLength;
    }
    paragraph += word;
    lineLength += word.size();
  }
  return paragraph + "\n";
}

std::string HelpText()
{
  return UsageHead +
         OptionParagraph("",
           std::string(AutomaticLead) + " (" + pcbilateral::DescribeAutomaticRule() + "; " +
             pcbilateral::DescribeEdgeAwareRule() + ")") +
         OptionParagraph(
           "  --paper", std::string(PaperLead) + " " + pcbilateral::DescribePaperRule()) +
         UsageTail;
}

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

/// Prints the filter's errors and warnings as one line each, as they arise.
/// What the program prints while it runs: each summary line as soon as it is known, and on a
/// terminal a progress bar for the filtering, with the time left, redrawn at most four times a
/// second and erased before anything else is printed. --quiet prints neither.
struct Terminal
{
  bool Quiet = false;
  bool ShowBar = false;
  bool BarShown = false;
  std::chrono::steady_clock::time_point Start, LastDrawn;

  void ClearBar()
  {
    if (this->BarShown)
    {
      std::fputs("\r\033[K", stdout);
      std::fflush(stdout);
      this->BarShown = false;
    }
  }

  void Bar(double fraction)
  {
    const auto now = std::chrono::steady_clock::now();
    if (!this->ShowBar || now - this->LastDrawn < std::chrono::milliseconds(250))
    {
      return;
    }
    this->LastDrawn = now;
    const double elapsed = std::chrono::duration<double>(now - this->Start).count();
    constexpr int Width = 30;
    const int filled = static_cast<int>(fraction * Width);
    char left[32] = "";
    if (fraction > 0.02 && fraction < 1.0)
    {
      std::snprintf(left, sizeof left, ", %.0f s left", elapsed * (1.0 - fraction) / fraction);
    }
    std::printf("\rfiltering:     [%s%s] %3.0f%%%s\033[K",
      std::string(static_cast<std::size_t>(filled), '#').c_str(),
      std::string(static_cast<std::size_t>(Width - filled), '.').c_str(),
      100.0 * fraction,
      left);
    std::fflush(stdout);
    this->BarShown = true;
  }
};

Terminal& Screen()
{
  static Terminal terminal;
  return terminal;
}

/// printf to the standard output, unless --quiet; the progress bar erased first, the line out at
/// once.
void Say(const char* format, ...)
{
  Terminal& screen = Screen();
  if (screen.Quiet)
  {
    return;
  }
  screen.ClearBar();
  va_list arguments;
  va_start(arguments, format);
  std::vprintf(format, arguments);
  va_end(arguments);
  std::fflush(stdout);
}

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
  pcbilateral::AutomaticParameters Automatic = pcbilateral::BilateralParameters().Automatic;
  bool OrientedNormals = false;
  int Threads = pcbilateral::BilateralParameters().NumberOfThreads;
  bool RemoveIsolated = pcbilateral::BilateralParameters().RemoveIsolatedPoints;
  bool EdgeAware = pcbilateral::BilateralParameters().EdgeAware;
  std::vector<long long> Classes;
  std::string ClassArray = "Classification";
  bool KeepNaNPoints = false;
  bool Quiet = false;
};

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

/// The core's checks and messages, before any file is read.
void CheckOptions(const Options& options)
{
  pcbilateral::BilateralParameters parameters;
  parameters.Radius = options.Radius;
  parameters.NormalRadius = options.NormalRadius;
  parameters.NumberOfIterations = options.Iterations;
  parameters.Automatic = options.Automatic;
  parameters.NumberOfThreads = options.Threads;
  const std::string problem = pcbilateral::CheckParameters(parameters);
  if (!problem.empty())
  {
    Fail(problem);
  }
  CheckFileName(options.Input, false);
  CheckFileName(options.Output, true);
}

Options ParseArguments(int argc, char* argv[])
{
  Options options;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i)
  {
    if (!ParseOption(argc, argv, i, options))
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

/// The input cloud; a file that cannot be read or holds no points is an error.
void ReadInput(vtkPointCloudFileIO* files, const Options& options, vtkPolyData* input)
{
  if (!files->Read(options.Input.c_str(), input))
  {
    Fail(files->GetErrorMessage());
  }
  if (input->GetNumberOfPoints() == 0)
  {
    Fail(options.Input + ": contains no points");
  }
  if (files->GetNumberOfDroppedPoints() > 0)
  {
    Say("input:         dropped %lld points without coordinates (NaN)\n",
      static_cast<long long>(files->GetNumberOfDroppedPoints()));
  }
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
void PrintClasses(vtkPointCloudBilateralFilter* filter, const Options& options)
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
    static_cast<long long>(filter->GetNumberOfFilteredPoints()));
}

/// The parameters the filter used, and for those the user left automatic, from what.
void PrintParametersUsed(vtkPointCloudBilateralFilter* filter, const Options& options)
{
  PrintClasses(filter, options);
  if (filter->GetNumberOfFilteredPoints() == 0)
  {
    return; // (no parameter was used)
  }
  const bool measured = filter->GetPointSpacing() > 0.0;
  if (measured)
  {
    Say("measured:      point spacing %.6g, noise sigma %.6g\n",
      filter->GetPointSpacing(),
      filter->GetNoiseSigma());
    const double* distances = filter->GetNearestNeighbourDistances();
    Say("sampling:      nearest-neighbour distance %.6g (5%%), %.6g (median), %.6g "
        "(95%%); local spacing varies %.3g times\n",
      distances[0],
      distances[1],
      distances[2],
      filter->GetSpacingSpread());
  }
  const char* automatic =
    measured ? " (automatic, from the measured spacing and noise)" : " (automatic: the paper's)";
  if (filter->GetRadiusFollowsDensity())
  {
    const double* radii = filter->GetRadiusRange();
    const double* normalRadii = filter->GetNormalRadiusRange();
    Say("radius:        %s, following the density (automatic, each point's from its "
        "local spacing)\n",
      Range(radii[0], radii[1]).c_str());
    Say("normal radius: %s%s\n",
      Range(normalRadii[0], normalRadii[1]).c_str(),
      options.NormalRadius > 0.0 ? "" : automatic);
  }
  else
  {
    Say("radius:        %.9g%s\n", filter->GetRadiusUsed(), options.Radius > 0.0 ? "" : automatic);
    Say("normal radius: %.9g%s\n",
      filter->GetNormalRadiusUsed(),
      options.NormalRadius > 0.0 ? "" : automatic);
  }
  Say("iterations:    %d%s\n",
    filter->GetNumberOfIterationsUsed(),
    options.Iterations > 0 ? "" : automatic);
  Say("mode:          %s\n",
    options.EdgeAware ? "edge-aware (normals filtered bilaterally, beyond the paper)"
                      : "the paper's filter");
}

void WriteOutput(vtkPointCloudFileIO* files, const Options& options, vtkPolyData* output)
{
  if (vtkPointCloudFileIO::IsTextFormat(options.Output.c_str()))
  {
    // The authors' layout: the input's columns in order, no columns of the filter's own.
    output->GetPointData()->RemoveArray("vtkOriginalPointIds");
  }
  if (!files->Write(output, options.Output.c_str()))
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
  Screen().Quiet = options.Quiet;
  Screen().ShowBar = !options.Quiet && isatty(fileno(stdout));

  // One place picks the reader and writer by extension and checks the file first.
  vtkNew<vtkPointCloudFileIO> files;
  files->SetOrientedNormals(options.OrientedNormals);
  files->SetKeepNaNPoints(options.KeepNaNPoints);
  vtkNew<vtkPolyData> input;
  ReadInput(files, options, input);

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
    [](vtkObject*, unsigned long event, void* client, void* callData)
    {
      auto* self = static_cast<Watch*>(client);
      if (event == vtkCommand::ProgressEvent)
      {
        Screen().Bar(*static_cast<double*>(callData));
        return;
      }
      PrintParametersUsed(self->Filter, *self->Chosen);
      self->ParametersSaid = true;
    });
  filter->AddObserver(vtkPointCloudBilateralFilter::ParametersChosenEvent, watcher);
  filter->AddObserver(vtkCommand::ProgressEvent, watcher);
  const auto start = std::chrono::steady_clock::now();
  Screen().Start = start;
  filter->Update();
  Screen().ClearBar();
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
  WriteOutput(files, options, output);
  return EXIT_SUCCESS;
}

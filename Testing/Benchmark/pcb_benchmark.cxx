// pcb_benchmark: times the bilateral filter on generated workloads and prints a table.
// Built with the project, not run by the tests (shared machines are too noisy for timed tests).
//
//   pcb_benchmark [--runs N] [--skip-10m] [--only WORKLOAD]
//       the filter alone, through the core, with 1 and 2 threads, on:
//       - cube600k: the unit cube's surface, 600,000 points, noise 0.5% of the diagonal,
//         r = 0.03, rn = 0.05, N = 2 (the paper's Table 1);
//       - sphere1M: a sphere, 1,000,000 points, noise 0.5%, the automatic radius, N = 1;
//       - sphere10M: the same with 10,000,000 points.
//       Each workload runs in a child process, so its peak resident memory is its own.
//   pcb_benchmark --write-cube600k FILE.xyz
//       writes the cube600k workload as an ASCII file, for other programs.
//   pcb_benchmark [--runs N] --las FOLDER
//       writes a 10,000,000-point LAS file (point format 3: GPS time and colours) in FOLDER,
//       then times reading it (decoded into columns), writing it again, and a plain read and
//       write of the file's bytes, in MB/s of the file (the file is in the page cache then).
//   pcb_benchmark --end-to-end [--runs N] PROGRAM ARGUMENTS...
//       times a whole program run (reading, filtering and writing), e.g. pcbilateral or the
//       authors' program on the same file, and reports its peak resident memory.
#include "BilateralFilter.h"
#include "BilateralKernel.h"
#include "LASFormat.h"
#include "PointCloudText.h"
#include "SampleShapes.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <memory>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace
{
using namespace pcbilateral_samples;

struct Workload
{
  const char* Name;
  std::size_t Points;
  bool Cube;
  double Radius, NormalRadius;
  int Iterations;
  int Runs; // 0: as given on the command line
};

std::vector<double> Generate(const Workload& workload)
{
  Random random(20171029);
  const std::unique_ptr<Shape> shape =
    workload.Cube ? Cube() : std::unique_ptr<Shape>(new Sphere());
  const double sigma = 0.005 * shape->Diagonal();
  std::vector<double> xyz(3 * workload.Points);
  for (std::size_t i = 0; i < workload.Points; ++i)
  {
    const Vec3 p = shape->Sample(random);
    for (int axis = 0; axis < 3; ++axis)
    {
      xyz[3 * i + axis] = p[axis] + sigma * random.Gaussian();
    }
  }
  return xyz;
}

double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// What a child process reports back through a pipe.
struct Measurement
{
  double Seconds = 0.0;
  double NeighbourEvaluations = 0.0;
  double RadiusUsed = 0.0;
  int Ok = 0;
};

/// Runs the workload `runs` times in a child process; returns the median and the child's peak
/// resident memory in MB.
Measurement RunInChild(const Workload& workload, int threads, int runs, double& peakMegabytes)
{
  int channel[2];
  if (pipe(channel) != 0)
  {
    std::perror("pipe");
    std::exit(EXIT_FAILURE);
  }
  const pid_t child = fork();
  if (child == 0)
  {
    close(channel[0]);
    const std::vector<double> xyz = Generate(workload);
    pcbilateral::PointCloudView cloud;
    cloud.NumberOfPoints = workload.Points;
    cloud.Positions = xyz.data();
    pcbilateral::BilateralParameters parameters;
    parameters.Radius = workload.Radius;
    parameters.NormalRadius = workload.NormalRadius;
    parameters.NumberOfIterations = workload.Iterations;
    // A radius of 0 is the paper's automatic radius, as in the speed table.
    parameters.Automatic = pcbilateral::AutomaticParameters::Paper;
    parameters.NumberOfThreads = threads;
    std::vector<double> times;
    Measurement measurement;
    for (int run = 0; run < runs; ++run)
    {
      const auto start = std::chrono::steady_clock::now();
      const pcbilateral::BilateralResult result =
        pcbilateral::RunBilateralFilter(cloud, parameters);
      times.push_back(Seconds(start));
      measurement.Ok = result.Status == pcbilateral::BilateralStatus::Completed;
      measurement.NeighbourEvaluations = static_cast<double>(result.NumberOfNeighbourEvaluations);
      measurement.RadiusUsed = result.RadiusUsed;
    }
    measurement.Seconds = Median(times);
    const ssize_t written = write(channel[1], &measurement, sizeof(measurement));
    _exit(written == static_cast<ssize_t>(sizeof(measurement)) ? 0 : 1);
  }
  close(channel[1]);
  Measurement measurement;
  const ssize_t got = read(channel[0], &measurement, sizeof(measurement));
  close(channel[0]);
  int status = 0;
  struct rusage usage;
  wait4(child, &status, 0, &usage);
  peakMegabytes = usage.ru_maxrss / 1024.0;
  if (got != static_cast<ssize_t>(sizeof(measurement)) || status != 0)
  {
    measurement.Ok = 0;
  }
  return measurement;
}

int Benchmark(int runs, bool skipTenMillion, const std::string& only)
{
  const Workload workloads[] = {
    { "cube600k", 600000, true, 0.03, 0.05, 2, 0 },
    { "sphere1M", 1000000, false, 0.0, 0.0, 1, 0 },
    { "sphere10M", 10000000, false, 0.0, 0.0, 1, 1 },
  };
  std::printf("kernel build: %s\n", pcbilateral::GetName(pcbilateral::GetKernelInstructionSet()));
  std::printf("%-10s %9s %3s %9s %7s %11s %12s %15s %8s %8s\n",
    "workload",
    "points",
    "N",
    "radius",
    "threads",
    "seconds",
    "points/s",
    "evals/s/core",
    "speedup",
    "peak MB");
  for (const Workload& workload : workloads)
  {
    if ((skipTenMillion && workload.Points >= 10000000) || (!only.empty() && only != workload.Name))
    {
      continue;
    }
    const int workloadRuns = workload.Runs > 0 ? workload.Runs : runs;
    double oneThread = 0.0;
    for (int threads : { 1, 2 })
    {
      double peak = 0.0;
      const Measurement m = RunInChild(workload, threads, workloadRuns, peak);
      if (!m.Ok)
      {
        std::printf("%-10s failed\n", workload.Name);
        return EXIT_FAILURE;
      }
      oneThread = threads == 1 ? m.Seconds : oneThread;
      const double pointsPerSecond = workload.Points * workload.Iterations / m.Seconds;
      const double evaluationsPerCore = m.NeighbourEvaluations / m.Seconds / threads;
      std::printf("%-10s %9zu %3d %9.4g %7d %11.3f %12.3g %15.3g %8s %8.0f\n",
        workload.Name,
        workload.Points,
        workload.Iterations,
        m.RadiusUsed,
        threads,
        m.Seconds,
        pointsPerSecond,
        evaluationsPerCore,
        threads == 1 ? "" : std::to_string(oneThread / m.Seconds).substr(0, 4).c_str(),
        peak);
      std::fflush(stdout);
    }
  }
  std::printf("(median of %d runs; sphere10M: 1 run; neighbour evaluations per second per "
              "thread used)\n",
    runs);
  return EXIT_SUCCESS;
}

int WriteCube(const char* path)
{
  const Workload cube{ "cube600k", 600000, true, 0.03, 0.05, 2, 0 };
  pcbilateral::PointCloudTable table;
  table.NumberOfPoints = cube.Points;
  table.Positions = Generate(cube);
  const std::string error = pcbilateral::WritePointCloudText(path, table);
  if (!error.empty())
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return EXIT_FAILURE;
  }
  std::printf("wrote %s (600,000 points); the paper's parameters: -r 0.03 -n 0.05 -N 2\n", path);
  return EXIT_SUCCESS;
}

/// The columns of a LAS file's dimensions, uninitialised (as a reader allocates them).
struct LASColumns
{
  std::unique_ptr<double[]> Positions;
  std::vector<std::unique_ptr<std::uint8_t[]>> Storage;
  std::vector<void*> Columns;

  LASColumns(const pcbilateral::LASFileInfo& info, std::size_t count)
    : Positions(new double[3 * count])
  {
    for (const pcbilateral::LASDimension& dimension : info.Dimensions)
    {
      Storage.emplace_back(
        new std::uint8_t[count * pcbilateral::LASSizeOf(dimension.Type) * dimension.Components]);
      Columns.push_back(Storage.back().get());
    }
  }
};

int BenchmarkLAS(int runs, const std::string& folder)
{
  const std::size_t count = 10000000;
  const std::string path = folder + "/pcb_benchmark_10M.las";
  const std::string copy = folder + "/pcb_benchmark_10M_copy.las";
  {
    const Workload sphere{ "sphere10M", count, false, 0.0, 0.0, 1, 1 };
    const std::vector<double> xyz = Generate(sphere);
    const double bounds[6] = { -1.1, -1.1, -1.1, 1.1, 1.1, 1.1 };
    const pcbilateral::LASFileInfo info =
      pcbilateral::DefaultLASFileInfo(count, bounds, true, true);
    LASColumns columns(info, count);
    for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
    {
      const std::size_t bytes =
        count * pcbilateral::LASSizeOf(info.Dimensions[d].Type) * info.Dimensions[d].Components;
      for (std::size_t b = 0; b < bytes; ++b)
      {
        columns.Storage[d][b] = static_cast<std::uint8_t>(b * 2654435761u >> 13);
      }
    }
    const std::string error =
      pcbilateral::WriteLAS(path, info, count, xyz.data(), columns.Columns.data());
    if (!error.empty())
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      return EXIT_FAILURE;
    }
  }
  std::vector<double> plain, plainWriting, reading, writing;
  std::size_t size = 0;
  for (int run = 0; run < runs; ++run)
  {
    {
      // The bytes alone, in blocks of 64 MB, into memory allocated for them.
      auto start = std::chrono::steady_clock::now();
      std::FILE* file = std::fopen(path.c_str(), "rb");
      std::fseek(file, 0, SEEK_END);
      size = static_cast<std::size_t>(std::ftell(file));
      std::fseek(file, 0, SEEK_SET);
      std::unique_ptr<char[]> bytes(new char[size]);
      for (std::size_t at = 0; at < size;)
      {
        const std::size_t read =
          std::fread(bytes.get() + at, 1, std::min<std::size_t>(64 << 20, size - at), file);
        if (read == 0)
        {
          break;
        }
        at += read;
      }
      std::fclose(file);
      plain.push_back(Seconds(start));
      // And written again as they are, in the same blocks: what any writer pays the system.
      start = std::chrono::steady_clock::now();
      file = std::fopen(copy.c_str(), "wb");
      for (std::size_t at = 0; at < size; at += 64 << 20)
      {
        std::fwrite(bytes.get() + at, 1, std::min<std::size_t>(64 << 20, size - at), file);
      }
      std::fclose(file);
      plainWriting.push_back(Seconds(start));
      std::remove(copy.c_str());
    }
    auto start = std::chrono::steady_clock::now();
    pcbilateral::LASFileBytes file;
    pcbilateral::LASFileInfo info;
    std::string error = file.Open(path);
    if (error.empty())
    {
      error = pcbilateral::ParseLASHeader(file.Data(), file.Size(), path, info);
    }
    if (!error.empty())
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      return EXIT_FAILURE;
    }
    LASColumns columns(info, count);
    pcbilateral::DecodeLASPoints(info,
      file.Data() + info.Header.OffsetToPointData,
      count,
      columns.Positions.get(),
      columns.Columns.data());
    reading.push_back(Seconds(start));
    start = std::chrono::steady_clock::now();
    std::vector<const void*> constant(columns.Columns.begin(), columns.Columns.end());
    error = pcbilateral::WriteLAS(copy, info, count, columns.Positions.get(), constant.data());
    if (!error.empty())
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      return EXIT_FAILURE;
    }
    writing.push_back(Seconds(start));
  }
  const double megabytes = size / 1e6;
  std::printf(
    "LAS, 10,000,000 points of format 3 (%.0f MB), median of %d runs:\n", megabytes, runs);
  std::printf(
    "  plain read of the bytes: %7.3f s %8.0f MB/s\n", Median(plain), megabytes / Median(plain));
  std::printf("  LAS read (decoded):      %7.3f s %8.0f MB/s\n",
    Median(reading),
    megabytes / Median(reading));
  std::printf("  LAS write:               %7.3f s %8.0f MB/s\n",
    Median(writing),
    megabytes / Median(writing));
  std::printf("  plain write of the bytes: %6.3f s %8.0f MB/s\n",
    Median(plainWriting),
    megabytes / Median(plainWriting));
  std::remove(path.c_str());
  std::remove(copy.c_str());
  return EXIT_SUCCESS;
}

int EndToEnd(int runs, char* command[])
{
  std::vector<double> times;
  double peak = 0.0;
  for (int run = 0; run < runs; ++run)
  {
    const auto start = std::chrono::steady_clock::now();
    const pid_t child = fork();
    if (child == 0)
    {
      const int null = open("/dev/null", O_WRONLY);
      dup2(null, STDOUT_FILENO);
      execvp(command[0], command);
      std::perror(command[0]);
      _exit(127);
    }
    int status = 0;
    struct rusage usage;
    wait4(child, &status, 0, &usage);
    times.push_back(Seconds(start));
    peak = std::max(peak, usage.ru_maxrss / 1024.0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    {
      std::fprintf(stderr, "%s failed (status %d)\n", command[0], status);
      return EXIT_FAILURE;
    }
  }
  std::printf("end to end: %s, median of %d runs: %.3f s (fastest %.3f s), peak %.0f MB\n",
    command[0],
    runs,
    Median(times),
    *std::min_element(times.begin(), times.end()),
    peak);
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char* argv[])
{
  int runs = 3;
  bool skipTenMillion = false;
  std::string only;
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    if (argument == "--runs" && i + 1 < argc)
    {
      runs = std::max(1, std::atoi(argv[++i]));
    }
    else if (argument == "--skip-10m")
    {
      skipTenMillion = true;
    }
    else if (argument == "--only" && i + 1 < argc)
    {
      only = argv[++i];
    }
    else if (argument == "--write-cube600k" && i + 1 < argc)
    {
      return WriteCube(argv[i + 1]);
    }
    else if (argument == "--las" && i + 1 < argc)
    {
      return BenchmarkLAS(runs, argv[i + 1]);
    }
    else if (argument == "--end-to-end" && i + 1 < argc)
    {
      return EndToEnd(runs, argv + i + 1);
    }
    else
    {
      std::fprintf(stderr,
        "usage: %s [--runs N] [--skip-10m] [--only cube600k|sphere1M|sphere10M] | "
        "--write-cube600k FILE.xyz | [--runs N] --las FOLDER | "
        "[--runs N] --end-to-end PROGRAM ARGUMENTS...\n",
        argv[0]);
      return EXIT_FAILURE;
    }
  }
  return Benchmark(runs, skipTenMillion, only);
}

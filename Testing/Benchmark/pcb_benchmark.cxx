// pcb_benchmark: times the bilateral filter on generated workloads and prints a table.
// Built with the project, not run by the tests (shared machines are too noisy for timed tests).
//
//   pcb_benchmark [--runs N] [--skip-10m] [--only WORKLOAD]
//       (--skip-10m skips the workloads of 10M points and more; --threads T runs T threads only)
//       the filter alone, through the core, with 1 and 2 threads, on:
//       - cube600k: the unit cube's surface, 600,000 points, noise 0.5% of the diagonal,
//         r = 0.03, rn = 0.05, N = 2 (the paper's Table 1);
//       - sphere1M: a sphere, 1,000,000 points, noise 0.5%, the automatic radius, N = 1;
//       - sphere10M: the same with 10,000,000 points;
//       - lidar20M: an airborne-LiDAR-like tile, 20,000,000 points (see Lidar below), r = 3.6
//         (about 40 neighbours), rn = 0.5, N = 2.
//       Each workload runs in a child process, so its peak resident memory is its own (the
//       generated input cloud included, as a program holding the cloud would have it).
//       First, the kernel's floor (see Floor below) and the kernel alone, per kernel build.
//   pcb_benchmark --floor
//       the floor and the kernel alone only.
//   pcb_benchmark --write-lidar20M FILE.las
//       writes the lidar20M workload as a LAS file (point format 1, millimetre scale).
//   pcb_benchmark --write-lidar COUNT FILE.las|FILE.laz
//       writes the same kind of tile with COUNT points (LAZ for .laz), a million points at a
//       time, so a tile of any size is never in memory (Testing/Benchmark/pcb_scale.sh); for
//       COUNT = 20000000 and a .las path, the same bytes as --write-lidar20M.
//   pcb_benchmark --write-cube600k FILE.xyz
//       writes the cube600k workload as an ASCII file, for other programs.
//   pcb_benchmark [--runs N] --text-io IN.xyz OUT.xyz
//       times parsing a text file and writing it again (pcbilateral's text input and output
//       without the filter), median of the runs.
//   pcb_benchmark [--runs N] --las FOLDER
//       writes a 10,000,000-point LAS file (point format 3: GPS time and colours) in FOLDER,
//       then times reading it (decoded into fresh columns, the file released), writing it
//       again, and a plain read and write of the file's bytes (fread into fresh memory, fwrite),
//       alternately, in MB/s of the file (the file is in the page cache then).
//   pcb_benchmark --end-to-end [--runs N] PROGRAM ARGUMENTS...
//       times a whole program run (reading, filtering and writing), e.g. pcbilateral or the
//       authors' program on the same file, and reports its peak resident memory.
#include "BenchmarkTiming.h"
#include "BilateralFilter.h"
#include "BilateralKernel.h"
#include "CloudView.h"
#include "LASHeader.h"
#include "LASReader.h"
#include "LASWriter.h"
#include "LidarTile.h"
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
using pcbilateral_benchmark::CpuSeconds;
using pcbilateral_benchmark::Seconds;

enum class Surface
{
  Cube,
  Sphere,
  Lidar
};

struct Workload
{
  const char* Name;
  std::size_t Points;
  Surface Shape;
  double Radius, NormalRadius;
  int Iterations;
  int Runs; // 0: as given on the command line
};

/// The lidar20M workload: pi r^2 = 40.7 neighbours per point at one point per square metre;
/// rn = 10 times the noise keeps the roof edges (buildings are 4 m high or more).
constexpr std::size_t LidarPoints = 20000000;
constexpr double LidarRadius = 3.6;
constexpr double LidarNormalRadius = 0.5;

/// The lidar20M workload's points (see LidarTile).
std::vector<double> GenerateLidar(std::size_t points)
{
  std::vector<double> xyz(3 * points);
  pcbilateral_benchmark::LidarTile(points).Next(points, xyz.data());
  return xyz;
}

std::vector<double> Generate(const Workload& workload)
{
  if (workload.Shape == Surface::Lidar)
  {
    return GenerateLidar(workload.Points);
  }
  Random random(20171029);
  const std::unique_ptr<Shape> shape =
    workload.Shape == Surface::Cube ? Cube() : std::unique_ptr<Shape>(new Sphere());
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

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// What a child process reports back through a pipe.
struct Measurement
{
  double Seconds = 0.0;
  /// Processor time (user and system, all threads) of the same run: on a machine shared with
  /// other work, it grows less than the elapsed time does when the cores are taken by others.
  double CpuSeconds = 0.0;
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
    const pcbilateral::PointCloudView cloud =
      pcbilateral_testing::ViewOf(xyz.data(), workload.Points);
    pcbilateral::BilateralParameters parameters;
    parameters.Radius = workload.Radius;
    parameters.NormalRadius = workload.NormalRadius;
    parameters.NumberOfIterations = workload.Iterations;
    // A radius of 0 is the paper's automatic radius, as in the speed table.
    parameters.Automatic = pcbilateral::AutomaticParameters::Paper;
    parameters.NumberOfThreads = threads;
    std::vector<double> times, cpuTimes;
    Measurement measurement;
    for (int run = 0; run < runs; ++run)
    {
      const double cpuStart = CpuSeconds();
      const auto start = std::chrono::steady_clock::now();
      const pcbilateral::BilateralResult result =
        pcbilateral::RunBilateralFilter(cloud, parameters);
      times.push_back(Seconds(start));
      cpuTimes.push_back(CpuSeconds() - cpuStart);
      measurement.Ok = result.Status == pcbilateral::BilateralStatus::Completed;
      measurement.NeighbourEvaluations = static_cast<double>(result.NumberOfNeighbourEvaluations);
      measurement.RadiusUsed = result.RadiusUsed;
    }
    measurement.Seconds = Median(times);
    measurement.CpuSeconds = Median(cpuTimes);
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
      Storage.emplace_back(new std::uint8_t[count * pcbilateral::LASColumnBytes(dimension)]);
      Columns.push_back(Storage.back().get());
    }
  }
};

/// Nanoseconds per call of `call`, the fastest of 5 rounds of at least 0.05 s each.
template<typename Call>
double FastestNanoseconds(Call call)
{
  double best = 1e300;
  for (int round = 0; round < 5; ++round)
  {
    std::size_t calls = 0;
    const auto start = std::chrono::steady_clock::now();
    double elapsed = 0.0;
    do
    {
      for (int k = 0; k < 64; ++k)
      {
        call();
      }
      calls += 64;
      elapsed = Seconds(start);
    } while (elapsed < 0.05);
    best = std::min(best, elapsed * 1e9 / static_cast<double>(calls));
  }
  return best;
}

/// Kernel ns per neighbour evaluation on one thread, by build, from Floor(): the arithmetic
/// alone and the whole kernel.
struct FloorMeasurement
{
  double Floor = 0.0;
  double Kernel = 0.0;
  /// The neighbours the whole kernel found per point (about the `neighbours` asked for).
  double Found = 0.0;
};

/**
 * The floor: the kernel's arithmetic alone (both exponentials and all the sums of its two
 * passes, KernelArithmetic) on `neighbours` packed, pre-selected offsets that stay in the L1
 * cache, in ns per neighbour evaluation on one thread. No selection, candidate gathering,
 * eigensolver, octree or memory traffic: what no formulation of these sums with this
 * exponential can go below on this machine. Beside it, the whole kernel (FilterPoints, 8 points
 * at a time as the filter runs it) on candidates spread uniformly over the square slab around
 * the ball's equator that the floor's rough plane fills (x and y within r, z within r / 10), as
 * many as make `neighbours` of them lie in the ball of the centre (about 74% do), in the cache:
 * the floor plus selection, padding and the eigensolver. (Before 2026-11-26 the candidates were
 * 6 / pi times `neighbours`, as for a cube around a full ball, so with the slab's z the kernel
 * found 56 neighbours per point at "40" and 362 at "256".)
 */
FloorMeasurement Floor(pcbilateral::KernelInstructionSet build, std::size_t neighbours)
{
  FloorMeasurement measurement;
  if (!pcbilateral::IsAvailable(build))
  {
    return measurement;
  }
  const double radius = 0.03;
  const pcbilateral::KernelConstants constants(radius, 0.05);
  Random random(7);
  // Neighbours uniform in the ball, a rough plane's offsets: as the cube's faces give them.
  const std::size_t padded = (neighbours + pcbilateral::KernelLanes - 1) /
                             pcbilateral::KernelLanes * pcbilateral::KernelLanes;
  std::vector<double> dx(padded), dy(padded), dz(padded), weights(padded);
  for (std::size_t k = 0; k < padded; ++k)
  {
    double o[3];
    do
    {
      for (double& c : o)
      {
        c = random.Uniform(-radius, radius);
      }
    } while (o[0] * o[0] + o[1] * o[1] + o[2] * o[2] >= radius * radius);
    dx[k] = o[0];
    dy[k] = o[1];
    dz[k] = 0.1 * o[2];
  }
  const double normal[3] = { 0.0, 0.0, 1.0 };
  volatile double sink = 0.0;
  const double floorCall = FastestNanoseconds(
    [&]
    {
      sink =
        sink + pcbilateral::KernelArithmetic(
                 build, dx.data(), dy.data(), dz.data(), padded, constants, normal, weights.data());
    });
  measurement.Floor = floorCall / static_cast<double>(padded);

  // Candidates in the slab until `neighbours` of them are within the radius of the centre.
  pcbilateral::CandidateNeighbours candidates;
  std::vector<double> cx, cy, cz;
  for (std::size_t inside = 0; inside < neighbours;)
  {
    cx.push_back(random.Uniform(-radius, radius));
    cy.push_back(random.Uniform(-radius, radius));
    cz.push_back(0.1 * random.Uniform(-radius, radius));
    inside +=
      cx.back() * cx.back() + cy.back() * cy.back() + cz.back() * cz.back() < radius * radius;
  }
  candidates.Append(cx.data(), cy.data(), cz.data(), cx.size());
  // As the filter runs it: the points of a leaf KernelLanes at a time against the same
  // candidates (here points near the centre, so that each has about as many neighbours).
  double points[pcbilateral::KernelLanes][3];
  for (std::size_t k = 0; k < pcbilateral::KernelLanes; ++k)
  {
    points[k][0] = 0.01 * radius * static_cast<double>(k);
    points[k][1] = -0.01 * radius * static_cast<double>(k);
    points[k][2] = 0.0;
  }
  const pcbilateral::KernelInstructionSet previous = pcbilateral::GetKernelInstructionSet();
  pcbilateral::SetKernelInstructionSet(build);
  std::uint64_t found = 0, calls = 0;
  const double kernelCall = FastestNanoseconds(
    [&]
    {
      pcbilateral::FilteredPoint results[pcbilateral::KernelLanes];
      pcbilateral::FilterPoints(points, pcbilateral::KernelLanes, candidates, constants, results);
      for (const pcbilateral::FilteredPoint& result : results)
      {
        found += result.NeighbourCount;
      }
      ++calls;
    });
  pcbilateral::SetKernelInstructionSet(previous);
  measurement.Found = static_cast<double>(found) /
                      (static_cast<double>(calls) * static_cast<double>(pcbilateral::KernelLanes));
  measurement.Kernel = kernelCall / (static_cast<double>(found) / static_cast<double>(calls));
  return measurement;
}

/// The floor table; returns the best build's floor at 256 neighbours (the cube's count).
double PrintFloor()
{
  using pcbilateral::KernelInstructionSet;
  std::printf("kernel floor: the arithmetic alone (2 exponentials and the sums) on packed "
              "neighbours in L1,\nand the whole kernel on in-cache candidates (about 74%% "
              "neighbours), ns per neighbour evaluation, 1 thread:\n");
  std::printf("%-8s %11s %9s %11s %12s %12s %14s\n",
    "build",
    "neighbours",
    "found",
    "floor ns",
    "kernel ns",
    "kernel/floor",
    "floor evals/s");
  double best = 0.0;
  for (const KernelInstructionSet build :
    { KernelInstructionSet::Generic, KernelInstructionSet::Avx2, KernelInstructionSet::Avx512 })
  {
    if (!pcbilateral::IsAvailable(build))
    {
      std::printf("%-8s not available on this machine or build\n", pcbilateral::GetName(build));
      continue;
    }
    for (const std::size_t neighbours : { std::size_t{ 40 }, std::size_t{ 256 } })
    {
      const FloorMeasurement m = Floor(build, neighbours);
      std::printf("%-8s %11zu %9.1f %11.3f %12.3f %12.2f %14.3g\n",
        pcbilateral::GetName(build),
        neighbours,
        m.Found,
        m.Floor,
        m.Kernel,
        m.Kernel / m.Floor,
        1e9 / m.Floor);
      if (build == pcbilateral::GetKernelInstructionSet() && neighbours == 256)
      {
        best = m.Floor;
      }
    }
    std::fflush(stdout);
  }
  std::printf("\n");
  return best;
}

int Benchmark(int runs, bool skipTenMillion, const std::string& only, int onlyThreads)
{
  const Workload workloads[] = {
    { "cube600k", 600000, Surface::Cube, 0.03, 0.05, 2, 0 },
    { "sphere1M", 1000000, Surface::Sphere, 0.0, 0.0, 1, 0 },
    { "sphere10M", 10000000, Surface::Sphere, 0.0, 0.0, 1, 1 },
    { "lidar20M", LidarPoints, Surface::Lidar, LidarRadius, LidarNormalRadius, 2, 1 },
  };
  const double floor = PrintFloor();
  std::printf("kernel build: %s (floor %.3f ns per evaluation)\n",
    pcbilateral::GetName(pcbilateral::GetKernelInstructionSet()),
    floor);
  std::printf("%-9s %9s %2s %8s %3s %8s %7s %10s %11s %8s %7s %8s %7s %7s\n",
    "workload",
    "points",
    "N",
    "radius",
    "thr",
    "seconds",
    "cpu s",
    "points/s",
    "evals/point",
    "ns/eval",
    "x floor",
    "speedup",
    "peak MB",
    "B/point");
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
      if (onlyThreads > 0 && threads != onlyThreads)
      {
        continue;
      }
      double peak = 0.0;
      const Measurement m = RunInChild(workload, threads, workloadRuns, peak);
      if (!m.Ok)
      {
        std::printf("%-9s failed\n", workload.Name);
        return EXIT_FAILURE;
      }
      oneThread = threads == 1 ? m.Seconds : oneThread;
      const double pointsPerSecond = workload.Points * workload.Iterations / m.Seconds;
      // Thread-seconds per neighbour evaluation: the whole filter's cost per unit of kernel work.
      const double nsPerEvaluation = m.Seconds * threads * 1e9 / m.NeighbourEvaluations;
      std::printf("%-9s %9zu %2d %8.4g %3d %8.3f %7.2f %10.3g %11.1f %8.2f %7.2f %8s %7.0f %7.0f\n",
        workload.Name,
        workload.Points,
        workload.Iterations,
        m.RadiusUsed,
        threads,
        m.Seconds,
        m.CpuSeconds,
        pointsPerSecond,
        m.NeighbourEvaluations / workload.Points / workload.Iterations,
        nsPerEvaluation,
        nsPerEvaluation / floor,
        threads == 1 ? "" : std::to_string(oneThread / m.Seconds).substr(0, 4).c_str(),
        peak,
        peak * 1048576.0 / workload.Points);
      std::fflush(stdout);
    }
  }
  std::printf("(median of %d runs; 10M and more: 1 run; cpu s: processor time of all threads; "
              "ns/eval: thread-seconds per neighbour evaluation; x floor: over the 256-neighbour "
              "floor; peak: the child's resident "
              "memory, input included)\n",
    runs);
  return EXIT_SUCCESS;
}

/// Writes the lidar tile of `points` points (LAZ for a .laz path), a block at a time.
int WriteLidar(const char* count, const char* path)
{
  char* end = nullptr;
  const unsigned long long points = std::strtoull(count, &end, 10);
  if (end == count || *end != '\0' || points == 0 || count[0] == '-')
  {
    std::fprintf(
      stderr, "--write-lidar: the point count must be a positive integer, not '%s'\n", count);
    return EXIT_FAILURE;
  }
  const std::string error = pcbilateral_benchmark::WriteLidarTile(path, points);
  if (!error.empty())
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return EXIT_FAILURE;
  }
  std::printf("wrote %s (%llu points); the workload's parameters: -r %g -n %g -N 2\n",
    path,
    points,
    LidarRadius,
    LidarNormalRadius);
  return EXIT_SUCCESS;
}

/// The text file's parse and write alone, as pcbilateral does them (ReadPointCloudText,
/// WritePointCloudText), one thread: the part of an end-to-end run that is not the filter.
int TimeTextIO(int runs, const char* input, const char* output)
{
  std::vector<double> reads, writes;
  for (int run = 0; run < runs; ++run)
  {
    pcbilateral::PointCloudTable table;
    const auto start = std::chrono::steady_clock::now();
    std::string error = pcbilateral::ReadPointCloudText(input, false, table);
    const double read = Seconds(start);
    error = error.empty() ? pcbilateral::WritePointCloudText(output, table) : error;
    const double written = Seconds(start);
    if (!error.empty())
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      return EXIT_FAILURE;
    }
    reads.push_back(read);
    writes.push_back(written - read);
  }
  std::sort(reads.begin(), reads.end());
  std::sort(writes.begin(), writes.end());
  std::printf("%s: parse %.3f s (fastest %.3f), write %.3f s (fastest %.3f), median of %d runs\n",
    input,
    reads[reads.size() / 2],
    reads.front(),
    writes[writes.size() / 2],
    writes.front(),
    runs);
  return EXIT_SUCCESS;
}

int WriteCube(const char* path)
{
  const Workload cube{ "cube600k", 600000, Surface::Cube, 0.03, 0.05, 2, 0 };
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

/// The --las benchmark's file: the sphere10M workload as point format 3 (GPS time and
/// colours), its other fields filled with a fixed pattern of bytes. False after printing the
/// error.
bool WriteBenchmarkLAS(const std::string& path, std::size_t count)
{
  const Workload sphere{ "sphere10M", count, Surface::Sphere, 0.0, 0.0, 1, 1 };
  const std::vector<double> xyz = Generate(sphere);
  const double bounds[6] = { -1.1, -1.1, -1.1, 1.1, 1.1, 1.1 };
  const pcbilateral::LASFileInfo info = pcbilateral::DefaultLASFileInfo(count, bounds, true, true);
  LASColumns columns(info, count);
  for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
  {
    const std::size_t bytes = count * pcbilateral::LASColumnBytes(info.Dimensions[d]);
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
    return false;
  }
  return true;
}

/// The times of each run of the --las benchmark.
struct LASTimes
{
  std::vector<double> PlainReading, PlainWriting, Reading, Writing;
};

/// The bytes alone, in blocks of 64 MB, into memory allocated for them, and written again as
/// they are, in the same blocks: what any reader and writer pay the system. Returns the file's
/// size.
std::size_t TimePlainReadAndWrite(const std::string& path, const std::string& copy, LASTimes& times)
{
  auto start = std::chrono::steady_clock::now();
  std::FILE* file = std::fopen(path.c_str(), "rb");
  std::fseek(file, 0, SEEK_END);
  const std::size_t size = static_cast<std::size_t>(std::ftell(file));
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
  times.PlainReading.push_back(Seconds(start));
  // Into a new file, as the LAS write: the previous run's LAS write is removed first, not
  // truncated by the clock (freeing its 340 MB took 20-60 ms of the plain write's time).
  std::remove(copy.c_str());
  start = std::chrono::steady_clock::now();
  file = std::fopen(copy.c_str(), "wb");
  for (std::size_t at = 0; at < size; at += 64 << 20)
  {
    std::fwrite(bytes.get() + at, 1, std::min<std::size_t>(64 << 20, size - at), file);
  }
  std::fclose(file);
  times.PlainWriting.push_back(Seconds(start));
  std::remove(copy.c_str());
  return size;
}

/// The LAS read as a reader does it: opened, decoded into fresh columns, and the file released
/// (its mapping undone) before the clock stops; then written to `copy`. False after printing
/// an error.
bool TimeLASReadAndWrite(const std::string& path,
  const std::string& copy,
  std::size_t count,
  LASTimes& times)
{
  auto start = std::chrono::steady_clock::now();
  pcbilateral::LASFileInfo info;
  std::unique_ptr<LASColumns> decoded;
  {
    pcbilateral::LASFileBytes file;
    std::string error = file.Open(path);
    if (error.empty())
    {
      error = pcbilateral::ParseLASHeader(file.Data(), file.Size(), path, info);
    }
    if (!error.empty())
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      return false;
    }
    decoded = std::make_unique<LASColumns>(info, count);
    pcbilateral::DecodeLASPoints(info,
      file.Data() + info.Header.OffsetToPointData,
      count,
      decoded->Positions.get(),
      decoded->Columns.data());
  }
  times.Reading.push_back(Seconds(start));
  start = std::chrono::steady_clock::now();
  std::vector<const void*> constant(decoded->Columns.begin(), decoded->Columns.end());
  const std::string error =
    pcbilateral::WriteLAS(copy, info, count, decoded->Positions.get(), constant.data());
  if (!error.empty())
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return false;
  }
  times.Writing.push_back(Seconds(start));
  return true;
}

/// One row of the --las table: the median time of the runs and the rate it gives.
void PrintRate(const char* format, const std::vector<double>& times, double megabytes)
{
  std::printf(format, Median(times), megabytes / Median(times));
}

void PrintLASTable(const LASTimes& times, std::size_t size, int runs)
{
  const double megabytes = size / 1e6;
  std::printf(
    "LAS, 10,000,000 points of format 3 (%.0f MB), median of %d runs:\n", megabytes, runs);
  PrintRate("  plain read of the bytes: %7.3f s %8.0f MB/s\n", times.PlainReading, megabytes);
  PrintRate("  LAS read (decoded):      %7.3f s %8.0f MB/s\n", times.Reading, megabytes);
  PrintRate("  LAS write:               %7.3f s %8.0f MB/s\n", times.Writing, megabytes);
  PrintRate("  plain write of the bytes: %6.3f s %8.0f MB/s\n", times.PlainWriting, megabytes);
}

int BenchmarkLAS(int runs, const std::string& folder)
{
  const std::size_t count = 10000000;
  const std::string path = folder + "/pcb_benchmark_10M.las";
  const std::string copy = folder + "/pcb_benchmark_10M_copy.las";
  if (!WriteBenchmarkLAS(path, count))
  {
    return EXIT_FAILURE;
  }
  LASTimes times;
  std::size_t size = 0;
  for (int run = 0; run < runs; ++run)
  {
    size = TimePlainReadAndWrite(path, copy, times);
    if (!TimeLASReadAndWrite(path, copy, count, times))
    {
      return EXIT_FAILURE;
    }
  }
  PrintLASTable(times, size, runs);
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
  int onlyThreads = 0;
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
    else if (argument == "--threads" && i + 1 < argc)
    {
      onlyThreads = std::atoi(argv[++i]);
    }
    else if (argument == "--floor")
    {
      PrintFloor();
      return EXIT_SUCCESS;
    }
    else if (argument == "--write-lidar20M" && i + 1 < argc)
    {
      return WriteLidar("20000000", argv[i + 1]);
    }
    else if (argument == "--write-lidar" && i + 2 < argc)
    {
      return WriteLidar(argv[i + 1], argv[i + 2]);
    }
    else if (argument == "--write-cube600k" && i + 1 < argc)
    {
      return WriteCube(argv[i + 1]);
    }
    else if (argument == "--text-io" && i + 2 < argc)
    {
      return TimeTextIO(runs, argv[i + 1], argv[i + 2]);
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
        "usage: %s [--runs N] [--skip-10m] [--threads 1|2] [--only "
        "cube600k|sphere1M|sphere10M|lidar20M] | "
        "--floor | --write-cube600k FILE.xyz | --write-lidar20M FILE.las | "
        "--write-lidar COUNT FILE.las|FILE.laz | [--runs N] --text-io IN.xyz OUT.xyz | "
        "[--runs N] --las FOLDER | "
        "[--runs N] --end-to-end PROGRAM ARGUMENTS...\n",
        argv[0]);
      return EXIT_FAILURE;
    }
  }
  return Benchmark(runs, skipTenMillion, only, onlyThreads);
}

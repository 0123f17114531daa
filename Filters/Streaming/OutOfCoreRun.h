// The bilateral filter on a file larger than a memory limit: the points bucketed on disk into
// slabs along the cloud's longest axis, each slab filtered with the halo the radius and the
// iterations need, the results kept on disk until the writer reads them back in file order.
// Plain C++17 over Core and Formats, no VTK (pcbilateral --memory-limit).
//
// Why the result is the same bits as the in-memory run (docs/streaming.md has the argument in
// full): every parameter is resolved from the whole cloud (its extent, and the measurement's
// selection, which a hash of each point's coordinates decides, so a stream gathers exactly the
// points the in-memory run measures); the octree's lattice comes from the whole cloud's extent;
// a point's sums run over its neighbours within its radius, in an order fixed by their
// coordinates alone (ProcessingOctree.h: leaves sorted by coordinates; BilateralKernelBody.h:
// candidates beyond the radius packed out before the lanes are assigned), so points beyond the
// radius, present or not, change no bit; and a slab's halo is wide enough that no point missing
// from it, and no halo point whose own neighbourhood is cut, can come within a radius of a core
// point in any iteration: N^2 x the largest radius (each iteration moves a point by less than its
// radius, so the uncertain region grows by 2k - 1 radii in iteration k).
#ifndef pcbilateral_OutOfCoreRun_h
#define pcbilateral_OutOfCoreRun_h

#include "BilateralFilter.h"
#include "BilateralParameters.h"
#include "CloudMeasurement.h"
#include "PointCloudView.h"

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pcbilateral
{

/// The points left alone (--classes) as read: they are written unchanged, so what the output's
/// writer decides over every position written (a PCD file's F4 coordinates, a LAS header's
/// scale and offset from the bounds) takes them too. Gathered on the first pass over the file.
struct LeftAlonePoints
{
  std::uint64_t Count = 0;
  /// Whether every coordinate is exactly a float (NaN counts as one, as for
  /// vtkPCDPointCloudWriter).
  bool Floats = true;
  /// The bounds of those with finite coordinates (min x, y, z, max x, y, z).
  double Bounds[6] = { HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  /// The ranges before this point were counted (ranges are read in order on the first pass).
  std::uint64_t CountedUpTo = 0;

  void Add(const double* position);
};

/// A file's points, read a range at a time in file order.
class StreamedPoints
{
public:
  virtual ~StreamedPoints() = default;
  virtual std::uint64_t GetNumberOfPoints() const = 0;
  /// Positions (x y z interleaved) of points [first, first + count); an empty string or a
  /// one-line message.
  virtual std::string ReadPositions(std::uint64_t first, std::size_t count, double* positions) = 0;
  /// The points left alone (--classes: not of the chosen classes), which ReadPositions gives
  /// NaN coordinates so that the run passes them through and never uses them as neighbours, as
  /// the run in memory does; unlike points without coordinates, no warning is said for them.
  /// Known after the first pass over the file.
  std::uint64_t GetNumberOfPointsLeftAlone() const { return this->LeftAlone.Count; }
  /// Their positions as read (for the output's float check and bounds).
  const LeftAlonePoints& GetLeftAlonePoints() const { return this->LeftAlone; }
  /// The point array (the file's dimension or field) whose classes were chosen, or empty.
  virtual std::string GetClassArrayName() const { return std::string(); }

protected:
  /// For ReadPositions of points [first, first + count) read as `positions`: each point whose
  /// `chosen` is 0 is counted and gathered on the first pass, then given NaN coordinates.
  void LeaveAlone(std::uint64_t first,
    std::size_t count,
    const std::uint8_t* chosen,
    double* positions);

  LeftAlonePoints LeftAlone;
};

struct OutOfCoreSettings
{
  /// The peak memory the run may take, in bytes, the caller's own share (`ReservedBytes`, e.g.
  /// the program and its libraries) included.
  std::uint64_t MemoryLimit = 0;
  std::uint64_t ReservedBytes = 0;
  /// Where the temporary files go (a folder of their own is made in it).
  std::string TemporaryDirectory;
  int NumberOfThreads = 0;
  /// At most this many points in a slab and its halo (0: as many as the memory limit allows):
  /// for tests of many slabs on small files.
  std::uint64_t MaximumSlabPoints = 0;
  /// Progress of each phase ("measuring", "bucketing", "slab k/n"...), fraction 0 to 1.
  std::function<void(const std::string& phase, double fraction)> Progress;
};

/// What the run decided: shown to the user.
struct OutOfCorePlan
{
  int Axis = 0;
  std::size_t NumberOfSlabs = 0;
  /// The widest halo of a slab, in the cloud's units.
  double Halo = 0.0;
  /// The most points a slab and its halo hold.
  std::uint64_t LargestSlabPoints = 0;
  /// The temporary files' size at their largest, in bytes, and where they are.
  std::uint64_t DiskBytes = 0;
  std::string TemporaryFolder;
};

/**
 * One out-of-core run:
 *
 *   OutOfCoreRun run(points, parameters, settings);
 *   run.Measure();     // pass 1: extent, count, measurement selection; parameters resolved
 *   run.Bucket();      // pass 2: points into bins on disk; slabs planned within the limit
 *   run.Filter();      // each slab and its halo filtered; results to disk
 *   run.ReadFiltered(first, count, positions) ... // the filtered positions in file order
 *
 * Each step returns an empty string or a one-line message; after a message, stop. The
 * temporary files are removed by the destructor, and by SIGINT, SIGTERM and SIGHUP
 * (RemoveTemporaryFilesOnSignals).
 */
class OutOfCoreRun
{
public:
  OutOfCoreRun(StreamedPoints& points,
    const BilateralParameters& parameters,
    const OutOfCoreSettings& settings);
  ~OutOfCoreRun();
  OutOfCoreRun(const OutOfCoreRun&) = delete;
  OutOfCoreRun& operator=(const OutOfCoreRun&) = delete;

  std::string Measure();
  /// The parameters used and the measured scales, as the in-memory run reports them (valid
  /// after Measure; the radius ranges where it follows the density after Bucket).
  const BilateralResult& GetSummary() const;
  /// The disk the run will take at most, known after Measure: checked against the free space
  /// of the temporary folder by Bucket.
  std::uint64_t GetDiskBytesNeeded() const;
  std::string Bucket();
  const OutOfCorePlan& GetPlan() const;
  std::string Filter();
  /// Filtered positions of points [first, first + count), read in increasing order of first;
  /// points that are not finite are left as they are in `positions`. With `removed`, 1 for each
  /// point --remove-isolated removed (to be left out of the output), else 0.
  std::string ReadFiltered(std::uint64_t first,
    std::size_t count,
    double* positions,
    std::uint8_t* removed = nullptr);
  /// The points --remove-isolated removed (known after Filter).
  std::uint64_t GetNumberOfRemovedPoints() const;
  /// Whether every filtered position of the points kept, and every position of the points left
  /// alone (--classes), is exactly a float (after Filter).
  bool AreFilteredPositionsFloats() const;
  /// The bounds of the filtered positions of the points kept and of the points left alone
  /// (min x, y, z, max x, y, z; the points without coordinates left out, as VTK's bounds leave
  /// NaN out), after Filter.
  void GetFilteredBounds(double bounds[6]) const;

  /// Bytes of memory a slab takes per point (the run's arrays, the octree, the bins read).
  static constexpr std::uint64_t BytesPerSlabPoint = 160;
  /// The same for the edge-aware mode, whose run also keeps the neighbour lists of its first
  /// step up to 2^26 entries (EdgeAwareNormals.cxx, NeighbourCache: 256 MB and the lists' own
  /// headers, 24 bytes a point): those are counted as a fixed share besides the slab's points.
  static constexpr std::uint64_t EdgeAwareBytesPerSlabPoint = 240;
  static constexpr std::uint64_t EdgeAwareNeighbourListBytes = std::uint64_t(272) << 20;

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

/// Installs handlers of SIGINT, SIGTERM and SIGHUP that remove every temporary file of the
/// running OutOfCoreRun, and `extraPath` (e.g. the output's partial file), then exit with 128 +
/// the signal. Call once, before the run.
void RemoveTemporaryFilesOnSignals(const std::string& extraPath);

/// "512M", "2G", "1.5G", "4096" (bytes), "800K": the size in bytes, or 0 when not a size.
std::uint64_t ParseMemorySize(const std::string& text);

/// The memory the system can give without swapping (MemAvailable of /proc/meminfo), 0 when
/// unknown.
std::uint64_t AvailableMemory();

/// The memory the run in memory takes per point, end to end (issue 27 measured 148 bytes on a
/// LAS file of point format 0; lidar20M, format 1: 3.14 GB for 20M points).
constexpr std::uint64_t InMemoryBytesPerPoint = 160;

/// The memory limit pcbilateral streams within when none is given: 0 (run in memory) when a
/// cloud of `numberOfPoints` points needs at most 80% of the `available` memory (or that is
/// unknown, 0), else that 80%.
std::uint64_t AutomaticMemoryLimit(std::uint64_t numberOfPoints, std::uint64_t available);

/// The memory this process holds now (VmRSS of /proc/self/status), 0 when unknown.
std::uint64_t ResidentMemory();

/// Where the temporary files of a run that writes `outputPath` go: TMPDIR when set, else the
/// output's folder.
std::string TemporaryDirectoryFor(const std::string& outputPath);

/// The settings of pcbilateral's streamed run within `limit` bytes into `outputPath`: the memory
/// the program holds now and 96 MB of buffers reserved, the temporary folder, and
/// PCB_STREAMING_SLAB_POINTS from the environment (tests: many slabs on a small file).
OutOfCoreSettings StreamingSettings(std::uint64_t limit,
  const std::string& outputPath,
  int numberOfThreads);

/// Why no run can work within the memory limit of these settings, judged before anything is
/// read, or empty: a limit below a megabyte (most likely a size given without its unit, which
/// means bytes), far below what the program holds besides the slabs (ReservedBytes, and in the
/// `edgeAware` mode the neighbour lists). A larger limit that cannot hold a slab is said once
/// the slabs are planned, with the limit that holds them (OutOfCoreRun::Bucket).
std::string MemoryLimitProblem(const OutOfCoreSettings& settings, bool edgeAware);

/// A size as people read it: "512 MB" in whole megabytes from 1 MB on, "800 KB" in whole
/// kilobytes from 1 KB on, "100 bytes" below (never "0 MB" for a size that is not 0).
std::string MemorySizeText(std::uint64_t bytes);

} // namespace pcbilateral

#endif

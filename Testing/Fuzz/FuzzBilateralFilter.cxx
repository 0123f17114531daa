// libFuzzer target for the core filter: arbitrary small clouds (NaN, infinities, duplicates,
// huge and tiny coordinates) and parameters. Invalid parameters must be refused with a message;
// otherwise every output point must be finite where its input was, and within N r of it, and
// the generic build of the kernel must give the same bits as the best one of the machine.
#include "BilateralFilter.h"
#include "BilateralKernel.h"
#include "CoreTesting.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <omp.h>
#include <vector>

namespace
{
/// Reads the next value from the fuzzer's bytes (zeros once they run out).
class Bytes
{
public:
  Bytes(const std::uint8_t* data, std::size_t size)
    : Data(data)
    , Size(size)
  {
  }
  template<typename T>
  T Next()
  {
    T value{};
    const std::size_t count = std::min(sizeof(T), this->Size - this->Offset);
    std::memcpy(&value, this->Data + this->Offset, count);
    this->Offset += count;
    return value;
  }
  /// A coordinate: half of the time a small integer grid value (duplicates, exact planes and
  /// lines), otherwise any double, special values included.
  double Coordinate()
  {
    const auto kind = this->Next<std::uint8_t>();
    if (kind & 1)
    {
      return static_cast<double>(this->Next<std::int8_t>()) / 16.0;
    }
    return this->Next<double>();
  }

private:
  const std::uint8_t* Data;
  std::size_t Size;
  std::size_t Offset = 0;
};

/// The parameters, from the first bytes. Threads: 1 or 2, but never more than OpenMP's maximum
/// (the reproducible runs of the test command set OMP_NUM_THREADS=1: coverage counted from two
/// threads at once varies from run to run).
pcbilateral::BilateralParameters ReadParameters(Bytes& bytes)
{
  pcbilateral::BilateralParameters parameters;
  const auto radiusKind = bytes.Next<std::uint8_t>();
  parameters.Radius = (radiusKind & 3) == 0   ? 0.0
                      : (radiusKind & 3) == 1 ? bytes.Next<double>()
                                              : (radiusKind % 64) / 8.0;
  const auto normalKind = bytes.Next<std::uint8_t>();
  parameters.NormalRadius = (normalKind & 3) == 0   ? 0.0
                            : (normalKind & 3) == 1 ? bytes.Next<double>()
                                                    : (normalKind % 64) / 16.0;
  parameters.NumberOfIterations = bytes.Next<std::uint8_t>() % 4;
  const auto flags = bytes.Next<std::uint8_t>();
  parameters.RemoveIsolatedPoints = flags & 1;
  parameters.EdgeAware = (flags & 2) != 0; // the edge-aware mode (EdgeAwareNormals.h)
  const int threads = 1 + bytes.Next<std::uint8_t>() % 2;
  parameters.NumberOfThreads = std::min(threads, omp_get_max_threads());
  parameters.ComputeNormals = true;
  return parameters;
}

/// Whether the generic build of the kernel gives the result's bits too.
bool SameBitsWithGenericKernel(const pcbilateral::PointCloudView& cloud,
  const pcbilateral::BilateralParameters& parameters,
  const pcbilateral::BilateralResult& result)
{
  const pcbilateral::KernelInstructionSet best = pcbilateral::GetKernelInstructionSet();
  if (best == pcbilateral::KernelInstructionSet::Generic)
  {
    return true;
  }
  pcbilateral::SetKernelInstructionSet(pcbilateral::KernelInstructionSet::Generic);
  const pcbilateral::BilateralResult generic = pcbilateral::RunBilateralFilter(cloud, parameters);
  pcbilateral::SetKernelInstructionSet(best);
  return pcbilateral_testing::SameBits(generic.Positions, result.Positions) &&
         pcbilateral_testing::SameBits(generic.Normals, result.Normals);
}

/// Whether every finite input point stayed finite and within N r of where it was.
bool StayedWithinReach(const std::vector<double>& xyz, const pcbilateral::BilateralResult& result)
{
  const double reach = result.NumberOfIterationsUsed * result.RadiusUsed; // N may be automatic
  for (std::size_t i = 0; i < xyz.size() / 3; ++i)
  {
    const double* before = &xyz[3 * i];
    const double* after = &result.Positions[3 * i];
    if (!(std::isfinite(before[0]) && std::isfinite(before[1]) && std::isfinite(before[2])))
    {
      continue;
    }
    double moved = 0.0;
    for (int axis = 0; axis < 3; ++axis)
    {
      if (!std::isfinite(after[axis]))
      {
        return false; // a finite point became NaN or infinite
      }
      moved = std::max(moved, std::abs(after[axis] - before[axis]));
    }
    if (moved > reach * (1 + 1e-9) && moved > 0.0)
    {
      return false; // a point moved further than N r
    }
  }
  return true;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Bytes bytes(data, size);
  const pcbilateral::BilateralParameters parameters = ReadParameters(bytes);
  const std::size_t count = bytes.Next<std::uint8_t>() % 48;
  std::vector<double> xyz(3 * count);
  for (double& value : xyz)
  {
    value = bytes.Coordinate();
  }

  pcbilateral::PointCloudView cloud;
  cloud.NumberOfPoints = count;
  cloud.Positions = xyz.data();
  const pcbilateral::BilateralResult result = pcbilateral::RunBilateralFilter(cloud, parameters);
  const bool validParameters = std::isfinite(parameters.Radius) && parameters.Radius >= 0 &&
                               std::isfinite(parameters.NormalRadius) &&
                               parameters.NormalRadius >= 0;
  if (result.Status == pcbilateral::BilateralStatus::Failed)
  {
    if (result.Error.empty())
    {
      std::abort(); // a refusal must say why
    }
    return 0;
  }
  if (!validParameters || result.Positions.size() != xyz.size())
  {
    std::abort();
  }
  if (!SameBitsWithGenericKernel(cloud, parameters, result))
  {
    std::abort(); // the instruction-set builds disagree
  }
  if (!StayedWithinReach(xyz, result))
  {
    std::abort();
  }
  return 0;
}

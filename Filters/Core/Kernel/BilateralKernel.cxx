#include "BilateralKernel.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <utility>

namespace pcbilateral
{

// The builds of the kernel body (BilateralKernelBody.h), one per instruction set.
#define PCB_DECLARE_KERNEL_BUILD(variant)                                                          \
  namespace variant                                                                                \
  {                                                                                                \
  void FilterPoints(const double (*points)[3],                                                     \
    std::size_t pointCount,                                                                        \
    const double* x,                                                                               \
    const double* y,                                                                               \
    const double* z,                                                                               \
    std::size_t count,                                                                             \
    const KernelConstants& constants,                                                              \
    const KernelScratch* scratch,                                                                  \
    FilteredPoint* results);                                                                       \
  void ExpOfNonPositive(const double* in, double* out, std::size_t count);                         \
  std::size_t CopyNearBox(const double* sx,                                                        \
    const double* sy,                                                                              \
    const double* sz,                                                                              \
    std::size_t count,                                                                             \
    const double low[3],                                                                           \
    const double high[3],                                                                          \
    double reachSquared,                                                                           \
    double* x,                                                                                     \
    double* y,                                                                                     \
    double* z);                                                                                    \
  void SmallestEigenvectorsOfMatrices(const double* matrices,                                      \
    double* eigenvectors,                                                                          \
    std::size_t count);                                                                            \
  double ArithmeticFloor(const double* dx,                                                         \
    const double* dy,                                                                              \
    const double* dz,                                                                              \
    std::size_t padded,                                                                            \
    const KernelConstants& constants,                                                              \
    const double n[3],                                                                             \
    double* distanceWeight);                                                                       \
  EdgeAwareKernel MakeEdgeAwareKernel();                                                           \
  }
PCB_DECLARE_KERNEL_BUILD(generic)
#if PCB_KERNEL_X86
PCB_DECLARE_KERNEL_BUILD(avx2)
PCB_DECLARE_KERNEL_BUILD(avx512)
#endif
#undef PCB_DECLARE_KERNEL_BUILD

// Returns FUNCTION(arguments...) of the build for INSTRUCTION_SET.
#if PCB_KERNEL_X86
#define PCB_RETURN_FROM_BUILD(INSTRUCTION_SET, FUNCTION, ...)                                      \
  switch (INSTRUCTION_SET)                                                                         \
  {                                                                                                \
    case KernelInstructionSet::Avx512:                                                             \
      return avx512::FUNCTION(__VA_ARGS__);                                                        \
    case KernelInstructionSet::Avx2:                                                               \
      return avx2::FUNCTION(__VA_ARGS__);                                                          \
    default:                                                                                       \
      return generic::FUNCTION(__VA_ARGS__);                                                       \
  }
#else
#define PCB_RETURN_FROM_BUILD(INSTRUCTION_SET, FUNCTION, ...)                                      \
  (void)(INSTRUCTION_SET);                                                                         \
  return generic::FUNCTION(__VA_ARGS__);
#endif

namespace
{
KernelInstructionSet BestInstructionSet()
{
  for (const auto candidate : { KernelInstructionSet::Avx512, KernelInstructionSet::Avx2 })
  {
    if (IsAvailable(candidate))
    {
      return candidate;
    }
  }
  return KernelInstructionSet::Generic;
}

std::atomic<KernelInstructionSet>& CurrentInstructionSet()
{
  static std::atomic<KernelInstructionSet> current{ BestInstructionSet() };
  return current;
}
} // namespace

KernelConstants::KernelConstants(double radius, double normalRadius)
{
  const double distanceSigma = radius / 3.0;
  const double normalSigma = normalRadius / 3.0;
  this->RadiusSquared = radius * radius;
  this->DistanceScale = 1.0 / (2.0 * distanceSigma * distanceSigma);
  this->NormalScale = 1.0 / (2.0 * normalSigma * normalSigma);
}

void CandidateNeighbours::Append(const double* x,
  const double* y,
  const double* z,
  std::size_t count)
{
  this->Reserve(this->Count + count);
  std::memcpy(this->X.data() + this->Count, x, count * sizeof(double));
  std::memcpy(this->Y.data() + this->Count, y, count * sizeof(double));
  std::memcpy(this->Z.data() + this->Count, z, count * sizeof(double));
  this->Count += count;
}

void CandidateNeighbours::Reserve(std::size_t size)
{
  if (this->X.size() < size)
  {
    // Grow geometrically: candidate counts vary from block to block.
    const std::size_t capacity = std::max(size, 2 * this->X.size());
    this->X.resize(capacity);
    this->Y.resize(capacity);
    this->Z.resize(capacity);
  }
}

void CandidateNeighbours::AppendNearBox(const double* x,
  const double* y,
  const double* z,
  std::size_t count,
  const double low[3],
  const double high[3],
  double reachSquared)
{
  this->Reserve(this->Count + count);
  double* to[3] = {
    this->X.data() + this->Count, this->Y.data() + this->Count, this->Z.data() + this->Count
  };
  this->Count += [&]() -> std::size_t
  {
    PCB_RETURN_FROM_BUILD(GetKernelInstructionSet(),
      CopyNearBox,
      x,
      y,
      z,
      count,
      low,
      high,
      reachSquared,
      to[0],
      to[1],
      to[2]);
  }();
}

void CandidateNeighbours::Scratch(KernelScratch* scratch, std::size_t points)
{
  if (points == 0)
  {
    return;
  }
  const std::size_t arrays = 4 * points;
  const std::size_t stride = this->Size() + KernelLanes;
  if (this->ScratchStorage.size() < arrays * stride)
  {
    // Grow geometrically: candidate counts vary from leaf to leaf.
    this->ScratchStorage.resize(std::max(arrays * stride, 2 * this->ScratchStorage.size()));
  }
  const std::size_t capacity = this->ScratchStorage.size() / arrays;
  double* storage = this->ScratchStorage.data();
  for (std::size_t point = 0; point < points; ++point)
  {
    double* own = storage + 4 * point * capacity;
    scratch[point].Dx = own;
    scratch[point].Dy = own + capacity;
    scratch[point].Dz = own + 2 * capacity;
    scratch[point].DistanceWeight = own + 3 * capacity;
  }
}

const char* GetName(KernelInstructionSet instructionSet)
{
  switch (instructionSet)
  {
    case KernelInstructionSet::Avx512:
      return "AVX-512";
    case KernelInstructionSet::Avx2:
      return "AVX2";
    default:
      return "generic";
  }
}

bool IsAvailable(KernelInstructionSet instructionSet)
{
  switch (instructionSet)
  {
#if PCB_KERNEL_X86
    case KernelInstructionSet::Avx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("popcnt");
    case KernelInstructionSet::Avx2:
      // Its multiply-adds are fused (BilateralKernelBody.h): AVX2 without FMA, which a few
      // processors have, runs the generic build.
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#endif
    case KernelInstructionSet::Generic:
      return true;
    default:
      return false;
  }
}

KernelInstructionSet GetKernelInstructionSet()
{
  return CurrentInstructionSet().load(std::memory_order_relaxed);
}

bool SetKernelInstructionSet(KernelInstructionSet instructionSet)
{
  if (!IsAvailable(instructionSet))
  {
    return false;
  }
  CurrentInstructionSet().store(instructionSet);
  return true;
}

void KernelExp(const double* x, double* result, std::size_t count)
{
  PCB_RETURN_FROM_BUILD(GetKernelInstructionSet(), ExpOfNonPositive, x, result, count);
}

void KernelSmallestEigenvectors(const double* matrices, double* eigenvectors, std::size_t count)
{
  PCB_RETURN_FROM_BUILD(
    GetKernelInstructionSet(), SmallestEigenvectorsOfMatrices, matrices, eigenvectors, count);
}

EdgeAwareKernel GetEdgeAwareKernel()
{
  PCB_RETURN_FROM_BUILD(GetKernelInstructionSet(), MakeEdgeAwareKernel);
}

double KernelArithmetic(KernelInstructionSet instructionSet,
  const double* dx,
  const double* dy,
  const double* dz,
  std::size_t count,
  const KernelConstants& constants,
  const double normal[3],
  double* distanceWeight)
{
  if (count % KernelLanes != 0 || !IsAvailable(instructionSet))
  {
    return 0.0;
  }
  PCB_RETURN_FROM_BUILD(
    instructionSet, ArithmeticFloor, dx, dy, dz, count, constants, normal, distanceWeight);
}

void FilterPoints(const double (*points)[3],
  std::size_t count,
  CandidateNeighbours& candidates,
  const KernelConstants& constants,
  FilteredPoint* results)
{
  if (count == 0)
  {
    return;
  }
  KernelScratch scratch[KernelLanes];
  candidates.Scratch(scratch, count);
  const double* x = candidates.X.data();
  const double* y = candidates.Y.data();
  const double* z = candidates.Z.data();
  const std::size_t candidateCount = candidates.Size();
  for (std::size_t point = 0; point < count; ++point)
  {
    results[point] = FilteredPoint();
  }
  PCB_RETURN_FROM_BUILD(GetKernelInstructionSet(),
    FilterPoints,
    points,
    count,
    x,
    y,
    z,
    candidateCount,
    constants,
    scratch,
    results);
}

FilteredPoint FilterPoint(const double p[3],
  CandidateNeighbours& candidates,
  const KernelConstants& constants)
{
  const double points[1][3] = { { p[0], p[1], p[2] } };
  FilteredPoint result;
  FilterPoints(points, 1, candidates, constants, &result);
  return result;
}

} // namespace pcbilateral

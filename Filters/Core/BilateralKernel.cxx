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
  void FilterPoint(const double p[3],                                                              \
    const double* x,                                                                               \
    const double* y,                                                                               \
    const double* z,                                                                               \
    std::size_t count,                                                                             \
    const KernelConstants& constants,                                                              \
    KernelScratch& scratch,                                                                        \
    FilteredPoint& result);                                                                        \
  void ExpOfNonPositive(const double* in, double* out, std::size_t count);                         \
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
  const std::size_t size = this->Count + count;
  if (this->X.size() < size)
  {
    // Grow geometrically: candidate counts vary from block to block.
    const std::size_t capacity = std::max(size, 2 * this->X.size());
    this->X.resize(capacity);
    this->Y.resize(capacity);
    this->Z.resize(capacity);
  }
  std::memcpy(this->X.data() + this->Count, x, count * sizeof(double));
  std::memcpy(this->Y.data() + this->Count, y, count * sizeof(double));
  std::memcpy(this->Z.data() + this->Count, z, count * sizeof(double));
  this->Count = size;
}

KernelScratch CandidateNeighbours::Scratch()
{
  const std::size_t stride = this->Size() + KernelLanes;
  if (this->ScratchStorage.size() < 4 * stride)
  {
    // Grow geometrically: candidate counts vary from leaf to leaf.
    this->ScratchStorage.resize(std::max(4 * stride, 2 * this->ScratchStorage.size()));
  }
  const std::size_t capacity = this->ScratchStorage.size() / 4;
  double* storage = this->ScratchStorage.data();
  KernelScratch scratch;
  scratch.Dx = storage;
  scratch.Dy = storage + capacity;
  scratch.Dz = storage + 2 * capacity;
  scratch.DistanceWeight = storage + 3 * capacity;
  return scratch;
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
      return __builtin_cpu_supports("avx2");
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
  switch (GetKernelInstructionSet())
  {
#if PCB_KERNEL_X86
    case KernelInstructionSet::Avx512:
      return avx512::ExpOfNonPositive(x, result, count);
    case KernelInstructionSet::Avx2:
      return avx2::ExpOfNonPositive(x, result, count);
#endif
    default:
      return generic::ExpOfNonPositive(x, result, count);
  }
}

EdgeAwareKernel GetEdgeAwareKernel()
{
  switch (GetKernelInstructionSet())
  {
#if PCB_KERNEL_X86
    case KernelInstructionSet::Avx512:
      return avx512::MakeEdgeAwareKernel();
    case KernelInstructionSet::Avx2:
      return avx2::MakeEdgeAwareKernel();
#endif
    default:
      return generic::MakeEdgeAwareKernel();
  }
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
  switch (instructionSet)
  {
#if PCB_KERNEL_X86
    case KernelInstructionSet::Avx512:
      return avx512::ArithmeticFloor(dx, dy, dz, count, constants, normal, distanceWeight);
    case KernelInstructionSet::Avx2:
      return avx2::ArithmeticFloor(dx, dy, dz, count, constants, normal, distanceWeight);
#endif
    default:
      return generic::ArithmeticFloor(dx, dy, dz, count, constants, normal, distanceWeight);
  }
}

void SmallestEigenvector(const double covariance[6], double eigenvector[3])
{
  // The eigenvectors of C are those of B = (C - shift I) / scale, with the shift making B's
  // trace zero and the scale its largest entry one: the closed form below then works on
  // numbers of order one, whatever the units and the offset of the cloud.
  const double shift = (covariance[0] + covariance[3] + covariance[5]) / 3.0;
  double b[6] = { covariance[0] - shift,
    covariance[1],
    covariance[2],
    covariance[3] - shift,
    covariance[4],
    covariance[5] - shift };
  double scale = 0.0;
  for (const double entry : b)
  {
    scale = std::max(scale, std::abs(entry));
  }
  eigenvector[0] = 0.0;
  eigenvector[1] = 0.0;
  eigenvector[2] = 1.0;
  if (!(scale > 0.0) || !std::isfinite(scale))
  {
    return; // C = shift I: every direction is an eigenvector
  }
  for (double& entry : b)
  {
    entry /= scale;
  }
  const double b00 = b[0], b01 = b[1], b02 = b[2], b11 = b[3], b12 = b[4], b22 = b[5];

  // B's eigenvalues are 2 p cos(phi + 2 pi j / 3) with p^2 = tr(B^2) / 6 and
  // cos(3 phi) = det(B) / (2 p^3) (trigonometric solution of the characteristic cubic).
  const double p = std::sqrt(
    (b00 * b00 + b11 * b11 + b22 * b22 + 2.0 * (b01 * b01 + b02 * b02 + b12 * b12)) / 6.0);
  const double determinant =
    b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) + b02 * (b01 * b12 - b11 * b02);
  const double cosine = std::min(1.0, std::max(-1.0, determinant / (2.0 * p * p * p)));
  constexpr double TwoPiOverThree = 2.0943951023931954923;
  const double smallest = 2.0 * p * std::cos(std::acos(cosine) / 3.0 + TwoPiOverThree);

  // The eigenvector is orthogonal to the rows of B - smallest I: the cross product of two rows.
  // The largest of the three cross products is the most accurate one.
  const double rows[3][3] = {
    { b00 - smallest, b01, b02 }, { b01, b11 - smallest, b12 }, { b02, b12, b22 - smallest }
  };
  double best[3] = { 0.0, 0.0, 0.0 };
  double bestNorm = 0.0;
  for (const auto& pair : { std::make_pair(0, 1), std::make_pair(0, 2), std::make_pair(1, 2) })
  {
    const double* u = rows[pair.first];
    const double* v = rows[pair.second];
    const double cross[3] = {
      u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]
    };
    const double norm = cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2];
    if (norm > bestNorm)
    {
      bestNorm = norm;
      std::copy(cross, cross + 3, best);
    }
  }
  // Below this, the rows are parallel to rounding: the smallest eigenvalue is double (points on
  // a line) and any direction orthogonal to the rows is an eigenvector of it.
  constexpr double ParallelRows = 1e-24;
  if (!(bestNorm > ParallelRows))
  {
    int largestRow = 0;
    double largestNorm = 0.0;
    for (int row = 0; row < 3; ++row)
    {
      const double* u = rows[row];
      const double norm = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
      if (norm > largestNorm)
      {
        largestNorm = norm;
        largestRow = row;
      }
    }
    if (!(largestNorm > 0.0))
    {
      return;
    }
    // Cross the row with the axis it is least aligned with.
    const double* u = rows[largestRow];
    int axis = 0;
    for (int other = 1; other < 3; ++other)
    {
      if (std::abs(u[other]) < std::abs(u[axis]))
      {
        axis = other;
      }
    }
    double unit[3] = { 0.0, 0.0, 0.0 };
    unit[axis] = 1.0;
    best[0] = u[1] * unit[2] - u[2] * unit[1];
    best[1] = u[2] * unit[0] - u[0] * unit[2];
    best[2] = u[0] * unit[1] - u[1] * unit[0];
    bestNorm = best[0] * best[0] + best[1] * best[1] + best[2] * best[2];
  }
  const double length = std::sqrt(bestNorm);
  for (int axis = 0; axis < 3; ++axis)
  {
    eigenvector[axis] = best[axis] / length;
  }
}

FilteredPoint FilterPoint(const double p[3],
  CandidateNeighbours& candidates,
  const KernelConstants& constants)
{
  FilteredPoint result;
  KernelScratch scratch = candidates.Scratch();
  const double* x = candidates.X.data();
  const double* y = candidates.Y.data();
  const double* z = candidates.Z.data();
  const std::size_t count = candidates.Size();
  switch (GetKernelInstructionSet())
  {
#if PCB_KERNEL_X86
    case KernelInstructionSet::Avx512:
      avx512::FilterPoint(p, x, y, z, count, constants, scratch, result);
      break;
    case KernelInstructionSet::Avx2:
      avx2::FilterPoint(p, x, y, z, count, constants, scratch, result);
      break;
#endif
    default:
      generic::FilterPoint(p, x, y, z, count, constants, scratch, result);
  }
  return result;
}

} // namespace pcbilateral

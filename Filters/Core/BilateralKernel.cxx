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

namespace
{
/**
 * The largest of the cross products of the rows of the symmetric matrix B - eigenvalue I (the
 * most accurate one): a vector along the eigenvector of that eigenvalue, when it is simple.
 * Returns its squared length.
 */
double EigenvectorFromRows(const double b[6], double eigenvalue, double vector[3])
{
  const double rows[3][3] = { { b[0] - eigenvalue, b[1], b[2] },
    { b[1], b[3] - eigenvalue, b[4] },
    { b[2], b[4], b[5] - eigenvalue } };
  double bestNorm = 0.0;
  vector[0] = vector[1] = vector[2] = 0.0;
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
      std::copy(cross, cross + 3, vector);
    }
  }
  return bestNorm;
}

/// A vector orthogonal to the non-zero vector u: u crossed with the axis it is least aligned
/// with. Returns its squared length.
double OrthogonalVector(const double u[3], double vector[3])
{
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
  vector[0] = u[1] * unit[2] - u[2] * unit[1];
  vector[1] = u[2] * unit[0] - u[0] * unit[2];
  vector[2] = u[0] * unit[1] - u[1] * unit[0];
  return vector[0] * vector[0] + vector[1] * vector[1] + vector[2] * vector[2];
}
} // namespace

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
  const double inverseScale = 1.0 / scale;
  for (double& entry : b)
  {
    entry *= inverseScale;
  }
  const double b00 = b[0], b01 = b[1], b02 = b[2], b11 = b[3], b12 = b[4], b22 = b[5];

  // B's eigenvalues are 2 p t for the three roots t of 4 t^3 - 3 t = c, with p^2 = tr(B^2) / 6
  // and c = det(B) / (2 p^3) in [-1, 1] (the characteristic cubic; classically t = cos(phi +
  // 2 pi j / 3) with cos(3 phi) = c). The smallest root is in [-1, -1/2]: t = -(1/2 + e) with e
  // in [0, 1/2] the root of (6 + 4 e) e^2 = 1 - c, found by Newton's method rather than with
  // acos and cos, whose last bits differ between libm versions and between their FMA and
  // non-FMA code paths, and which cost half of this function. Written in e, the cubic stays
  // well conditioned where the two smallest roots meet (c near 1, e near 0).
  const double p = std::sqrt(
    (b00 * b00 + b11 * b11 + b22 * b22 + 2.0 * (b01 * b01 + b02 * b02 + b12 * b12)) / 6.0);
  const double determinant =
    b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) + b02 * (b01 * b12 - b11 * b02);
  const double cosine = std::min(1.0, std::max(-1.0, determinant / (2.0 * p * p * p)));
  const double gap = 1.0 - cosine;
  // The start, a cubic in s = sqrt((1 - c) / 2) fitted to the root (e = sqrt((1 - c) / 6) near
  // c = 1, e = 1/2 at c = -1), is within 0.02% of it; two steps then give the root to 1.7e-16
  // relative (checked against a 50-digit solution over c in [-1, 1]).
  const double s = std::sqrt(0.5 * gap);
  double e = s * (0.57725885 + s * (-0.10911916 + s * (0.04309189 - 0.01129872 * s)));
  if (e > 0.0)
  {
    for (int step = 0; step < 2; ++step)
    {
      e -= ((6.0 + 4.0 * e) * (e * e) - gap) / (12.0 * e * (1.0 + e));
    }
  }

  double best[3];
  double bestNorm;
  // Below this, the two smallest eigenvalues are within 4e-6 p of each other (points along a
  // line): the smallest is then known only to about the square root of the rounding error, and
  // so is the plane of its eigenvectors, while the largest is simple and well conditioned. Any
  // unit vector orthogonal to the largest's eigenvector is then the answer.
  if (e < MeetingEigenvalueRoots)
  {
    // The largest root, near 1 (f'(1) = 9: two steps from 1 suffice).
    double t = 1.0;
    for (int step = 0; step < 2; ++step)
    {
      t -= ((4.0 * t * t - 3.0) * t - cosine) / (12.0 * t * t - 3.0);
    }
    double largest[3];
    if (!(EigenvectorFromRows(b, 2.0 * p * t, largest) > 0.0))
    {
      return;
    }
    bestNorm = OrthogonalVector(largest, best);
  }
  else
  {
    bestNorm = EigenvectorFromRows(b, -p * (1.0 + 2.0 * e), best);
  }
  if (!(bestNorm > 0.0))
  {
    return;
  }
  // Divided rather than multiplied by the inverse: an axis-aligned plane then gets exactly the
  // axis as its normal.
  const double length = std::sqrt(bestNorm);
  for (int axis = 0; axis < 3; ++axis)
  {
    eigenvector[axis] = best[axis] / length;
  }
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

// The per-point bilateral filter of Digne & de Franchis, "The Bilateral Filter for Point
// Clouds", IPOL 2017, Algorithm 1. Plain C++17, no VTK types.
#ifndef pcbilateral_BilateralKernel_h
#define pcbilateral_BilateralKernel_h

#include "PointCloudView.h"       // IsFinitePoint, for every user of the kernel
#include "SymmetricEigensolver.h" // the kernel's eigensolver

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcbilateral
{

/// The paper's rule: a point with fewer neighbours than this (itself included) is not filtered.
constexpr std::uint32_t MinimumNeighbourCount = 5;

/// Constants of one run, derived once from the radius r and the normal radius rn.
struct KernelConstants
{
  KernelConstants(double radius, double normalRadius);

  double RadiusSquared;
  /// 1 / (2 sd^2) with sd = r / 3: the distance weight is exp(-|q - p|^2 * DistanceScale).
  double DistanceScale;
  /// 1 / (2 sn^2) with sn = rn / 3: the normal weight is exp(-h^2 * NormalScale).
  double NormalScale;
};

/// Partial sums the kernel keeps per quantity; the result does not depend on the hardware's
/// vector width (see BilateralKernelBody.h).
constexpr std::size_t KernelLanes = 8;

/// Per-neighbour scratch arrays of the kernel, each with room for every candidate and
/// KernelLanes more.
struct KernelScratch
{
  double* Dx = nullptr;
  double* Dy = nullptr;
  double* Dz = nullptr;
  double* DistanceWeight = nullptr;
};

/// Candidate neighbours of a block of points, gathered once and read for each of them.
/// Coordinates are absolute; the kernel subtracts the filtered point before any other
/// arithmetic, so large offsets (georeferenced data) do not cost precision.
struct CandidateNeighbours
{
  /// The candidates are the first Size() values of each (the arrays keep their size from one
  /// block to the next, so that gathering never fills or frees memory).
  std::vector<double> X, Y, Z;

  std::size_t Size() const { return this->Count; }
  void Clear() { this->Count = 0; }
  void Append(const double* x, const double* y, const double* z, std::size_t count);
  /// Appends, in order, those of the `count` points whose squared distance to the box
  /// [low, high] is below reachSquared: with the box of the points to filter and a reach a
  /// little over r, the points that can be a neighbour of one of them.
  void AppendNearBox(const double* x,
    const double* y,
    const double* z,
    std::size_t count,
    const double low[3],
    const double high[3],
    double reachSquared);
  /// The kernel's scratch for `points` points filtered together (at most KernelLanes), each
  /// with room for the current candidates.
  void Scratch(KernelScratch* scratch, std::size_t points);

private:
  /// Room for `size` candidates in X, Y and Z.
  void Reserve(std::size_t size);
  std::size_t Count = 0;
  std::vector<double> ScratchStorage;
};

/// What the kernel computed for one point.
struct FilteredPoint
{
  /// Signed displacement along Normal: the new point is p + Displacement * Normal.
  double Displacement = 0.0;
  /// Unit normal of the weighted regression plane (zero when not estimated).
  double Normal[3] = { 0.0, 0.0, 0.0 };
  /// Candidates q with |q - p| < r, p itself included.
  std::uint32_t NeighbourCount = 0;
  /// False when the point has too few neighbours or a zero weight sum: it does not move.
  bool Filtered = false;
};

/**
 * Algorithm 1 for the point p against the candidates, which must contain every point q with
 * |q - p| < r (and may contain more: they are masked out). Sums run over the neighbours in
 * candidate order, so the result depends only on that order, never on threads.
 *
 * Runs the build of the kernel for the best instruction set of the machine (see
 * KernelInstructionSet); all builds give the same bits.
 */
FilteredPoint FilterPoint(const double p[3],
  CandidateNeighbours& candidates,
  const KernelConstants& constants);

/**
 * FilterPoint for `count` points (at most KernelLanes) against the same candidates, with the
 * same results bit for bit: their eigenvectors are computed side by side, one per lane, which
 * costs about what one does alone (the 3x3 solve is a chain of dependent divisions and square
 * roots, as long as the two passes of a point with 40 neighbours).
 */
void FilterPoints(const double (*points)[3],
  std::size_t count,
  CandidateNeighbours& candidates,
  const KernelConstants& constants,
  FilteredPoint* results);

/// The instruction sets the kernel is built for. Every one computes the same bits.
enum class KernelInstructionSet
{
  Generic, ///< what the compiler targets by default (SSE2 on x86-64)
  Avx2,
  Avx512
};
const char* GetName(KernelInstructionSet instructionSet);
/// Whether this build has the kernel for that instruction set and the machine can run it.
bool IsAvailable(KernelInstructionSet instructionSet);
/// The instruction set FilterPoint uses: the best available, unless set.
KernelInstructionSet GetKernelInstructionSet();
/// For tests and benchmarks; ignored (returns false) if that set is not available.
bool SetKernelInstructionSet(KernelInstructionSet instructionSet);

/// exp(x) as the kernel computes it, for x <= 0 (-inf included): within 1 ulp of the true
/// value, 0 below x = -708. For tests.
void KernelExp(const double* x, double* result, std::size_t count);

/// A point's neighbours for steps 2 and 3 of the edge-aware mode: Count indices into the
/// sorted coordinates X, Y, Z and the normals (3 per index), and the same in Records, 8 values
/// per sorted point (x, y, z, the normal, 2 unused; the AVX-512 build reads these) with a
/// padding row at PaddingRow (1e300 three times, then zeros).
struct SortedNeighbours
{
  const std::uint32_t* Index = nullptr;
  std::size_t Count = 0;
  const double* X = nullptr;
  const double* Y = nullptr;
  const double* Z = nullptr;
  const double* Normals = nullptr;
  const double* Records = nullptr;
  std::size_t PaddingRow = 0;
};

/// One point's neighbours as step 1 of the edge-aware mode selected them: Count packed offsets
/// q - p, with room for KernelLanes more (padding), and room for their distance weights.
struct PackedNeighbours
{
  double* Dx = nullptr;
  double* Dy = nullptr;
  double* Dz = nullptr;
  double* Weight = nullptr;
  std::size_t Count = 0;
};

/// The sums of step 3 of the edge-aware mode for one point (see EdgeAwareHeightSums in
/// EdgeAwareKernelBody.h).
struct EdgeAwareHeights
{
  double WeightSum = 0.0;
  double WeightedHeightSum = 0.0;
  /// The weighted sum of the moves onto the neighbours' own tangent planes.
  double Projection[3] = { 0.0, 0.0, 0.0 };
  /// The sums of the distance bumps, and of the same times the wide agreement bump (see
  /// EdgeAwareHeightSums).
  double DistanceWeightSum = 0.0;
  double AgreeingWeightSum = 0.0;
};

/**
 * The per-point arithmetic of the edge-aware mode (EdgeAwareNormals.h), built with the kernel
 * for each instruction set: the same lanes, sum tree and exponential, so the same bits in every
 * build. Step 1 packs the neighbours' offsets q - p in arrays with room for KernelLanes values
 * more, for padding; steps 2 and 3 read them through their sorted indices. See
 * EdgeAwareKernelBody.h.
 */
struct EdgeAwareKernel
{
  /// Appends the neighbours among the sorted candidates [begin, end) to the `count` packed ones
  /// (offsets and sorted indices; room for count + end - begin + KernelLanes); the new count.
  std::size_t (*Select)(const double p[3],
    const double* x,
    const double* y,
    const double* z,
    std::size_t begin,
    std::size_t end,
    double radiusSquared,
    double* dx,
    double* dy,
    double* dz,
    std::uint32_t* index,
    std::size_t count);
  /// For each of `count` points (at most KernelLanes), the paper's regression plane normal of
  /// its selected neighbours, then `rounds` refits with the weights multiplied by
  /// Bump(-res^2 * residualScale), res the height over the last plane (through the weighted
  /// mean); found[point] false (normal untouched) if none.
  void (*PlaneNormals)(const PackedNeighbours* points,
    std::size_t count,
    double distanceScale,
    double residualScale,
    int rounds,
    double (*normals)[3],
    bool* found);
  /// The bilateral sum of the neighbours' normals (step 2).
  void (*NormalSum)(const double p[3],
    const SortedNeighbours& neighbours,
    const double own[3],
    double distanceScale,
    double agreementScale,
    double sum[3]);
  /// The sums of the displacement (step 3).
  void (*HeightSums)(const double p[3],
    const SortedNeighbours& neighbours,
    const double m[3],
    double distanceScale,
    double normalScale,
    double agreementScale,
    double smoothAgreementScale,
    EdgeAwareHeights& sums);
};

/// The edge-aware functions of the instruction set FilterPoint uses (GetKernelInstructionSet).
EdgeAwareKernel GetEdgeAwareKernel();

/**
 * The kernel's arithmetic alone, for the benchmark's floor: FilterPoint's two passes (the two
 * exponentials and the sums per neighbour) over `count` neighbours already selected and packed
 * (offsets q - p; count a multiple of KernelLanes), with the given normal, in the given build
 * of the kernel. No selection, padding or eigensolver. Returns a sum of all the sums (0 if that
 * build is not available here); distanceWeight holds count values.
 */
double KernelArithmetic(KernelInstructionSet instructionSet,
  const double* dx,
  const double* dy,
  const double* dz,
  std::size_t count,
  const KernelConstants& constants,
  const double normal[3],
  double* distanceWeight);

/// The eigensolver of FilterPoints, several matrices side by side (6 entries each, as
/// SmallestEigenvector takes them; 3 per eigenvector), in the kernel's current build: the same
/// bits as SmallestEigenvector on each. For tests.
void KernelSmallestEigenvectors(const double* matrices, double* eigenvectors, std::size_t count);

} // namespace pcbilateral

#endif

// The body of the per-point kernel (Algorithm 1), compiled once per instruction set by
// BilateralKernelGeneric.cxx, BilateralKernelAvx2.cxx and BilateralKernelAvx512.cxx, each with
// PCB_KERNEL_VARIANT naming its own namespace. Private to the core.
//
// Every build computes the same bits. What makes that true:
// - arithmetic is element-wise IEEE double (+, -, *, /) on GCC/Clang vector types, with
//   floating-point contraction off, so a lane computes what a scalar would; the multiply-adds
//   that are fused are written as MultiplyAdd, one rounding in every build (the AVX-512 and
//   AVX2 instructions, or the C library's fma in the generic build);
// - every sum runs in Lanes partial sums (neighbour k goes to lane k % Lanes) that are added in a
//   fixed tree at the end, whatever the hardware vector width;
// - the exponential is this file's own (no libm call, whose last bit differs between libm
//   versions and between its FMA and non-FMA code paths).
// Nothing here may call out-of-line C++ library templates: this header is compiled with
// instruction sets the machine may lack, and such a template instantiated here could be the
// copy the linker keeps for the whole program.
#ifndef PCB_KERNEL_VARIANT
#error "define PCB_KERNEL_VARIANT (the namespace of this build) before including this file"
#endif

#include "BilateralKernel.h"
#include "BitOperations.h"

#include <cstdint>
#include <cstring>

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace pcbilateral
{
namespace PCB_KERNEL_VARIANT
{

constexpr std::size_t Lanes = KernelLanes;
typedef double DoubleLanes __attribute__((vector_size(Lanes * sizeof(double))));
typedef std::int64_t IntLanes __attribute__((vector_size(Lanes * sizeof(double))));
typedef std::uint64_t BitsLanes __attribute__((vector_size(Lanes * sizeof(double))));

inline DoubleLanes Load(const double* values)
{
  DoubleLanes lanes;
  std::memcpy(&lanes, values, sizeof(lanes));
  return lanes;
}

inline void Store(double* values, DoubleLanes lanes)
{
  std::memcpy(values, &lanes, sizeof(lanes));
}

/// a where the mask is set (all ones), b elsewhere.
inline DoubleLanes Select(IntLanes mask, DoubleLanes a, DoubleLanes b)
{
  return (DoubleLanes)((mask & (IntLanes)a) | (~mask & (IntLanes)b));
}

/// All ones in the lanes where a < b (false for NaN), zero elsewhere.
inline IntLanes Less(DoubleLanes a, DoubleLanes b)
{
#if defined(__AVX2__) && !defined(__AVX512F__)
  // GCC compiles the vector comparison below one lane at a time for AVX2 (a scalar compare and
  // a conditional move per lane, which made the AVX2 build as slow as the SSE2 one); two AVX
  // comparisons give the same masks.
  __m256d halves[2], bounds[2];
  std::memcpy(halves, &a, sizeof(halves));
  std::memcpy(bounds, &b, sizeof(bounds));
  halves[0] = _mm256_cmp_pd(halves[0], bounds[0], _CMP_LT_OQ);
  halves[1] = _mm256_cmp_pd(halves[1], bounds[1], _CMP_LT_OQ);
  IntLanes mask;
  std::memcpy(&mask, halves, sizeof(mask));
  return mask;
#else
  return (IntLanes)(a < b);
#endif
}

/// All ones in the lanes where x < limit, zero elsewhere.
inline IntLanes LessThan(DoubleLanes x, double limit)
{
  const DoubleLanes zero = {};
  return Less(x, zero + limit);
}

/**
 * a * b + c rounded once, as IEEE 754's fusedMultiplyAdd: the same bits in every build. The
 * AVX-512 and AVX2 builds use the processors' instructions (the AVX2 build is picked only where
 * FMA is there too); the generic build calls the C library's fma for each lane, correct
 * everywhere and as fast as a function call on processors with FMA (x86 since about 2013), slow
 * where the library must compute it in software.
 */
inline DoubleLanes MultiplyAdd(DoubleLanes a, DoubleLanes b, DoubleLanes c)
{
#if defined(__AVX512F__)
  __m512d x, y, z;
  std::memcpy(&x, &a, sizeof(x));
  std::memcpy(&y, &b, sizeof(y));
  std::memcpy(&z, &c, sizeof(z));
  x = _mm512_fmadd_pd(x, y, z);
  std::memcpy(&a, &x, sizeof(a));
  return a;
#elif defined(__FMA__)
  __m256d x[2], y[2], z[2];
  std::memcpy(x, &a, sizeof(x));
  std::memcpy(y, &b, sizeof(y));
  std::memcpy(z, &c, sizeof(z));
  x[0] = _mm256_fmadd_pd(x[0], y[0], z[0]);
  x[1] = _mm256_fmadd_pd(x[1], y[1], z[1]);
  std::memcpy(&a, x, sizeof(a));
  return a;
#else
  for (std::size_t lane = 0; lane < Lanes; ++lane)
  {
    a[lane] = __builtin_fma(a[lane], b[lane], c[lane]);
  }
  return a;
#endif
}

/// b in every lane. (GCC builds `zero + b` for the AVX2 build in memory, one lane at a time.)
inline DoubleLanes Broadcast(double b)
{
  DoubleLanes lanes;
#if defined(__AVX512F__)
  const __m512d all = _mm512_set1_pd(b);
  std::memcpy(&lanes, &all, sizeof(lanes));
#elif defined(__AVX2__)
  const __m256d halves[2] = { _mm256_set1_pd(b), _mm256_set1_pd(b) };
  std::memcpy(&lanes, halves, sizeof(lanes));
#else
  const DoubleLanes zero = {};
  lanes = zero + b;
#endif
  return lanes;
}

/// MultiplyAdd with b, or b and c, the same in every lane.
inline DoubleLanes MultiplyAdd(DoubleLanes a, double b, DoubleLanes c)
{
  return MultiplyAdd(a, Broadcast(b), c);
}
inline DoubleLanes MultiplyAdd(DoubleLanes a, double b, double c)
{
  return MultiplyAdd(a, Broadcast(b), Broadcast(c));
}

/// The sum of the lanes, in a fixed tree: the same bits for any vector width.
inline double SumLanes(DoubleLanes lanes)
{
  static_assert(Lanes == 8, "the tree below adds 8 lanes");
  return ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) +
         ((lanes[4] + lanes[5]) + (lanes[6] + lanes[7]));
}

/**
 * SumLanes of each of the Lanes vectors v[0..7] at once: lane i of the result is
 * SumLanes(v[i]), the same additions in the same tree, made lane-wise across the vectors (a
 * transpose as it adds), so the same bits for a tenth of the instructions.
 */
inline DoubleLanes SumLanesOfEach(const DoubleLanes* v)
{
  static_assert(Lanes == 8, "the tree below adds 8 lanes");
#if defined(__AVX2__) && !defined(__AVX512F__)
  // The same shuffles on the vectors' halves (GCC builds the 8-lane shuffles below for AVX2 one
  // lane at a time, in memory).
  __m256d half[Lanes][2];
  std::memcpy(half, v, sizeof(half));
  __m256d pairs[4][2], quads[2][2];
  for (int k = 0; k < 4; ++k)
  {
    for (int h = 0; h < 2; ++h)
    {
      pairs[k][h] = _mm256_add_pd(_mm256_unpacklo_pd(half[2 * k][h], half[2 * k + 1][h]),
        _mm256_unpackhi_pd(half[2 * k][h], half[2 * k + 1][h]));
    }
  }
  for (int k = 0; k < 2; ++k)
  {
    for (int h = 0; h < 2; ++h)
    {
      quads[k][h] =
        _mm256_add_pd(_mm256_permute2f128_pd(pairs[2 * k][h], pairs[2 * k + 1][h], 0x20),
          _mm256_permute2f128_pd(pairs[2 * k][h], pairs[2 * k + 1][h], 0x31));
    }
  }
  const __m256d sums[2] = { _mm256_add_pd(quads[0][0], quads[0][1]),
    _mm256_add_pd(quads[1][0], quads[1][1]) };
  DoubleLanes result;
  std::memcpy(&result, sums, sizeof(result));
  return result;
#else
  // Level 1, l0 + l1 and so on: s01 = [v0 01, v1 01, v0 23, v1 23, v0 45, v1 45, v0 67, v1 67].
  DoubleLanes pairs[4];
  for (int k = 0; k < 4; ++k)
  {
    pairs[k] = __builtin_shufflevector(v[2 * k], v[2 * k + 1], 0, 8, 2, 10, 4, 12, 6, 14) +
               __builtin_shufflevector(v[2 * k], v[2 * k + 1], 1, 9, 3, 11, 5, 13, 7, 15);
  }
  // Level 2, (l0 + l1) + (l2 + l3) and (l4 + l5) + (l6 + l7): four vectors' halves by lane.
  DoubleLanes quads[2];
  for (int k = 0; k < 2; ++k)
  {
    quads[k] = __builtin_shufflevector(pairs[2 * k], pairs[2 * k + 1], 0, 1, 8, 9, 4, 5, 12, 13) +
               __builtin_shufflevector(pairs[2 * k], pairs[2 * k + 1], 2, 3, 10, 11, 6, 7, 14, 15);
  }
  // Level 3: the two halves.
  return __builtin_shufflevector(quads[0], quads[1], 0, 1, 2, 3, 8, 9, 10, 11) +
         __builtin_shufflevector(quads[0], quads[1], 4, 5, 6, 7, 12, 13, 14, 15);
#endif
}

/**
 * exp(x) for x <= 0, -inf included, within 1 ulp: exp(x) = 2^k exp(r) with r = x - k ln2 in
 * [-ln2/2, ln2/2], exp(r) by its Taylor polynomial of degree 13 (remainder below 0.1 ulp), 2^k
 * put in the exponent bits. Results below 2^-1021 (x < -708) are 0: the kernel's weights are
 * summed with the point's own weight exp(0) = 1, next to which they vanish.
 *
 * Constants: 1/ln2 and 1/k! are the doubles nearest to them; ln2 = Ln2High + Ln2Low with
 * Ln2High rounded to 28 significant bits, so that k * Ln2High is exact for any k here.
 */
inline DoubleLanes ExpOfNonPositive(DoubleLanes x)
{
  constexpr double InverseLn2 = 0x1.71547652b82fep+0;
  constexpr double Ln2High = 0x1.62e42ffp-1;
  constexpr double Ln2Low = -0x1.718432a1b0e26p-35;
  // Adding 1.5 * 2^52 rounds to an integer and leaves it in the low bits of the mantissa.
  constexpr double RoundingShift = 0x1.8p52;
  constexpr double Lowest = -708.0;

  const DoubleLanes zero = {};
  const IntLanes underflows = LessThan(x, Lowest);
  x = Select(underflows, zero + Lowest, x); // also turns -inf into a finite number
  const DoubleLanes shifted = MultiplyAdd(x, InverseLn2, RoundingShift);
  const DoubleLanes k = shifted - RoundingShift;
  const DoubleLanes r = MultiplyAdd(-k, Ln2Low, MultiplyAdd(-k, Ln2High, x));

  // exp(r) = 1 + (r + tail), the tail (r^2/2! to r^13/13!) by Estrin's scheme: a tree four
  // products deep instead of Horner's chain of thirteen, so that consecutive vectors overlap in
  // the pipeline. Adding the large terms last keeps the rounding errors below one ulp.
  const DoubleLanes r2 = r * r;
  const DoubleLanes r4 = r2 * r2;
  const DoubleLanes r8 = r4 * r4;
  const DoubleLanes c23 = MultiplyAdd(r, 0x1.5555555555555p-3, 0.5);                  // 1/2!, 1/3!
  const DoubleLanes c45 = MultiplyAdd(r, 0x1.1111111111111p-7, 0x1.5555555555555p-5); // 1/4!, 1/5!
  const DoubleLanes c67 =
    MultiplyAdd(r, 0x1.a01a01a01a01ap-13, 0x1.6c16c16c16c17p-10); // 1/6!, 1/7!
  const DoubleLanes c89 =
    MultiplyAdd(r, 0x1.71de3a556c734p-19, 0x1.a01a01a01a01ap-16); // 1/8!, 1/9!
  const DoubleLanes c1011 =
    MultiplyAdd(r, 0x1.ae64567f544e4p-26, 0x1.27e4fb7789f5cp-22); // 1/10!, 1/11!
  const DoubleLanes c1213 =
    MultiplyAdd(r, 0x1.6124613a86d09p-33, 0x1.1eed8eff8d898p-29); // 1/12!, 1/13!
  const DoubleLanes c47 = MultiplyAdd(c67, r2, c45);
  const DoubleLanes c813 = MultiplyAdd(c1213, r4, MultiplyAdd(c1011, r2, c89));
  const DoubleLanes tail = MultiplyAdd(c23, r2, MultiplyAdd(c47, r4, c813 * r8));
  const DoubleLanes p = (r + tail) + 1.0;

  // 2^k: k sits in the low bits of `shifted`; the biased exponent k + 1023 goes in bits 52-62.
  constexpr std::int64_t ShiftBits = 0x4338000000000000LL; // the bits of RoundingShift
  const IntLanes exponent = (IntLanes)shifted - ShiftBits + 1023;
  const DoubleLanes scale = (DoubleLanes)((BitsLanes)exponent << 52);
  return Select(underflows, zero, p * scale);
}

/**
 * Packs the candidates [begin, end) of x, y, z with |q - p|^2 < r^2, in candidate order, after
 * the `count` neighbours already packed: their offsets q - p to dx, dy, dz and, when
 * WithIndices, their candidate indices to index. The arrays need room for
 * count + (end - begin) + Lanes values. Returns the new count. Shared by the paper's kernel
 * (FilterPoint, without indices) and the edge-aware mode's step 1 (with them), so that both
 * compute their offsets and distances the same way.
 */
template<bool WithIndices>
inline std::size_t PackNeighbours(const double p[3],
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
  std::size_t count)
{
#if defined(__AVX512F__)
  // Eight candidates at a time, the neighbours (and their indices) packed with a compress each.
  const __m512d px = _mm512_set1_pd(p[0]);
  const __m512d py = _mm512_set1_pd(p[1]);
  const __m512d pz = _mm512_set1_pd(p[2]);
  const __m512d limit = _mm512_set1_pd(radiusSquared);
  for (std::size_t j = begin; j < end; j += 8)
  {
    const std::size_t left = end - j;
    const __mmask8 valid = left >= 8 ? __mmask8(0xFF) : __mmask8((1u << left) - 1u);
    const __m512d ox = _mm512_sub_pd(_mm512_maskz_loadu_pd(valid, x + j), px);
    const __m512d oy = _mm512_sub_pd(_mm512_maskz_loadu_pd(valid, y + j), py);
    const __m512d oz = _mm512_sub_pd(_mm512_maskz_loadu_pd(valid, z + j), pz);
    const __m512d d2 = _mm512_add_pd(
      _mm512_add_pd(_mm512_mul_pd(ox, ox), _mm512_mul_pd(oy, oy)), _mm512_mul_pd(oz, oz));
    const __mmask8 inside = _mm512_mask_cmp_pd_mask(valid, d2, limit, _CMP_LT_OQ);
    _mm512_storeu_pd(dx + count, _mm512_maskz_compress_pd(inside, ox));
    _mm512_storeu_pd(dy + count, _mm512_maskz_compress_pd(inside, oy));
    _mm512_storeu_pd(dz + count, _mm512_maskz_compress_pd(inside, oz));
    if constexpr (WithIndices)
    {
      const __m256i indices = _mm256_add_epi32(
        _mm256_set1_epi32(static_cast<int>(j)), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
      _mm256_storeu_si256(
        reinterpret_cast<__m256i*>(index + count), _mm256_maskz_compress_epi32(inside, indices));
    }
    count += static_cast<std::size_t>(PopCount(inside));
  }
#else
  // Without a branch per candidate: most candidates are not neighbours, and a branch on that
  // is mispredicted often. Every candidate is written, and kept by advancing only for a
  // neighbour.
  const double px = p[0], py = p[1], pz = p[2];
  for (std::size_t j = begin; j < end; ++j)
  {
    const double ox = x[j] - px;
    const double oy = y[j] - py;
    const double oz = z[j] - pz;
    const double d2 = (ox * ox + oy * oy) + oz * oz;
    dx[count] = ox;
    dy[count] = oy;
    dz[count] = oz;
    if constexpr (WithIndices)
    {
      index[count] = static_cast<std::uint32_t>(j);
    }
    count += d2 < radiusSquared ? 1 : 0;
  }
#endif
  return count;
}

/**
 * Copies, in order, the points [0, count) of sx, sy, sz whose squared distance to the box
 * [low, high] is below reachSquared to x, y, z. Returns their number.
 */
std::size_t CopyNearBox(const double* sx,
  const double* sy,
  const double* sz,
  std::size_t count,
  const double low[3],
  const double high[3],
  double reachSquared,
  double* x,
  double* y,
  double* z)
{
  std::size_t kept = 0;
#if defined(__AVX512F__)
  const __m512d zero = _mm512_setzero_pd();
  const __m512d lowX = _mm512_set1_pd(low[0]), highX = _mm512_set1_pd(high[0]);
  const __m512d lowY = _mm512_set1_pd(low[1]), highY = _mm512_set1_pd(high[1]);
  const __m512d lowZ = _mm512_set1_pd(low[2]), highZ = _mm512_set1_pd(high[2]);
  const __m512d limit = _mm512_set1_pd(reachSquared);
  for (std::size_t j = 0; j < count; j += 8)
  {
    const std::size_t left = count - j;
    const __mmask8 valid = left >= 8 ? __mmask8(0xFF) : __mmask8((1u << left) - 1u);
    const __m512d qx = _mm512_maskz_loadu_pd(valid, sx + j);
    const __m512d qy = _mm512_maskz_loadu_pd(valid, sy + j);
    const __m512d qz = _mm512_maskz_loadu_pd(valid, sz + j);
    const __m512d gx =
      _mm512_max_pd(_mm512_max_pd(_mm512_sub_pd(lowX, qx), _mm512_sub_pd(qx, highX)), zero);
    const __m512d gy =
      _mm512_max_pd(_mm512_max_pd(_mm512_sub_pd(lowY, qy), _mm512_sub_pd(qy, highY)), zero);
    const __m512d gz =
      _mm512_max_pd(_mm512_max_pd(_mm512_sub_pd(lowZ, qz), _mm512_sub_pd(qz, highZ)), zero);
    const __m512d d2 = _mm512_add_pd(
      _mm512_add_pd(_mm512_mul_pd(gx, gx), _mm512_mul_pd(gy, gy)), _mm512_mul_pd(gz, gz));
    const __mmask8 near = _mm512_mask_cmp_pd_mask(valid, d2, limit, _CMP_LT_OQ);
    const int found = PopCount(near);
    const __mmask8 stored = static_cast<__mmask8>(0xFFu >> (8 - found));
    _mm512_mask_storeu_pd(x + kept, stored, _mm512_maskz_compress_pd(near, qx));
    _mm512_mask_storeu_pd(y + kept, stored, _mm512_maskz_compress_pd(near, qy));
    _mm512_mask_storeu_pd(z + kept, stored, _mm512_maskz_compress_pd(near, qz));
    kept += static_cast<std::size_t>(found);
  }
#else
  for (std::size_t j = 0; j < count; ++j)
  {
    const double q[3] = { sx[j], sy[j], sz[j] };
    double d2 = 0.0;
    for (int axis = 0; axis < 3; ++axis)
    {
      const double below = low[axis] - q[axis], above = q[axis] - high[axis];
      const double gap = below > above ? below : above;
      d2 += gap > 0.0 ? gap * gap : 0.0;
    }
    // Written whatever the test says, kept by advancing: no branch to mispredict.
    x[kept] = q[0];
    y[kept] = q[1];
    z[kept] = q[2];
    kept += d2 < reachSquared ? 1 : 0;
  }
#endif
  return kept;
}

/// The weighted sums of pass 1 (see FilterPoint), one partial sum per lane.
struct DistanceMoments
{
  DoubleLanes WeightSum, FirstX, FirstY, FirstZ, XX, XY, XZ, YY, YZ, ZZ;
};

/// Adds offsets (x, y, z), weighted by w, to the moments, lane by lane: pass 1's sums and the
/// edge-aware refit's, in one order.
inline void AddWeightedOffsets(DistanceMoments& m,
  DoubleLanes w,
  DoubleLanes x,
  DoubleLanes y,
  DoubleLanes z)
{
  m.WeightSum += w;
  const DoubleLanes wx = w * x, wy = w * y, wz = w * z;
  m.FirstX += wx;
  m.FirstY += wy;
  m.FirstZ += wz;
  m.XX = MultiplyAdd(wx, x, m.XX);
  m.XY = MultiplyAdd(wx, y, m.XY);
  m.XZ = MultiplyAdd(wx, z, m.XZ);
  m.YY = MultiplyAdd(wy, y, m.YY);
  m.YZ = MultiplyAdd(wy, z, m.YZ);
  m.ZZ = MultiplyAdd(wz, z, m.ZZ);
}

/**
 * Pass 1 over `padded` packed offsets (a multiple of Lanes): the distance weights, stored for
 * pass 2, and the weighted first and second moments of the offsets q - p, for the regression
 * plane. Shared by FilterPoint and ArithmeticFloor, so that the floor times this very code.
 */
inline DistanceMoments AccumulateDistanceMoments(const double* dx,
  const double* dy,
  const double* dz,
  std::size_t padded,
  double distanceScale,
  double* distanceWeight)
{
  DistanceMoments moments = {};
  for (std::size_t k = 0; k < padded; k += Lanes)
  {
    const DoubleLanes ox = Load(dx + k);
    const DoubleLanes oy = Load(dy + k);
    const DoubleLanes oz = Load(dz + k);
    // The squared distance again (cheaper than packing it), with fused multiply-adds: it only
    // weighs the neighbour, whose selection PackNeighbours made unfused, as the paper's
    // program does.
    const DoubleLanes distanceSquared = MultiplyAdd(oz, oz, MultiplyAdd(oy, oy, ox * ox));
    const DoubleLanes w = ExpOfNonPositive(-distanceSquared * distanceScale);
    Store(distanceWeight + k, w);
    AddWeightedOffsets(moments, w, ox, oy, oz);
  }
  return moments;
}

/**
 * The weighted covariance (xx, xy, xz, yy, yz, zz) of pass 1's moments, whose smallest
 * eigenvector is the regression plane's normal. Returns false (covariance untouched) when the
 * weights sum to zero.
 */
inline bool RegressionCovariance(const DistanceMoments& m, double covariance[6])
{
  const double totalWeight = SumLanes(m.WeightSum);
  if (!(totalWeight > 0.0))
  {
    return false;
  }
  // Weighted covariance about the weighted mean; the offsets are small, so the one-pass form
  // loses nothing that matters next to the noise it measures.
  const double mean[3] = { SumLanes(m.FirstX) / totalWeight,
    SumLanes(m.FirstY) / totalWeight,
    SumLanes(m.FirstZ) / totalWeight };
  covariance[0] = SumLanes(m.XX) / totalWeight - mean[0] * mean[0];
  covariance[1] = SumLanes(m.XY) / totalWeight - mean[0] * mean[1];
  covariance[2] = SumLanes(m.XZ) / totalWeight - mean[0] * mean[2];
  covariance[3] = SumLanes(m.YY) / totalWeight - mean[1] * mean[1];
  covariance[4] = SumLanes(m.YZ) / totalWeight - mean[1] * mean[2];
  covariance[5] = SumLanes(m.ZZ) / totalWeight - mean[2] * mean[2];
  return true;
}

/// SumLanes of one of the moments of each of Lanes points, lane by point.
inline DoubleLanes SumLanesOfEach(const DistanceMoments* moments,
  DoubleLanes DistanceMoments::*member)
{
  DoubleLanes each[Lanes];
  for (std::size_t point = 0; point < Lanes; ++point)
  {
    each[point] = moments[point].*member;
  }
  return SumLanesOfEach(each);
}

/**
 * RegressionCovariance for Lanes points at once, one per lane (covariance[entry][point]), with
 * its bits: the same sums, divisions and products, lane-wise. Returns the lanes whose weights
 * sum to more than zero; the others' covariance is zero.
 */
inline IntLanes RegressionCovariances(const DistanceMoments* moments, double (*covariance)[Lanes])
{
  const DoubleLanes zero = {};
  const DoubleLanes total = SumLanesOfEach(moments, &DistanceMoments::WeightSum);
  const IntLanes planed = Less(zero, total);
  const DoubleLanes mean[3] = { SumLanesOfEach(moments, &DistanceMoments::FirstX) / total,
    SumLanesOfEach(moments, &DistanceMoments::FirstY) / total,
    SumLanesOfEach(moments, &DistanceMoments::FirstZ) / total };
  DoubleLanes DistanceMoments::*const second[6] = { &DistanceMoments::XX,
    &DistanceMoments::XY,
    &DistanceMoments::XZ,
    &DistanceMoments::YY,
    &DistanceMoments::YZ,
    &DistanceMoments::ZZ };
  const int axes[6][2] = { { 0, 0 }, { 0, 1 }, { 0, 2 }, { 1, 1 }, { 1, 2 }, { 2, 2 } };
  for (int entry = 0; entry < 6; ++entry)
  {
    const DoubleLanes value =
      SumLanesOfEach(moments, second[entry]) / total - mean[axes[entry][0]] * mean[axes[entry][1]];
    Store(covariance[entry], Select(planed, value, zero));
  }
  return planed;
}

/**
 * The normal of the weighted regression plane of pass 1's moments. Returns false (n untouched)
 * when the weights sum to zero.
 */
inline bool RegressionNormal(const DistanceMoments& m, double n[3])
{
  double covariance[6];
  if (!RegressionCovariance(m, covariance))
  {
    return false;
  }
  SmallestEigenvector(covariance, n);
  return true;
}

/// |x|, by clearing the sign bit.
inline DoubleLanes Abs(DoubleLanes x)
{
  const BitsLanes zero = {};
  const BitsLanes magnitude = zero + ~(std::uint64_t(1) << 63);
  return (DoubleLanes)((BitsLanes)x & magnitude);
}

/// Lane-wise square root, rounded as IEEE 754 requires (the scalar std::sqrt's bits).
inline DoubleLanes Sqrt(DoubleLanes x)
{
#if defined(__AVX512F__)
  __m512d lanes;
  std::memcpy(&lanes, &x, sizeof(lanes));
  lanes = _mm512_sqrt_pd(lanes);
  std::memcpy(&x, &lanes, sizeof(x));
#elif defined(__AVX2__)
  __m256d halves[2];
  std::memcpy(halves, &x, sizeof(halves));
  halves[0] = _mm256_sqrt_pd(halves[0]);
  halves[1] = _mm256_sqrt_pd(halves[1]);
  std::memcpy(&x, halves, sizeof(x));
#elif defined(__SSE2__)
  __m128d quarters[4];
  std::memcpy(quarters, &x, sizeof(quarters));
  for (__m128d& quarter : quarters)
  {
    quarter = _mm_sqrt_pd(quarter);
  }
  std::memcpy(&x, quarters, sizeof(x));
#else
  for (std::size_t lane = 0; lane < Lanes; ++lane)
  {
    x[lane] = std::sqrt(x[lane]);
  }
#endif
  return x;
}

#include "SymmetricEigensolverSteps.h"

/**
 * SmallestEigenvector (SymmetricEigensolver.h) for Lanes matrices at once, one per lane, with the
 * same steps (SymmetricEigensolverSteps.h), so the same bits. Entries are by lane
 * (covariance[k][lane]). Returns the lanes whose matrix takes one of the scalar function's other
 * paths (no spread, a NaN or infinity, two smallest eigenvalues that meet, parallel rows): their
 * vectors here are meaningless, and the caller solves them with the scalar function.
 */
inline IntLanes SmallestEigenvectors(const double (*covariance)[Lanes],
  double (*eigenvector)[Lanes])
{
  const DoubleLanes zero = {};
  const DoubleLanes c[6] = { Load(covariance[0]),
    Load(covariance[1]),
    Load(covariance[2]),
    Load(covariance[3]),
    Load(covariance[4]),
    Load(covariance[5]) };
  DoubleLanes b[6];
  const DoubleLanes scale = CenteredMatrix(c, b);
  IntLanes scalar = ~(Less(zero, scale) & Less(scale, zero + HUGE_VAL));
  DoubleLanes p;
  const DoubleLanes e = SmallestRootOffset(CubicCosine(b, scale, p));
  scalar |= Less(e, zero + MeetingEigenvalueRoots);
  DoubleLanes best[3];
  const DoubleLanes bestNorm = EigenvectorFromRows(b, -p * (1.0 + 2.0 * e), best);
  scalar |= ~Less(zero, bestNorm);
  const DoubleLanes length = Sqrt(bestNorm);
  for (int axis = 0; axis < 3; ++axis)
  {
    Store(eigenvector[axis], best[axis] / length);
  }
  return scalar;
}

/**
 * The smallest eigenvectors of the matrices of the lanes marked in `solve` (others are left
 * alone), given by lane (covariance[k][lane]), each with SmallestEigenvector's bits: side by
 * side (SmallestEigenvectors), and those it flags through the scalar solver. A single matrix
 * goes straight to the scalar solver, which is then as fast and does not compute 8 lanes.
 */
inline void SolveNormals(const double (*covariance)[Lanes],
  const bool* solve,
  double (*normal)[Lanes])
{
  std::size_t count = 0;
  for (std::size_t lane = 0; lane < Lanes; ++lane)
  {
    count += solve[lane] ? 1 : 0;
  }
  IntLanes scalar = {};
  if (count > 1)
  {
    scalar = SmallestEigenvectors(covariance, normal);
  }
  for (std::size_t lane = 0; lane < Lanes; ++lane)
  {
    if (solve[lane] && (count == 1 || scalar[lane]))
    {
      const double matrix[6] = { covariance[0][lane],
        covariance[1][lane],
        covariance[2][lane],
        covariance[3][lane],
        covariance[4][lane],
        covariance[5][lane] };
      double n[3];
      SmallestEigenvector(matrix, n);
      for (int axis = 0; axis < 3; ++axis)
      {
        normal[axis][lane] = n[axis];
      }
    }
  }
}

/// Pass 2 over the same offsets: the sums of the bilateral weights and of the weighted heights
/// h = <n, q - p>, one partial sum per lane.
inline void AccumulateBilateralHeights(const double* dx,
  const double* dy,
  const double* dz,
  const double* distanceWeight,
  std::size_t padded,
  const double n[3],
  double normalScale,
  DoubleLanes& bilateralWeightSum,
  DoubleLanes& weightedHeightSum)
{
  const DoubleLanes zero = {};
  bilateralWeightSum = zero;
  weightedHeightSum = zero;
  const DoubleLanes nx = Broadcast(n[0]), ny = Broadcast(n[1]), nz = Broadcast(n[2]);
  for (std::size_t k = 0; k < padded; k += Lanes)
  {
    const DoubleLanes h =
      MultiplyAdd(Load(dz + k), nz, MultiplyAdd(Load(dy + k), ny, Load(dx + k) * nx));
    const DoubleLanes w = Load(distanceWeight + k) * ExpOfNonPositive(-(h * h) * normalScale);
    bilateralWeightSum += w;
    weightedHeightSum = MultiplyAdd(w, h, weightedHeightSum);
  }
}

/// What FilterPoints keeps per point between its passes, by lane.
struct KernelLanesState
{
  std::size_t Padded[Lanes] = {};
  DistanceMoments Moments[Lanes] = {};
  bool Planed[Lanes] = {};
  double Normals[3][Lanes] = {};
  DoubleLanes BilateralWeightSums[Lanes] = {};
  DoubleLanes WeightedHeightSums[Lanes] = {};
};

/// Pass 1 for the points [first, last): their neighbours, packed, their distance weights and
/// the moments of the weighted regression plane. Points with too few neighbours keep zero
/// moments, hence no plane.
inline void KernelFirstPass(const double (*points)[3],
  std::size_t first,
  std::size_t last,
  const double* x,
  const double* y,
  const double* z,
  std::size_t count,
  const KernelConstants& constants,
  const KernelScratch* scratch,
  FilteredPoint* results,
  KernelLanesState& state)
{
  for (std::size_t point = first; point < last; ++point)
  {
    const KernelScratch& own = scratch[point];
    const std::size_t neighbours = PackNeighbours<false>(points[point],
      x,
      y,
      z,
      0,
      count,
      constants.RadiusSquared,
      own.Dx,
      own.Dy,
      own.Dz,
      nullptr,
      0);
    results[point].NeighbourCount = static_cast<std::uint32_t>(neighbours);
    if (neighbours < MinimumNeighbourCount)
    {
      continue;
    }
    // Pad to whole vectors with neighbours so far away that their squared distance overflows
    // to infinity: their weights are exp(-inf) = 0, and they add exact zeros to every sum (the
    // offsets are finite, so no 0 x inf).
    const std::size_t padded = (neighbours + Lanes - 1) / Lanes * Lanes;
    for (std::size_t k = neighbours; k < padded; ++k)
    {
      own.Dx[k] = own.Dy[k] = own.Dz[k] = 1e300;
    }
    state.Padded[point] = padded;
    state.Moments[point] = AccumulateDistanceMoments(
      own.Dx, own.Dy, own.Dz, padded, constants.DistanceScale, own.DistanceWeight);
  }
}

/// The regression planes' normals of the points [first, last), one point per lane, from the
/// moments of pass 1 (the other lanes' moments must be zero or those of points already solved).
inline void KernelPlaneNormals(std::size_t first, std::size_t last, KernelLanesState& state)
{
  double covariance[6][Lanes];
  const IntLanes planes = RegressionCovariances(state.Moments, covariance);
  bool solve[Lanes] = {};
  for (std::size_t point = first; point < last; ++point)
  {
    solve[point] = state.Planed[point] = planes[point] != 0;
  }
  double normals[3][Lanes];
  SolveNormals(covariance, solve, normals);
  for (int axis = 0; axis < 3; ++axis)
  {
    for (std::size_t point = first; point < last; ++point)
    {
      state.Normals[axis][point] = normals[axis][point];
    }
  }
}

/// Pass 2 for the points [first, last) that have a plane: the sums of the bilateral weights and
/// of the weighted heights h = <n, q - p> over the same neighbours.
inline void KernelSecondPass(std::size_t first,
  std::size_t last,
  const KernelConstants& constants,
  const KernelScratch* scratch,
  KernelLanesState& state)
{
  for (std::size_t point = first; point < last; ++point)
  {
    if (!state.Planed[point])
    {
      continue;
    }
    const double n[3] = {
      state.Normals[0][point], state.Normals[1][point], state.Normals[2][point]
    };
    const KernelScratch& own = scratch[point];
    AccumulateBilateralHeights(own.Dx,
      own.Dy,
      own.Dz,
      own.DistanceWeight,
      state.Padded[point],
      n,
      constants.NormalScale,
      state.BilateralWeightSums[point],
      state.WeightedHeightSums[point]);
  }
}

/**
 * Algorithm 1 for `pointCount` points (at most Lanes) against the same candidates (see
 * FilterPoints in BilateralKernel.h), the entry point of this build (declared in
 * BilateralKernel.cxx): pass 1 for each point, their eigenvectors side by side, pass 2 for each,
 * and the sums of both passes side by side. `results` arrive zeroed: a point does not move
 * unless this says so.
 */
void FilterPoints(const double (*points)[3],
  std::size_t pointCount,
  const double* x,
  const double* y,
  const double* z,
  std::size_t count,
  const KernelConstants& constants,
  const KernelScratch* scratch,
  FilteredPoint* results)
{
  KernelLanesState state;
  KernelFirstPass(points, 0, pointCount, x, y, z, count, constants, scratch, results, state);
  KernelPlaneNormals(0, pointCount, state);
  KernelSecondPass(0, pointCount, constants, scratch, state);

  // The bilateral averages of all the points, one per lane.
  const DoubleLanes zero = {};
  const DoubleLanes totalBilateralWeight = SumLanesOfEach(state.BilateralWeightSums);
  const IntLanes moved = Less(zero, totalBilateralWeight);
  const DoubleLanes displacement = SumLanesOfEach(state.WeightedHeightSums) / totalBilateralWeight;
  for (std::size_t point = 0; point < pointCount; ++point)
  {
    if (!state.Planed[point] || !moved[point])
    {
      continue;
    }
    FilteredPoint& result = results[point];
    result.Displacement = displacement[point];
    result.Normal[0] = state.Normals[0][point];
    result.Normal[1] = state.Normals[1][point];
    result.Normal[2] = state.Normals[2][point];
    result.Filtered = true;
  }
}

/// The kernel's arithmetic alone (see KernelArithmetic in BilateralKernel.h): both passes over
/// packed neighbours with a given normal, without selection, padding or eigensolver.
double ArithmeticFloor(const double* dx,
  const double* dy,
  const double* dz,
  std::size_t padded,
  const KernelConstants& constants,
  const double n[3],
  double* distanceWeight)
{
  const DistanceMoments m =
    AccumulateDistanceMoments(dx, dy, dz, padded, constants.DistanceScale, distanceWeight);
  DoubleLanes bilateralWeightSum, weightedHeightSum;
  AccumulateBilateralHeights(dx,
    dy,
    dz,
    distanceWeight,
    padded,
    n,
    constants.NormalScale,
    bilateralWeightSum,
    weightedHeightSum);
  // Every sum reaches the result, so that none of the arithmetic can be left out.
  const DoubleLanes all = ((m.WeightSum + m.FirstX) + (m.FirstY + m.FirstZ)) +
                          ((m.XX + m.XY) + (m.XZ + m.YY)) +
                          ((m.YZ + m.ZZ) + (bilateralWeightSum + weightedHeightSum));
  return SumLanes(all);
}

/// The eigensolver of FilterPoints in this build, for the tests: `count` matrices (6 entries
/// each, as SmallestEigenvector takes them) solved Lanes at a time.
void SmallestEigenvectorsOfMatrices(const double* matrices, double* eigenvectors, std::size_t count)
{
  for (std::size_t first = 0; first < count; first += Lanes)
  {
    double covariance[6][Lanes] = {};
    double normal[3][Lanes];
    const std::size_t lanes = count - first < Lanes ? count - first : Lanes;
    for (std::size_t lane = 0; lane < lanes; ++lane)
    {
      for (int entry = 0; entry < 6; ++entry)
      {
        covariance[entry][lane] = matrices[6 * (first + lane) + entry];
      }
    }
    bool solve[Lanes] = {};
    for (std::size_t lane = 0; lane < lanes; ++lane)
    {
      solve[lane] = true;
    }
    SolveNormals(covariance, solve, normal);
    for (std::size_t lane = 0; lane < lanes; ++lane)
    {
      for (int axis = 0; axis < 3; ++axis)
      {
        eigenvectors[3 * (first + lane) + axis] = normal[axis][lane];
      }
    }
  }
}

/// The exponential of this build, for the tests: out[i] = exp(in[i]) for in[i] <= 0.
void ExpOfNonPositive(const double* in, double* out, std::size_t count)
{
  for (std::size_t i = 0; i + Lanes <= count; i += Lanes)
  {
    Store(out + i, ExpOfNonPositive(Load(in + i)));
  }
  for (std::size_t i = count / Lanes * Lanes; i < count; ++i)
  {
    double lanes[Lanes] = { in[i], 0, 0, 0, 0, 0, 0, 0 };
    out[i] = ExpOfNonPositive(Load(lanes))[0];
  }
}

} // namespace PCB_KERNEL_VARIANT
} // namespace pcbilateral

// The edge-aware mode's per-point arithmetic (EdgeAwareNormals.h), compiled once per instruction
// set after BilateralKernelBody.h (whose lanes, fixed sum tree and exponential it uses, so the
// same bits in every build) by BilateralKernelGeneric.cxx, BilateralKernelAvx2.cxx and
// BilateralKernelAvx512.cxx. Private to the core. Its arrays of packed neighbours hold whole
// vectors: a count is padded up to a multiple of Lanes with neighbours that add exact zeros to
// every sum (see PadNeighbours).
#ifndef PCB_KERNEL_VARIANT
#error "include BilateralKernelBody.h, with PCB_KERNEL_VARIANT defined, before this file"
#endif

namespace pcbilateral
{
namespace PCB_KERNEL_VARIANT
{

/**
 * Pads `count` packed neighbours up to whole vectors with neighbours so far away that their
 * squared distance overflows to infinity (weight exp(-inf) = 0, exact zeros in every sum, as in
 * FilterPoint). Steps 2 and 3 pad the same way, with a zero normal (a finite agreement
 * exponent). Returns the padded count.
 */
inline std::size_t PadNeighbours(double* dx, double* dy, double* dz, std::size_t count)
{
  const std::size_t padded = (count + Lanes - 1) / Lanes * Lanes;
  for (std::size_t k = count; k < padded; ++k)
  {
    dx[k] = dy[k] = dz[k] = 1e300;
  }
  return padded;
}

/**
 * (1 + x / width)^4 for x > -width, 0 below: a smooth bump, 1 at x = 0, like exp(x) near 0 but
 * without an exponential's cost, for weights whose exact profile matters little (the refit's
 * residual weight, the agreement share of step 3).
 */
inline DoubleLanes Bump(DoubleLanes x, double width)
{
  const DoubleLanes zero = {};
  const DoubleLanes t = x * (1.0 / width) + 1.0;
  const DoubleLanes positive = Select(LessThan(t, 0.0), zero, t);
  const DoubleLanes square = positive * positive;
  return square * square;
}

/// The width of Bump for the distance exponent -|q - p|^2 * distanceScale = -4.5 |q - p|^2 / r^2:
/// the bump vanishes at |q - p| = r.
constexpr double DistanceBumpWidth = 4.5;

/**
 * The moments of the offsets with the weights distanceWeight x Bump(-res^2 * residualScale),
 * res = <n, d - c> the offset's height over the plane of normal n through c. Padding (distance
 * weight 0) adds exact zeros.
 */
inline DistanceMoments AccumulateResidualMoments(const double* dx,
  const double* dy,
  const double* dz,
  std::size_t padded,
  const double* distanceWeight,
  const double n[3],
  const double c[3],
  double residualScale)
{
  const DoubleLanes zero = {};
  DistanceMoments moments = {};
  const double offset = (n[0] * c[0] + n[1] * c[1]) + n[2] * c[2];
  for (std::size_t k = 0; k < padded; k += Lanes)
  {
    const DoubleLanes ox = Load(dx + k);
    const DoubleLanes oy = Load(dy + k);
    const DoubleLanes oz = Load(dz + k);
    // Padding: weight 0 already, and its huge offsets must not make inf * 0.
    const DoubleLanes weight = Load(distanceWeight + k);
    const IntLanes padding = LessThan(weight, 1e-300);
    const DoubleLanes residual =
      Select(padding, zero, ((ox * n[0] + oy * n[1]) + oz * n[2]) - offset);
    const DoubleLanes w = weight * Bump(-(residual * residual) * residualScale, 4.0);
    AddWeightedOffsets(
      moments, w, Select(padding, zero, ox), Select(padding, zero, oy), Select(padding, zero, oz));
  }
  return moments;
}

/// The weighted covariance of `moments` in lane `lane` of `covariance`; false (lane untouched)
/// when the weights sum to zero.
inline bool CovarianceInLane(const DistanceMoments& moments,
  double (*covariance)[Lanes],
  std::size_t lane)
{
  double entries[6];
  if (!RegressionCovariance(moments, entries))
  {
    return false;
  }
  for (int entry = 0; entry < 6; ++entry)
  {
    covariance[entry][lane] = entries[entry];
  }
  return true;
}

/**
 * Step 1 for `count` points (at most Lanes) whose neighbours PackNeighbours<true> packed (room
 * for Lanes more in every array): the paper's regression plane normal, weighted by
 * exp(-|q - p|^2 * distanceScale), with the kernel's own pass 1; then `rounds` refits with the
 * weights multiplied by Bump(-res^2 * residualScale), res the neighbour's height over the last
 * plane: a plane fitted across an edge is tilted, the refit leaves out the far side's points
 * (the most off the plane) and turns toward the point's own face. The points' 3 x 3 solves run
 * side by side, one per lane (SolveNormals: the bits of one solve alone). found[point] is false
 * (its normal untouched) when its weights sum to zero.
 */
void EdgeAwarePlaneNormals(const PackedNeighbours* points,
  std::size_t count,
  double distanceScale,
  double residualScale,
  int rounds,
  double (*normals)[3],
  bool* found)
{
  DistanceMoments moments[Lanes];
  double covariance[6][Lanes] = {};
  bool solve[Lanes] = {};
  for (std::size_t point = 0; point < count; ++point)
  {
    const PackedNeighbours& own = points[point];
    const std::size_t padded = PadNeighbours(own.Dx, own.Dy, own.Dz, own.Count);
    moments[point] =
      AccumulateDistanceMoments(own.Dx, own.Dy, own.Dz, padded, distanceScale, own.Weight);
    solve[point] = CovarianceInLane(moments[point], covariance, point);
    found[point] = solve[point];
  }
  double solved[3][Lanes];
  for (int round = 0; round <= rounds; ++round)
  {
    SolveNormals(covariance, solve, solved);
    for (std::size_t point = 0; point < count; ++point)
    {
      if (!solve[point])
      {
        continue;
      }
      double* n = normals[point];
      n[0] = solved[0][point];
      n[1] = solved[1][point];
      n[2] = solved[2][point];
      if (round == rounds)
      {
        continue;
      }
      // The refit: a point whose reweighted moments sum to zero keeps its last plane.
      const PackedNeighbours& own = points[point];
      const double total = SumLanes(moments[point].WeightSum);
      const double c[3] = { SumLanes(moments[point].FirstX) / total,
        SumLanes(moments[point].FirstY) / total,
        SumLanes(moments[point].FirstZ) / total };
      const std::size_t padded = (own.Count + Lanes - 1) / Lanes * Lanes;
      moments[point] =
        AccumulateResidualMoments(own.Dx, own.Dy, own.Dz, padded, own.Weight, n, c, residualScale);
      solve[point] = CovarianceInLane(moments[point], covariance, point);
    }
  }
}

/// The exponent of the agreement weight of two unit normals of cosine c: -((1 - |c|) s)^2, with
/// s = 1 / (1 - cos theta).
inline DoubleLanes AgreementExponent(DoubleLanes cosine, double agreementScale)
{
  const DoubleLanes gap = (1.0 - Abs(cosine)) * agreementScale;
  return -(gap * gap);
}

/// Neighbours k to k + Lanes - 1 of a list of sorted indices, for steps 2 and 3.
struct NeighbourLanes
{
  DoubleLanes Dx, Dy, Dz, Nx, Ny, Nz;
};

#if defined(__AVX512F__)
/// Columns 0 to 5 of the 8 x 8 matrix of `rows` (a transpose, columns 6 and 7 left out).
inline void TransposeRows(const __m512d rows[8], __m512d columns[6])
{
  const __m512d t0 = _mm512_unpacklo_pd(rows[0], rows[1]);
  const __m512d t1 = _mm512_unpackhi_pd(rows[0], rows[1]);
  const __m512d t2 = _mm512_unpacklo_pd(rows[2], rows[3]);
  const __m512d t3 = _mm512_unpackhi_pd(rows[2], rows[3]);
  const __m512d t4 = _mm512_unpacklo_pd(rows[4], rows[5]);
  const __m512d t5 = _mm512_unpackhi_pd(rows[4], rows[5]);
  const __m512d t6 = _mm512_unpacklo_pd(rows[6], rows[7]);
  const __m512d t7 = _mm512_unpackhi_pd(rows[6], rows[7]);
  // The even (0, 2) or odd (1, 3) 128-bit blocks of the first source, then of the second.
  constexpr int Even = 0 | (2 << 2) | (0 << 4) | (2 << 6);
  constexpr int Odd = 1 | (3 << 2) | (1 << 4) | (3 << 6);
  const __m512d a = _mm512_shuffle_f64x2(t0, t2, Even), b = _mm512_shuffle_f64x2(t4, t6, Even);
  const __m512d a2 = _mm512_shuffle_f64x2(t0, t2, Odd), b2 = _mm512_shuffle_f64x2(t4, t6, Odd);
  const __m512d c = _mm512_shuffle_f64x2(t1, t3, Even), d = _mm512_shuffle_f64x2(t5, t7, Even);
  const __m512d c2 = _mm512_shuffle_f64x2(t1, t3, Odd), d2 = _mm512_shuffle_f64x2(t5, t7, Odd);
  columns[0] = _mm512_shuffle_f64x2(a, b, Even);
  columns[1] = _mm512_shuffle_f64x2(c, d, Even);
  columns[2] = _mm512_shuffle_f64x2(a2, b2, Even);
  columns[3] = _mm512_shuffle_f64x2(c2, d2, Even);
  columns[4] = _mm512_shuffle_f64x2(a, b, Odd);
  columns[5] = _mm512_shuffle_f64x2(c, d, Odd);
}
#endif

/**
 * Loads neighbours k to k + Lanes - 1 of `neighbours`: their offsets q - p
 * from the sorted coordinates (computed as PackNeighbours does: the same bits) and their
 * normals. The lanes past the last neighbour are padding, as in PadNeighbours.
 */
inline NeighbourLanes LoadNeighbours(const double p[3],
  const SortedNeighbours& neighbours,
  std::size_t k)
{
  NeighbourLanes lanes;
  const std::uint32_t* index = neighbours.Index;
  const std::size_t count = neighbours.Count;
#if defined(__AVX512F__)
  // Each neighbour's record (coordinates and normal) in one 64-byte load, the eight records
  // turned into lanes by a transpose: cheaper than six gathers.
  const std::size_t left = count - k;
  const __mmask8 valid = left >= 8 ? __mmask8(0xFF) : __mmask8((1u << left) - 1u);
  const double* records = neighbours.Records;
  __m512d rows[8];
  if (left >= 8)
  {
    for (std::size_t lane = 0; lane < 8; ++lane)
    {
      rows[lane] = _mm512_loadu_pd(records + 8 * static_cast<std::size_t>(index[k + lane]));
    }
  }
  else
  {
    for (std::size_t lane = 0; lane < 8; ++lane)
    {
      const std::size_t row = lane < left ? index[k + lane] : neighbours.PaddingRow;
      rows[lane] = _mm512_loadu_pd(records + 8 * row);
    }
  }
  __m512d columns[6];
  TransposeRows(rows, columns);
  const __m512d far = _mm512_set1_pd(1e300);
  lanes.Dx =
    (DoubleLanes)_mm512_mask_blend_pd(valid, far, _mm512_sub_pd(columns[0], _mm512_set1_pd(p[0])));
  lanes.Dy =
    (DoubleLanes)_mm512_mask_blend_pd(valid, far, _mm512_sub_pd(columns[1], _mm512_set1_pd(p[1])));
  lanes.Dz =
    (DoubleLanes)_mm512_mask_blend_pd(valid, far, _mm512_sub_pd(columns[2], _mm512_set1_pd(p[2])));
  lanes.Nx = (DoubleLanes)columns[3];
  lanes.Ny = (DoubleLanes)columns[4];
  lanes.Nz = (DoubleLanes)columns[5];
#else
  const double *x = neighbours.X, *y = neighbours.Y, *z = neighbours.Z;
  const double* normals = neighbours.Normals;
  double values[6][Lanes];
  const double px = p[0], py = p[1], pz = p[2];
  for (std::size_t lane = 0; lane < Lanes; ++lane)
  {
    if (k + lane < count)
    {
      const std::size_t j = index[k + lane];
      values[0][lane] = x[j] - px;
      values[1][lane] = y[j] - py;
      values[2][lane] = z[j] - pz;
      values[3][lane] = normals[3 * j];
      values[4][lane] = normals[3 * j + 1];
      values[5][lane] = normals[3 * j + 2];
    }
    else
    {
      values[0][lane] = values[1][lane] = values[2][lane] = 1e300;
      values[3][lane] = values[4][lane] = values[5][lane] = 0.0;
    }
  }
  lanes.Dx = Load(values[0]);
  lanes.Dy = Load(values[1]);
  lanes.Dz = Load(values[2]);
  lanes.Nx = Load(values[3]);
  lanes.Ny = Load(values[4]);
  lanes.Nz = Load(values[5]);
#endif
  return lanes;
}

/**
 * Step 2 for sorted point p of normal `own` over its neighbours: the sum of exp(-|q - p|^2 *
 * distanceScale) psi(own, n_j) sign(own . n_j) n_j.
 */
void EdgeAwareNormalSum(const double p[3],
  const SortedNeighbours& neighbours,
  const double own[3],
  double distanceScale,
  double agreementScale,
  double sum[3])
{
  const DoubleLanes zero = {};
  DoubleLanes sumX = zero, sumY = zero, sumZ = zero;
  for (std::size_t k = 0; k < neighbours.Count; k += Lanes)
  {
    const NeighbourLanes q = LoadNeighbours(p, neighbours, k);
    const DoubleLanes distanceSquared = (q.Dx * q.Dx + q.Dy * q.Dy) + q.Dz * q.Dz;
    const DoubleLanes cosine = (q.Nx * own[0] + q.Ny * own[1]) + q.Nz * own[2];
    const DoubleLanes w = ExpOfNonPositive(
      -distanceSquared * distanceScale + AgreementExponent(cosine, agreementScale));
    // The fitted normals are not oriented: a neighbour's counts with the sign of the cosine.
    const DoubleLanes signedWeight = Select(LessThan(cosine, 0.0), -w, w);
    sumX += signedWeight * q.Nx;
    sumY += signedWeight * q.Ny;
    sumZ += signedWeight * q.Nz;
  }
  sum[0] = SumLanes(sumX);
  sum[1] = SumLanes(sumY);
  sum[2] = SumLanes(sumZ);
}

/**
 * Step 3 for sorted point p of filtered normal m over its neighbours (with their filtered
 * normals m_j, turned to agree with m), with the weights
 * w = exp(-|q - p|^2 * distanceScale - h^2 * normalScale) psi(m, m_j):
 *  - the sums of w and of w h, h = <(m + m_j) / 2, q - p> the height along the mean of the two
 *    normals: the chord q - p between two points of a sphere is orthogonal to the sum of their
 *    normals, and on any smooth surface the error is of third order in |q - p| (second order
 *    along m alone), so a curved surface is not shrunk; on a plane h is the paper's;
 *  - the sum of w <m_j, q - p> m_j: p projected on each neighbour's own tangent plane (Huang et
 *    al. 2013), which keeps a point on its own face up to an edge;
 *  - the sums of Bump(-|q - p|^2 * distanceScale, DistanceBumpWidth) and of the same times
 *    Bump of psi(m, m_j)'s exponent at the wider angle of smoothAgreementScale: how much of the
 *    neighbourhood agrees with m (a share, whose exact weights matter little: bumps cost two
 *    exponentials less per neighbour).
 */
void EdgeAwareHeightSums(const double p[3],
  const SortedNeighbours& neighbours,
  const double m[3],
  double distanceScale,
  double normalScale,
  double agreementScale,
  double smoothAgreementScale,
  EdgeAwareHeights& sums)
{
  const DoubleLanes zero = {};
  DoubleLanes weights = zero, heights = zero, planeX = zero, planeY = zero, planeZ = zero;
  DoubleLanes near = zero, agreeing = zero;
  for (std::size_t k = 0; k < neighbours.Count; k += Lanes)
  {
    const NeighbourLanes q = LoadNeighbours(p, neighbours, k);
    const DoubleLanes distanceSquared = (q.Dx * q.Dx + q.Dy * q.Dy) + q.Dz * q.Dz;
    const DoubleLanes cosine = (q.Nx * m[0] + q.Ny * m[1]) + q.Nz * m[2];
    // The neighbour's normal turned to agree with m (the normals are not oriented).
    const IntLanes opposite = LessThan(cosine, 0.0);
    const DoubleLanes nx = Select(opposite, -q.Nx, q.Nx);
    const DoubleLanes ny = Select(opposite, -q.Ny, q.Ny);
    const DoubleLanes nz = Select(opposite, -q.Nz, q.Nz);
    const DoubleLanes own = (q.Dx * nx + q.Dy * ny) + q.Dz * nz;
    const DoubleLanes h = ((q.Dx * (nx + m[0]) + q.Dy * (ny + m[1])) + q.Dz * (nz + m[2])) * 0.5;
    const DoubleLanes distanceExponent = -distanceSquared * distanceScale;
    const DoubleLanes w = ExpOfNonPositive(
      (distanceExponent - (h * h) * normalScale) + AgreementExponent(cosine, agreementScale));
    weights += w;
    heights += w * h;
    const DoubleLanes projection = w * own;
    planeX += projection * nx;
    planeY += projection * ny;
    planeZ += projection * nz;
    const DoubleLanes nearWeight = Bump(distanceExponent, DistanceBumpWidth);
    near += nearWeight;
    agreeing += nearWeight * Bump(AgreementExponent(cosine, smoothAgreementScale), 4.0);
  }
  sums.WeightSum = SumLanes(weights);
  sums.WeightedHeightSum = SumLanes(heights);
  sums.Projection[0] = SumLanes(planeX);
  sums.Projection[1] = SumLanes(planeY);
  sums.Projection[2] = SumLanes(planeZ);
  sums.DistanceWeightSum = SumLanes(near);
  sums.AgreeingWeightSum = SumLanes(agreeing);
}

/// This build's edge-aware functions (declared in BilateralKernel.cxx).
EdgeAwareKernel MakeEdgeAwareKernel()
{
  EdgeAwareKernel kernel;
  kernel.Select = &PackNeighbours<true>;
  kernel.PlaneNormals = &EdgeAwarePlaneNormals;
  kernel.NormalSum = &EdgeAwareNormalSum;
  kernel.HeightSums = &EdgeAwareHeightSums;
  return kernel;
}

} // namespace PCB_KERNEL_VARIANT
} // namespace pcbilateral

// The steps of the core's 3x3 eigensolver (SmallestEigenvector, SymmetricEigensolver.h), written
// once for a single matrix (Real = double) and for one matrix per vector lane (Real = the kernel
// body's DoubleLanes, Kernel/BilateralKernelBody.h), so that every lane computes exactly the
// scalar solver's bits. Private to the core.
//
// No include guard and no #include: this file is included inside a namespace that has declared,
// for Real and its comparison result, Abs(Real), Sqrt(Real) (rounded as IEEE 754 requires),
// Less(Real, Real) (a < b, false for NaN) and Select(mask, Real, Real) (the first where the mask
// holds, else the second). Each including namespace gets its own copy of the templates.

/// B = C - shift I, the shift making B's trace zero (C given by its upper triangle xx, xy, xz, yy,
/// yz, zz). Returns B's largest entry in magnitude, NaN entries passed over: 0 when C = shift I.
template<typename Real>
inline Real CenteredMatrix(const Real covariance[6], Real b[6])
{
  const Real shift = (covariance[0] + covariance[3] + covariance[5]) / 3.0;
  b[0] = covariance[0] - shift;
  b[1] = covariance[1];
  b[2] = covariance[2];
  b[3] = covariance[3] - shift;
  b[4] = covariance[4];
  b[5] = covariance[5] - shift;
  Real scale{};
  for (int entry = 0; entry < 6; ++entry)
  {
    const Real magnitude = Abs(b[entry]);
    scale = Select(Less(scale, magnitude), magnitude, scale);
  }
  return scale;
}

/**
 * Divides B by its scale (numbers of order one, whatever the units and the offset of the cloud),
 * then returns c and sets p of its characteristic cubic: B's eigenvalues are 2 p t for the three
 * roots t of 4 t^3 - 3 t = c, with p^2 = tr(B^2) / 6 and c = det(B) / (2 p^3) in [-1, 1]
 * (classically t = cos(phi + 2 pi j / 3) with cos(3 phi) = c).
 */
template<typename Real>
inline Real CubicCosine(Real b[6], Real scale, Real& p)
{
  const Real inverseScale = 1.0 / scale;
  for (int entry = 0; entry < 6; ++entry)
  {
    b[entry] *= inverseScale;
  }
  const Real b00 = b[0], b01 = b[1], b02 = b[2], b11 = b[3], b12 = b[4], b22 = b[5];
  p = Sqrt((b00 * b00 + b11 * b11 + b22 * b22 + 2.0 * (b01 * b01 + b02 * b02 + b12 * b12)) / 6.0);
  const Real determinant =
    b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) + b02 * (b01 * b12 - b11 * b02);
  const Real ratio = determinant / (2.0 * p * p * p);
  const Real minusOne = Real{} - 1.0, one = Real{} + 1.0;
  const Real atLeastMinusOne = Select(Less(minusOne, ratio), ratio, minusOne);
  return Select(Less(atLeastMinusOne, one), atLeastMinusOne, one);
}

/**
 * e in [0, 1/2] with -(1/2 + e) the smallest root of 4 t^3 - 3 t = c: the root of
 * (6 + 4 e) e^2 = 1 - c, found by Newton's method rather than with acos and cos, whose last bits
 * differ between C libraries and between their FMA and non-FMA code paths. Written in e, the
 * cubic stays well conditioned where the two smallest roots meet (c near 1, e near 0). The
 * start, a cubic in s = sqrt((1 - c) / 2) fitted to the root (e = sqrt((1 - c) / 6) near c = 1,
 * e = 1/2 at c = -1), is within 0.02% of it; two steps then give the root to 1.7e-16 relative
 * (checked against a 50-digit solution over c in [-1, 1]).
 */
template<typename Real>
inline Real SmallestRootOffset(Real cosine)
{
  const Real gap = 1.0 - cosine;
  const Real s = Sqrt(0.5 * gap);
  const Real start = s * (0.57725885 + s * (-0.10911916 + s * (0.04309189 - 0.01129872 * s)));
  Real e = start;
  for (int step = 0; step < 2; ++step)
  {
    e -= ((6.0 + 4.0 * e) * (e * e) - gap) / (12.0 * e * (1.0 + e));
  }
  return Select(Less(Real{}, start), e, start); // at e = 0 a step divides by zero
}

/**
 * The first largest of the cross products of the rows of the symmetric matrix B - eigenvalue I
 * (the most accurate one): a vector along the eigenvector of that eigenvalue, when it is simple.
 * Returns its squared length (0 when all three vanish).
 */
template<typename Real>
inline Real EigenvectorFromRows(const Real b[6], Real eigenvalue, Real vector[3])
{
  const Real rows[3][3] = { { b[0] - eigenvalue, b[1], b[2] },
    { b[1], b[3] - eigenvalue, b[4] },
    { b[2], b[4], b[5] - eigenvalue } };
  const int pairs[3][2] = { { 0, 1 }, { 0, 2 }, { 1, 2 } };
  Real bestNorm{};
  vector[0] = vector[1] = vector[2] = Real{};
  for (const auto& pair : pairs)
  {
    const Real* u = rows[pair[0]];
    const Real* v = rows[pair[1]];
    const Real cross[3] = {
      u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]
    };
    const Real norm = cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2];
    const auto larger = Less(bestNorm, norm);
    bestNorm = Select(larger, norm, bestNorm);
    for (int axis = 0; axis < 3; ++axis)
    {
      vector[axis] = Select(larger, cross[axis], vector[axis]);
    }
  }
  return bestNorm;
}

// The measurement's local fits: a robust quadric (or plane) height function over a
// neighbourhood's least-squares plane, and the correction of the noise a ball of a given radius
// sees. Plain C++17, no VTK types.
//
// Around a point, the points within a radius rho are fitted by a quadric height function
// z = q(x, y) over their principal plane, robustly (points more than 3 robust deviations off are
// left out, then the fit is redone): the quadric takes the surface's curvature away, the
// clipping takes outliers and the far side of edges away. The residuals' spread estimates the
// noise sigma. Two effects bias that estimate and are corrected:
// - the fit absorbs 6 degrees of freedom (variance x m / (m - 6) for m points) and the clipping
//   at 3 deviations removes 2.7% of the variance (FitQuadric);
// - the ball cuts the noise's slab: a point at height z above the surface is in the ball over
//   a disc of area pi (rho^2 - z^2), so the heights seen have the density g(z) (rho^2 - z^2)
//   (g the noise's Gaussian), whose variance is less than sigma^2. It is inverted numerically
//   (SigmaFromBallVariance).
#ifndef pcbilateral_LocalSurfaceFit_h
#define pcbilateral_LocalSurfaceFit_h

#include <array>
#include <cstddef>
#include <vector>

namespace pcbilateral
{

/// Terms of the quadric height function (1, x, y, x^2, xy, y^2); a plane uses the first 3.
constexpr int QuadricTerms = 6;
/// A neighbourhood of fewer points is not fitted.
constexpr std::size_t FewestPointsToFit = 16;

/// The fit of one neighbourhood.
struct LocalFit
{
  bool Fitted = false;
  /// Residual variance of the inliers, corrected for the fit's degrees of freedom and the
  /// clipping (not yet for the ball's cut of the slab).
  double Variance = 0.0;
  /// Inliers, per unit of ball cross-section (still to be divided by the level's fraction).
  std::size_t Inliers = 0;
  /// The point of the fitted surface below the centre.
  double SurfacePoint[3] = { 0, 0, 0 };
  /// The fitted surface: z = q(x, y) in the frame (TangentU, TangentV, Normal) at Origin, in
  /// units of Scale.
  double Origin[3] = { 0, 0, 0 };
  double TangentU[3] = { 1, 0, 0 };
  double TangentV[3] = { 0, 1, 0 };
  double Normal[3] = { 0, 0, 1 };
  double Coefficients[QuadricTerms] = {};
  double Scale = 1.0;
  /// The foot's local (x, y).
  double FootX = 0.0, FootY = 0.0;

  double Height(double x, double y) const
  {
    const double* c = this->Coefficients;
    return c[0] + c[1] * x + c[2] * y + c[3] * x * x + c[4] * x * y + c[5] * y * y;
  }
  /// The point's local coordinates (x, y along the tangents, z along the normal).
  void Local(const double* p, double local[3]) const;
};

/// Robust quadric fit (terms 6), or plane fit (terms 3), of the given points (coordinates
/// relative to centre, in units of radius for conditioning).
LocalFit FitQuadric(const std::vector<std::array<double, 3>>& points,
  const double centre[3],
  double radius,
  int terms = QuadricTerms);

/// The sigma of Gaussian offsets from a plane whose heights, seen in a ball of radius rho
/// centred on the plane, have the given variance; +infinity when the ball is too small to tell
/// (the heights fill it as if uniformly).
double SigmaFromBallVariance(double variance, double rho);

} // namespace pcbilateral

#endif

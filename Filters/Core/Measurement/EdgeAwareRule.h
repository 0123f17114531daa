// The automatic rule of the edge-aware mode (EdgeAware/EdgeAwareNormals.h): its parameters from
// a cloud's measured spacing, noise and creases. The paper's filter has its own rule
// (AutomaticRule.h), which dispatches here when the edge-aware mode is on. This is the one place
// the edge-aware rule is written; docs/edge-aware.md gives the measurements behind it. Plain
// C++17, no VTK types.
#ifndef pcbilateral_EdgeAwareRule_h
#define pcbilateral_EdgeAwareRule_h

#include "BilateralParameters.h"
#include "CloudMeasurement.h"

#include <string>

namespace pcbilateral
{

/// The edge-aware rule's constants (measured with Testing/Benchmark/pcb_edges.cxx):
///   with creases, r = RadiusInSpacings x spacing + RadiusInSigmas x sigma,
///   rn = NormalRadiusInSigmas x sigma, N = NumberOfIterations (a third iteration gains 2 to 6%
///   on the edges at 0.5% and 1% noise for half as much time again, and loses at 0.1%); where
///   the noise is thin (sigma below ThinNoiseInSpacings x spacing: pcb_edges's shapes at 0.1%
///   noise, 0.2 to 0.4 spacings, against 1 to 1.9 at 0.5%) one iteration does as well as two on
///   the edges and about as well overall with a wider radius and a wider normal radius:
///   r = ThinRadiusInSpacings x spacing + RadiusInSigmas x sigma,
///   rn = ThinNormalRadiusInSigmas x sigma, N = ThinIterations (half the time); r at most
///   MaximumRadiusInSpacings x spacing (reached where sigma passes 3.2 spacings: the wedge at
///   1% noise, 3.7, keeps an edge RMS of 2.30e-3 of the diagonal with 24 spacings against 2.25e-3
///   with 26.5, in 0.82 of the time; the grid's best edge settings at 1% sit at 24, its largest);
///   on a smooth cloud (CreaseFraction at most SmoothCreaseFraction and FeatureFraction at most
///   SmoothFeatureFraction: no edge found, not even one the noise hides from the quadric fit),
///   r = SmoothRadiusInSpacings x spacing + SmoothRadiusInSigmas x sigma,
///   rn = SmoothNormalRadiusInSigmas x sigma, N = SmoothIterations: the mode's mean-normal
///   heights do not shrink a curved surface, so little but the noise limits the radius there,
///   up to SmoothRadiusInCurvatureRadii of the surface's radius of curvature (SurfaceRadius).
struct EdgeAwareRule
{
  double RadiusInSpacings = 8.0;
  double RadiusInSigmas = 5.0;
  double NormalRadiusInSigmas = 8.0;
  int NumberOfIterations = 2;
  double ThinNoiseInSpacings = 0.6;
  double ThinRadiusInSpacings = 10.0;
  double ThinNormalRadiusInSigmas = 16.0;
  int ThinIterations = 1;
  double MaximumRadiusInSpacings = 24.0;
  double SmoothCreaseFraction = 0.002;
  double SmoothFeatureFraction = 0.02;
  double SmoothRadiusInSpacings = 30.0;
  double SmoothRadiusInSigmas = 2.0;
  double SmoothNormalRadiusInSigmas = 16.0;
  int SmoothIterations = 4;
  double SmoothRadiusInCurvatureRadii = 0.4;
};

/// The surface's radius of curvature that the measurement's CurvatureExcess implies: a sphere
/// of radius R leaves a plane fit over a disc of radius rho a residual variance of
/// rho^4 / (48 R^2) beyond a quadric fit's, so R = rho^2 / (sigma sqrt(48 excess)) with
/// rho = FlatnessRadius. Infinite for a flat cloud (excess at most 0) or one not measured.
double SurfaceRadius(const CloudScales& scales);

/// Whether the edge-aware rule treats the cloud as smooth (no crease, no feature found).
bool IsSmoothForEdgeAware(const CloudScales& scales, const EdgeAwareRule& rule = EdgeAwareRule());

/// Whether the edge-aware rule treats the noise of a cloud with creases as thin (sigma below
/// ThinNoiseInSpacings spacings).
bool IsThinNoiseForEdgeAware(const CloudScales& scales,
  const EdgeAwareRule& rule = EdgeAwareRule());

/// The parameters of the automatic edge-aware mode, as ChooseParameters for the paper's
/// filter: each of Radius, NormalRadius and NumberOfIterations that the user gave (> 0) is kept,
/// the others come from the rule; every other field is copied from userParameters; when the
/// scales are not valid, the unset parameters are left at 0 (the paper's heuristic).
BilateralParameters ChooseEdgeAwareParameters(const CloudScales& scales,
  const BilateralParameters& userParameters,
  const EdgeAwareRule& rule = EdgeAwareRule());

/// The rule in words, with the numbers of `rule`.
std::string DescribeEdgeAwareRule(const EdgeAwareRule& rule = EdgeAwareRule());

} // namespace pcbilateral

#endif

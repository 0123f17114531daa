// Measures a cloud's point spacing and noise level, and derives the filter's parameters from
// them (the automatic mode). Plain C++17, no VTK types. The measurement only chooses
// parameters: the filter itself is unchanged.
#ifndef pcbilateral_CloudMeasurement_h
#define pcbilateral_CloudMeasurement_h

#include "BilateralFilter.h"

#include <cstddef>
#include <string>
#include <vector>

namespace pcbilateral
{

struct ScaleMeasurementOptions
{
  /// Points around which the surface is fitted, picked deterministically (stratified by index
  /// with a hashed offset). More gives steadier estimates; the cost grows linearly.
  std::size_t NumberOfSamples = 512;
  /// Optional: the indices of the sample points (into the cloud's points). When empty, the
  /// stratified sample above is used.
  std::vector<std::size_t> SampleIndices;
  /// The fraction of the whole cloud that the given points are, when they are a uniform random
  /// subset of it (e.g. gathered from the processes of a distributed run): the measured density
  /// is divided by it, so that the spacing is that of the whole cloud. 1: the whole cloud.
  double PointFraction = 1.0;
  /// Threads for the fits; 0 uses all cores. Results do not depend on it.
  int NumberOfThreads = 0;
};

/// What MeasureScales found. Lengths are in the cloud's units.
struct CloudScales
{
  /// False when the cloud is too small or degenerate to measure (Problem says why).
  bool Valid = false;
  std::string Problem;
  /// The mean distance from a point to its nearest neighbour on the noise-free surface,
  /// 1 / (2 sqrt(density)) (exact for points spread at random), averaged over the samples.
  double PointSpacing = 0.0;
  /// The standard deviation of the points' offsets from the underlying surface (the noise),
  /// curvature removed by a local quadric fit.
  double NoiseSigma = 0.0;
  /// The median number of points per unit area of surface.
  double SurfaceDensity = 0.0;
  /// The radius of the neighbourhoods the fits used (about 5 sigma, at least ~50 points).
  double NeighbourhoodRadius = 0.0;
  /// How far the surface is from flat at FlatnessRadius (1.5 times the automatic radius): the
  /// median over the samples of the residual variance a plane fit leaves beyond a quadric fit,
  /// in units of sigma^2 (about 0 on flat parts), and the fraction of samples where it exceeds
  /// 0.5 (edges, strong bends).
  double FlatnessRadius = 0.0;
  double CurvatureExcess = 0.0;
  double FeatureFraction = 0.0;
  std::size_t NumberOfSamples = 0;
  /// Samples whose neighbourhood could be fitted (enough points, not an isolated outlier).
  std::size_t NumberOfFittedSamples = 0;
  /// Rounds of the radius/noise fixed point (see CloudMeasurement.cxx).
  int NumberOfRounds = 0;
};

/// Measures the point spacing and the noise level of the finite points of a cloud (ghost
/// points count as points of the surface). Deterministic and independent of the number of
/// threads.
CloudScales MeasureScales(const PointCloudView& cloud,
  const ScaleMeasurementOptions& options = ScaleMeasurementOptions());

/// The automatic rule's constants (where they come from: README.md, "Automatic parameters"):
///   r = RadiusInSpacings x spacing + RadiusInSigmas x sigma,
///   rn = NormalRadiusInSigmas x sigma, N = NumberOfIterations;
/// on a flat cloud (CurvatureExcess below FlatExcess and FeatureFraction below
/// FlatFeatureFraction: no edge, no bend at that scale), r is FlatRadiusFactor times larger and
/// N = FlatIterations, since nothing limits the smoothing there but the noise.
/// The spacing term gives every point enough neighbours for a stable normal and average on a
/// clean cloud; the sigma term widens the neighbourhood as the noise grows.
struct AutomaticRule
{
  double RadiusInSpacings = 5.0;
  double RadiusInSigmas = 4.0;
  double NormalRadiusInSigmas = 5.0;
  int NumberOfIterations = 2;
  double FlatExcess = 0.007;
  double FlatFeatureFraction = 0.01;
  double FlatRadiusFactor = 1.5;
  int FlatIterations = 3;
};

/// Whether the rule treats the cloud as flat.
bool IsFlat(const CloudScales& scales, const AutomaticRule& rule = AutomaticRule());

/// The parameters of the automatic mode: each of Radius, NormalRadius and NumberOfIterations
/// that the user gave (Radius > 0, NormalRadius > 0, NumberOfIterations > 0; pass 0 for
/// "automatic", also for the iterations) is kept; the others come from the rule applied to the
/// measured scales. Every other field is copied from
/// userParameters. When the scales are not valid, the unset radii are left at 0, so that the
/// filter falls back to the paper's automatic radius.
BilateralParameters ChooseParameters(const CloudScales& scales,
  const BilateralParameters& userParameters,
  const AutomaticRule& rule = AutomaticRule());

} // namespace pcbilateral

#endif

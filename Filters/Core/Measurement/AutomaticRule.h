// The automatic rule: the filter's parameters from a cloud's measured spacing and noise, and
// the paper's heuristic. This is the one place the rule is written; the command line's help,
// the VTK class's documentation, ParaView's help text (generated from DescribeAutomaticRule at
// build time) and docs/parameters.md point here. Plain C++17, no VTK types.
#ifndef pcbilateral_AutomaticRule_h
#define pcbilateral_AutomaticRule_h

#include "BilateralParameters.h"
#include "CloudMeasurement.h"

#include <cstddef>
#include <string>

namespace pcbilateral
{

/// The automatic rule's constants (where they come from: docs/parameters.md):
///   r = RadiusInSpacings x spacing + RadiusInSigmas x sigma,
///   rn = NormalRadiusInSigmas x sigma, N = NumberOfIterations (with edges, the Edge* constants
///   below);
/// on a flat cloud (CurvatureExcess below FlatExcess and FeatureFraction below
/// FlatFeatureFraction: no edge, no bend at that scale), r is FlatRadiusFactor times larger and
/// N = FlatIterations, since nothing limits the smoothing there but the noise.
/// On a smooth cloud with thin noise (not flat, CreaseFraction below SmoothCreaseFraction, sigma
/// below ThinNoiseInSpacings spacings), r is SmoothRadiusFactor times larger, rn = r and
/// N = SmoothIterations: there is no edge for the range weight to keep, and one plain average
/// along the normal beats two bilateral ones (measured on pcb_quality's spheres at 0.1% noise).
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
  double SmoothCreaseFraction = 0.01;
  double ThinNoiseInSpacings = 0.5;
  double SmoothRadiusFactor = 1.25;
  int SmoothIterations = 1;
  /// With edges (neither flat nor smooth with thin noise, and at least EdgeFeatureFraction of
  /// the samples see a feature), r = EdgeRadiusInSpacings x spacing + EdgeRadiusInSigmas x
  /// sigma and rn = EdgeNormalRadiusInSigmas x sigma: a tighter normal radius keeps the points
  /// right at an edge (within 3 sigma of it) on their own face, a wider ball flattens the faces
  /// (fitted to pcb_quality's grid with the 3-sigma edge band, docs/parameters.md).
  double EdgeFeatureFraction = 0.01;
  double EdgeRadiusInSpacings = 8.0;
  double EdgeRadiusInSigmas = 3.0;
  double EdgeNormalRadiusInSigmas = 3.3;
  /// Where the local spacing varies more than this many times across the cloud (the ratio of
  /// the 95th to the 5th percentile of SpacingField, read at the samples), one radius cannot
  /// serve it: the automatic radius follows the density, each point's from its local spacing
  /// (RadiusAt). A scan from one position spans 100 to 300 times; an evenly sampled cloud about
  /// 1.5 to 2.
  double FollowDensitySpread = 4.0;
  /// Where the radius follows the density, it is this many times the rule's radius at the local
  /// spacing: measured on a terrestrial scan (docs/structure-metrics.md), whose scan lines make
  /// the nearest-neighbour distance (along a line) shorter than the spacing between lines.
  double FollowDensityRadiusFactor = 2.0;
  /// Structured noise (CloudScales::StructuredNoise, e.g. a depth camera's quantised depths):
  /// the terraces need this many iterations to be smoothed into one surface.
  int StructuredNoiseIterations = 3;
};

/// Whether the rule treats the cloud as flat.
bool IsFlat(const CloudScales& scales, const AutomaticRule& rule = AutomaticRule());

/// Whether the rule treats the cloud as having edges (never when it is flat or smooth with thin
/// noise).
bool HasEdges(const CloudScales& scales, const AutomaticRule& rule = AutomaticRule());

/// Whether the rule treats the cloud as smooth with thin noise (never when it is flat).
bool IsSmoothWithThinNoise(const CloudScales& scales, const AutomaticRule& rule = AutomaticRule());

/// The parameters of the automatic mode: each of Radius, NormalRadius and NumberOfIterations
/// that the user gave (Radius > 0, NormalRadius > 0, NumberOfIterations > 0; pass 0 for
/// "automatic", also for the iterations) is kept; the others come from the rule applied to the
/// measured scales. Every other field is copied from
/// userParameters. When the scales are not valid, the unset parameters are left at 0, so that
/// the filter falls back to the paper's heuristic for them.
BilateralParameters ChooseParameters(const CloudScales& scales,
  const BilateralParameters& userParameters,
  const AutomaticRule& rule = AutomaticRule());

/// Whether the spacing varies more than FollowDensitySpread times across the cloud (the scales
/// were measured with their spacing field).
bool SpacingVaries(const CloudScales& scales, const AutomaticRule& rule = AutomaticRule());

/// (Where the radius follows the density, the chosen Radius is the rule's at SurfaceSpacing.)
/// Whether the automatic radius follows the density: the radius is automatic, the scales were
/// measured with their spacing field, and the spacing varies more than FollowDensitySpread times.
bool RadiusFollowsDensity(const CloudScales& scales,
  const BilateralParameters& userParameters,
  const AutomaticRule& rule = AutomaticRule());

/// The spacing of most of the surface (SpacingField::GetAreaWeightedMedian, in PointSpacing's
/// sense): where the radius follows the density, the spacing of the reference radius
/// (ChooseParameters' Radius) and the one reported.
double SurfaceSpacing(const CloudScales& scales);

/// The rule's radius before its factors (flat, smooth, following the density):
/// InSpacings x spacing + InSigmas x sigma, with the constants of the cloud's case.
struct RadiusTerms
{
  double InSpacings;
  double InSigmas;
};
RadiusTerms RuleRadiusTerms(const CloudScales& scales, const AutomaticRule& rule = AutomaticRule());

/// The automatic radius where the spacing (in PointSpacing's sense) is `localSpacing`: the
/// rule of ChooseParameters with that spacing. Where the radius follows the density, a point's
/// local spacing is the field's value at it times SpacingPerNeighbourDistance.
double RadiusAt(const CloudScales& scales,
  double localSpacing,
  const AutomaticRule& rule = AutomaticRule());

/// The normal radius that goes with an automatic radius where the radius follows the density:
/// the user's if given; in the edge-aware mode the one its rule chose (`chosen`, which does not
/// depend on the radius); else the paper rule's (which depends on the radius only where it is
/// the radius, on a smooth cloud with thin noise, or at its floor).
double NormalRadiusAt(const CloudScales& scales,
  const BilateralParameters& userParameters,
  const BilateralParameters& chosen,
  double radius,
  const AutomaticRule& rule = AutomaticRule());

/// The rule in words, with the numbers of `rule`, e.g. "r = 5 spacings + 4 sigma, rn = 5 sigma,
/// N = 2 (on a flat cloud ...)": every front end shows this text rather than its own copy.
std::string DescribeAutomaticRule(const AutomaticRule& rule = AutomaticRule());

/// The paper's heuristic radius (AutomaticParameters::Paper, and the fallback for a cloud that
/// could not be measured): sqrt(20 / numberOfPoints) x largestExtent; rn = r and N = 1 go with
/// it. 0 for no points.
double PaperRadius(std::size_t numberOfPoints, double largestExtent);

/// The paper's heuristic in words.
const char* DescribePaperRule();

} // namespace pcbilateral

#endif

#include "AutomaticRule.h"

#include "EdgeAwareRule.h"

#include <cmath>
#include <sstream>

namespace pcbilateral
{

bool IsFlat(const CloudScales& scales, const AutomaticRule& rule)
{
  return scales.Valid && scales.CurvatureExcess < rule.FlatExcess &&
         scales.FeatureFraction < rule.FlatFeatureFraction;
}

bool IsSmoothWithThinNoise(const CloudScales& scales, const AutomaticRule& rule)
{
  return scales.Valid && !IsFlat(scales, rule) &&
         scales.CreaseFraction < rule.SmoothCreaseFraction &&
         scales.NoiseSigma < rule.ThinNoiseInSpacings * scales.PointSpacing;
}

BilateralParameters ChooseParameters(const CloudScales& scales,
  const BilateralParameters& userParameters,
  const AutomaticRule& rule)
{
  if (userParameters.EdgeAware)
  {
    return ChooseEdgeAwareParameters(scales, userParameters);
  }
  BilateralParameters parameters = userParameters;
  if (!scales.Valid)
  {
    return parameters;
  }
  const bool flat = IsFlat(scales, rule);
  const bool smooth = IsSmoothWithThinNoise(scales, rule);
  if (parameters.NumberOfIterations <= 0)
  {
    parameters.NumberOfIterations = flat     ? rule.FlatIterations
                                    : smooth ? rule.SmoothIterations
                                             : rule.NumberOfIterations;
  }
  if (!(parameters.Radius > 0.0))
  {
    parameters.Radius =
      (flat      ? rule.FlatRadiusFactor
        : smooth ? rule.SmoothRadiusFactor
                 : 1.0) *
      (rule.RadiusInSpacings * scales.PointSpacing + rule.RadiusInSigmas * scales.NoiseSigma);
  }
  if (!(parameters.NormalRadius > 0.0))
  {
    // A noise-free cloud measures sigma 0 (or round-off): the floor keeps the normal radius
    // positive and computable, far below anything a real noise would give. A smooth surface
    // with thin noise has nothing for the range weight to keep: the normal radius is the
    // radius (plain averaging along the normal), the paper's own choice.
    parameters.NormalRadius =
      smooth ? parameters.Radius
             : std::max(rule.NormalRadiusInSigmas * scales.NoiseSigma, 1e-3 * parameters.Radius);
  }
  return parameters;
}

std::string DescribeAutomaticRule(const AutomaticRule& rule)
{
  std::ostringstream text;
  text << "r = " << rule.RadiusInSpacings << " spacings + " << rule.RadiusInSigmas
       << " sigma, rn = " << rule.NormalRadiusInSigmas << " sigma, N = " << rule.NumberOfIterations
       << "; on a flat cloud " << rule.FlatRadiusFactor
       << " times that r and N = " << rule.FlatIterations
       << "; on a smooth cloud (no crease) with noise below " << rule.ThinNoiseInSpacings
       << " spacing, " << rule.SmoothRadiusFactor
       << " times that r, rn = r and N = " << rule.SmoothIterations;
  return text.str();
}

double PaperRadius(std::size_t numberOfPoints, double largestExtent)
{
  if (numberOfPoints == 0)
  {
    return 0.0;
  }
  return std::sqrt(20.0 / static_cast<double>(numberOfPoints)) * largestExtent;
}

const char* DescribePaperRule()
{
  return "r = sqrt(20 / number of points) x the largest bounding-box extent, rn = r, N = 1";
}

} // namespace pcbilateral

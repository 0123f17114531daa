#include "EdgeAwareRule.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace pcbilateral
{

bool IsSmoothForEdgeAware(const CloudScales& scales, const EdgeAwareRule& rule)
{
  return scales.Valid && scales.CreaseFraction <= rule.SmoothCreaseFraction &&
         scales.FeatureFraction <= rule.SmoothFeatureFraction;
}

bool IsThinNoiseForEdgeAware(const CloudScales& scales, const EdgeAwareRule& rule)
{
  return scales.Valid && scales.NoiseSigma < rule.ThinNoiseInSpacings * scales.PointSpacing;
}

double SurfaceRadius(const CloudScales& scales)
{
  if (!scales.Valid || !(scales.CurvatureExcess > 0.0) || !(scales.NoiseSigma > 0.0))
  {
    return std::numeric_limits<double>::infinity();
  }
  return scales.FlatnessRadius * scales.FlatnessRadius /
         (scales.NoiseSigma * std::sqrt(48.0 * scales.CurvatureExcess));
}

BilateralParameters ChooseEdgeAwareParameters(const CloudScales& scales,
  const BilateralParameters& userParameters,
  const EdgeAwareRule& rule)
{
  BilateralParameters parameters = userParameters;
  if (!scales.Valid)
  {
    return parameters;
  }
  const double s = scales.PointSpacing, sigma = scales.NoiseSigma;
  const bool smooth = IsSmoothForEdgeAware(scales, rule);
  const bool thin = !smooth && IsThinNoiseForEdgeAware(scales, rule);
  if (parameters.NumberOfIterations <= 0)
  {
    parameters.NumberOfIterations = smooth ? rule.SmoothIterations
                                    : thin ? rule.ThinIterations
                                           : rule.NumberOfIterations;
  }
  if (!(parameters.Radius > 0.0))
  {
    parameters.Radius =
      smooth ? std::min(rule.SmoothRadiusInSpacings * s + rule.SmoothRadiusInSigmas * sigma,
                 rule.SmoothRadiusInCurvatureRadii * SurfaceRadius(scales))
             : std::min((thin ? rule.ThinRadiusInSpacings : rule.RadiusInSpacings) * s +
                          rule.RadiusInSigmas * sigma,
                 rule.MaximumRadiusInSpacings * s);
  }
  if (!(parameters.NormalRadius > 0.0))
  {
    // As in the paper's rule: a noise-free cloud measures sigma 0 (or round-off), and the floor
    // keeps the normal radius positive and computable.
    const double inSigmas = smooth ? rule.SmoothNormalRadiusInSigmas
                            : thin ? rule.ThinNormalRadiusInSigmas
                                   : rule.NormalRadiusInSigmas;
    parameters.NormalRadius = std::max(inSigmas * sigma, 1e-3 * parameters.Radius);
  }
  return parameters;
}

std::string DescribeEdgeAwareRule(const EdgeAwareRule& rule)
{
  std::ostringstream text;
  text << "edge-aware mode: r = " << rule.RadiusInSpacings << " spacings + " << rule.RadiusInSigmas
       << " sigma, rn = " << rule.NormalRadiusInSigmas << " sigma, N = " << rule.NumberOfIterations
       << "; with noise thinner than " << rule.ThinNoiseInSpacings
       << " spacings r = " << rule.ThinRadiusInSpacings << " spacings + " << rule.RadiusInSigmas
       << " sigma, rn = " << rule.ThinNormalRadiusInSigmas << " sigma, N = " << rule.ThinIterations
       << "; r at most " << rule.MaximumRadiusInSpacings
       << " spacings; on a smooth cloud (crease fraction at most " << rule.SmoothCreaseFraction
       << ", feature fraction at most " << rule.SmoothFeatureFraction
       << ") r = " << rule.SmoothRadiusInSpacings << " spacings + " << rule.SmoothRadiusInSigmas
       << " sigma, rn = " << rule.SmoothNormalRadiusInSigmas
       << " sigma, N = " << rule.SmoothIterations << ", r at most "
       << rule.SmoothRadiusInCurvatureRadii << " times the surface's radius of curvature";
  return text.str();
}

} // namespace pcbilateral

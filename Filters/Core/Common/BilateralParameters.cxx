#include "BilateralParameters.h"

#include <cmath>
#include <sstream>

namespace pcbilateral
{

namespace
{
std::string Describe(const char* what, double value)
{
  std::ostringstream message;
  message << what << " must be a finite number >= 0 (0 means automatic), got " << value;
  return message.str();
}
} // namespace

std::string CheckParameters(const BilateralParameters& parameters)
{
  if (!(std::isfinite(parameters.Radius) && parameters.Radius >= 0.0))
  {
    return Describe("the radius", parameters.Radius);
  }
  if (!(std::isfinite(parameters.NormalRadius) && parameters.NormalRadius >= 0.0))
  {
    return Describe("the normal radius", parameters.NormalRadius);
  }
  if (parameters.NumberOfIterations < 0)
  {
    return "the number of iterations must be >= 0 (0 means automatic), got " +
           std::to_string(parameters.NumberOfIterations);
  }
  if (parameters.NumberOfIterations > limits::MaximumIterations)
  {
    return "the number of iterations must be at most " + std::to_string(limits::MaximumIterations) +
           ", got " + std::to_string(parameters.NumberOfIterations) +
           " (each iteration moves the points by up to the radius: a few are enough)";
  }
  if (parameters.Automatic != AutomaticParameters::Measured &&
      parameters.Automatic != AutomaticParameters::Paper)
  {
    return "the automatic parameters must be measured (0) or the paper's (1), got " +
           std::to_string(static_cast<int>(parameters.Automatic));
  }
  if (parameters.NumberOfThreads < 0)
  {
    return "the number of threads must be >= 0 (0 means all cores), got " +
           std::to_string(parameters.NumberOfThreads);
  }
  if (parameters.NumberOfThreads > limits::MaximumThreads)
  {
    return "the number of threads must be at most " + std::to_string(limits::MaximumThreads) +
           ", got " + std::to_string(parameters.NumberOfThreads) +
           " (the result is the same for any count; 0 uses all cores)";
  }
  return std::string();
}

} // namespace pcbilateral

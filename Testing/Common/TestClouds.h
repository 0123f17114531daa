// Generated noisy clouds for the tests, from the samples' fixed-seed generator
// (Data/SampleShapes.h), so that every test draws its noise the same way. Plain C++17.
#ifndef pcbilateral_TestClouds_h
#define pcbilateral_TestClouds_h

#include "SampleShapes.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcbilateral_testing
{

/// A noisy square patch of the plane z = 0, unit side, side x side jittered grid points, with
/// Gaussian noise of standard deviation sigma along z.
inline std::vector<double> NoisyPlane(double sigma, std::uint64_t seed, int side = 140)
{
  pcbilateral_samples::Random random(seed);
  std::vector<double> xyz;
  xyz.reserve(3 * static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
  for (int j = 0; j < side; ++j)
  {
    for (int i = 0; i < side; ++i)
    {
      xyz.push_back((i + random.Uniform()) / side);
      xyz.push_back((j + random.Uniform()) / side);
      xyz.push_back(sigma * random.Gaussian());
    }
  }
  return xyz;
}

/// Points spread uniformly over the six faces of the cube [-0.5, 0.5]^3, each coordinate with
/// Gaussian noise of standard deviation sigma.
inline std::vector<double> NoisyCube(std::size_t count, double sigma, std::uint64_t seed)
{
  pcbilateral_samples::Random random(seed);
  std::vector<double> xyz;
  xyz.reserve(3 * count);
  for (std::size_t i = 0; i < count; ++i)
  {
    const int face = static_cast<int>(i % 6);
    double p[3] = { random.Uniform() - 0.5, random.Uniform() - 0.5, random.Uniform() - 0.5 };
    p[face / 2] = face % 2 ? 0.5 : -0.5;
    for (const double c : p)
    {
      xyz.push_back(c + sigma * random.Gaussian());
    }
  }
  return xyz;
}

/// Points on the folded sheet z = 0.3 |u - 0.5| over the unit square whose density falls
/// `densityRatio` times from u = 0 to u = 1 (exponentially in u, as a scan's density falls
/// with the distance from the scanner), each coordinate with Gaussian noise of standard
/// deviation sigma. The mean nearest-neighbour distance at u is NearestNeighbourDistanceAt.
inline std::vector<double> DensityVaryingSheet(std::size_t count,
  double densityRatio,
  double sigma,
  std::uint64_t seed)
{
  pcbilateral_samples::Random random(seed);
  std::vector<double> xyz;
  xyz.reserve(3 * count);
  const double logRatio = std::log(densityRatio);
  for (std::size_t i = 0; i < count; ++i)
  {
    // The inverse of the cumulative distribution of a density proportional to ratio^-u.
    const double u = -std::log(1.0 - random.Uniform() * (1.0 - 1.0 / densityRatio)) / logRatio;
    const double v = random.Uniform();
    xyz.push_back(u + sigma * random.Gaussian());
    xyz.push_back(v + sigma * random.Gaussian());
    xyz.push_back(0.3 * std::abs(u - 0.5) + sigma * random.Gaussian());
  }
  return xyz;
}

/// The mean nearest-neighbour distance at u of DensityVaryingSheet's noise-free points:
/// 1 / (2 sqrt(density)) for points spread at random, the sheet's area element included.
inline double NearestNeighbourDistanceAt(double u, std::size_t count, double densityRatio)
{
  const double logRatio = std::log(densityRatio);
  const double density = static_cast<double>(count) * logRatio * std::pow(densityRatio, -u) /
                         (1.0 - 1.0 / densityRatio) / std::sqrt(1.0 + 0.3 * 0.3);
  return 0.5 / std::sqrt(density);
}

} // namespace pcbilateral_testing

#endif

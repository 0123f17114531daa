// Generated noisy clouds for the tests, from the samples' fixed-seed generator
// (Data/SampleShapes.h), so that every test draws its noise the same way. Plain C++17.
#ifndef pcbilateral_TestClouds_h
#define pcbilateral_TestClouds_h

#include "SampleShapes.h"

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

} // namespace pcbilateral_testing

#endif

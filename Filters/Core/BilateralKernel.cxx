#include "BilateralKernel.h"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace pcbilateral
{

KernelConstants::KernelConstants(double radius, double normalRadius)
{
  const double distanceSigma = radius / 3.0;
  const double normalSigma = normalRadius / 3.0;
  this->RadiusSquared = radius * radius;
  this->DistanceScale = 1.0 / (2.0 * distanceSigma * distanceSigma);
  this->NormalScale = 1.0 / (2.0 * normalSigma * normalSigma);
}

void CandidateNeighbours::Clear()
{
  this->X.clear();
  this->Y.clear();
  this->Z.clear();
}

void CandidateNeighbours::Append(const double* x,
  const double* y,
  const double* z,
  std::size_t count)
{
  this->X.insert(this->X.end(), x, x + count);
  this->Y.insert(this->Y.end(), y, y + count);
  this->Z.insert(this->Z.end(), z, z + count);
}

void SmallestEigenvector(const double covariance[6], double eigenvector[3])
{
  Eigen::Matrix3d matrix;
  matrix << covariance[0], covariance[1], covariance[2], //
    covariance[1], covariance[3], covariance[4],         //
    covariance[2], covariance[4], covariance[5];
  // The iterative solver, not the closed form: it stays accurate when two eigenvalues are
  // close or zero (flat patches, lines, repeated points), where the closed form loses digits.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(matrix, Eigen::ComputeEigenvectors);
  const Eigen::Vector3d smallest = solver.eigenvectors().col(0).normalized();
  eigenvector[0] = smallest[0];
  eigenvector[1] = smallest[1];
  eigenvector[2] = smallest[2];
}

FilteredPoint FilterPoint(const double p[3],
  CandidateNeighbours& candidates,
  const KernelConstants& constants)
{
  FilteredPoint result;
  const std::size_t count = candidates.Size();
  candidates.DistanceSquared.resize(count);
  candidates.NeighbourIndex.resize(count);
  candidates.DistanceWeight.resize(count);
  const double* x = candidates.X.data();
  const double* y = candidates.Y.data();
  const double* z = candidates.Z.data();
  double* distanceSquared = candidates.DistanceSquared.data();
  std::uint32_t* neighbour = candidates.NeighbourIndex.data();
  double* distanceWeight = candidates.DistanceWeight.data();

  // The neighbours, |q - p| < r, in candidate order, selected without a branch: most candidates
  // are not neighbours, and a branch per candidate is mispredicted often. The distances come
  // first, in a loop the compiler vectorises.
  const double px = p[0], py = p[1], pz = p[2];
  for (std::size_t j = 0; j < count; ++j)
  {
    const double dx = x[j] - px;
    const double dy = y[j] - py;
    const double dz = z[j] - pz;
    distanceSquared[j] = dx * dx + dy * dy + dz * dz;
  }
  std::uint32_t neighbours = 0;
  for (std::size_t j = 0; j < count; ++j)
  {
    neighbour[neighbours] = static_cast<std::uint32_t>(j);
    neighbours += (distanceSquared[j] < constants.RadiusSquared) ? 1 : 0;
  }
  result.NeighbourCount = neighbours;

  // Pass 1: distance weights, and the weighted first and second moments of the offsets q - p,
  // for the regression plane.
  double weightSum = 0.0;
  double first[3] = { 0.0, 0.0, 0.0 };
  double second[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  for (std::uint32_t k = 0; k < neighbours; ++k)
  {
    const std::uint32_t j = neighbour[k];
    const double dx = x[j] - p[0];
    const double dy = y[j] - p[1];
    const double dz = z[j] - p[2];
    const double w = std::exp(-distanceSquared[j] * constants.DistanceScale);
    distanceWeight[k] = w;
    weightSum += w;
    first[0] += w * dx;
    first[1] += w * dy;
    first[2] += w * dz;
    second[0] += w * dx * dx;
    second[1] += w * dx * dy;
    second[2] += w * dx * dz;
    second[3] += w * dy * dy;
    second[4] += w * dy * dz;
    second[5] += w * dz * dz;
  }
  if (neighbours < MinimumNeighbourCount || !(weightSum > 0.0))
  {
    return result;
  }

  // Weighted covariance about the weighted mean; the offsets are small, so the one-pass form
  // loses nothing that matters next to the noise it measures.
  const double mean[3] = { first[0] / weightSum, first[1] / weightSum, first[2] / weightSum };
  const double covariance[6] = {
    second[0] / weightSum - mean[0] * mean[0],
    second[1] / weightSum - mean[0] * mean[1],
    second[2] / weightSum - mean[0] * mean[2],
    second[3] / weightSum - mean[1] * mean[1],
    second[4] / weightSum - mean[1] * mean[2],
    second[5] / weightSum - mean[2] * mean[2],
  };
  double n[3];
  SmallestEigenvector(covariance, n);

  // Pass 2: the bilateral average of the heights h = <n, q - p> over the same neighbours.
  double bilateralWeightSum = 0.0;
  double weightedHeightSum = 0.0;
  for (std::uint32_t k = 0; k < neighbours; ++k)
  {
    const std::uint32_t j = neighbour[k];
    const double h = n[0] * (x[j] - p[0]) + n[1] * (y[j] - p[1]) + n[2] * (z[j] - p[2]);
    const double w = distanceWeight[k] * std::exp(-h * h * constants.NormalScale);
    bilateralWeightSum += w;
    weightedHeightSum += w * h;
  }
  if (!(bilateralWeightSum > 0.0))
  {
    return result;
  }

  result.Displacement = weightedHeightSum / bilateralWeightSum;
  result.Normal[0] = n[0];
  result.Normal[1] = n[1];
  result.Normal[2] = n[2];
  result.Filtered = true;
  return result;
}

} // namespace pcbilateral

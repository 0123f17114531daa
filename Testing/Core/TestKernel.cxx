// The kernel's own numerics, against independent references:
// - its exponential against long double expl, within 1 ulp, and 0 below -708;
// - its closed-form smallest eigenvector against Eigen's iterative solver, on covariances of
//   planes, noisy patches, edges, lines, repeated points and exact planes;
// - FilterPoint against a plain transcription of Algorithm 1 (sequential sums, std::exp,
//   Eigen), within 1e-12 of the radius;
// - every instruction-set build of the kernel gives the same bits;
// - the eigensolver of FilterPoints (8 matrices side by side) gives the scalar solver's bits on
//   every kind of matrix, those it hands to the scalar solver included;
// - AppendNearBox keeps exactly the candidates near a box, in order, in every build;
// - FilterPoints (up to 8 points at once) gives each point the bits it gets alone, on clouds
//   that take every path (planes, points on a line, repeated points, too few neighbours).
#include "BilateralKernel.h"
#include "CoreTesting.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace
{
using namespace pcbilateral;

std::vector<KernelInstructionSet> AvailableInstructionSets()
{
  std::vector<KernelInstructionSet> sets;
  for (const auto set :
    { KernelInstructionSet::Generic, KernelInstructionSet::Avx2, KernelInstructionSet::Avx512 })
  {
    if (IsAvailable(set))
    {
      sets.push_back(set);
    }
  }
  return sets;
}

double UlpsApart(double value, long double reference)
{
  const double nearest = static_cast<double>(reference);
  const double ulp = std::nextafter(nearest, HUGE_VAL) - nearest;
  return static_cast<double>(std::abs(static_cast<long double>(value) - reference) / ulp);
}

void TestExp()
{
  std::mt19937_64 random(1);
  std::vector<double> x;
  for (const double special : { 0.0,
         -0.0,
         -1e-300,
         -1e-17,
         -0.5,
         -0.34657359027997264,
         -1.0,
         -4.5,
         -700.0,
         -708.0,
         -708.0000001,
         -745.0,
         -1e300,
         -HUGE_VAL })
  {
    x.push_back(special);
  }
  // Uniform over the weights' usual range, then over the whole range, then near the
  // range-reduction boundaries (k ln2 / 2).
  std::uniform_real_distribution<double> usual(-5.0, 0.0), whole(-708.0, 0.0), tiny(-1e-9, 1e-9);
  for (int i = 0; i < 400000; ++i)
  {
    x.push_back(usual(random));
    x.push_back(whole(random));
    const int k = static_cast<int>(random() % 2000);
    x.push_back(std::min(0.0, -0.34657359027997264 * k + tiny(random)));
  }
  std::vector<std::vector<double>> results;
  for (const auto set : AvailableInstructionSets())
  {
    SetKernelInstructionSet(set);
    std::vector<double> y(x.size());
    KernelExp(x.data(), y.data(), x.size());
    double worst = 0.0, worstAt = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i)
    {
      if (x[i] < -708.0)
      {
        PCB_CHECK(y[i] == 0.0, "%s: exp(%.17g) = %g, not 0", GetName(set), x[i], y[i]);
        continue;
      }
      const double error = UlpsApart(y[i], std::exp(static_cast<long double>(x[i])));
      if (error > worst)
      {
        worst = error;
        worstAt = x[i];
      }
    }
    PCB_CHECK(worst <= 1.0, "%s: exp is %.3f ulp off at %.17g", GetName(set), worst, worstAt);
    std::printf("exp, %s: %zu values, largest error %.3f ulp (at %.17g)\n",
      GetName(set),
      x.size(),
      worst,
      worstAt);
    PCB_CHECK(y[0] == 1.0 && y[1] == 1.0, "%s: exp(0) = %.17g", GetName(set), y[0]);
    results.push_back(y);
  }
  for (std::size_t s = 1; s < results.size(); ++s)
  {
    PCB_CHECK(std::memcmp(results[0].data(), results[s].data(), x.size() * sizeof(double)) == 0,
      "the exponential differs between instruction sets");
  }
}

/// The upper triangle of a symmetric matrix, as the kernel stores covariances.
void UpperTriangle(const Eigen::Matrix3d& c, double upper[6])
{
  const double entries[6] = { c(0, 0), c(0, 1), c(0, 2), c(1, 1), c(1, 2), c(2, 2) };
  std::copy(entries, entries + 6, upper);
}

/// Weighted covariance (upper triangle) of offsets, as the kernel forms it.
void Covariance(const std::vector<Eigen::Vector3d>& offsets, double covariance[6])
{
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& o : offsets)
  {
    mean += o;
  }
  mean /= static_cast<double>(offsets.size());
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  for (const auto& o : offsets)
  {
    c += (o - mean) * (o - mean).transpose();
  }
  c /= static_cast<double>(offsets.size());
  UpperTriangle(c, covariance);
}

/// A uniformly random rotation.
Eigen::Matrix3d RandomFrame(std::mt19937_64& random, std::normal_distribution<double>& gaussian)
{
  return Eigen::Quaterniond(gaussian(random), gaussian(random), gaussian(random), gaussian(random))
    .normalized()
    .toRotationMatrix();
}

bool IsUnitVector(const double n[3])
{
  return std::abs(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1.0) < 1e-14;
}

/// 40 offsets of one of five shapes (trial % 5): a plane of random thickness, an edge, an exact
/// axis-aligned plane, in a random frame and random units.
std::vector<Eigen::Vector3d> RandomShapeOffsets(int trial,
  std::mt19937_64& random,
  std::normal_distribution<double>& gaussian,
  std::uniform_real_distribution<double>& uniform)
{
  const Eigen::Matrix3d frame = RandomFrame(random, gaussian);
  const int shape = trial % 5;
  const double thickness = std::pow(10.0, -1.0 - 5.0 * (uniform(random) + 1.0) / 2.0);
  const double units = std::pow(10.0, 6.0 * uniform(random));
  std::vector<Eigen::Vector3d> offsets;
  for (int i = 0; i < 40; ++i)
  {
    Eigen::Vector3d local(uniform(random), uniform(random), thickness * gaussian(random));
    if (shape == 1) // an edge: two half-planes at an angle
    {
      local.z() += 0.5 * std::abs(local.x());
    }
    if (shape == 2) // an exact plane, axis-aligned
    {
      offsets.emplace_back(units * uniform(random), units * uniform(random), 0.0);
      continue;
    }
    offsets.push_back(units * (frame * local));
  }
  return offsets;
}

/// SmallestEigenvector of `covariance` against Eigen's; the worst angle times the eigenvalue
/// gap and the number of well-determined cases are accumulated.
void CheckEigenvector(const double covariance[6], int shape, double& worstAngle, int& cases)
{
  double n[3];
  SmallestEigenvector(covariance, n);
  Eigen::Matrix3d c;
  c << covariance[0], covariance[1], covariance[2], covariance[1], covariance[3], covariance[4],
    covariance[2], covariance[4], covariance[5];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(c);
  const Eigen::Vector3d expected = solver.eigenvectors().col(0);
  const Eigen::Vector3d found(n[0], n[1], n[2]);
  PCB_CHECK(std::abs(found.norm() - 1.0) < 1e-14, "not a unit vector: %.17g", found.norm());
  // How well the eigenvector is determined: the gap to the next eigenvalue.
  const double gap = (solver.eigenvalues()(1) - solver.eigenvalues()(0)) / solver.eigenvalues()(2);
  // (The cross product, not acos of the dot product, which cannot resolve angles below 1e-8.)
  const double angle = std::asin(std::min(1.0, found.cross(expected).norm()));
  if (gap > 1e-6)
  {
    const double tolerance = 1e-13 / gap;
    PCB_CHECK(
      angle <= tolerance, "shape %d, gap %g: %g rad from Eigen's eigenvector", shape, gap, angle);
    worstAngle = std::max(worstAngle, angle * gap);
    ++cases;
  }
  if (shape == 2)
  {
    PCB_CHECK(n[0] == 0.0 && n[1] == 0.0 && std::abs(n[2]) == 1.0,
      "exact plane: normal (%.17g, %.17g, %.17g), not exactly the z axis",
      n[0],
      n[1],
      n[2]);
  }
}

/// Degenerate covariances: a line (double smallest eigenvalue), repeated points (zero), an
/// isotropic blob (triple): any unit vector orthogonal to the line, or any unit vector.
void CheckDegenerateEigenvectors()
{
  const double line[6] = { 1.0, 2.0, 3.0, 4.0, 6.0, 9.0 }; // (1,2,3)(1,2,3)^T
  const double zero[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  const double isotropic[6] = { 2.0, 0.0, 0.0, 2.0, 0.0, 2.0 };
  double n[3];
  SmallestEigenvector(line, n);
  PCB_CHECK(std::abs(n[0] + 2 * n[1] + 3 * n[2]) < 1e-14 && IsUnitVector(n),
    "line: normal (%g, %g, %g) is not a unit vector orthogonal to it",
    n[0],
    n[1],
    n[2]);
  for (const double* degenerate : { zero, isotropic })
  {
    SmallestEigenvector(degenerate, n);
    PCB_CHECK(IsUnitVector(n), "degenerate: (%g, %g, %g) is not a unit vector", n[0], n[1], n[2]);
  }
}

void TestEigenvector()
{
  std::mt19937_64 random(2);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  double worstAngle = 0.0;
  int cases = 0;
  for (int trial = 0; trial < 20000; ++trial)
  {
    double covariance[6];
    Covariance(RandomShapeOffsets(trial, random, gaussian, uniform), covariance);
    CheckEigenvector(covariance, trial % 5, worstAngle, cases);
  }
  CheckDegenerateEigenvectors();
  std::printf(
    "eigenvector: %d well-determined cases, largest angle x gap %.3g\n", cases, worstAngle);
}

/// Algorithm 1 as the paper writes it, sequential sums, libm's exp and Eigen's solver.
FilteredPoint ReferenceFilterPoint(const double p[3],
  const CandidateNeighbours& candidates,
  double radius,
  double normalRadius)
{
  const double sd = radius / 3.0, sn = normalRadius / 3.0;
  std::vector<Eigen::Vector3d> offsets;
  std::vector<double> weights;
  for (std::size_t j = 0; j < candidates.Size(); ++j)
  {
    const Eigen::Vector3d o(candidates.X[j] - p[0], candidates.Y[j] - p[1], candidates.Z[j] - p[2]);
    if (o.squaredNorm() < radius * radius)
    {
      offsets.push_back(o);
      weights.push_back(std::exp(-o.squaredNorm() / (2 * sd * sd)));
    }
  }
  FilteredPoint result;
  result.NeighbourCount = static_cast<std::uint32_t>(offsets.size());
  if (offsets.size() < MinimumNeighbourCount)
  {
    return result;
  }
  double total = 0.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < offsets.size(); ++k)
  {
    total += weights[k];
    mean += weights[k] * offsets[k];
  }
  mean /= total;
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < offsets.size(); ++k)
  {
    c += weights[k] * (offsets[k] - mean) * (offsets[k] - mean).transpose();
  }
  const Eigen::Vector3d n =
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c / total).eigenvectors().col(0).normalized();
  double sum = 0.0, weighted = 0.0;
  for (std::size_t k = 0; k < offsets.size(); ++k)
  {
    const double h = n.dot(offsets[k]);
    const double w = weights[k] * std::exp(-h * h / (2 * sn * sn));
    sum += w;
    weighted += w * h;
  }
  result.Displacement = weighted / sum;
  std::copy(n.data(), n.data() + 3, result.Normal);
  result.Filtered = true;
  return result;
}

void TestFilterPoint()
{
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  const double radius = 0.1;
  int compared = 0;
  for (int trial = 0; trial < 3000; ++trial)
  {
    // A noisy patch around a point far from the origin (georeferenced coordinates), with a
    // candidate count that is not a multiple of the vector width.
    const double origin[3] = { 6.5e5 + uniform(random), 4.1e6 + uniform(random), 250.0 };
    const double noise = 0.002 + 0.02 * (trial % 7) / 7.0;
    const std::size_t count = 1 + static_cast<std::size_t>(trial % 301);
    CandidateNeighbours candidates;
    for (std::size_t j = 0; j < count; ++j)
    {
      const double u = 1.5 * radius * uniform(random), v = 1.5 * radius * uniform(random);
      const double z = noise * gaussian(random) + (trial % 2 ? 0.3 * std::abs(u) : 0.0);
      const double q[3] = { origin[0] + u, origin[1] + v, origin[2] + z };
      candidates.Append(q, q + 1, q + 2, 1);
    }
    const double p[3] = {
      candidates.X[count / 2], candidates.Y[count / 2], candidates.Z[count / 2]
    };
    const double normalRadius = trial % 3 ? 0.03 : 10.0;
    const KernelConstants constants(radius, normalRadius);
    const FilteredPoint expected = ReferenceFilterPoint(p, candidates, radius, normalRadius);

    std::vector<FilteredPoint> results;
    for (const auto set : AvailableInstructionSets())
    {
      SetKernelInstructionSet(set);
      results.push_back(FilterPoint(p, candidates, constants));
    }
    const FilteredPoint& found = results[0];
    PCB_CHECK(
      found.NeighbourCount == expected.NeighbourCount && found.Filtered == expected.Filtered,
      "trial %d: %u neighbours (filtered %d), expected %u (%d)",
      trial,
      found.NeighbourCount,
      found.Filtered,
      expected.NeighbourCount,
      expected.Filtered);
    if (found.Filtered && expected.Filtered)
    {
      double difference = 0.0;
      for (int axis = 0; axis < 3; ++axis)
      {
        difference = std::max(difference,
          std::abs(found.Displacement * found.Normal[axis] -
                   expected.Displacement * expected.Normal[axis]));
      }
      PCB_CHECK(difference < 1e-12 * radius,
        "trial %d: the move differs from the reference by %g",
        trial,
        difference);
      ++compared;
    }
    for (std::size_t s = 1; s < results.size(); ++s)
    {
      PCB_CHECK(std::memcmp(&results[s].Displacement, &found.Displacement, sizeof(double)) == 0 &&
                  std::memcmp(results[s].Normal, found.Normal, sizeof(found.Normal)) == 0,
        "trial %d: %s and %s give different bits",
        trial,
        GetName(AvailableInstructionSets()[s]),
        GetName(AvailableInstructionSets()[0]));
    }
  }
  PCB_CHECK(compared > 2000, "only %d filtered points compared", compared);
  std::printf("FilterPoint: %d points against the reference, %zu instruction set(s)\n",
    compared,
    AvailableInstructionSets().size());
}
/// One of eight kinds of symmetric matrix (trial % 8), upper triangle: rotated planes of any
/// thickness, lines, zero, isotropic and diagonal ones, non-finite ones and any.
void RandomSymmetricMatrix(int trial,
  std::mt19937_64& random,
  std::normal_distribution<double>& gaussian,
  std::uniform_real_distribution<double>& uniform,
  double m[6])
{
  const double units = std::pow(10.0, 6.0 * uniform(random));
  const double thickness = std::pow(10.0, -1.0 - 8.0 * (uniform(random) + 1.0) / 2.0);
  switch (trial % 8)
  {
    case 0: // a rotated plane of some thickness
    case 1:
    {
      const Eigen::Matrix3d frame = RandomFrame(random, gaussian);
      const Eigen::Vector3d spread(1.0, 0.3 + 0.7 * std::abs(uniform(random)), thickness);
      UpperTriangle(units * frame * spread.asDiagonal() * frame.transpose(), m);
      break;
    }
    case 2: // a line, (a, b, c)(a, b, c)^T plus a little
    {
      const double a = uniform(random), b = uniform(random), c = uniform(random);
      const double entries[6] = { a * a, a * b, a * c, b * b, b * c, c * c };
      for (int k = 0; k < 6; ++k)
      {
        m[k] = units * entries[k] + (k == 0 || k == 3 || k == 5 ? thickness * units : 0.0);
      }
      break;
    }
    case 3: // zero, isotropic, diagonal
    {
      const double entries[4][6] = {
        { 0, 0, 0, 0, 0, 0 }, { 2, 0, 0, 2, 0, 2 }, { 1, 0, 0, 2, 0, 3 }, { 3, 0, 0, 1, 0, 1 }
      };
      for (int k = 0; k < 6; ++k)
      {
        m[k] = units * entries[(trial / 8) % 4][k];
      }
      break;
    }
    case 4: // not finite
    {
      for (int k = 0; k < 6; ++k)
      {
        m[k] = uniform(random);
      }
      m[(trial / 8) % 6] = (trial / 48) % 2 ? NAN : HUGE_VAL;
      break;
    }
    default: // any symmetric matrix
      for (int k = 0; k < 6; ++k)
      {
        m[k] = units * uniform(random);
      }
  }
}

/// KernelSmallestEigenvectors against SmallestEigenvector, bit for bit, in every build.
void TestSmallestEigenvectors()
{
  std::mt19937_64 random(5);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> matrices(6 * 20000);
  const std::size_t count = matrices.size() / 6;
  for (std::size_t i = 0; i < count; ++i)
  {
    RandomSymmetricMatrix(static_cast<int>(i), random, gaussian, uniform, matrices.data() + 6 * i);
  }
  std::vector<double> expected(3 * count);
  for (std::size_t i = 0; i < count; ++i)
  {
    SmallestEigenvector(matrices.data() + 6 * i, expected.data() + 3 * i);
  }
  for (const auto set : AvailableInstructionSets())
  {
    SetKernelInstructionSet(set);
    std::vector<double> found(3 * count);
    KernelSmallestEigenvectors(matrices.data(), found.data(), count);
    std::size_t differing = 0;
    for (std::size_t i = 0; i < count; ++i)
    {
      if (std::memcmp(found.data() + 3 * i, expected.data() + 3 * i, 3 * sizeof(double)) != 0)
      {
        if (differing++ == 0)
        {
          PCB_CHECK(false,
            "%s: matrix %zu (kind %zu): (%.17g, %.17g, %.17g), the scalar solver (%.17g, %.17g, "
            "%.17g)",
            GetName(set),
            i,
            i % 8,
            found[3 * i],
            found[3 * i + 1],
            found[3 * i + 2],
            expected[3 * i],
            expected[3 * i + 1],
            expected[3 * i + 2]);
        }
      }
    }
    PCB_CHECK(differing == 0, "%s: %zu of %zu matrices differ", GetName(set), differing, count);
  }
  std::printf("eigensolver side by side: %zu matrices, bit for bit with the scalar one\n", count);
}

/// CandidateNeighbours::AppendNearBox against a plain loop, in every build: the same candidates
/// in the same order, at georeferenced coordinates, points on the box's faces and at the reach.
void TestAppendNearBox()
{
  std::mt19937_64 random(6);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const double low[3] = { 6.5e5, 4.1e6, 250.0 }, high[3] = { 6.5e5 + 2.0, 4.1e6 + 2.0, 252.0 };
  const double reach = 3.0;
  int kept = 0, dropped = 0;
  for (int trial = 0; trial < 300; ++trial)
  {
    const std::size_t count = static_cast<std::size_t>(trial % 131);
    std::vector<double> x(count), y(count), z(count);
    for (std::size_t j = 0; j < count; ++j)
    {
      double* q[3] = { &x[j], &y[j], &z[j] };
      for (int axis = 0; axis < 3; ++axis)
      {
        *q[axis] = 0.5 * (low[axis] + high[axis]) + 5.0 * uniform(random);
      }
      if (j % 5 == 0) // on a face, or exactly at the reach beyond it
      {
        x[j] = j % 10 ? high[0] : high[0] + reach;
        y[j] = low[1];
        z[j] = low[2];
      }
    }
    std::vector<std::size_t> expected;
    for (std::size_t j = 0; j < count; ++j)
    {
      const double q[3] = { x[j], y[j], z[j] };
      double d2 = 0.0;
      for (int axis = 0; axis < 3; ++axis)
      {
        const double gap = std::max(std::max(low[axis] - q[axis], q[axis] - high[axis]), 0.0);
        d2 += gap * gap;
      }
      if (d2 < reach * reach)
      {
        expected.push_back(j);
      }
    }
    kept += static_cast<int>(expected.size());
    dropped += static_cast<int>(count - expected.size());
    for (const auto set : AvailableInstructionSets())
    {
      SetKernelInstructionSet(set);
      // In two parts, as runs of leaves are gathered.
      CandidateNeighbours candidates;
      const std::size_t part = count / 3;
      candidates.AppendNearBox(x.data(), y.data(), z.data(), part, low, high, reach * reach);
      candidates.AppendNearBox(
        x.data() + part, y.data() + part, z.data() + part, count - part, low, high, reach * reach);
      bool same = candidates.Size() == expected.size();
      for (std::size_t k = 0; same && k < expected.size(); ++k)
      {
        same = candidates.X[k] == x[expected[k]] && candidates.Y[k] == y[expected[k]] &&
               candidates.Z[k] == z[expected[k]];
      }
      PCB_CHECK(same,
        "%s, trial %d: kept %zu candidates, expected %zu in order",
        GetName(set),
        trial,
        candidates.Size(),
        expected.size());
    }
  }
  PCB_CHECK(kept > 1000 && dropped > 1000, "kept %d, dropped %d: not a test", kept, dropped);
  std::printf("AppendNearBox: %d kept and %d dropped as a plain loop does\n", kept, dropped);
}

/// `count` candidates around a point at georeferenced coordinates, in a patch of half-side
/// `radius` of one of five shapes: a noisy plane (0 and 5), an exact axis-aligned plane (1),
/// points on a line (2), one point repeated (3), an edge (4).
CandidateNeighbours RandomPatch(int shape,
  std::size_t count,
  double radius,
  std::mt19937_64& random,
  std::normal_distribution<double>& gaussian,
  std::uniform_real_distribution<double>& uniform)
{
  const double origin[3] = { 6.5e5 + uniform(random), 4.1e6 + uniform(random), 250.0 };
  CandidateNeighbours candidates;
  for (std::size_t j = 0; j < count; ++j)
  {
    const double u = radius * uniform(random), v = radius * uniform(random);
    double q[3] = { origin[0] + u, origin[1] + v, origin[2] + 0.01 * gaussian(random) };
    if (shape == 1) // an exact, axis-aligned plane
    {
      q[2] = origin[2];
    }
    if (shape == 2) // points on a line: the two smallest eigenvalues meet
    {
      q[0] = origin[0] + u;
      q[1] = origin[1] + 2.0 * u;
      q[2] = origin[2] + 3.0 * u;
    }
    if (shape == 3) // one point repeated: no spread at all
    {
      q[0] = origin[0];
      q[1] = origin[1];
      q[2] = origin[2];
    }
    if (shape == 4) // an edge
    {
      q[2] += 0.5 * std::abs(u);
    }
    candidates.Append(q, q + 1, q + 2, 1);
  }
  return candidates;
}

/// FilterPoints on the batch against FilterPoint on each of its points, in every build.
void CheckBatchAgainstAlone(const double points[][3],
  std::size_t batch,
  CandidateNeighbours& candidates,
  const KernelConstants& constants,
  int trial)
{
  for (const auto set : AvailableInstructionSets())
  {
    SetKernelInstructionSet(set);
    FilteredPoint together[KernelLanes];
    FilterPoints(points, batch, candidates, constants, together);
    for (std::size_t k = 0; k < batch; ++k)
    {
      const FilteredPoint alone = FilterPoint(points[k], candidates, constants);
      PCB_CHECK(
        alone.NeighbourCount == together[k].NeighbourCount &&
          alone.Filtered == together[k].Filtered &&
          std::memcmp(&alone.Displacement, &together[k].Displacement, sizeof(double)) == 0 &&
          std::memcmp(alone.Normal, together[k].Normal, sizeof(alone.Normal)) == 0,
        "%s, trial %d (shape %d), point %zu of %zu: FilterPoints differs from FilterPoint "
        "(normal %.17g %.17g %.17g against %.17g %.17g %.17g)",
        GetName(set),
        trial,
        trial % 6,
        k,
        batch,
        together[k].Normal[0],
        together[k].Normal[1],
        together[k].Normal[2],
        alone.Normal[0],
        alone.Normal[1],
        alone.Normal[2]);
    }
  }
}

/// FilterPoints on batches of 1 to 8 points against each point alone, bit for bit, on clouds
/// that take every path of the eigensolver.
void TestFilterPoints()
{
  std::mt19937_64 random(4);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  const double radius = 0.1;
  const KernelConstants constants(radius, 0.03);
  int batches = 0;
  for (int trial = 0; trial < 600; ++trial)
  {
    const int shape = trial % 6;
    const std::size_t count = 1 + static_cast<std::size_t>(trial % 97);
    CandidateNeighbours candidates = RandomPatch(shape, count, radius, random, gaussian, uniform);
    const std::size_t batch = 1 + static_cast<std::size_t>(trial % KernelLanes);
    double points[KernelLanes][3];
    for (std::size_t k = 0; k < batch; ++k)
    {
      // Candidates, and points away from all of them (too few neighbours) in the last shape.
      const std::size_t j = (k * 7919) % count;
      const double away = shape == 5 && k % 2 ? 10.0 * radius : 0.0;
      points[k][0] = candidates.X[j] + away;
      points[k][1] = candidates.Y[j];
      points[k][2] = candidates.Z[j];
    }
    CheckBatchAgainstAlone(points, batch, candidates, constants, trial);
    ++batches;
  }
  std::printf("FilterPoints: %d batches of 1 to %zu points, bit for bit with FilterPoint\n",
    batches,
    KernelLanes);
}
} // namespace

int main()
{
  const KernelInstructionSet best = GetKernelInstructionSet();
  std::printf("best instruction set here: %s\n", GetName(best));
  TestExp();
  TestEigenvector();
  TestFilterPoint();
  TestSmallestEigenvectors();
  TestAppendNearBox();
  TestFilterPoints();
  SetKernelInstructionSet(best);
  return PCB_TEST_RESULT();
}

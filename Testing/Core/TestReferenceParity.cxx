// Parity with the authors' original program: the outputs in the reference folder (see its
// README.md) must be reproduced to 1e-9, point by point, matched by the index column.
// The folder comes from the first argument or the PCB_REFERENCE_DIR environment variable;
// without it the test reports itself skipped.
#include "BilateralFilter.h"
#include "CoreTesting.h"
#include "PointCloudText.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
struct ReferenceCase
{
  const char* Input;
  const char* Output;
  bool OrientedNormals;
  double Radius;       // 0: automatic
  double NormalRadius; // 0: same as the radius
  int Iterations;
};

constexpr double Tolerance = 1e-9;

void CheckCase(const std::string& folder, const ReferenceCase& c)
{
  using namespace pcbilateral;
  PointCloudTable input, expected;
  std::string error = ReadPointCloudText(folder + "/" + c.Input, c.OrientedNormals, input);
  PCB_CHECK(error.empty(), "%s", error.c_str());
  error = ReadPointCloudText(folder + "/" + c.Output, c.OrientedNormals, expected);
  PCB_CHECK(error.empty(), "%s", error.c_str());
  if (input.NumberOfPoints == 0 || expected.NumberOfPoints == 0)
  {
    return;
  }

  BilateralParameters parameters;
  parameters.Radius = c.Radius;
  parameters.NormalRadius = c.NormalRadius;
  parameters.NumberOfIterations = c.Iterations;
  parameters.RemoveIsolatedPoints = true;
  PointCloudView cloud;
  cloud.NumberOfPoints = input.NumberOfPoints;
  cloud.Positions = input.Positions.data();
  cloud.OrientationNormals = c.OrientedNormals ? input.Normals.data() : nullptr;
  const BilateralResult result = RunBilateralFilter(cloud, parameters);
  PCB_CHECK(result.Status == BilateralStatus::Completed, "%s: %s", c.Input, result.Error.c_str());

  // The index is the last column of both files; input point i has index i.
  const std::vector<double>& expectedIndex = expected.ExtraColumns.back();
  std::vector<char> seen(input.NumberOfPoints, 0);
  double largestDifference = 0.0;
  std::size_t mismatches = 0;
  for (std::size_t row = 0; row < expected.NumberOfPoints; ++row)
  {
    const auto id = static_cast<std::size_t>(expectedIndex[row]);
    PCB_CHECK(id < input.NumberOfPoints && !seen[id], "%s: bad index %zu", c.Output, id);
    if (id >= input.NumberOfPoints || seen[id])
    {
      return;
    }
    seen[id] = 1;
    PCB_CHECK(
      !result.Removed[id], "%s: point %zu was removed but the reference keeps it", c.Input, id);
    for (int axis = 0; axis < 3; ++axis)
    {
      const double difference =
        std::abs(result.Positions[3 * id + axis] - expected.Positions[3 * row + axis]);
      largestDifference = std::max(largestDifference, difference);
      mismatches += difference > Tolerance ? 1 : 0;
    }
  }
  std::size_t extraKept = 0;
  for (std::size_t id = 0; id < input.NumberOfPoints; ++id)
  {
    extraKept += (!seen[id] && !result.Removed[id]) ? 1 : 0;
  }
  std::printf("%-28s r=%-10g rn=%-10g N=%d: %zu points compared, %zu removed, largest "
              "difference %.3g\n",
    c.Input,
    result.RadiusUsed,
    result.NormalRadiusUsed,
    c.Iterations,
    expected.NumberOfPoints,
    result.NumberOfRemovedPoints,
    largestDifference);
  PCB_CHECK(mismatches == 0,
    "%s: %zu coordinates differ by more than %g (largest %g)",
    c.Output,
    mismatches,
    Tolerance,
    largestDifference);
  PCB_CHECK(extraKept == 0, "%s: %zu points kept that the reference removed", c.Output, extraKept);
}
} // namespace

int main(int argc, char* argv[])
{
  const char* environment = std::getenv("PCB_REFERENCE_DIR");
  const std::string folder = argc > 1 ? argv[1] : (environment ? environment : "");
  if (folder.empty())
  {
    std::printf("SKIPPED: no reference folder (set PCB_REFERENCE_DIR)\n");
    return PCB_SKIP_RETURN_CODE;
  }
  const ReferenceCase cases[] = {
    { "sphere_oriented_idx.txt",
      "sphere_oriented_idx.out_R_r0.04_n0.04_N1.txt",
      true,
      0.04,
      0.04,
      1 },
    { "sphere_unoriented_idx.txt",
      "sphere_unoriented_idx.out_r0.05_n0.01_N3.txt",
      false,
      0.05,
      0.01,
      3 },
    { "sphere_unoriented_idx.txt", "sphere_unoriented_idx.out_auto.txt", false, 0.0, 0.0, 1 },
    { "cube50k_idx.txt", "cube50k_idx.out_r0.04_n1_N1.txt", false, 0.04, 1.0, 1 },
    { "wedge_idx.txt", "wedge_idx.out_r0.04_n0.04_N4.txt", false, 0.04, 0.04, 4 },
  };
  for (const auto& c : cases)
  {
    CheckCase(folder, c);
  }
  return PCB_TEST_RESULT();
}

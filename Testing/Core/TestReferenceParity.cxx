// Parity with the authors' original program: the outputs in the reference folder (see its
// README.md) must be reproduced to 1e-9, point by point, matched by the index column.
// The folder comes from the first argument or the PCB_REFERENCE_DIR environment variable;
// without it the test reports itself skipped. With a second argument, the path of the
// pcbilateral program, the outputs are computed by that program from the reference files
// instead of by the core directly, which also covers its reading and writing.
#include "BilateralFilter.h"
#include "CoreTesting.h"
#include "PointCloudText.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
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

/// Filtered positions by input index; removed points are absent.
using PositionsById = std::map<std::size_t, std::array<double, 3>>;

std::string Arguments(const ReferenceCase& c)
{
  std::string arguments = c.OrientedNormals ? " -R" : "";
  if (c.Radius > 0)
  {
    arguments += " -r " + std::to_string(c.Radius);
  }
  if (c.NormalRadius > 0)
  {
    arguments += " -n " + std::to_string(c.NormalRadius);
  }
  // The authors' program chooses what is not given by the paper's heuristic.
  return arguments + " -N " + std::to_string(c.Iterations) + " --paper --remove-isolated";
}

/// Runs the core on the input table.
PositionsById RunCore(const ReferenceCase& c, const pcbilateral::PointCloudTable& input)
{
  using namespace pcbilateral;
  BilateralParameters parameters;
  parameters.Radius = c.Radius;
  parameters.NormalRadius = c.NormalRadius;
  parameters.NumberOfIterations = c.Iterations;
  parameters.RemoveIsolatedPoints = true;
  parameters.Automatic = AutomaticParameters::Paper;
  PointCloudView cloud;
  cloud.NumberOfPoints = input.NumberOfPoints;
  cloud.Positions = input.Positions.data();
  cloud.OrientationNormals = c.OrientedNormals ? input.Normals.data() : nullptr;
  const BilateralResult result = RunBilateralFilter(cloud, parameters);
  PCB_CHECK(result.Status == BilateralStatus::Completed, "%s: %s", c.Input, result.Error.c_str());
  PositionsById positions;
  for (std::size_t id = 0; id < input.NumberOfPoints && !result.Positions.empty(); ++id)
  {
    if (!result.Removed[id])
    {
      const double* p = &result.Positions[3 * id];
      positions[id] = { p[0], p[1], p[2] };
    }
  }
  return positions;
}

/// Positions by the index column (the last one) of a point file.
PositionsById ByIndexColumn(const pcbilateral::PointCloudTable& table, const std::string& name)
{
  PositionsById positions;
  if (table.ExtraColumns.empty())
  {
    PCB_CHECK(false, "%s has no index column", name.c_str());
    return positions;
  }
  const std::vector<double>& index = table.ExtraColumns.back();
  for (std::size_t row = 0; row < table.NumberOfPoints; ++row)
  {
    const double* p = &table.Positions[3 * row];
    const bool fresh =
      positions
        .emplace(static_cast<std::size_t>(index[row]), std::array<double, 3>{ p[0], p[1], p[2] })
        .second;
    PCB_CHECK(fresh, "%s: index %g twice", name.c_str(), index[row]);
  }
  return positions;
}

/// Runs the command-line program on the input file and reads what it wrote.
PositionsById RunProgram(const ReferenceCase& c,
  const std::string& folder,
  const std::string& program)
{
  const std::string output = std::string("parity_") + c.Output;
  const std::string command = "\"" + program + "\" \"" + folder + "/" + c.Input + "\" " + output +
                              Arguments(c) + " > /dev/null";
  const int status = std::system(command.c_str());
  PCB_CHECK(status == 0, "'%s' failed (%d)", command.c_str(), status);
  pcbilateral::PointCloudTable table;
  const std::string error = pcbilateral::ReadPointCloudText(output, c.OrientedNormals, table);
  PCB_CHECK(error.empty(), "%s", error.c_str());
  std::remove(output.c_str());
  return ByIndexColumn(table, output);
}

void CheckCase(const std::string& folder, const std::string& program, const ReferenceCase& c)
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
  const PositionsById reference = ByIndexColumn(expected, c.Output);
  const PositionsById ours = program.empty() ? RunCore(c, input) : RunProgram(c, folder, program);

  double largestDifference = 0.0;
  std::size_t mismatches = 0, missing = 0;
  for (const auto& entry : reference)
  {
    const auto found = ours.find(entry.first);
    if (found == ours.end())
    {
      ++missing;
      continue;
    }
    for (int axis = 0; axis < 3; ++axis)
    {
      const double difference = std::abs(found->second[axis] - entry.second[axis]);
      largestDifference = std::max(largestDifference, difference);
      mismatches += difference > Tolerance ? 1 : 0;
    }
  }
  std::printf("%-26s%-26s: %zu points compared, %zu removed, largest difference %.3g\n",
    c.Input,
    Arguments(c).c_str(),
    reference.size(),
    input.NumberOfPoints - ours.size(),
    largestDifference);
  PCB_CHECK(mismatches == 0,
    "%s: %zu coordinates differ by more than %g (largest %g)",
    c.Output,
    mismatches,
    Tolerance,
    largestDifference);
  PCB_CHECK(missing == 0, "%s: %zu points of the reference were removed", c.Output, missing);
  PCB_CHECK(ours.size() == reference.size(),
    "%s: %zu points kept, the reference keeps %zu",
    c.Output,
    ours.size(),
    reference.size());
}
} // namespace

int main(int argc, char* argv[])
{
  const char* environment = std::getenv("PCB_REFERENCE_DIR");
  const std::string folder = argc > 1 ? argv[1] : (environment ? environment : "");
  const std::string program = argc > 2 ? argv[2] : "";
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
    CheckCase(folder, program, c);
  }
  return PCB_TEST_RESULT();
}

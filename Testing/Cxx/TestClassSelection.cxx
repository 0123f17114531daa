// vtkPointCloudBilateralFilter with classes (issue 26, item 9): only the points of the chosen
// classes are filtered, the others keep their exact coordinates and are nobody's neighbours.
// Run as: TestClassSelection CASE, CASE one of the names in main().
#include "CoreTesting.h"
#include "TestClouds.h"
#include "VTKTesting.h"
#include "vtkPointCloudBilateralFilter.h"

#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace
{
using namespace pcbilateral_testing;

/// Ground and canopy: a noisy plane (class 2) with, over every third point, a point 0.02 above
/// it (class 5, "vegetation"), interleaved in one cloud; and the ground alone.
struct GroundAndCanopy
{
  vtkSmartPointer<vtkPolyData> Both;
  vtkSmartPointer<vtkPolyData> GroundAlone;
  std::vector<unsigned char> Classes;
};

GroundAndCanopy MakeGroundAndCanopy()
{
  const std::vector<double> ground = NoisyPlane(0.004, 17, 60);
  std::vector<double> both;
  GroundAndCanopy cloud;
  for (std::size_t i = 0; i < ground.size() / 3; ++i)
  {
    both.insert(both.end(), &ground[3 * i], &ground[3 * i] + 3);
    cloud.Classes.push_back(2);
    if (i % 3 == 0)
    {
      both.insert(both.end(), { ground[3 * i] + 0.001, ground[3 * i + 1], 0.02 });
      cloud.Classes.push_back(5);
    }
  }
  cloud.Both = MakeCloud(both);
  vtkNew<vtkUnsignedCharArray> classes;
  classes->SetName("Classification");
  for (unsigned char value : cloud.Classes)
  {
    classes->InsertNextValue(value);
  }
  cloud.Both->GetPointData()->AddArray(classes);
  cloud.GroundAlone = MakeCloud(ground);
  return cloud;
}

std::vector<double> Positions(vtkPolyData* cloud)
{
  std::vector<double> xyz(3 * static_cast<std::size_t>(cloud->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
  {
    cloud->GetPoint(i, &xyz[3 * static_cast<std::size_t>(i)]);
  }
  return xyz;
}

/// The positions of the points of one class.
std::vector<double> OfClass(const std::vector<double>& xyz,
  const std::vector<unsigned char>& classes,
  unsigned char value)
{
  std::vector<double> chosen;
  for (std::size_t i = 0; i < classes.size(); ++i)
  {
    if (classes[i] == value)
    {
      chosen.insert(chosen.end(), &xyz[3 * i], &xyz[3 * i] + 3);
    }
  }
  return chosen;
}

void TestChosenClasses()
{
  const GroundAndCanopy cloud = MakeGroundAndCanopy();
  const std::vector<double> input = Positions(cloud.Both);
  for (const bool edgeAware : { false, true })
  {
    auto setup = [&](vtkPointCloudBilateralFilter* filter)
    {
      filter->SetEdgeAware(edgeAware);
      filter->SetNumberOfIterations(2);
      filter->AddClass(2);
    };
    const FilterRun chosen = RunFilter(cloud.Both, setup);
    const FilterRun alone = RunFilter(cloud.GroundAlone,
      [&](vtkPointCloudBilateralFilter* filter)
      {
        filter->SetEdgeAware(edgeAware);
        filter->SetNumberOfIterations(2);
      });
    const FilterRun all = RunFilter(cloud.Both,
      [&](vtkPointCloudBilateralFilter* filter)
      {
        filter->SetEdgeAware(edgeAware);
        filter->SetNumberOfIterations(2);
      });
    const std::vector<double> output = Positions(chosen.Output);
    const char* mode = edgeAware ? "edge-aware" : "paper";
    PCB_CHECK(chosen.Errors == 0 && output.size() == input.size(),
      "%s: %d errors, %zu of %zu coordinates",
      mode,
      chosen.Errors,
      output.size(),
      input.size());
    PCB_CHECK(SameBits(OfClass(output, cloud.Classes, 5), OfClass(input, cloud.Classes, 5)),
      "%s: the canopy points moved",
      mode);
    PCB_CHECK(SameBits(OfClass(output, cloud.Classes, 2), Positions(alone.Output)),
      "%s: the ground points differ from the ground filtered alone",
      mode);
    PCB_CHECK(
      chosen.RadiusUsed == alone.RadiusUsed && chosen.NormalRadiusUsed == alone.NormalRadiusUsed,
      "%s: the automatic parameters were not measured on the chosen points (r %g vs %g)",
      mode,
      chosen.RadiusUsed,
      alone.RadiusUsed);
    // Without classes, the canopy is among the ground's neighbours and pulls it.
    PCB_CHECK(!SameBits(OfClass(Positions(all.Output), cloud.Classes, 2), Positions(alone.Output)),
      "%s: the canopy made no difference to the ground: the test cannot tell",
      mode);
    PCB_CHECK(chosen.Output->GetPointData()->GetArray("Classification") != nullptr,
      "%s: the class array did not pass through",
      mode);
  }
}

void TestClassInputs()
{
  const GroundAndCanopy cloud = MakeGroundAndCanopy();
  // No point of the class: a warning, every point unchanged, no error.
  const FilterRun none = RunFilter(cloud.Both,
    [](vtkPointCloudBilateralFilter* filter)
    {
      filter->AddClass(9);
      filter->GenerateEstimatedNormalsOn();
    });
  PCB_CHECK(none.Errors == 0 && none.Warnings == 1 &&
              SameBits(Positions(none.Output), Positions(cloud.Both)) &&
              none.Output->GetPointData()->GetArray("EstimatedNormals"),
    "no point of class 9: %d errors, %d warnings (%s)",
    none.Errors,
    none.Warnings,
    none.Messages.c_str());
  // A missing array and a non-integer one: one error, empty output.
  vtkNew<vtkDoubleArray> heights;
  heights->SetName("Height");
  heights->SetNumberOfValues(cloud.Both->GetNumberOfPoints());
  heights->Fill(1.0);
  cloud.Both->GetPointData()->AddArray(heights);
  for (const char* name : { "Nope", "Height" })
  {
    const FilterRun refused = RunFilter(cloud.Both,
      [&](vtkPointCloudBilateralFilter* filter)
      {
        filter->SetClassArrayName(name);
        filter->AddClass(2);
      });
    PCB_CHECK(refused.Errors == 1 && refused.Output->GetNumberOfPoints() == 0 &&
                refused.Messages.find(name) != std::string::npos,
      "class array '%s': %d errors, %lld points out (%s)",
      name,
      refused.Errors,
      static_cast<long long>(refused.Output->GetNumberOfPoints()),
      refused.Messages.c_str());
  }
  // RemoveAllClasses: every point filtered again, the class array not needed.
  const FilterRun every = RunFilter(cloud.Both,
    [](vtkPointCloudBilateralFilter* filter)
    {
      filter->SetClassArrayName("Nope");
      filter->AddClass(2);
      filter->RemoveAllClasses();
    });
  PCB_CHECK(
    every.Errors == 0 && every.Output->GetNumberOfPoints() == cloud.Both->GetNumberOfPoints(),
    "after RemoveAllClasses: %d errors",
    every.Errors);
}
} // namespace

int main(int argc, char* argv[])
{
  const std::map<std::string, std::function<void()>> cases = {
    { "chosen", TestChosenClasses },
    { "inputs", TestClassInputs },
  };
  return RunNamedCase(argc, argv, cases);
}

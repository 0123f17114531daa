// Degenerate and hostile inputs through vtkPointCloudBilateralFilter: each gives a sane result
// (finite, no point moved by r or more per iteration, arrays intact) or a clear message.
// Run as: TestRobustness CASE.
#include "CoreTesting.h"
#include "TestClouds.h"
#include "VTKTesting.h"
#include "vtkPointCloudBilateralFilter.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace
{

using namespace pcbilateral_testing;

/// A cloud whose points carry their ids in the point array "Tag", to check that arrays follow.
vtkSmartPointer<vtkPolyData> Cloud(const std::vector<double>& xyz, int type = VTK_DOUBLE)
{
  auto cloud = MakeCloud(xyz, type);
  vtkNew<vtkDoubleArray> tag;
  tag->SetName("Tag");
  for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
  {
    tag->InsertNextValue(static_cast<double>(i));
  }
  cloud->GetPointData()->AddArray(tag);
  return cloud;
}

using Run = FilterRun;

/// Filters `input`; counts the progress events into `progressEvents` if given.
Run Filter(vtkPolyData* input,
  double radius,
  int iterations = 1,
  double normalRadius = 0.0,
  int* progressEvents = nullptr)
{
  Run run = RunFilter(input,
    [&](vtkPointCloudBilateralFilter* filter)
    {
      filter->SetRadius(radius);
      filter->SetNormalRadius(normalRadius);
      filter->SetNumberOfIterations(iterations);
    });
  if (progressEvents)
  {
    *progressEvents = run.ProgressEvents;
  }
  return run;
}

/// Every finite input point is finite in the output and moved less than `reach`.
void CheckSane(const char* what, vtkPolyData* input, const Run& run, double reach)
{
  PCB_CHECK(run.Output->GetNumberOfPoints() == input->GetNumberOfPoints(),
    "%s: %lld of %lld points",
    what,
    (long long)run.Output->GetNumberOfPoints(),
    (long long)input->GetNumberOfPoints());
  if (run.Output->GetNumberOfPoints() != input->GetNumberOfPoints())
  {
    return;
  }
  double largest = 0.0;
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    double a[3], b[3];
    input->GetPoint(i, a);
    run.Output->GetPoint(i, b);
    if (!(std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2])))
    {
      PCB_CHECK(std::memcmp(a, b, sizeof(a)) == 0 || (std::isnan(a[0]) && std::isnan(b[0])),
        "%s: a non-finite point %lld changed",
        what,
        (long long)i);
      continue;
    }
    PCB_CHECK(std::isfinite(b[0]) && std::isfinite(b[1]) && std::isfinite(b[2]),
      "%s: point %lld is no longer finite",
      what,
      (long long)i);
    largest = std::max(largest,
      std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2])));
  }
  PCB_CHECK(largest < reach || largest == 0.0,
    "%s: a point moved by %g (at most %g)",
    what,
    largest,
    reach);
  vtkDataArray* tag = run.Output->GetPointData()->GetArray("Tag");
  PCB_CHECK(
    tag && tag->GetNumberOfTuples() == input->GetNumberOfPoints(), "%s: Tag array lost", what);
  std::printf("%s: %lld points, largest move %.3g, %d warning(s)\n",
    what,
    (long long)input->GetNumberOfPoints(),
    largest,
    run.Warnings);
}

std::vector<double> NoisyPatch(std::size_t count, double offset, unsigned seed)
{
  pcbilateral_samples::Random random(seed);
  std::vector<double> xyz;
  for (std::size_t i = 0; i < count; ++i)
  {
    xyz.push_back(offset + random.Uniform());
    xyz.push_back(offset + random.Uniform());
    xyz.push_back(offset + 0.003 * random.Gaussian());
  }
  return xyz;
}

void TestSmallClouds()
{
  // No points, one point, four points: nothing can be filtered; no error, points unchanged.
  for (std::size_t count : { 0, 1, 4 })
  {
    const std::vector<double> xyz = NoisyPatch(count, 0.0, 3);
    auto input = Cloud(xyz);
    for (double radius : { 0.0, 0.5 })
    {
      const Run run = Filter(input, radius);
      PCB_CHECK(
        run.Errors == 0, "%zu points, radius %g: error '%s'", count, radius, run.Messages.c_str());
      CheckSane(("small cloud of " + std::to_string(count)).c_str(), input, run, 1e-300);
    }
  }
  // Last Run says so, rather than radii of 0 chosen by the paper's rule.
  vtkNew<vtkPointCloudBilateralFilter> filter;
  filter->SetInputData(Cloud({}));
  filter->Update();
  PCB_CHECK(
    std::string(filter->GetLastRunSummary()) == "nothing to filter: the input has no points",
    "an empty cloud's last run: %s",
    filter->GetLastRunSummary());
}

void TestCoincidentAndDegenerate()
{
  // All points identical: automatic radius impossible (a warning, unchanged); given radius: sane.
  auto same = Cloud(std::vector<double>(3 * 500, 0.25));
  Run run = Filter(same, 0.0);
  PCB_CHECK(run.Errors == 0 && run.Warnings == 1,
    "identical points, automatic radius: %d errors, %d "
    "warnings",
    run.Errors,
    run.Warnings);
  CheckSane("identical points, automatic radius", same, run, 1e-300);
  CheckSane("identical points, radius 0.1", same, Filter(same, 0.1, 3), 1e-300);

  // Many duplicates of one point inside a noisy patch.
  std::vector<double> duplicates = NoisyPatch(2000, 0.0, 4);
  for (int i = 0; i < 2000; ++i)
  {
    duplicates.insert(duplicates.end(), { 0.5, 0.5, 0.0 });
  }
  auto withDuplicates = Cloud(duplicates);
  CheckSane("2000 duplicates in a patch", withDuplicates, Filter(withDuplicates, 0.05, 2), 0.1);

  // All points on a line; a very flat bounding box (a 2D scan with no z at all).
  std::vector<double> line;
  for (int i = 0; i < 3000; ++i)
  {
    const double t = i / 3000.0;
    line.insert(line.end(), { t, 2 * t, -t });
  }
  auto lineCloud = Cloud(line);
  CheckSane("points on a line", lineCloud, Filter(lineCloud, 0.02, 2), 0.04);
  std::vector<double> flat = NoisyPatch(5000, 0.0, 5);
  for (std::size_t i = 2; i < flat.size(); i += 3)
  {
    flat[i] = 0.0;
  }
  auto flatCloud = Cloud(flat);
  const Run flatRun = Filter(flatCloud, 0.0, 2);
  CheckSane("a flat 2D scan, automatic radius", flatCloud, flatRun, 2 * flatRun.RadiusUsed);
}

void TestNonFinitePoints()
{
  std::vector<double> xyz = NoisyPatch(4000, 0.0, 6);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 40; ++i)
  {
    xyz[30 * i + 3 * (i % 3)] = (i % 2) ? nan : (i % 4 ? inf : -inf);
  }
  auto input = Cloud(xyz);
  const Run run = Filter(input, 0.05, 2);
  PCB_CHECK(run.Errors == 0 && run.Warnings == 1,
    "NaN/Inf points: %d errors, %d warnings (one "
    "expected): %s",
    run.Errors,
    run.Warnings,
    run.Messages.c_str());
  PCB_CHECK(run.Messages.find("40 point(s)") != std::string::npos,
    "the warning does not count 40 "
    "points: %s",
    run.Messages.c_str());
  CheckSane("40 NaN/Inf points in a patch", input, run, 0.1);
  // The automatic radius ignores them too.
  const Run automatic = Filter(input, 0.0);
  PCB_CHECK(std::isfinite(automatic.RadiusUsed) && automatic.RadiusUsed > 0,
    "automatic radius %g",
    automatic.RadiusUsed);
}

void TestRadiusLargerThanCloud()
{
  // Every point a neighbour of every other: the run finishes, keeps reporting progress, and
  // warns once about the neighbour count, naming the parameter to lower.
  auto input = Cloud(NoisyPatch(12000, 0.0, 7));
  int progressEvents = 0;
  const Run run = Filter(input, 50.0, 1, 0.01, &progressEvents);
  std::printf("radius 50: %d warning(s): %s; %d progress events\n",
    run.Warnings,
    run.Messages.c_str(),
    progressEvents);
  CheckSane("radius 50 on a unit patch", input, run, 50.0);
  PCB_CHECK(
    run.Errors == 0 && run.Warnings == 1, "%d errors, %d warnings", run.Errors, run.Warnings);
  PCB_CHECK(run.Messages.find("neighbours per point") != std::string::npos &&
              run.Messages.find("lower the radius") != std::string::npos,
    "the warning does not say what to lower: %s",
    run.Messages.c_str());
  PCB_CHECK(progressEvents >= 20, "only %d progress events", progressEvents);

  // A radius of the right size does not warn.
  const Run usual = Filter(input, 0.05, 1, 0.01);
  PCB_CHECK(usual.Warnings == 0, "a usual radius warned: %s", usual.Messages.c_str());
}

void TestOtherPointSets()
{
  // Any vtkPointSet is a cloud: an unstructured grid gives exactly the points and arrays a
  // polydata with the same points gives, and one warning that its cells are not carried.
  // Data sets without explicit points (image data) are refused by the pipeline, with a message.
  auto cloud = Cloud(NoisyPatch(3000, 0.0, 11));
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(cloud->GetPoints());
  grid->GetPointData()->ShallowCopy(cloud->GetPointData());
  grid->Allocate(1);
  const vtkIdType tetra[4] = { 0, 1, 2, 3 };
  grid->InsertNextCell(VTK_TETRA, 4, tetra);

  auto setup = [](vtkPointCloudBilateralFilter* filter)
  {
    filter->SetRadius(0.05);
    filter->SetNormalRadius(0.02);
  };
  const Run fromPolyData = RunFilter(cloud, setup);
  const Run fromGrid = RunFilter(grid, setup);
  vtkPolyData* a = fromPolyData.Output;
  vtkPolyData* b = fromGrid.Output;
  PCB_CHECK(b->GetNumberOfPoints() == a->GetNumberOfPoints() && b->GetNumberOfVerts() == 3000,
    "unstructured grid: %lld points, %lld vertices",
    (long long)b->GetNumberOfPoints(),
    (long long)b->GetNumberOfVerts());
  PCB_CHECK(b->GetPointData()->GetArray("Tag") != nullptr, "unstructured grid: the array is lost");
  bool same = b->GetNumberOfPoints() == a->GetNumberOfPoints();
  for (vtkIdType i = 0; same && i < a->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    a->GetPoint(i, p);
    b->GetPoint(i, q);
    same = std::memcmp(p, q, sizeof(p)) == 0;
  }
  PCB_CHECK(same, "unstructured grid: the points differ from the polydata's");
  PCB_CHECK(fromPolyData.Warnings == 0 && fromGrid.Warnings == 1 &&
              fromGrid.Messages.find("cells") != std::string::npos,
    "warnings: %d for the polydata, %d for the grid: %s",
    fromPolyData.Warnings,
    fromGrid.Warnings,
    fromGrid.Messages.c_str());

  vtkNew<vtkImageData> image;
  image->SetDimensions(4, 4, 4);
  const Run fromImage = RunFilter(image, {});
  PCB_CHECK(fromImage.Errors >= 1 && fromImage.Messages.find("vtkPointSet") != std::string::npos &&
              fromImage.Output->GetNumberOfPoints() == 0,
    "image data: %d errors, %lld points: %s",
    fromImage.Errors,
    (long long)fromImage.Output->GetNumberOfPoints(),
    fromImage.Messages.c_str());
}

void TestBadParameters()
{
  // Each refused with one error and an empty output; 0 iterations give the input back.
  auto input = Cloud(NoisyPatch(2000, 0.0, 10));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Bad
  {
    const char* Name;
    double Radius, NormalRadius;
    int Iterations;
    const char* Says;
  };
  for (const Bad& bad : { Bad{ "negative radius", -0.1, 0.0, 1, "radius" },
         Bad{ "NaN radius", nan, 0.0, 1, "radius" },
         Bad{ "infinite radius", inf, 0.0, 1, "radius" },
         Bad{ "negative normal radius", 0.05, -1.0, 1, "normal radius" },
         Bad{ "NaN normal radius", 0.05, nan, 1, "normal radius" },
         Bad{ "infinite normal radius", 0.05, inf, 1, "normal radius" },
         Bad{ "negative iterations", 0.05, 0.0, -1, "iterations" },
         Bad{ "a huge number of iterations", 0.05, 0.0, 1000000, "at most 1000" },
         // The octree numbers its lattice in 32 bits: at most 1e8 radii across.
         Bad{ "a radius 1e-9 of the cloud", 1e-9, 0.0, 1, "give a larger radius" } })
  {
    const Run run = Filter(input, bad.Radius, bad.Iterations, bad.NormalRadius);
    // Exactly one: the filter's own message, without the executive's "returned failure" dump.
    PCB_CHECK(run.Errors == 1 && run.Output->GetNumberOfPoints() == 0,
      "%s: %d errors, %lld output points",
      bad.Name,
      run.Errors,
      (long long)run.Output->GetNumberOfPoints());
    PCB_CHECK(run.Messages.find(bad.Says) != std::string::npos,
      "%s: the message does not say '%s': %s",
      bad.Name,
      bad.Says,
      run.Messages.c_str());
  }
  // Just inside that limit (5e7 radii), the lattice's coordinates still fit: the run completes,
  // no point moving by more than r.
  const Run tiny = Filter(input, 2e-8, 2, 2e-8);
  PCB_CHECK(tiny.Errors == 0 && tiny.Output->GetNumberOfPoints() == input->GetNumberOfPoints(),
    "radius 2e-8: %d errors, %lld points: %s",
    tiny.Errors,
    (long long)tiny.Output->GetNumberOfPoints(),
    tiny.Messages.c_str());
  CheckSane("radius 2e-8", input, tiny, 2e-8);

  // 0 iterations means automatic, as 0 radii do: the filter runs.
  const Run automatic = Filter(input, 0.05, 0);
  PCB_CHECK(
    automatic.Errors == 0 && automatic.Output->GetNumberOfPoints() == input->GetNumberOfPoints(),
    "0 iterations: %d errors, %lld points",
    automatic.Errors,
    (long long)automatic.Output->GetNumberOfPoints());
  vtkIdType moved = 0;
  for (vtkIdType i = 0; i < automatic.Output->GetNumberOfPoints(); ++i)
  {
    double a[3], b[3];
    input->GetPoint(i, a);
    automatic.Output->GetPoint(i, b);
    moved += std::memcmp(a, b, sizeof(a)) != 0;
  }
  PCB_CHECK(moved > 0, "0 (automatic) iterations moved no point");
}

void TestGeoreferencedOffset()
{
  // The same cloud at the origin and 1e6 away: the same result, shifted back, to the precision
  // of the point type.
  const std::vector<double> local = NoisyPatch(6000, 0.0, 8);
  std::vector<double> shifted = local;
  for (double& value : shifted)
  {
    value += 1e6;
  }
  for (int type : { VTK_DOUBLE, VTK_FLOAT })
  {
    const double tolerance = type == VTK_DOUBLE ? 1e-9 : 0.07; // a float ulp at 1e6 is 0.0625
    auto atOrigin = Cloud(local, VTK_DOUBLE);
    auto far = Cloud(shifted, type);
    const Run a = Filter(atOrigin, 0.05, 2, 0.02);
    const Run b = Filter(far, 0.05, 2, 0.02);
    double largest = 0.0, moved = 0.0;
    for (vtkIdType i = 0; i < atOrigin->GetNumberOfPoints(); ++i)
    {
      double p[3], q[3], before[3];
      a.Output->GetPoint(i, p);
      b.Output->GetPoint(i, q);
      far->GetPoint(i, before);
      for (int axis = 0; axis < 3; ++axis)
      {
        largest = std::max(largest, std::abs((q[axis] - 1e6) - p[axis]));
        moved = std::max(moved, std::abs(q[axis] - before[axis]));
      }
    }
    std::printf("offset 1e6 (%s): largest difference from the cloud at the origin %.3g, moves "
                "up to %.3g\n",
      type == VTK_DOUBLE ? "double" : "float",
      largest,
      moved);
    PCB_CHECK(largest < tolerance, "offset 1e6: difference %g", largest);
    PCB_CHECK(type == VTK_FLOAT || moved > 1e-3, "offset 1e6: the points did not move (%g)", moved);
  }
}
void TestAbortFromAnotherThread()
{
  // A long run (every point a neighbour of every other: the radius is larger than the cloud),
  // aborted from another thread: the filter returns within 0.5 s, with an empty output.
  auto input = Cloud(NoisyPatch(200000, 0.0, 9));
  vtkNew<vtkPointCloudBilateralFilter> filter;
  filter->SetInputData(input);
  filter->SetRadius(5.0);
  filter->SetNumberOfIterations(3);
  std::atomic<bool> requested{ false };
  std::chrono::steady_clock::time_point requestTime;
  std::thread aborter(
    [&]()
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(1500));
      requestTime = std::chrono::steady_clock::now();
      requested = true;
      filter->AbortExecuteOn();
    });
  const auto start = std::chrono::steady_clock::now();
  filter->Update();
  const auto end = std::chrono::steady_clock::now();
  aborter.join();
  const double total = std::chrono::duration<double>(end - start).count();
  const double afterRequest =
    requested ? std::chrono::duration<double>(end - requestTime).count() : -1.0;
  std::printf("abort: the run took %.2f s, %.3f s after the request; %lld output points\n",
    total,
    afterRequest,
    (long long)filter->GetOutput()->GetNumberOfPoints());
  PCB_CHECK(
    requested, "the run ended (%.2f s) before the abort was requested: make it longer", total);
  PCB_CHECK(
    afterRequest >= 0.0 && afterRequest < 0.5, "returned %.3f s after the request", afterRequest);
  PCB_CHECK(filter->GetOutput()->GetNumberOfPoints() == 0,
    "an aborted run output %lld points",
    (long long)filter->GetOutput()->GetNumberOfPoints());
}
} // namespace

int main(int argc, char* argv[])
{
  const std::map<std::string, std::function<void()>> cases = {
    { "small-clouds", TestSmallClouds },
    { "coincident-and-degenerate", TestCoincidentAndDegenerate },
    { "non-finite-points", TestNonFinitePoints },
    { "radius-larger-than-cloud", TestRadiusLargerThanCloud },
    { "bad-parameters", TestBadParameters },
    { "other-point-sets", TestOtherPointSets },
    { "georeferenced-offset", TestGeoreferencedOffset },
    { "abort-from-another-thread", TestAbortFromAnotherThread },
  };
  return RunNamedCase(argc, argv, cases);
}

// Tests of vtkPointCloudBilateralFilter on synthetic clouds with known surfaces.
// Run as: TestPointCloudBilateralFilter CASE, CASE one of the names in main().
#include "CoreTesting.h"
#include "TestClouds.h"
#include "VTKTesting.h"
#include "vtkPointCloudBilateralFilter.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVariant.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace
{

using namespace pcbilateral_testing;

/// Updates the filter with these parameters (and whatever `setup` sets) and returns its output.
vtkSmartPointer<vtkPolyData> Filter(vtkPolyData* input,
  double radius,
  double normalRadius,
  int iterations,
  int threads = 0,
  const std::function<void(vtkPointCloudBilateralFilter*)>& setup = {})
{
  return RunFilter(input,
    [&](vtkPointCloudBilateralFilter* filter)
    {
      filter->SetRadius(radius);
      filter->SetNormalRadius(normalRadius);
      filter->SetNumberOfIterations(iterations);
      filter->SetNumberOfThreads(threads);
      if (setup)
      {
        setup(filter);
      }
    })
    .Output;
}

double RootMeanSquareZ(vtkPolyData* cloud, double trim)
{
  double sum = 0.0;
  std::size_t count = 0;
  for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
  {
    double p[3];
    cloud->GetPoint(i, p);
    // Away from the patch border, where the filter is known to bend an open surface.
    if (p[0] > trim && p[0] < 1 - trim && p[1] > trim && p[1] < 1 - trim)
    {
      sum += p[2] * p[2];
      ++count;
    }
  }
  return std::sqrt(sum / count);
}

/// Distance from p to the surface of the cube [-0.5, 0.5]^3.
double DistanceToCube(const double p[3])
{
  double outside = 0.0;
  double inside = 1e300;
  for (int axis = 0; axis < 3; ++axis)
  {
    const double excess = std::abs(p[axis]) - 0.5;
    outside += excess > 0 ? excess * excess : 0.0;
    inside = std::min(inside, -excess);
  }
  return outside > 0 ? std::sqrt(outside) : std::max(inside, 0.0);
}

/// Number of coordinates at least 0.5 - margin in absolute value: 2 or 3 near an edge.
int CloseFaces(const double p[3], double margin)
{
  int count = 0;
  for (int axis = 0; axis < 3; ++axis)
  {
    count += std::abs(p[axis]) > 0.5 - margin ? 1 : 0;
  }
  return count;
}

void TestPlane()
{
  const double sigma = 0.005;
  auto noisy = MakeCloud(NoisyPlane(sigma, 1));
  auto filtered = Filter(noisy, 0.05, 0.05, 2);
  const double before = RootMeanSquareZ(noisy, 0.1);
  const double after = RootMeanSquareZ(filtered, 0.1);
  std::printf("noisy plane: rms height %.3g before, %.3g after (factor %.1f)\n",
    before,
    after,
    before / after);
  PCB_CHECK(after < before / 8, "the plane became flatter only by %.2f", before / after);

  // An exact plane does not move at all: every neighbour has height 0 exactly.
  std::vector<double> flat = NoisyPlane(0.0, 2);
  for (std::size_t i = 2; i < flat.size(); i += 3)
  {
    flat[i] = 0.375;
  }
  auto exact = MakeCloud(flat);
  auto unchanged = Filter(exact, 0.05, 0.05, 3);
  auto* in = vtkDoubleArray::SafeDownCast(exact->GetPoints()->GetData());
  auto* out = vtkDoubleArray::SafeDownCast(unchanged->GetPoints()->GetData());
  PCB_CHECK(
    in && out && in->GetNumberOfValues() == out->GetNumberOfValues() &&
      std::memcmp(
        in->GetPointer(0), out->GetPointer(0), sizeof(double) * in->GetNumberOfValues()) == 0,
    "an exact plane moved");
}

void TestCubeEdges()
{
  // The paper's Figure 5: noise 0.1% of the bounding box, r = 0.04; rn = 0.01 keeps the edges,
  // rn = 1 rounds them.
  const double sigma = 0.001 * std::sqrt(3.0);
  const std::vector<double> xyz = NoisyCube(60000, sigma, 5);
  auto noisy = MakeCloud(xyz);
  auto sharp = Filter(noisy, 0.04, 0.01, 1);
  auto round = Filter(noisy, 0.04, 1.0, 1);

  // Points near an edge (two or three faces within 0.01): mean distance to the cube's surface,
  // and how many still reach out to the edge region.
  double noisyError = 0, sharpError = 0, roundError = 0;
  std::size_t edgePoints = 0, sharpOnSurface = 0, roundOnSurface = 0;
  for (vtkIdType i = 0; i < noisy->GetNumberOfPoints(); ++i)
  {
    double p[3], s[3], r[3];
    noisy->GetPoint(i, p);
    if (CloseFaces(p, 0.01) < 2)
    {
      continue;
    }
    sharp->GetPoint(i, s);
    round->GetPoint(i, r);
    ++edgePoints;
    noisyError += DistanceToCube(p);
    sharpError += DistanceToCube(s);
    roundError += DistanceToCube(r);
    sharpOnSurface += DistanceToCube(s) < 2 * sigma ? 1 : 0;
    roundOnSurface += DistanceToCube(r) < 2 * sigma ? 1 : 0;
  }
  noisyError /= edgePoints;
  sharpError /= edgePoints;
  roundError /= edgePoints;
  std::printf("cube edges (%zu points): mean distance to the cube %.3g noisy, %.3g with rn = "
              "0.01, %.3g with rn = 1; within 2 sigma of the cube: %zu and %zu\n",
    edgePoints,
    noisyError,
    sharpError,
    roundError,
    sharpOnSurface,
    roundOnSurface);
  PCB_CHECK(sharpError < noisyError,
    "a small rn did not denoise the edges (%g vs %g)",
    sharpError,
    noisyError);
  PCB_CHECK(roundError > 2.5 * sharpError,
    "a large rn did not round the edges (%g vs %g)",
    roundError,
    sharpError);
  PCB_CHECK(sharpOnSurface > 1.5 * roundOnSurface,
    "edge points within 2 sigma of the cube: %zu with a small rn, %zu with a large one",
    sharpOnSurface,
    roundOnSurface);
}

/// Point arrays of four types, two of them the active scalars and vectors, that the filter
/// must pass through unchanged.
struct PassThroughArrays
{
  vtkNew<vtkDoubleArray> Scalars;
  vtkNew<vtkUnsignedCharArray> Colours;
  vtkNew<vtkFloatArray> Vectors;
  vtkNew<vtkIntArray> Labels;

  /// Values for each of the cloud's points, added to its point data.
  void AddTo(vtkPolyData* cloud)
  {
    this->Scalars->SetName("Intensity");
    this->Colours->SetName("RGB");
    this->Colours->SetNumberOfComponents(3);
    this->Vectors->SetName("Velocity");
    this->Vectors->SetNumberOfComponents(3);
    this->Labels->SetName("Label");
    for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
    {
      this->Scalars->InsertNextValue(0.5 * i);
      const unsigned char rgb[3] = { static_cast<unsigned char>(i % 256),
        static_cast<unsigned char>((7 * i) % 256),
        static_cast<unsigned char>((13 * i) % 256) };
      this->Colours->InsertNextTypedTuple(rgb);
      const float v[3] = { float(i), float(-i), float(2 * i) };
      this->Vectors->InsertNextTypedTuple(v);
      this->Labels->InsertNextValue(static_cast<int>(i % 17));
    }
    cloud->GetPointData()->SetScalars(this->Scalars);
    cloud->GetPointData()->AddArray(this->Colours);
    cloud->GetPointData()->SetVectors(this->Vectors);
    cloud->GetPointData()->AddArray(this->Labels);
  }

  /// A few far-away points, which have no neighbours, with values of their own.
  void AddFarPoints(vtkPolyData* cloud)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double far[3] = { 10.0 + k, 10.0, 10.0 };
      cloud->GetPoints()->InsertNextPoint(far);
      this->Scalars->InsertNextValue(-1);
      const unsigned char black[3] = { 0, 0, 0 };
      this->Colours->InsertNextTypedTuple(black);
      const float zero[3] = { 0, 0, 0 };
      this->Vectors->InsertNextTypedTuple(zero);
      this->Labels->InsertNextValue(-1);
    }
  }

  /// Whether the output's point data are these arrays, in order and with their roles, point
  /// i holding the values of input point source(i); and one vertex per point.
  void CheckPassedTo(vtkPolyData* output,
    const std::function<vtkIdType(vtkIdType)>& source,
    const char* what) const
  {
    vtkPointData* pd = output->GetPointData();
    PCB_CHECK(output->GetNumberOfVerts() == output->GetNumberOfPoints(),
      "%s: %lld vertices for %lld points",
      what,
      (long long)output->GetNumberOfVerts(),
      (long long)output->GetNumberOfPoints());
    const char* names[] = { "Intensity", "RGB", "Velocity", "Label" };
    for (int a = 0; a < 4; ++a)
    {
      PCB_CHECK(pd->GetArray(a) && pd->GetArray(a)->GetName() == std::string(names[a]),
        "%s: array %d is not %s",
        what,
        a,
        names[a]);
    }
    PCB_CHECK(pd->GetScalars() && std::string(pd->GetScalars()->GetName()) == "Intensity",
      "%s: scalars not active",
      what);
    PCB_CHECK(pd->GetVectors() && std::string(pd->GetVectors()->GetName()) == "Velocity",
      "%s: vectors not active",
      what);
    this->CheckValuesPassedTo(output, source, what);
  }

  void CheckValuesPassedTo(vtkPolyData* output,
    const std::function<vtkIdType(vtkIdType)>& source,
    const char* what) const
  {
    vtkPointData* pd = output->GetPointData();
    auto* outColours = vtkUnsignedCharArray::SafeDownCast(pd->GetArray("RGB"));
    auto* outVectors = vtkFloatArray::SafeDownCast(pd->GetArray("Velocity"));
    auto* outScalars = vtkDoubleArray::SafeDownCast(pd->GetArray("Intensity"));
    auto* outLabels = vtkIntArray::SafeDownCast(pd->GetArray("Label"));
    PCB_CHECK(outColours && outVectors && outScalars && outLabels, "%s: array types changed", what);
    if (!(outColours && outVectors && outScalars && outLabels))
    {
      return;
    }
    std::size_t wrong = 0;
    for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
    {
      const vtkIdType j = source(i);
      wrong += outScalars->GetValue(i) != this->Scalars->GetValue(j);
      wrong += outLabels->GetValue(i) != this->Labels->GetValue(j);
      for (int c = 0; c < 3; ++c)
      {
        wrong += outColours->GetTypedComponent(i, c) != this->Colours->GetTypedComponent(j, c);
        wrong += outVectors->GetTypedComponent(i, c) != this->Vectors->GetTypedComponent(j, c);
      }
    }
    PCB_CHECK(wrong == 0, "%s: %zu values differ from the input's", what, wrong);
  }
};

/// With removal: the far-away points go, in order; the rest keep their values.
void CheckRemovalKeepsValues(vtkPolyData* cloud, PassThroughArrays& arrays)
{
  const vtkIdType n = cloud->GetNumberOfPoints();
  arrays.AddFarPoints(cloud);
  auto removed = Filter(
    cloud, 0.08, 0.08, 1, 0, [](vtkPointCloudBilateralFilter* f) { f->RemoveIsolatedPointsOn(); });
  auto* ids =
    vtkIdTypeArray::SafeDownCast(removed->GetPointData()->GetArray("vtkOriginalPointIds"));
  PCB_CHECK(ids != nullptr, "no vtkOriginalPointIds array");
  if (!ids)
  {
    return;
  }
  PCB_CHECK(removed->GetNumberOfPoints() > n * 0.99 && removed->GetNumberOfPoints() <= n,
    "removal kept %lld of %lld points",
    (long long)removed->GetNumberOfPoints(),
    (long long)n);
  for (vtkIdType i = 0; i < ids->GetNumberOfValues(); ++i)
  {
    PCB_CHECK(ids->GetValue(i) < n && (i == 0 || ids->GetValue(i) > ids->GetValue(i - 1)),
      "original id %lld at %lld: out of order or a far point",
      (long long)ids->GetValue(i),
      (long long)i);
  }
  arrays.CheckPassedTo(
    removed, [ids](vtkIdType i) { return ids->GetValue(i); }, "removal");
}

void TestPassThrough()
{
  const std::vector<double> xyz = NoisyCube(3000, 0.002, 7);
  auto cloud = MakeCloud(xyz);
  const vtkIdType n = cloud->GetNumberOfPoints();
  PassThroughArrays arrays;
  arrays.AddTo(cloud);
  vtkNew<vtkIntArray> scanId;
  scanId->SetName("ScanId");
  scanId->InsertNextValue(42);
  cloud->GetFieldData()->AddArray(scanId);

  auto output = Filter(cloud, 0.08, 0.08, 1);
  vtkDataArray* scanIdOut = output->GetFieldData()->GetArray("ScanId");
  PCB_CHECK(scanIdOut && scanIdOut->GetComponent(0, 0) == 42, "the input's field data was lost");
  PCB_CHECK(output->GetNumberOfPoints() == n,
    "%lld points out of %lld",
    (long long)output->GetNumberOfPoints(),
    (long long)n);
  arrays.CheckPassedTo(
    output, [](vtkIdType i) { return i; }, "kept");
  CheckRemovalKeepsValues(cloud, arrays);
}

/// The output's point coordinates as raw bytes, to compare bit for bit.
std::vector<unsigned char> PointBytes(vtkPolyData* cloud)
{
  vtkDataArray* data = cloud->GetPoints()->GetData();
  const auto* begin = static_cast<const unsigned char*>(data->GetVoidPointer(0));
  return std::vector<unsigned char>(
    begin, begin + data->GetNumberOfValues() * data->GetDataTypeSize());
}

void TestThreadsGiveIdenticalBits()
{
  auto cloud = MakeCloud(NoisyCube(40000, 0.005, 11));
  const auto reference = PointBytes(Filter(cloud, 0.05, 0.03, 3, 1));
  for (int threads : { 2, 4 })
  {
    for (int run = 0; run < 2; ++run)
    {
      PCB_CHECK(PointBytes(Filter(cloud, 0.05, 0.03, 3, threads)) == reference,
        "%d threads (run %d) differ from 1 thread",
        threads,
        run);
    }
  }
  std::printf("1, 2 and 4 threads: identical output bits\n");
}

void TestPointTypes()
{
  const std::vector<double> xyz = NoisyCube(20000, 0.005, 13);
  auto asDouble = Filter(MakeCloud(xyz, VTK_DOUBLE), 0.06, 0.06, 1);
  auto asFloat = Filter(MakeCloud(xyz, VTK_FLOAT), 0.06, 0.06, 1);
  PCB_CHECK(asDouble->GetPoints()->GetDataType() == VTK_DOUBLE,
    "double points became %s",
    asDouble->GetPoints()->GetData()->GetDataTypeAsString());
  PCB_CHECK(asFloat->GetPoints()->GetDataType() == VTK_FLOAT,
    "float points became %s",
    asFloat->GetPoints()->GetData()->GetDataTypeAsString());
  double largest = 0.0, moved = 0.0;
  for (vtkIdType i = 0; i < asDouble->GetNumberOfPoints(); ++i)
  {
    double a[3], b[3];
    asDouble->GetPoint(i, a);
    asFloat->GetPoint(i, b);
    for (int axis = 0; axis < 3; ++axis)
    {
      largest = std::max(largest, std::abs(a[axis] - b[axis]));
      moved = std::max(moved, std::abs(a[axis] - xyz[3 * i + axis]));
    }
  }
  std::printf(
    "float vs double points: largest difference %.3g (points moved up to %.3g)\n", largest, moved);
  PCB_CHECK(largest < 1e-5, "float and double inputs differ by %g", largest);
  PCB_CHECK(moved > 1e-3, "the points did not move (%g)", moved);
}

/// Each point's outward normal, for the points of NoisyCube (point i on face i % 6).
vtkSmartPointer<vtkDoubleArray> OutwardCubeNormals(vtkIdType count)
{
  auto outward = vtkSmartPointer<vtkDoubleArray>::New();
  outward->SetName("Normals");
  outward->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < count; ++i)
  {
    const int face = static_cast<int>(i % 6);
    double n[3] = { 0, 0, 0 };
    n[face / 2] = face % 2 ? 1.0 : -1.0;
    outward->InsertNextTypedTuple(n);
  }
  return outward;
}

/// The automatic mode (the default) on NoisyCube(30000, 0.003): 5000 points per unit face are
/// 0.5 / sqrt(5000) apart on average; r = 5 spacings + 4 sigma, rn = 5 sigma, N = 2 (a cube
/// is not flat), recorded in the output's field data.
void CheckAutomaticParameters(vtkPointCloudBilateralFilter* filter)
{
  const double spacing = 0.5 / std::sqrt(5000.0);
  std::printf("measured spacing %.6g (true %.6g), sigma %.6g (true 0.003): r %.6g, rn %.6g, "
              "N %d\n",
    filter->GetPointSpacing(),
    spacing,
    filter->GetNoiseSigma(),
    filter->GetRadiusUsed(),
    filter->GetNormalRadiusUsed(),
    filter->GetNumberOfIterationsUsed());
  PCB_CHECK(std::abs(filter->GetPointSpacing() / spacing - 1.0) < 0.1 &&
              std::abs(filter->GetNoiseSigma() / 0.003 - 1.0) < 0.25,
    "measured spacing %g, sigma %g",
    filter->GetPointSpacing(),
    filter->GetNoiseSigma());
  // A cube has edges: the rule's r = 8 spacings + 3 sigma, rn = 3.3 sigma
  // (pcbilateral::AutomaticRule's Edge* constants).
  const double measuredRadius = 8.0 * filter->GetPointSpacing() + 3.0 * filter->GetNoiseSigma();
  PCB_CHECK(
    std::abs(filter->GetRadiusUsed() / measuredRadius - 1.0) < 1e-12 &&
      std::abs(filter->GetNormalRadiusUsed() / (3.3 * filter->GetNoiseSigma()) - 1.0) < 1e-12 &&
      filter->GetNumberOfIterationsUsed() == 2,
    "automatic r %g, rn %g, N %d",
    filter->GetRadiusUsed(),
    filter->GetNormalRadiusUsed(),
    filter->GetNumberOfIterationsUsed());
  vtkFieldData* fd = filter->GetOutput()->GetFieldData();
  const std::pair<const char*, double> records[] = { { "BilateralRadius", filter->GetRadiusUsed() },
    { "BilateralNormalRadius", filter->GetNormalRadiusUsed() },
    { "BilateralNumberOfIterations", 2.0 },
    { "BilateralPointSpacing", filter->GetPointSpacing() },
    { "BilateralNoiseSigma", filter->GetNoiseSigma() } };
  for (const auto& [name, value] : records)
  {
    vtkDataArray* record = fd->GetArray(name);
    PCB_CHECK(record && record->GetComponent(0, 0) == value,
      "the output's field data does not record %s = %g",
      name,
      value);
  }
}

/// The paper's heuristic, by name: r = sqrt(20 / n) x largest extent, rn = r, N = 1, nothing
/// measured (the filter has run on NoisyCube(30000, ...)).
void CheckPaperParameters(vtkPointCloudBilateralFilter* filter)
{
  const double expected =
    std::sqrt(20.0 / 30000.0) * filter->GetOutput()->GetLength() / std::sqrt(3.0);
  std::printf("paper's radius %.6g (largest extent x sqrt(20/n) = %.6g), normal radius %.6g\n",
    filter->GetRadiusUsed(),
    expected,
    filter->GetNormalRadiusUsed());
  PCB_CHECK(std::abs(filter->GetRadiusUsed() - expected) < 0.02 * expected,
    "paper's radius %g",
    filter->GetRadiusUsed());
  PCB_CHECK(filter->GetNormalRadiusUsed() == filter->GetRadiusUsed() &&
              filter->GetNumberOfIterationsUsed() == 1 && filter->GetPointSpacing() == 0.0,
    "paper's normal radius %g, N %d, spacing %g",
    filter->GetNormalRadiusUsed(),
    filter->GetNumberOfIterationsUsed(),
    filter->GetPointSpacing());
  PCB_CHECK(
    std::string(filter->GetLastRunSummary()).find("N 1 (paper's rule)") != std::string::npos,
    "last run: %s",
    filter->GetLastRunSummary());
  vtkFieldData* fd = filter->GetOutput()->GetFieldData();
  PCB_CHECK(fd->GetArray("BilateralRadius") && !fd->GetArray("BilateralPointSpacing"),
    "the paper's run records a measured spacing");
}

/// The estimated normals of the face points agree with the input's outward normals, and the
/// displacement lengths are below the radius.
void CheckEstimatedNormals(vtkPointCloudBilateralFilter* filter,
  vtkPolyData* cloud,
  vtkDataArray* outward)
{
  vtkPointData* pd = filter->GetOutput()->GetPointData();
  vtkDataArray* normals = pd->GetArray("EstimatedNormals");
  vtkDataArray* lengths = pd->GetArray("DisplacementLength");
  PCB_CHECK(normals && normals->GetNumberOfComponents() == 3, "no EstimatedNormals");
  PCB_CHECK(lengths && lengths->GetNumberOfComponents() == 1, "no DisplacementLength");
  PCB_CHECK(pd->GetNormals() && std::string(pd->GetNormals()->GetName()) == "Normals",
    "the input's normals are not the output's point normals");
  if (!normals || !lengths)
  {
    return;
  }
  std::size_t disagreeing = 0, faceInterior = 0, notEstimated = 0;
  double largestLength = 0.0;
  for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
  {
    double p[3], n[3], reference[3];
    cloud->GetPoint(i, p);
    normals->GetTuple(i, n);
    outward->GetTuple(i, reference);
    largestLength = std::max(largestLength, lengths->GetComponent(i, 0));
    if (CloseFaces(p, 0.05) == 1)
    {
      ++faceInterior;
      const double agreement = n[0] * reference[0] + n[1] * reference[1] + n[2] * reference[2];
      notEstimated += agreement == 0.0 ? 1 : 0;
      disagreeing += agreement < 0.0 ? 1 : 0;
    }
  }
  std::printf("face points: %zu, normals against the input's: %zu, not estimated: %zu\n",
    faceInterior,
    disagreeing,
    notEstimated);
  PCB_CHECK(disagreeing == 0,
    "%zu of %zu face normals point against the input's",
    disagreeing,
    faceInterior);
  PCB_CHECK(notEstimated < faceInterior / 100,
    "%zu of %zu face normals not estimated",
    notEstimated,
    faceInterior);
  PCB_CHECK(largestLength > 0.0 && largestLength < filter->GetRadiusUsed(),
    "displacement lengths up to %g, radius %g",
    largestLength,
    filter->GetRadiusUsed());
}

void TestParametersAndNormals()
{
  // The automatic radius, read back; estimated normals oriented by the input's normals.
  auto cloud = MakeCloud(NoisyCube(30000, 0.003, 17));
  const auto outward = OutwardCubeNormals(cloud->GetNumberOfPoints());
  cloud->GetPointData()->SetNormals(outward);
  vtkNew<vtkPointCloudBilateralFilter> filter;
  filter->SetInputData(cloud);
  filter->GenerateEstimatedNormalsOn();
  filter->GenerateDisplacementLengthOn();
  PCB_CHECK(std::string(filter->GetLastRunSummary()) == "not run yet",
    "before a run: %s",
    filter->GetLastRunSummary());
  filter->Update();
  PCB_CHECK(std::string(filter->GetLastRunSummary()).find("N 2 (measured)") != std::string::npos,
    "last run: %s",
    filter->GetLastRunSummary());
  CheckAutomaticParameters(filter);

  // A given parameter overrides only itself.
  const double automaticNormalRadius = filter->GetNormalRadiusUsed();
  filter->SetRadius(0.05);
  filter->Update();
  PCB_CHECK(filter->GetRadiusUsed() == 0.05 &&
              filter->GetNormalRadiusUsed() == automaticNormalRadius &&
              filter->GetNumberOfIterationsUsed() == 2,
    "given radius: r %g, rn %g, N %d",
    filter->GetRadiusUsed(),
    filter->GetNormalRadiusUsed(),
    filter->GetNumberOfIterationsUsed());

  // The mode is said too: the edge-aware rules choose other parameters.
  filter->SetEdgeAware(true);
  filter->Update();
  PCB_CHECK(std::string(filter->GetLastRunSummary()).find("; edge-aware") != std::string::npos,
    "edge-aware run: %s",
    filter->GetLastRunSummary());
  filter->SetEdgeAware(false);

  filter->SetRadius(0.0);
  filter->SetAutomaticParametersToPaper();
  filter->Update();
  CheckPaperParameters(filter);
  const FilterRun unknown =
    RunFilter(cloud, [](vtkPointCloudBilateralFilter* f) { f->SetAutomaticParameters(7); });
  PCB_CHECK(unknown.Output->GetNumberOfPoints() == 0 && unknown.Errors == 1 &&
              unknown.Messages.find("the automatic parameters must be") != std::string::npos,
    "an unknown automatic mode: %d errors, %s",
    unknown.Errors,
    unknown.Messages.c_str());
  CheckEstimatedNormals(filter, cloud, outward);
}

void TestProgressAndAbort()
{
  auto cloud = MakeCloud(NoisyCube(200000, 0.005, 19));
  vtkNew<vtkPointCloudBilateralFilter> filter;
  filter->SetInputData(cloud);
  filter->SetRadius(0.03);
  filter->SetNumberOfIterations(2);
  std::vector<double> reported;
  vtkNew<vtkCallbackCommand> recorder;
  recorder->SetClientData(&reported);
  recorder->SetCallback([](vtkObject*, unsigned long, void* clientData, void* callData)
    { static_cast<std::vector<double>*>(clientData)->push_back(*static_cast<double*>(callData)); });
  filter->AddObserver(vtkCommand::ProgressEvent, recorder);
  filter->Update();
  const bool increasing = std::is_sorted(reported.begin(), reported.end());
  std::printf("progress: %zu reports, from %g to %g\n",
    reported.size(),
    reported.empty() ? -1.0 : reported.front(),
    reported.empty() ? -1.0 : reported.back());
  PCB_CHECK(reported.size() >= 20 && increasing && reported.back() == 1.0,
    "%zu progress reports, increasing: %d",
    reported.size(),
    int(increasing));
  PCB_CHECK(filter->GetOutput()->GetNumberOfPoints() == cloud->GetNumberOfPoints(), "no output");

  // An observer that aborts a third of the way: the filter stops soon and outputs nothing.
  vtkNew<vtkPointCloudBilateralFilter> aborted;
  aborted->SetInputData(cloud);
  aborted->SetRadius(0.03);
  aborted->SetNumberOfIterations(2);
  std::size_t reportsAfterAbort = 0;
  vtkNew<vtkCallbackCommand> stopper;
  stopper->SetClientData(&reportsAfterAbort);
  stopper->SetCallback(
    [](vtkObject* caller, unsigned long, void* clientData, void* callData)
    {
      auto* algorithm = static_cast<vtkAlgorithm*>(caller);
      if (algorithm->GetAbortExecute())
      {
        ++*static_cast<std::size_t*>(clientData);
      }
      if (*static_cast<double*>(callData) > 0.3)
      {
        algorithm->AbortExecuteOn();
      }
    });
  aborted->AddObserver(vtkCommand::ProgressEvent, stopper);
  aborted->Update();
  std::printf("abort: %lld output points, %zu progress reports after the abort request\n",
    (long long)aborted->GetOutput()->GetNumberOfPoints(),
    reportsAfterAbort);
  PCB_CHECK(aborted->GetOutput()->GetNumberOfPoints() == 0,
    "an aborted run output %lld points",
    (long long)aborted->GetOutput()->GetNumberOfPoints());
  PCB_CHECK(
    reportsAfterAbort <= 2, "the run went on for %zu reports after the abort", reportsAfterAbort);

  // The abort does not stick: the next run, with no one aborting it, runs to the end (the flag
  // once stayed set, and every later update aborted at once).
  aborted->RemoveObserver(stopper);
  aborted->SetRadius(0.031);
  aborted->Update();
  PCB_CHECK(aborted->GetOutput()->GetNumberOfPoints() == cloud->GetNumberOfPoints(),
    "the run after an aborted one output %lld of %lld points",
    (long long)aborted->GetOutput()->GetNumberOfPoints(),
    (long long)cloud->GetNumberOfPoints());
}

/// An abort asked once the core's last iteration is done (its progress of 1), while the result
/// is handed over and the output built, still ends the run: no output, "aborted".
void TestAbortAtTheEnd()
{
  auto cloud = MakeCloud(NoisyPlane(0.002, 5));
  vtkNew<vtkPointCloudBilateralFilter> filter;
  filter->SetInputData(cloud);
  filter->SetRadius(0.03);
  filter->SetNumberOfIterations(2);
  vtkNew<vtkCallbackCommand> stopper;
  stopper->SetCallback(
    [](vtkObject* caller, unsigned long, void*, void* callData)
    {
      // (The core's run reports up to 0.99; the hand-over and the output the rest.)
      if (*static_cast<double*>(callData) >= 0.99)
      {
        static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn();
      }
    });
  filter->AddObserver(vtkCommand::ProgressEvent, stopper);
  filter->Update();
  PCB_CHECK(filter->GetOutput()->GetNumberOfPoints() == 0 &&
              std::string(filter->GetLastRunSummary()) == "aborted",
    "aborted at the end: %lld output points, summary '%s'",
    (long long)filter->GetOutput()->GetNumberOfPoints(),
    filter->GetLastRunSummary());
}

/// Once the core's iterations are done, the filter still reports progress (below 1) while the
/// result is handed over and the output built: ParaView sees an Abort click only while a run
/// reports, and those steps took 0.6 s on 20M points without a report. An abort asked at such a
/// report, the second one after the last iteration's end, ends the run.
void TestAbortWhileBuildingTheOutput()
{
  auto cloud = MakeCloud(NoisyPlane(0.002, 5));
  vtkNew<vtkPointCloudBilateralFilter> filter;
  filter->SetInputData(cloud);
  filter->SetRadius(0.03);
  filter->SetNumberOfIterations(2);
  int reportsAfterTheIterations = 0;
  vtkNew<vtkCallbackCommand> stopper;
  stopper->SetClientData(&reportsAfterTheIterations);
  stopper->SetCallback(
    [](vtkObject* caller, unsigned long, void* clientData, void* callData)
    {
      auto* bilateral = static_cast<vtkPointCloudBilateralFilter*>(caller);
      int& reports = *static_cast<int*>(clientData);
      if (std::string(bilateral->GetProgressPhase()) == "iteration 2 of 2" &&
          bilateral->GetPhaseProgress() >= 1.0 && *static_cast<double*>(callData) < 1.0 &&
          ++reports == 2)
      {
        bilateral->AbortExecuteOn();
      }
    });
  filter->AddObserver(vtkCommand::ProgressEvent, stopper);
  filter->Update();
  PCB_CHECK(reportsAfterTheIterations >= 2 && filter->GetOutput()->GetNumberOfPoints() == 0 &&
              std::string(filter->GetLastRunSummary()) == "aborted",
    "%d progress reports below 1 after the iterations; aborted at the second: %lld output "
    "points, summary '%s'",
    reportsAfterTheIterations,
    (long long)filter->GetOutput()->GetNumberOfPoints(),
    filter->GetLastRunSummary());
}

void TestDegenerateNeighbourhoods()
{
  // Flat, linear and single-point neighbourhoods: the eigen solver must give a usable normal or
  // none, never NaN, and no point may move by r or more.
  pcbilateral_samples::Random noise(23);
  std::vector<double> line, repeated, mixed;
  for (int i = 0; i < 2000; ++i)
  {
    const double t = noise.Uniform();
    const double onLine[3] = { t, 2 * t, -t };
    line.insert(line.end(), onLine, onLine + 3);
    const double same[3] = { 0.25, -1.5, 3.0 };
    repeated.insert(repeated.end(), same, same + 3);
    // Half the points are copies of ten points, the others a noisy patch around them.
    const double patch[3] = { i % 2 ? double(i % 10) * 0.01 : noise.Uniform() * 0.1,
      i % 2 ? 0.0 : noise.Uniform() * 0.1,
      i % 2 ? 0.0 : 0.002 * noise.Gaussian() };
    mixed.insert(mixed.end(), patch, patch + 3);
  }
  struct Case
  {
    const char* Name;
    std::vector<double>* Points;
    double Radius;
  };
  for (const Case& c : { Case{ "line", &line, 0.05 },
         Case{ "one repeated point", &repeated, 0.1 },
         Case{ "duplicates in a patch", &mixed, 0.03 } })
  {
    auto input = MakeCloud(*c.Points);
    auto output = Filter(input, c.Radius, c.Radius, 3);
    double largestMove = 0.0;
    std::size_t nonFinite = 0;
    for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
    {
      double a[3], b[3];
      input->GetPoint(i, a);
      output->GetPoint(i, b);
      nonFinite += std::isfinite(b[0] + b[1] + b[2]) ? 0 : 1;
      largestMove = std::max(largestMove,
        std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                  (a[2] - b[2]) * (a[2] - b[2])));
    }
    std::printf("%s: %lld points, largest move %.3g (3 iterations of r = %g)\n",
      c.Name,
      (long long)output->GetNumberOfPoints(),
      largestMove,
      c.Radius);
    PCB_CHECK(output->GetNumberOfPoints() == input->GetNumberOfPoints(), "%s: points lost", c.Name);
    PCB_CHECK(nonFinite == 0, "%s: %zu non-finite points", c.Name, nonFinite);
    PCB_CHECK(largestMove < 3 * c.Radius, "%s: a point moved by %g", c.Name, largestMove);
  }
}
/// A cloud whose density falls 100 times: the automatic radius follows it, and the filter says
/// so through its getters, the output's field data and the per-point array of radii; a given
/// radius is kept, and then none of it is reported.
void TestFollowsDensity()
{
  vtkSmartPointer<vtkPolyData> sheet = MakeCloud(DensityVaryingSheet(12000, 100.0, 0.002, 3u));
  vtkNew<vtkPointCloudBilateralFilter> filter;
  filter->SetInputData(sheet);
  filter->SetNumberOfIterations(1);
  filter->Update();
  PCB_CHECK(!filter->GetOutput()->GetPointData()->GetArray("BilateralPointRadius"),
    "BilateralPointRadius without GeneratePointRadius");
  filter->GeneratePointRadiusOn();
  filter->Update();
  const double* radii = filter->GetRadiusRange();
  std::printf("spacing varies %.3g times: radius %s, %g to %g (at the surface's spacing %g)\n",
    filter->GetSpacingSpread(),
    filter->GetRadiusFollowsDensity() ? "follows the density" : "fixed",
    radii[0],
    radii[1],
    filter->GetRadiusUsed());
  PCB_CHECK(filter->GetRadiusFollowsDensity() && filter->GetSpacingSpread() > 4.0 &&
              radii[1] > 2.0 * radii[0] && radii[0] <= filter->GetRadiusUsed() &&
              filter->GetRadiusUsed() <= radii[1],
    "the radius does not follow the density: spread %g, radii %g to %g",
    filter->GetSpacingSpread(),
    radii[0],
    radii[1]);
  vtkPolyData* output = filter->GetOutput();
  vtkDataArray* perPoint = output->GetPointData()->GetArray("BilateralPointRadius");
  double range[2] = { 0.0, 0.0 };
  if (perPoint)
  {
    perPoint->GetRange(range);
  }
  PCB_CHECK(perPoint && perPoint->GetNumberOfTuples() == sheet->GetNumberOfPoints() &&
              range[0] == radii[0] && range[1] == radii[1],
    "BilateralPointRadius: missing or not the range %g to %g",
    radii[0],
    radii[1]);
  vtkFieldData* fd = output->GetFieldData();
  vtkDataArray* recorded = fd->GetArray("BilateralRadiusRange");
  PCB_CHECK(recorded && recorded->GetComponent(0, 0) == radii[0] &&
              recorded->GetComponent(0, 1) == radii[1] &&
              fd->GetArray("BilateralNormalRadiusRange") &&
              fd->GetArray("BilateralSpacingSpread") && fd->GetAbstractArray("BilateralMode") &&
              fd->GetAbstractArray("BilateralMode")->GetVariantValue(0).ToString() == "paper",
    "the field data does not record the radius range, the spread and the mode");

  filter->SetRadius(0.05);
  filter->Update();
  PCB_CHECK(!filter->GetRadiusFollowsDensity() &&
              !filter->GetOutput()->GetPointData()->GetArray("BilateralPointRadius") &&
              !filter->GetOutput()->GetFieldData()->GetArray("BilateralRadiusRange"),
    "a given radius is kept, and nothing follows the density");
}

} // namespace

int main(int argc, char* argv[])
{
  const std::map<std::string, std::function<void()>> cases = {
    { "plane", TestPlane },
    { "cube-edges", TestCubeEdges },
    { "pass-through", TestPassThrough },
    { "threads", TestThreadsGiveIdenticalBits },
    { "point-types", TestPointTypes },
    { "parameters-and-normals", TestParametersAndNormals },
    { "progress-and-abort", TestProgressAndAbort },
    { "abort-at-the-end", TestAbortAtTheEnd },
    { "abort-while-building-the-output", TestAbortWhileBuildingTheOutput },
    { "degenerate-neighbourhoods", TestDegenerateNeighbourhoods },
    { "follows-density", TestFollowsDensity },
  };
  return RunNamedCase(argc, argv, cases);
}

// The filter on the bundled samples: the RMS distance to the true surface must drop by at least
// the factor measured when the recommended parameters were chosen (minus a margin).
//   TestSampleData DATA_DIR NAME RADIUS NORMAL_RADIUS ITERATIONS MINIMUM_FACTOR
//   TestSampleData DATA_DIR NAME --sweep     (prints the error for a grid of parameters)
#include "SampleShapes.h"
#include "vtkPointCloudBilateralFilter.h"

#include "vtkAlgorithm.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkXMLPolyDataReader.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
using namespace pcbilateral_samples;

double RootMeanSquareDistance(vtkPolyData* cloud, const Shape& shape)
{
  double sum = 0.0;
  for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
  {
    Vec3 p;
    cloud->GetPoint(i, p.data());
    const double d = shape.Distance(p);
    sum += d * d;
  }
  return std::sqrt(sum / cloud->GetNumberOfPoints());
}

double FilteredError(vtkPolyData* noisy, const Shape& shape, double r, double rn, int iterations)
{
  vtkNew<vtkPointCloudBilateralFilter> filter;
  filter->SetInputData(noisy);
  filter->SetRadius(r);
  filter->SetNormalRadius(rn);
  filter->SetNumberOfIterations(iterations);
  filter->Update();
  if (r == 0.0 || rn == 0.0 || iterations == 0)
  {
    std::printf("automatic: measured spacing %.4g, noise sigma %.4g; r = %.4g, rn = %.4g, N = %d\n",
      filter->GetPointSpacing(),
      filter->GetNoiseSigma(),
      filter->GetRadiusUsed(),
      filter->GetNormalRadiusUsed(),
      filter->GetNumberOfIterationsUsed());
  }
  return RootMeanSquareDistance(filter->GetOutput(), shape);
}

/// The sample named `name`, or null.
const SampleSpec* FindSample(const std::vector<SampleSpec>& samples, const std::string& name)
{
  const SampleSpec* spec = nullptr;
  for (const SampleSpec& candidate : samples)
  {
    spec = candidate.Name == name ? &candidate : spec;
  }
  return spec;
}

/// The sample's file (.vtp with attributes, .ply without), or null when it does not hold the
/// sample's number of points.
vtkSmartPointer<vtkPolyData> ReadSample(const std::string& dataDirectory, const SampleSpec& spec)
{
  const std::string path = dataDirectory + "/" + spec.Name + (spec.Attributes ? ".vtp" : ".ply");
  vtkSmartPointer<vtkAlgorithm> reader;
  if (spec.Attributes)
  {
    auto xml = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    xml->SetFileName(path.c_str());
    reader = xml;
  }
  else
  {
    auto ply = vtkSmartPointer<vtkPLYReader>::New();
    ply->SetFileName(path.c_str());
    reader = ply;
  }
  reader->Update();
  vtkPolyData* noisy = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!noisy || noisy->GetNumberOfPoints() != static_cast<vtkIdType>(spec.Points))
  {
    std::fprintf(stderr, "%s: could not read %zu points\n", path.c_str(), spec.Points);
    return nullptr;
  }
  return noisy;
}

/// Prints the error for a grid of parameters.
void Sweep(vtkPolyData* noisy, const Shape& shape, double sigma, double before)
{
  std::printf("%8s %8s %3s %10s %7s\n", "r", "rn", "N", "rms", "factor");
  for (double r : { 0.03, 0.04, 0.05, 0.06, 0.08 })
  {
    for (double rnInSigmas : { 1.5, 2.0, 3.0, 5.0 })
    {
      for (int iterations : { 1, 2, 4 })
      {
        const double rn = rnInSigmas * sigma;
        const double after = FilteredError(noisy, shape, r, rn, iterations);
        std::printf("%8.4g %8.4g %3d %10.4g %7.2f\n", r, rn, iterations, after, before / after);
      }
    }
  }
}

/// The exit status: whether the parameters of argv[3..5] make the error at least argv[6] times
/// smaller.
int CheckFactor(int argc, char* argv[], vtkPolyData* noisy, const Shape& shape, double before)
{
  if (argc < 7)
  {
    std::fprintf(stderr, "missing parameters\n");
    return EXIT_FAILURE;
  }
  const double r = std::atof(argv[3]);
  const double rn = std::atof(argv[4]);
  const int iterations = std::atoi(argv[5]);
  const double minimumFactor = std::atof(argv[6]);
  const double after = FilteredError(noisy, shape, r, rn, iterations);
  std::printf("filtered with r = %g, rn = %g, N = %d: rms distance %.4g, %.2f times smaller "
              "(at least %.2f expected)\n",
    r,
    rn,
    iterations,
    after,
    before / after,
    minimumFactor);
  return before / after >= minimumFactor ? EXIT_SUCCESS : EXIT_FAILURE;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 4)
  {
    std::fprintf(stderr,
      "usage: %s DATA_DIR NAME (R RN N MINIMUM_FACTOR | --sweep)\n"
      "(R, RN or N 0: automatic)\n",
      argv[0]);
    return EXIT_FAILURE;
  }
  const std::string name = argv[2];
  const auto samples = Samples();
  const SampleSpec* spec = FindSample(samples, name);
  if (!spec)
  {
    std::fprintf(stderr, "unknown sample %s\n", name.c_str());
    return EXIT_FAILURE;
  }
  const vtkSmartPointer<vtkPolyData> noisy = ReadSample(argv[1], *spec);
  if (!noisy)
  {
    return EXIT_FAILURE;
  }
  const auto shape = spec->Make();
  const double before = RootMeanSquareDistance(noisy, *shape);
  const double sigma = spec->Noise * shape->Diagonal();
  std::printf("%s: %zu points, noise sigma %.4g, rms distance to the surface %.4g\n",
    name.c_str(),
    spec->Points,
    sigma,
    before);
  if (std::string(argv[3]) == "--sweep")
  {
    Sweep(noisy, *shape, sigma, before);
    return EXIT_SUCCESS;
  }
  return CheckFactor(argc, argv, noisy, *shape, before);
}

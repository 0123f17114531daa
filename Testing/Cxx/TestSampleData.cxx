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
  const SampleSpec* spec = nullptr;
  const auto samples = Samples();
  for (const SampleSpec& candidate : samples)
  {
    spec = candidate.Name == name ? &candidate : spec;
  }
  if (!spec)
  {
    std::fprintf(stderr, "unknown sample %s\n", name.c_str());
    return EXIT_FAILURE;
  }
  const std::string path = std::string(argv[1]) + "/" + name + (spec->Attributes ? ".vtp" : ".ply");
  vtkSmartPointer<vtkAlgorithm> reader;
  if (spec->Attributes)
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
  if (!noisy || noisy->GetNumberOfPoints() != static_cast<vtkIdType>(spec->Points))
  {
    std::fprintf(stderr, "%s: could not read %zu points\n", path.c_str(), spec->Points);
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
    std::printf("%8s %8s %3s %10s %7s\n", "r", "rn", "N", "rms", "factor");
    for (double r : { 0.03, 0.04, 0.05, 0.06, 0.08 })
    {
      for (double rnInSigmas : { 1.5, 2.0, 3.0, 5.0 })
      {
        for (int iterations : { 1, 2, 4 })
        {
          const double rn = rnInSigmas * sigma;
          const double after = FilteredError(noisy, *shape, r, rn, iterations);
          std::printf("%8.4g %8.4g %3d %10.4g %7.2f\n", r, rn, iterations, after, before / after);
        }
      }
    }
    return EXIT_SUCCESS;
  }

  if (argc < 7)
  {
    std::fprintf(stderr, "missing parameters\n");
    return EXIT_FAILURE;
  }
  const double r = std::atof(argv[3]);
  const double rn = std::atof(argv[4]);
  const int iterations = std::atoi(argv[5]);
  const double minimumFactor = std::atof(argv[6]);
  const double after = FilteredError(noisy, *shape, r, rn, iterations);
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

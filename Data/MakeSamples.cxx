// Makes the sample clouds in Data/ with a fixed seed, so anyone can remake them bit for bit:
//   pcbilateral_make_samples OUTPUT_FOLDER [--clean]
// For each shape it writes SHAPE_noisy.ply (float coordinates) and, with --clean, the
// noise-free points SHAPE_clean.ply in the same order, to measure the error of a filter.
// Noise is Gaussian, its standard deviation a fraction of the bounding-box diagonal, as in
// the paper's experiments.
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPLYWriter.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace
{
struct Sample
{
  std::vector<double> Clean; // xyz
  double Diagonal = 1.0;     // of the clean shape's bounding box
};

class Random
{
public:
  explicit Random(std::uint64_t seed)
    : Engine(seed)
  {
  }
  double Uniform(double low = 0.0, double high = 1.0)
  {
    return low + (high - low) * std::uniform_real_distribution<double>(0.0, 1.0)(this->Engine);
  }
  /// Box-Muller, so the numbers do not depend on the standard library's normal distribution.
  double Gaussian()
  {
    const double u = std::max(this->Uniform(), 1e-300);
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * M_PI * this->Uniform());
  }

private:
  std::mt19937_64 Engine;
};

/// The surface of the cube [-0.5, 0.5]^3, uniformly.
Sample Cube(std::size_t count, Random& random)
{
  Sample sample;
  for (std::size_t i = 0; i < count; ++i)
  {
    const int face = static_cast<int>(random.Uniform(0, 6));
    double p[3] = {
      random.Uniform(-0.5, 0.5), random.Uniform(-0.5, 0.5), random.Uniform(-0.5, 0.5)
    };
    p[face / 2] = face % 2 ? 0.5 : -0.5;
    sample.Clean.insert(sample.Clean.end(), p, p + 3);
  }
  sample.Diagonal = std::sqrt(3.0);
  return sample;
}

/// The paper's sharp edge (Figure 6): two unit squares meeting at a 90-degree ridge along y.
Sample SharpEdge(std::size_t count, Random& random)
{
  Sample sample;
  const double half = std::sqrt(0.5);
  for (std::size_t i = 0; i < count; ++i)
  {
    const double along = random.Uniform(-0.5, 0.5);
    const double across = random.Uniform(-1.0, 1.0); // signed distance from the ridge
    const double p[3] = { across * half, along, -std::abs(across) * half };
    sample.Clean.insert(sample.Clean.end(), p, p + 3);
  }
  sample.Diagonal = std::sqrt(2 * half * 2 * half + 1 + half * half);
  return sample;
}

/// The sphere of radius 0.5, uniformly.
Sample Sphere(std::size_t count, Random& random)
{
  Sample sample;
  for (std::size_t i = 0; i < count; ++i)
  {
    const double z = random.Uniform(-1, 1);
    const double angle = random.Uniform(0, 2 * M_PI);
    const double ring = std::sqrt(1 - z * z);
    const double p[3] = { 0.5 * ring * std::cos(angle), 0.5 * ring * std::sin(angle), 0.5 * z };
    sample.Clean.insert(sample.Clean.end(), p, p + 3);
  }
  sample.Diagonal = std::sqrt(3.0);
  return sample;
}

bool Write(const std::string& path, const std::vector<double>& xyz)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(static_cast<vtkIdType>(xyz.size() / 3));
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    points->SetPoint(i, &xyz[3 * i]);
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  vtkNew<vtkPLYWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetFileTypeToBinary();
  writer->SetInputData(cloud);
  const bool ok = writer->Write() == 1;
  std::printf("%s: %zu points%s\n", path.c_str(), xyz.size() / 3, ok ? "" : " (FAILED)");
  return ok;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: %s OUTPUT_FOLDER [--clean]\n", argv[0]);
    return 1;
  }
  const std::string folder = argv[1];
  const bool clean = argc > 2 && std::string(argv[2]) == "--clean";
  struct Shape
  {
    const char* Name;
    std::function<Sample(Random&)> Make;
    double NoiseOfDiagonal;
  };
  const Shape shapes[] = {
    { "cube", [](Random& r) { return Cube(60000, r); }, 0.005 },
    { "sharp_edge", [](Random& r) { return SharpEdge(30000, r); }, 0.005 },
    { "sphere", [](Random& r) { return Sphere(40000, r); }, 0.005 },
  };
  bool ok = true;
  std::uint64_t seed = 20171029; // the paper's publication date
  for (const Shape& shape : shapes)
  {
    Random random(seed++);
    const Sample sample = shape.Make(random);
    std::vector<double> noisy = sample.Clean;
    const double sigma = shape.NoiseOfDiagonal * sample.Diagonal;
    for (double& value : noisy)
    {
      value += sigma * random.Gaussian();
    }
    ok = Write(folder + "/" + shape.Name + "_noisy.ply", noisy) && ok;
    if (clean)
    {
      ok = Write(folder + "/" + shape.Name + "_clean.ply", sample.Clean) && ok;
    }
  }
  return ok ? 0 : 1;
}

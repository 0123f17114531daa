// Makes the sample clouds in Data/ with fixed seeds, so anyone can remake them bit for bit:
//   pcbilateral_make_samples OUTPUT_FOLDER [--clean]
// For each sample of SampleShapes.h it writes NAME.ply (float coordinates), or NAME.vtp for
// the sample with colours and an intensity; with --clean also the noise-free points,
// NAME_clean.ply, in the same order. Noise is Gaussian, its standard deviation a fraction of
// the shape's bounding-box diagonal, as in the paper's experiments.
#include "SampleShapes.h"

#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPLYWriter.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataWriter.h"

#include <cstdio>
#include <string>
#include <vector>

namespace
{
using namespace pcbilateral_samples;

vtkNew<vtkPolyData> MakeCloud(const std::vector<Vec3>& points)
{
  vtkNew<vtkPoints> coordinates;
  coordinates->SetDataTypeToFloat();
  coordinates->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    coordinates->SetPoint(static_cast<vtkIdType>(i), points[i].data());
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(coordinates);
  return cloud;
}

/// Colours by height, as a scanner's camera might see a landscape, and an intensity that
/// depends on the slope and on the noise of the sensor.
void AddAttributes(vtkPolyData* cloud, const std::vector<Vec3>& clean, Random& random)
{
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("RGB");
  colours->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> intensity;
  intensity->SetName("Intensity");
  for (const Vec3& p : clean)
  {
    const double t = std::clamp((p[2] + 0.1) / 0.25, 0.0, 1.0);
    const unsigned char rgb[3] = { static_cast<unsigned char>(60 + 150 * t),
      static_cast<unsigned char>(140 - 40 * t),
      static_cast<unsigned char>(60 + 60 * t) };
    colours->InsertNextTypedTuple(rgb);
    const double dx = Terrain::Height(p[0] + 1e-4, p[1]) - Terrain::Height(p[0], p[1]);
    intensity->InsertNextValue(
      static_cast<float>(0.8 - 500 * std::abs(dx) + 0.05 * random.Gaussian()));
  }
  cloud->GetPointData()->SetScalars(colours);
  cloud->GetPointData()->AddArray(intensity);
}

bool Write(const std::string& path, vtkPolyData* cloud)
{
  int written = 0;
  if (path.size() > 4 && path.substr(path.size() - 4) == ".vtp")
  {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetInputData(cloud);
    written = writer->Write();
  }
  else
  {
    vtkNew<vtkPLYWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetFileTypeToBinary();
    writer->SetInputData(cloud);
    written = writer->Write();
  }
  std::printf("%s: %lld points%s\n",
    path.c_str(),
    static_cast<long long>(cloud->GetNumberOfPoints()),
    written == 1 ? "" : " (FAILED)");
  return written == 1;
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
  bool ok = true;
  std::uint64_t seed = 20171029; // the paper's publication date
  for (const SampleSpec& spec : Samples())
  {
    Random random(seed++);
    const auto shape = spec.Make();
    std::vector<Vec3> points(spec.Points);
    for (Vec3& p : points)
    {
      p = shape->Sample(random);
    }
    std::vector<Vec3> noisy = points;
    const double sigma = spec.Noise * shape->Diagonal();
    for (Vec3& p : noisy)
    {
      for (double& c : p)
      {
        c += sigma * random.Gaussian();
      }
    }
    auto cloud = MakeCloud(noisy);
    if (spec.Attributes)
    {
      AddAttributes(cloud, points, random);
    }
    ok = Write(folder + "/" + spec.Name + (spec.Attributes ? ".vtp" : ".ply"), cloud) && ok;
    if (clean)
    {
      ok = Write(folder + "/" + spec.Name + "_clean.ply", MakeCloud(points)) && ok;
    }
  }
  return ok ? 0 : 1;
}

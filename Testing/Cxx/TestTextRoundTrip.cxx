// The text writer, then the text reader, in the working folder:
// - round-trip: every array keeps its name, its number of components and its values (the
//   writer's header line names the columns), normals included;
// - layout-kept: a file read and written again is the same bytes (header line or not, the
//   header's names, spaces or tabs, with and without normals);
// - default-layout: a cloud from elsewhere gets tabs, and a header line only when it has arrays
//   besides the normals.
#include "CoreTesting.h"

#include "vtkPointCloudTextReader.h"
#include "vtkPointCloudTextWriter.h"

#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace
{
constexpr vtkIdType PointCount = 50;

/// Writes the cloud to the path; false, with the writer's message as a failure, on error.
bool Write(vtkPolyData* cloud, const std::string& path, bool writeNormals)
{
  vtkNew<vtkPointCloudTextWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetWriteNormals(writeNormals);
  writer->SetInputData(cloud);
  writer->Write();
  PCB_CHECK(writer->GetErrorMessage()[0] == '\0', "%s", writer->GetErrorMessage());
  return writer->GetErrorMessage()[0] == '\0';
}

vtkSmartPointer<vtkPolyData> Read(const std::string& path, bool hasNormals)
{
  vtkNew<vtkPointCloudTextReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetHasNormals(hasNormals);
  reader->Update();
  PCB_CHECK(reader->GetErrorMessage()[0] == '\0', "%s", reader->GetErrorMessage());
  return reader->GetOutput();
}

/// A cloud of PointCount points with normals, a scalar array named with a space, an integer
/// array and a 3-component colour array.
vtkSmartPointer<vtkPolyData> MakeCloudWithArrays()
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkDoubleArray> intensity;
  intensity->SetName("intensity value"); // a space: written as '_'
  vtkNew<vtkIntArray> label;
  label->SetName("label");
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("RGB");
  rgb->SetNumberOfComponents(3);
  for (int i = 0; i < PointCount; ++i)
  {
    points->InsertNextPoint(0.1 * i, 1.0 / (i + 1), std::sqrt(i));
    normals->InsertNextTuple3(0, 0.6, 0.8);
    intensity->InsertNextValue(1e-3 * i * i);
    label->InsertNextValue(i % 7 - 3);
    rgb->InsertNextTuple3(i, 255 - i, 5 * i);
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  cloud->GetPointData()->SetNormals(normals);
  cloud->GetPointData()->AddArray(intensity);
  cloud->GetPointData()->AddArray(label);
  cloud->GetPointData()->AddArray(rgb);
  return cloud;
}

/// Whether the array of `back` named readName holds the values of writtenName in `cloud`.
void CheckArrayReadBack(vtkPolyData* cloud,
  vtkPolyData* back,
  const char* writtenName,
  const char* readName)
{
  vtkDataArray* written = cloud->GetPointData()->GetArray(writtenName);
  vtkDataArray* read = back->GetPointData()->GetArray(readName);
  PCB_CHECK(read != nullptr, "no array '%s' read back", readName);
  if (!read)
  {
    return;
  }
  const int components = written->GetNumberOfComponents();
  PCB_CHECK(read->GetNumberOfComponents() == components,
    "%s: %d components",
    readName,
    read->GetNumberOfComponents());
  bool same = read->GetNumberOfComponents() == components;
  for (vtkIdType i = 0; i < PointCount && same; ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      same = same && written->GetComponent(i, c) == read->GetComponent(i, c);
    }
  }
  PCB_CHECK(same, "%s: the values read back differ", readName);
}

void RoundTrip()
{
  const std::string path = "roundtrip.xyz";
  vtkSmartPointer<vtkPolyData> cloud = MakeCloudWithArrays();
  if (!Write(cloud, path, true))
  {
    return;
  }
  vtkSmartPointer<vtkPolyData> read = Read(path, true);
  PCB_CHECK(read->GetNumberOfPoints() == PointCount,
    "%lld points",
    static_cast<long long>(read->GetNumberOfPoints()));
  if (read->GetNumberOfPoints() != PointCount)
  {
    return;
  }
  bool samePoints = true;
  for (vtkIdType i = 0; i < PointCount; ++i)
  {
    double a[3], b[3];
    cloud->GetPoint(i, a);
    read->GetPoint(i, b);
    samePoints = samePoints && a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
  }
  PCB_CHECK(samePoints, "the points read back differ");
  CheckArrayReadBack(cloud, read, "Normals", "Normals");
  CheckArrayReadBack(cloud, read, "intensity value", "intensity_value");
  CheckArrayReadBack(cloud, read, "label", "label");
  CheckArrayReadBack(cloud, read, "RGB", "RGB");
  PCB_CHECK(read->GetPointData()->GetNumberOfArrays() == 4,
    "%d arrays read back",
    read->GetPointData()->GetNumberOfArrays());
}

void LayoutKept()
{
  struct Case
  {
    const char* Name;
    bool Normals;
    const char* Text;
  };
  const Case cases[] = {
    { "no header, spaces, an index", false, "0.5 0.25 1 7\n-1.5 2 3e+20 8\n" },
    { "no header, spaces", false, "0.5 0.25 1\n-1.5 2 3\n" },
    { "header, tabs", false, "X\tY\tZ\tintensity\n0.5\t0.25\t1\t7\n-1.5\t2\t3\t8\n" },
    { "header without extra columns", false, "x y z\n0.5 0.25 1\n" },
    { "the authors' -R: no header, tabs, normals, an index",
      true,
      "0.5\t0.25\t1\t0\t0.6\t0.8\t0\n-1.5\t2\t3\t1\t0\t0\t1\n" },
    { "header, spaces, normals",
      true,
      "px py pz normal_x normal_y normal_z id\n0.5 0.25 1 0 0.6 0.8 0\n" },
  };
  for (const Case& c : cases)
  {
    const std::string input = "layout-in.xyz", output = "layout-out.xyz";
    std::ofstream(input, std::ios::binary) << c.Text;
    if (Write(Read(input, c.Normals), output, c.Normals))
    {
      const std::string written = pcbilateral_testing::FileContents(output);
      PCB_CHECK(written == c.Text,
        "%s: written back as\n%s\ninstead of\n%s",
        c.Name,
        written.c_str(),
        c.Text);
    }
  }
}

void DefaultLayout()
{
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0.5, 1, -2);
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  const std::string path = "default-layout.xyz";
  if (Write(cloud, path, true))
  {
    PCB_CHECK(pcbilateral_testing::FileContents(path) == "0.5\t1\t-2\n",
      "x y z alone: %s",
      pcbilateral_testing::FileContents(path).c_str());
  }
  vtkNew<vtkIntArray> label;
  label->SetName("label");
  label->InsertNextValue(3);
  cloud->GetPointData()->AddArray(label);
  if (Write(cloud, path, true))
  {
    PCB_CHECK(pcbilateral_testing::FileContents(path) == "x\ty\tz\tlabel\n0.5\t1\t-2\t3\n",
      "with an array: %s",
      pcbilateral_testing::FileContents(path).c_str());
  }
}
} // namespace

int main(int argc, char* argv[])
{
  return RunNamedCase(argc,
    argv,
    { { "round-trip", RoundTrip },
      { "layout-kept", LayoutKept },
      { "default-layout", DefaultLayout } });
}

// The text writer, then the text reader: every array keeps its name, its number of components
// and its values (the writer's header line names the columns), normals included.
#include "CoreTesting.h"

#include "vtkPointCloudTextReader.h"
#include "vtkPointCloudTextWriter.h"

#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <string>

int main(int argc, char* argv[])
{
  const std::string path = argc > 1 ? argv[1] : "roundtrip.xyz";
  vtkNew<vtkPolyData> cloud;
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
  for (int i = 0; i < 50; ++i)
  {
    points->InsertNextPoint(0.1 * i, 1.0 / (i + 1), std::sqrt(i));
    normals->InsertNextTuple3(0, 0.6, 0.8);
    intensity->InsertNextValue(1e-3 * i * i);
    label->InsertNextValue(i % 7 - 3);
    rgb->InsertNextTuple3(i, 255 - i, 5 * i);
  }
  cloud->SetPoints(points);
  cloud->GetPointData()->SetNormals(normals);
  cloud->GetPointData()->AddArray(intensity);
  cloud->GetPointData()->AddArray(label);
  cloud->GetPointData()->AddArray(rgb);

  vtkNew<vtkPointCloudTextWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetWriteNormals(true);
  writer->SetInputData(cloud);
  writer->Write();
  PCB_CHECK(writer->GetErrorMessage()[0] == '\0', "%s", writer->GetErrorMessage());

  vtkNew<vtkPointCloudTextReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetHasNormals(true);
  reader->Update();
  vtkPolyData* read = reader->GetOutput();
  PCB_CHECK(read->GetNumberOfPoints() == 50,
    "%lld points",
    static_cast<long long>(read->GetNumberOfPoints()));
  if (read->GetNumberOfPoints() != 50)
  {
    return PCB_TEST_RESULT();
  }
  bool samePoints = true;
  for (vtkIdType i = 0; i < 50; ++i)
  {
    double a[3], b[3];
    cloud->GetPoint(i, a);
    read->GetPoint(i, b);
    samePoints = samePoints && a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
  }
  PCB_CHECK(samePoints, "the points read back differ");
  struct Expected
  {
    const char* WrittenName;
    const char* ReadName;
  };
  for (const Expected& e : { Expected{ "Normals", "Normals" },
         Expected{ "intensity value", "intensity_value" },
         Expected{ "label", "label" },
         Expected{ "RGB", "RGB" } })
  {
    vtkDataArray* written = cloud->GetPointData()->GetArray(e.WrittenName);
    vtkDataArray* back = read->GetPointData()->GetArray(e.ReadName);
    PCB_CHECK(back != nullptr, "no array '%s' read back", e.ReadName);
    if (!back)
    {
      continue;
    }
    PCB_CHECK(back->GetNumberOfComponents() == written->GetNumberOfComponents(),
      "%s: %d components",
      e.ReadName,
      back->GetNumberOfComponents());
    bool same = back->GetNumberOfComponents() == written->GetNumberOfComponents();
    for (vtkIdType i = 0; i < 50 && same; ++i)
    {
      for (int c = 0; c < written->GetNumberOfComponents(); ++c)
      {
        same = same && written->GetComponent(i, c) == back->GetComponent(i, c);
      }
    }
    PCB_CHECK(same, "%s: the values read back differ", e.ReadName);
  }
  PCB_CHECK(read->GetPointData()->GetNumberOfArrays() == 4,
    "%d arrays read back",
    read->GetPointData()->GetNumberOfArrays());
  return PCB_TEST_RESULT();
}

#include "vtkPointCloudTextReader.h"
#include "vtkPointCloudVertices.h"

#include "PointCloudText.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>

vtkStandardNewMacro(vtkPointCloudTextReader);

namespace
{
/// A vtkDoubleArray holding a copy of interleaved values.
vtkNew<vtkDoubleArray> MakeArray(const char* name,
  int components,
  const std::vector<double>& values)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  return array;
}
} // namespace

vtkPointCloudTextReader::vtkPointCloudTextReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkPointCloudTextReader::~vtkPointCloudTextReader()
{
  this->SetFileName(nullptr);
}

int vtkPointCloudTextReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->ErrorMessage.clear();
  if (!this->FileName || !*this->FileName)
  {
    this->ErrorMessage = "no file name was given";
    vtkErrorMacro(<< this->ErrorMessage);
    return 0;
  }
  pcbilateral::PointCloudTable table;
  this->ErrorMessage = pcbilateral::ReadPointCloudText(this->FileName, this->HasNormals, table);
  if (!this->ErrorMessage.empty())
  {
    vtkErrorMacro(<< this->ErrorMessage);
    return 0;
  }

  const auto count = static_cast<vtkIdType>(table.NumberOfPoints);
  vtkNew<vtkPoints> points;
  points->SetData(MakeArray("Points", 3, table.Positions));
  output->SetPoints(points);
  output->SetVerts(vtkPointCloudVertices(count));

  vtkPointData* pointData = output->GetPointData();
  if (this->HasNormals)
  {
    pointData->SetNormals(MakeArray("Normals", 3, table.Normals));
  }
  for (std::size_t column = 0; column < table.ExtraColumns.size(); ++column)
  {
    pointData->AddArray(
      MakeArray(table.ExtraColumnNames[column].c_str(), 1, table.ExtraColumns[column]));
  }
  return 1;
}

void vtkPointCloudTextReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "HasNormals: " << this->HasNormals << "\n";
}

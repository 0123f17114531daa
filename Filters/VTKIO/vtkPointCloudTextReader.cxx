#include "vtkPointCloudTextReader.h"
#include "vtkPointCloudProgress.h"
#include "vtkPointCloudVertices.h"

#include "PointCloudText.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <string>
#include <vector>

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

/// A string array of the given values.
vtkNew<vtkStringArray> MakeStrings(const char* name, const std::vector<std::string>& values)
{
  vtkNew<vtkStringArray> array;
  array->SetName(name);
  for (const std::string& value : values)
  {
    array->InsertNextValue(value);
  }
  return array;
}

/// The extra columns as point arrays: columns "name:0", "name:1", ... (as the text writer names
/// an array's components) are one array of as many components.
void AddExtraColumns(const pcbilateral::PointCloudTable& table, vtkPointData* pointData)
{
  const auto count = static_cast<vtkIdType>(table.NumberOfPoints);
  for (std::size_t column = 0; column < table.ExtraColumns.size();)
  {
    const std::string& first = table.ExtraColumnNames[column];
    std::size_t components = 1;
    if (first.size() > 2 && first.compare(first.size() - 2, 2, ":0") == 0)
    {
      const std::string base = first.substr(0, first.size() - 1);
      while (column + components < table.ExtraColumns.size() &&
             table.ExtraColumnNames[column + components] == base + std::to_string(components))
      {
        ++components;
      }
    }
    if (components == 1)
    {
      pointData->AddArray(MakeArray(first.c_str(), 1, table.ExtraColumns[column]));
      ++column;
      continue;
    }
    std::vector<double> values(components * count);
    for (std::size_t c = 0; c < components; ++c)
    {
      for (vtkIdType id = 0; id < count; ++id)
      {
        values[id * components + c] = table.ExtraColumns[column + c][id];
      }
    }
    const std::string name = first.substr(0, first.size() - 2);
    pointData->AddArray(MakeArray(name.c_str(), static_cast<int>(components), values));
    column += components;
  }
}

/// The file's layout as field data (see the class's documentation).
void StoreLayout(const pcbilateral::PointCloudTextLayout& layout, vtkFieldData* fieldData)
{
  fieldData->AddArray(MakeStrings(vtkPointCloudTextReader::GetDelimiterArrayName(),
    { vtkPointCloudTextReader::GetDelimiterName(layout.Delimiter) }));
  if (layout.Header == pcbilateral::PointCloudTextLayout::HeaderLine::Always)
  {
    fieldData->AddArray(
      MakeStrings(vtkPointCloudTextReader::GetHeaderArrayName(), layout.LeadingColumnNames));
  }
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

int vtkPointCloudTextReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  // Each piece parses only its own share of the points' lines (ParsePointCloudTextPiece).
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkPointCloudTextReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->ErrorMessage.clear();
  vtkPointCloudProgress progress(this, this->AbortExecute);
  if (!this->FileName || !*this->FileName)
  {
    this->ErrorMessage = "no file name was given";
    vtkErrorMacro(<< this->ErrorMessage);
    return 0;
  }
  pcbilateral::PointCloudTable table;
  this->ErrorMessage = pcbilateral::ReadPointCloudText(this->FileName,
    this->HasNormals,
    table,
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()),
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()));
  if (progress.StopAsked())
  {
    // Aborted: an empty output and no error event; GetErrorMessage() says "aborted", which a
    // distributed read takes as this piece's failure, so that every process stops.
    output->Initialize();
    this->ErrorMessage = pcbilateral::AbortedMessage;
    return 1;
  }
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
  AddExtraColumns(table, pointData);
  StoreLayout(table.Layout, output->GetFieldData());
  return 1;
}

void vtkPointCloudTextReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "HasNormals: " << this->HasNormals << "\n";
}

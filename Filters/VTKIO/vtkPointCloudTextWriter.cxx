#include "vtkPointCloudTextWriter.h"
#include "vtkLASPointCloudFieldData.h"
#include "vtkPointCloudProgress.h"
#include "vtkPointCloudTextReader.h"

#include "FileBytes.h"
#include "PointCloudText.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include <string>

vtkStandardNewMacro(vtkPointCloudTextWriter);

namespace
{
/// The layout of the text file the cloud was read from (the field data of
/// vtkPointCloudTextReader), or the default layout for a cloud from elsewhere.
pcbilateral::PointCloudTextLayout LoadLayout(vtkFieldData* fieldData)
{
  using Reader = vtkPointCloudTextReader;
  pcbilateral::PointCloudTextLayout layout;
  auto* delimiter = vtkStringArray::SafeDownCast(
    fieldData ? fieldData->GetAbstractArray(Reader::GetDelimiterArrayName()) : nullptr);
  if (!delimiter || delimiter->GetNumberOfValues() != 1)
  {
    return layout;
  }
  char named = 0;
  for (const char candidate : { '\t', ' ' })
  {
    named = delimiter->GetValue(0) == Reader::GetDelimiterName(candidate) ? candidate : named;
  }
  if (!named)
  {
    return layout; // a value no reader wrote: the default layout
  }
  layout.Delimiter = named;
  auto* header =
    vtkStringArray::SafeDownCast(fieldData->GetAbstractArray(Reader::GetHeaderArrayName()));
  layout.Header = header ? pcbilateral::PointCloudTextLayout::HeaderLine::Always
                         : pcbilateral::PointCloudTextLayout::HeaderLine::Never;
  for (vtkIdType k = 0; header && k < header->GetNumberOfValues(); ++k)
  {
    layout.LeadingColumnNames.push_back(header->GetValue(k));
  }
  return layout;
}

/// The input's points, normals (when written) and other point arrays as the text writer's
/// table; stops early (at a progress point) when the write is aborted.
pcbilateral::PointCloudTable CopyColumns(vtkPolyData* input, bool writeNormals)
{
  const vtkIdType count = input->GetNumberOfPoints();
  const auto copyStopped = [count](vtkIdType id)
  {
    return id % static_cast<vtkIdType>(pcbilateral::PointsPerProgressPoint) == 0 &&
           pcbilateral::ProgressPoint(static_cast<std::uint64_t>(id), count);
  };
  pcbilateral::PointCloudTable table;
  table.NumberOfPoints = static_cast<std::size_t>(count);
  table.Positions.resize(3 * table.NumberOfPoints);
  for (vtkIdType id = 0; id < count && !copyStopped(id); ++id)
  {
    input->GetPoint(id, table.Positions.data() + 3 * id);
  }
  vtkPointData* pointData = input->GetPointData();
  vtkDataArray* normals = writeNormals ? pointData->GetNormals() : nullptr;
  if (normals && normals->GetNumberOfComponents() == 3)
  {
    table.Normals.resize(3 * table.NumberOfPoints);
    for (vtkIdType id = 0; id < count; ++id)
    {
      normals->GetTuple(id, table.Normals.data() + 3 * id);
    }
  }
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pointData->GetArray(a);
    if (!array || (array == normals && !table.Normals.empty()))
    {
      continue;
    }
    for (int component = 0; component < array->GetNumberOfComponents(); ++component)
    {
      std::vector<double> column(table.NumberOfPoints);
      for (vtkIdType id = 0; id < count && !copyStopped(id); ++id)
      {
        column[id] = array->GetComponent(id, component);
      }
      table.ExtraColumns.push_back(std::move(column));
      // Components are "name:0", "name:1"...: the text reader makes them one array again.
      std::string name = array->GetName() ? array->GetName() : "";
      if (array->GetNumberOfComponents() > 1)
      {
        name += ":" + std::to_string(component);
      }
      table.ExtraColumnNames.push_back(name);
    }
  }
  return table;
}

} // namespace

vtkPointCloudTextWriter::vtkPointCloudTextWriter() = default;

vtkPointCloudTextWriter::~vtkPointCloudTextWriter()
{
  this->SetFileName(nullptr);
}

int vtkPointCloudTextWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

void vtkPointCloudTextWriter::WriteData()
{
  this->ErrorMessage.clear();
  vtkPointCloudProgress progress(this, this->AbortExecute);
  vtkPolyData* input = vtkPolyData::SafeDownCast(this->GetInput());
  if (!this->FileName || !*this->FileName)
  {
    this->ErrorMessage = "no file name was given";
  }
  else if (!input)
  {
    this->ErrorMessage = "the input is not a vtkPolyData";
  }
  if (!this->ErrorMessage.empty())
  {
    vtkErrorMacro(<< this->ErrorMessage);
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }

  // Copying the arrays out takes about a third of the time.
  progress.SetStage(0.0, 0.3);
  pcbilateral::PointCloudTable table = CopyColumns(input, this->WriteNormals);
  table.Layout = LoadLayout(input->GetFieldData());
  const std::string notHeld = vtkLASInformationNotHeld(input->GetFieldData());
  if (!notHeld.empty())
  {
    vtkWarningMacro(<< this->FileName << ": a text file cannot hold " << notHeld
                    << ", which are not written (the coordinates are)");
  }
  progress.SetStage(0.3, 1.0);
  this->ErrorMessage = progress.StopAsked()
                         ? pcbilateral::AbortedMessage
                         : pcbilateral::WritePointCloudText(this->FileName, table);
  if (progress.StopAsked())
  {
    this->SetErrorCode(vtkErrorCode::UserError); // aborted: no file, no error message
  }
  else if (!this->ErrorMessage.empty())
  {
    vtkErrorMacro(<< this->ErrorMessage);
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}

void vtkPointCloudTextWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "WriteNormals: " << this->WriteNormals << "\n";
}

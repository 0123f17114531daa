#include "vtkPCDPointCloudReader.h"

#include "PCDFile.h"
#include "vtkPCDPointCloudFieldData.h"
#include "vtkPointCloudProgress.h"
#include "vtkPointCloudVertices.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPCDPointCloudReader);

namespace
{
/// A field's values as an array of its own type.
vtkSmartPointer<vtkDataArray> MakeArray(const pcbilateral::PCDColumn& column)
{
  const pcbilateral::PCDField& field = column.Field;
  auto array =
    vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(vtkPCDArrayType(field)));
  array->SetName(field.Name.c_str());
  array->SetNumberOfComponents(static_cast<int>(field.Count));
  array->SetNumberOfTuples(static_cast<vtkIdType>(column.Bytes.size() / field.Bytes()));
  std::copy(
    column.Bytes.begin(), column.Bytes.end(), static_cast<std::uint8_t*>(array->GetVoidPointer(0)));
  return array;
}

/// "RGB" or "RGBA", unless another field has that name: then "Colors", as the LAS reader names
/// its 8-bit colours (a LAS file's 16-bit RGB written to PCD is such a field, and one array
/// would silently replace the other).
std::string ColourName(const pcbilateral::PCDColumn& column,
  const std::vector<pcbilateral::PCDColumn>& columns)
{
  const std::string name = column.Field.Name == "rgba" ? "RGBA" : "RGB";
  const bool taken = std::any_of(columns.begin(),
    columns.end(),
    [&](const pcbilateral::PCDColumn& other) { return other.Field.Name == name; });
  return taken ? "Colors" : name;
}

vtkSmartPointer<vtkDataArray> MakeColours(const pcbilateral::PCDColumn& column,
  const std::vector<pcbilateral::PCDColumn>& columns)
{
  const std::vector<std::uint8_t> channels = pcbilateral::UnpackPCDColours(column);
  const int components = column.Field.Name == "rgba" ? 4 : 3;
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetName(ColourName(column, columns).c_str());
  colours->SetNumberOfComponents(components);
  colours->SetNumberOfTuples(static_cast<vtkIdType>(channels.size() / components));
  std::copy(channels.begin(), channels.end(), colours->GetPointer(0));
  return colours;
}

/// normal_x, normal_y and normal_z, of one type and one value each, as one 3-component array.
vtkSmartPointer<vtkDataArray> MakeNormals(const std::vector<pcbilateral::PCDColumn>& columns)
{
  const pcbilateral::PCDColumn* axes[3] = { nullptr, nullptr, nullptr };
  for (const pcbilateral::PCDColumn& column : columns)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      if (column.Field.Name == std::string("normal_") + static_cast<char>('x' + axis) &&
          column.Field.Count == 1)
      {
        axes[axis] = &column;
      }
    }
  }
  if (!axes[0] || !axes[1] || !axes[2] || axes[0]->Field.Type != axes[1]->Field.Type ||
      axes[0]->Field.Type != axes[2]->Field.Type || axes[0]->Field.Size != axes[1]->Field.Size ||
      axes[0]->Field.Size != axes[2]->Field.Size)
  {
    return nullptr;
  }
  const std::size_t size = axes[0]->Field.Size;
  const std::size_t count = axes[0]->Bytes.size() / size;
  auto normals = vtkSmartPointer<vtkDataArray>::Take(
    vtkDataArray::CreateDataArray(vtkPCDArrayType(axes[0]->Field)));
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(static_cast<vtkIdType>(count));
  auto* out = static_cast<std::uint8_t*>(normals->GetVoidPointer(0));
  for (std::size_t i = 0; i < count; ++i)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      std::memcpy(out + (3 * i + axis) * size, axes[axis]->Bytes.data() + i * size, size);
    }
  }
  return normals;
}

void AddPointArrays(const std::vector<pcbilateral::PCDColumn>& columns, vtkPointData* pointData)
{
  vtkSmartPointer<vtkDataArray> normals = MakeNormals(columns);
  if (normals)
  {
    pointData->SetNormals(normals);
  }
  for (const pcbilateral::PCDColumn& column : columns)
  {
    if (normals && column.Field.Name.compare(0, 7, "normal_") == 0 && column.Field.Name.size() == 8)
    {
      continue;
    }
    pointData->AddArray(pcbilateral::IsPCDPackedColour(column.Field) ? MakeColours(column, columns)
                                                                     : MakeArray(column));
  }
}
} // namespace

vtkPCDPointCloudReader::vtkPCDPointCloudReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkPCDPointCloudReader::~vtkPCDPointCloudReader()
{
  this->SetFileName(nullptr);
}

int vtkPCDPointCloudReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  // Each piece reads its own share of the points (PCDReadOptions::Piece).
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkPCDPointCloudReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->ErrorMessage.clear();
  vtkPointCloudProgress progress(this, this->AbortExecute);
  this->NumberOfDroppedPoints = 0;
  if (!this->FileName || !*this->FileName)
  {
    this->ErrorMessage = "no file name was given";
    vtkErrorMacro(<< this->ErrorMessage);
    return 0;
  }
  pcbilateral::PCDReadOptions options;
  options.KeepNaNPoints = this->KeepNaNPoints;
  options.Piece = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
  options.NumberOfPieces =
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES());
  pcbilateral::PCDCloud cloud;
  this->ErrorMessage = pcbilateral::ReadPCD(this->FileName, options, cloud);
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
  this->NumberOfDroppedPoints = static_cast<vtkIdType>(cloud.NumberOfDroppedPoints);
  const auto count = static_cast<vtkIdType>(cloud.NumberOfPoints);
  vtkNew<vtkDoubleArray> positions;
  positions->SetNumberOfComponents(3);
  positions->SetNumberOfTuples(count);
  std::copy(cloud.Positions.begin(), cloud.Positions.end(), positions->GetPointer(0));
  vtkNew<vtkPoints> points;
  points->SetData(positions);
  output->SetPoints(points);
  output->SetVerts(vtkPointCloudVertices(count));
  AddPointArrays(cloud.Columns, output->GetPointData());
  vtkPCDStoreLayout(cloud.Header, output->GetFieldData());
  return 1;
}

void vtkPCDPointCloudReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "KeepNaNPoints: " << this->KeepNaNPoints << "\n";
  os << indent << "NumberOfDroppedPoints: " << this->NumberOfDroppedPoints << "\n";
}

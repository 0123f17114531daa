#include "vtkLASPointCloudReader.h"

#include "LASHeader.h"
#include "LASReader.h"
#include "LAZReader.h"
#include "vtkLASPointCloudFieldData.h"
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
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkLASPointCloudReader);

namespace
{
/// 8-bit colours for display: the 16-bit values' high bytes, unless the file stored 8-bit
/// values in its 16-bit fields (as many programs do).
vtkSmartPointer<vtkUnsignedCharArray> DisplayColours(vtkUnsignedShortArray* rgb)
{
  const vtkIdType values = rgb->GetNumberOfValues();
  const unsigned short* in = rgb->GetPointer(0);
  const bool eightBit = std::all_of(in, in + values, [](unsigned short v) { return v <= 255; });
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetName("Colors");
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(rgb->GetNumberOfTuples());
  unsigned char* out = colours->GetPointer(0);
  for (vtkIdType i = 0; i < values; ++i)
  {
    out[i] = static_cast<unsigned char>(eightBit ? in[i] : in[i] >> 8);
  }
  return colours;
}
} // namespace

vtkLASPointCloudReader::vtkLASPointCloudReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkLASPointCloudReader::~vtkLASPointCloudReader()
{
  this->SetFileName(nullptr);
}

int vtkLASPointCloudReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->ErrorMessage.clear();
  pcbilateral::LASFileBytes file;
  pcbilateral::LASFileInfo info;
  if (!this->FileName || !*this->FileName)
  {
    this->ErrorMessage = "no file name was given";
  }
  else
  {
    this->ErrorMessage = file.Open(this->FileName);
  }
  if (this->ErrorMessage.empty())
  {
    this->ErrorMessage =
      pcbilateral::ParseLASHeader(file.Data(), file.Size(), this->FileName, info, true);
  }
  // A LAZ file's records are decompressed first (in parallel, by chunk); a LAS file's are read
  // where they lie.
  std::vector<std::uint8_t> decompressed;
  const std::uint8_t* records = nullptr;
  if (this->ErrorMessage.empty())
  {
    this->ErrorMessage = pcbilateral::UncompressedLASRecords(
      file.Data(), file.Size(), info, this->FileName, decompressed, records);
  }
  if (!this->ErrorMessage.empty())
  {
    // One error and an empty output: a failed request would add the pipeline's own report.
    vtkErrorMacro(<< this->ErrorMessage);
    return 1;
  }

  const auto count = static_cast<vtkIdType>(info.Header.NumberOfPoints);
  vtkNew<vtkDoubleArray> positions;
  positions->SetNumberOfComponents(3);
  positions->SetNumberOfTuples(count);
  std::vector<vtkSmartPointer<vtkDataArray>> arrays;
  std::vector<void*> columns;
  for (const pcbilateral::LASDimension& dimension : info.Dimensions)
  {
    auto array = vtkSmartPointer<vtkDataArray>::Take(
      vtkDataArray::CreateDataArray(vtkLASArrayType(dimension.ColumnType)));
    array->SetName(dimension.Name.c_str());
    array->SetNumberOfComponents(dimension.Components);
    array->SetNumberOfTuples(count);
    arrays.push_back(array);
    columns.push_back(array->GetVoidPointer(0));
  }
  pcbilateral::DecodeLASPoints(
    info, records, static_cast<std::size_t>(count), positions->GetPointer(0), columns.data());

  vtkNew<vtkPoints> points;
  points->SetData(positions);
  output->SetPoints(points);
  output->SetVerts(vtkPointCloudVertices(count));
  vtkPointData* pointData = output->GetPointData();
  for (const auto& array : arrays)
  {
    pointData->AddArray(array);
  }
  if (auto* rgb = vtkUnsignedShortArray::SafeDownCast(pointData->GetArray("RGB")))
  {
    pointData->AddArray(DisplayColours(rgb));
  }
  vtkLASStoreFileInfo(info, output->GetFieldData());
  return 1;
}

void vtkLASPointCloudReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}

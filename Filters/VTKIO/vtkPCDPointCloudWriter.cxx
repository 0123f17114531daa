#include "vtkPCDPointCloudWriter.h"

#include "PCDFile.h"
#include "PCDValues.h"
#include "vtkLASPointCloudFieldData.h"
#include "vtkPCDPointCloudFieldData.h"
#include "vtkPointCloudProgress.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

vtkStandardNewMacro(vtkPCDPointCloudWriter);

namespace
{
using pcbilateral::PCDColumn;
using pcbilateral::PCDField;

/// Builds the PCD cloud of a vtkPolyData: the fields of the layout read first, then the arrays
/// left (see the class's documentation).
class CloudBuilder
{
public:
  explicit CloudBuilder(vtkPointSet* input)
    : PointData(input->GetPointData())
  {
    const vtkIdType count = input->GetNumberOfPoints();
    this->Cloud.NumberOfPoints = static_cast<std::size_t>(count);
    this->Cloud.Positions.resize(3 * this->Cloud.NumberOfPoints);
    for (vtkIdType id = 0; id < count; ++id)
    {
      input->GetPoint(id, this->Cloud.Positions.data() + 3 * id);
    }
  }

  /// The layout read, when there is one: its fields that still have their values.
  bool AddLayout(vtkFieldData* fieldData)
  {
    pcbilateral::PCDHeader layout;
    if (!vtkPCDLoadLayout(fieldData, layout))
    {
      return false;
    }
    this->Cloud.Header = layout;
    this->Cloud.Header.Fields.clear();
    for (const PCDField& field : layout.Fields)
    {
      this->AddField(field);
    }
    return true;
  }

  /// x y z for a cloud without a layout: F4 when every coordinate is a float, else F8.
  void AddCoordinates()
  {
    const bool floats = std::all_of(this->Cloud.Positions.begin(),
      this->Cloud.Positions.end(),
      [](double v) { return std::isnan(v) || static_cast<double>(static_cast<float>(v)) == v; });
    this->Cloud.Header.Width = this->Cloud.NumberOfPoints;
    for (const char* name : { "x", "y", "z" })
    {
      this->Cloud.Header.Fields.push_back(PCDField{ name, 'F', floats ? 4u : 8u, 1 });
    }
  }

  void AddRemainingArrays();

  pcbilateral::PCDCloud Cloud;

private:
  bool HasField(const std::string& name) const
  {
    const auto& fields = this->Cloud.Header.Fields;
    return std::any_of(
      fields.begin(), fields.end(), [&](const PCDField& field) { return field.Name == name; });
  }

  vtkDataArray* Colours(int components) const
  {
    for (const char* name : { "RGBA", "RGB", "Colors" })
    {
      auto* array = vtkUnsignedCharArray::SafeDownCast(this->PointData->GetArray(name));
      if (array && array->GetNumberOfComponents() == components)
      {
        return array;
      }
    }
    return nullptr;
  }

  void AddField(const PCDField& field);
  void AddValues(const PCDField& field, vtkDataArray* array, int component);
  void AddColours(const PCDField& field, vtkDataArray* colours);

  vtkPointData* PointData;
  std::set<vtkDataArray*> Used;
};

/// Appends the field with the values of `array` (its `component`, or all of them when -1).
void CloudBuilder::AddValues(const PCDField& field, vtkDataArray* array, int component)
{
  const std::size_t count = this->Cloud.NumberOfPoints;
  PCDColumn column{ field, std::vector<std::uint8_t>(count * field.Bytes()) };
  if (component < 0 && vtkPCDArrayType(field) == array->GetDataType())
  {
    std::memcpy(column.Bytes.data(), array->GetVoidPointer(0), column.Bytes.size());
  }
  else
  {
    const unsigned values = component < 0 ? field.Count : 1;
    for (std::size_t i = 0; i < count; ++i)
    {
      for (unsigned c = 0; c < values; ++c)
      {
        const double value = array->GetComponent(
          static_cast<vtkIdType>(i), component < 0 ? static_cast<int>(c) : component);
        pcbilateral::StorePCDValue(
          field, value, column.Bytes.data() + (i * values + c) * field.Size);
      }
    }
  }
  this->Cloud.Header.Fields.push_back(field);
  this->Cloud.Columns.push_back(std::move(column));
  this->Used.insert(array);
}

void CloudBuilder::AddColours(const PCDField& field, vtkDataArray* colours)
{
  const int channels = colours->GetNumberOfComponents();
  this->Cloud.Header.Fields.push_back(field);
  this->Cloud.Columns.push_back(pcbilateral::PackPCDColours(field,
    static_cast<const std::uint8_t*>(colours->GetVoidPointer(0)),
    channels,
    this->Cloud.NumberOfPoints));
  this->Used.insert(colours);
}

/// A field of the layout read, from the array that holds its values; left out when none does.
void CloudBuilder::AddField(const PCDField& field)
{
  if (field.IsCoordinate() || field.IsPadding())
  {
    this->Cloud.Header.Fields.push_back(field);
    return;
  }
  if (pcbilateral::IsPCDPackedColour(field))
  {
    vtkDataArray* colours = this->Colours(field.Name == "rgba" ? 4 : 3);
    colours = colours ? colours : this->Colours(field.Name == "rgba" ? 3 : 4);
    if (colours)
    {
      this->AddColours(field, colours);
    }
    return;
  }
  vtkDataArray* array = this->PointData->GetArray(field.Name.c_str());
  if (array && array->GetNumberOfComponents() == static_cast<int>(field.Count))
  {
    this->AddValues(field, array, -1);
    return;
  }
  vtkDataArray* normals = this->PointData->GetNormals();
  if (field.Count == 1 && field.Name.size() == 8 && field.Name.compare(0, 7, "normal_") == 0 &&
      field.Name[7] >= 'x' && field.Name[7] <= 'z' && normals &&
      normals->GetNumberOfComponents() == 3)
  {
    this->AddValues(field, normals, field.Name[7] - 'x');
  }
}

void CloudBuilder::AddRemainingArrays()
{
  vtkDataArray* normals = this->PointData->GetNormals();
  if (normals && !this->Used.count(normals) && normals->GetNumberOfComponents() == 3 &&
      !this->HasField("normal_x"))
  {
    PCDField field{ "normal_x", 'F', 4, 1 };
    vtkPCDFieldType(normals, field);
    for (int axis = 0; axis < 3; ++axis)
    {
      field.Name = std::string("normal_") + static_cast<char>('x' + axis);
      this->AddValues(field, normals, axis);
    }
  }
  vtkDataArray* rgba = this->Colours(4);
  vtkDataArray* rgb = this->Colours(3);
  if (!this->HasField("rgb") && !this->HasField("rgba") && (rgba || rgb) &&
      !this->Used.count(rgba ? rgba : rgb))
  {
    this->AddColours(
      rgba ? PCDField{ "rgba", 'U', 4, 1 } : PCDField{ "rgb", 'F', 4, 1 }, rgba ? rgba : rgb);
  }
  for (int a = 0; a < this->PointData->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = this->PointData->GetArray(a);
    PCDField field;
    if (!array || this->Used.count(array) || !array->GetName() || !*array->GetName() ||
        std::strcmp(array->GetName(), "vtkOriginalPointIds") == 0 || !vtkPCDFieldType(array, field))
    {
      continue;
    }
    field.Name = array->GetName();
    std::replace_if(
      field.Name.begin(), field.Name.end(), [](char c) { return c == ' ' || c == '\t'; }, '_');
    field.Count = static_cast<unsigned>(array->GetNumberOfComponents());
    if (!this->HasField(field.Name) && !field.IsPadding())
    {
      this->AddValues(field, array, -1);
    }
  }
}
} // namespace

vtkPCDPointCloudWriter::vtkPCDPointCloudWriter() = default;

vtkPCDPointCloudWriter::~vtkPCDPointCloudWriter()
{
  this->SetFileName(nullptr);
}

int vtkPCDPointCloudWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

void vtkPCDPointCloudWriter::WriteData()
{
  this->ErrorMessage.clear();
  vtkPointCloudProgress progress(this, this->AbortExecute);
  auto* input = vtkPointSet::SafeDownCast(this->GetInput());
  if (!this->FileName || !*this->FileName)
  {
    this->ErrorMessage = "no file name was given";
  }
  else if (!input)
  {
    this->ErrorMessage = "the input is not a point set";
  }
  if (!this->ErrorMessage.empty())
  {
    vtkErrorMacro(<< this->ErrorMessage);
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  CloudBuilder builder(input);
  const bool asRead = builder.AddLayout(input->GetFieldData());
  if (!asRead)
  {
    builder.AddCoordinates();
  }
  builder.AddRemainingArrays();
  const std::string unwritten = vtkLASInformationNotHeld(input->GetFieldData());
  if (!unwritten.empty())
  {
    vtkWarningMacro(<< this->FileName << ": a PCD file cannot hold " << unwritten
                    << ", which are not written");
  }
  pcbilateral::PCDEncoding encoding =
    asRead ? builder.Cloud.Header.Encoding : pcbilateral::PCDEncoding::Binary;
  if (this->DataEncoding != AS_READ)
  {
    encoding = static_cast<pcbilateral::PCDEncoding>(this->DataEncoding);
  }
  this->ErrorMessage = pcbilateral::WritePCD(this->FileName, builder.Cloud, encoding);
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

void vtkPCDPointCloudWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "DataEncoding: " << this->DataEncoding << "\n";
}

#include "vtkPCDPointCloudFieldData.h"

#include "vtkLASPointCloudFieldData.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkStringArray.h"
#include "vtkType.h"

#include <algorithm>
#include <sstream>

namespace
{
struct TypePair
{
  char Type;
  unsigned Size;
  int VTKType;
};

// VTK_LONG and VTK_ID_TYPE (64-bit here) are written as I8, VTK_UNSIGNED_LONG as U8, VTK_CHAR
// as I1; they read back as the first type of their row.
constexpr TypePair Types[] = { { 'F', 4, VTK_FLOAT },
  { 'F', 8, VTK_DOUBLE },
  { 'I', 1, VTK_SIGNED_CHAR },
  { 'I', 2, VTK_SHORT },
  { 'I', 4, VTK_INT },
  { 'I', 8, VTK_LONG_LONG },
  { 'U', 1, VTK_UNSIGNED_CHAR },
  { 'U', 2, VTK_UNSIGNED_SHORT },
  { 'U', 4, VTK_UNSIGNED_INT },
  { 'U', 8, VTK_UNSIGNED_LONG_LONG } };

void AddStrings(vtkFieldData* fieldData, const char* name, const std::vector<std::string>& values)
{
  vtkNew<vtkStringArray> array;
  array->SetName(name);
  for (const std::string& value : values)
  {
    array->InsertNextValue(value);
  }
  fieldData->AddArray(array);
}

void AddDoubles(vtkFieldData* fieldData, const char* name, const double* values, int count)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  for (int k = 0; k < count; ++k)
  {
    array->InsertNextValue(values[k]);
  }
  fieldData->AddArray(array);
}

/// The field of a "PCD Fields" value, "name TYPE SIZE COUNT".
bool ParseField(const std::string& text, pcbilateral::PCDField& field)
{
  std::istringstream words(text);
  return static_cast<bool>(words >> field.Name >> field.Type >> field.Size >> field.Count) &&
         field.Count > 0 && vtkPCDArrayType(field) != VTK_VOID;
}
} // namespace

int vtkPCDArrayType(const pcbilateral::PCDField& field)
{
  for (const TypePair& pair : Types)
  {
    if (pair.Type == field.Type && pair.Size == field.Size)
    {
      return pair.VTKType;
    }
  }
  return VTK_VOID;
}

bool vtkPCDFieldType(vtkDataArray* array, pcbilateral::PCDField& field)
{
  int type = array->GetDataType();
  const int size = array->GetDataTypeSize();
  if (type == VTK_CHAR || type == VTK_LONG || type == VTK_ID_TYPE || type == VTK_UNSIGNED_LONG)
  {
    const bool isSigned = type != VTK_UNSIGNED_LONG;
    type = size == 1 ? VTK_SIGNED_CHAR : isSigned ? VTK_LONG_LONG : VTK_UNSIGNED_LONG_LONG;
  }
  for (const TypePair& pair : Types)
  {
    if (pair.VTKType == type && static_cast<int>(pair.Size) == size)
    {
      field.Type = pair.Type;
      field.Size = pair.Size;
      return true;
    }
  }
  return false;
}

void vtkPCDStoreLayout(const pcbilateral::PCDHeader& header, vtkFieldData* fieldData)
{
  std::vector<std::string> fields;
  for (const pcbilateral::PCDField& field : header.Fields)
  {
    fields.push_back(field.Name + " " + field.Type + " " + std::to_string(field.Size) + " " +
                     std::to_string(field.Count));
  }
  AddStrings(fieldData, "PCD Fields", fields);
  const double width = static_cast<double>(header.Width);
  const double height = static_cast<double>(header.Height);
  AddDoubles(fieldData, "PCD Width", &width, 1);
  AddDoubles(fieldData, "PCD Height", &height, 1);
  AddDoubles(fieldData, "PCD Viewpoint", header.Viewpoint, 7);
  AddStrings(fieldData, "PCD Data", { pcbilateral::PCDEncodingName(header.Encoding) });
}

bool vtkPCDLoadLayout(vtkFieldData* fieldData, pcbilateral::PCDHeader& header)
{
  header = pcbilateral::PCDHeader();
  auto* fields =
    vtkStringArray::SafeDownCast(fieldData ? fieldData->GetAbstractArray("PCD Fields") : nullptr);
  if (!fields)
  {
    return false;
  }
  for (vtkIdType k = 0; k < fields->GetNumberOfValues(); ++k)
  {
    pcbilateral::PCDField field;
    if (!ParseField(fields->GetValue(k), field))
    {
      header = pcbilateral::PCDHeader();
      return false;
    }
    header.Fields.push_back(field);
  }
  for (const char* axis : { "x", "y", "z" })
  {
    if (std::none_of(header.Fields.begin(),
          header.Fields.end(),
          [axis](const pcbilateral::PCDField& field) { return field.Name == axis; }))
    {
      header = pcbilateral::PCDHeader();
      return false;
    }
  }
  auto* width = vtkDataArray::SafeDownCast(fieldData->GetAbstractArray("PCD Width"));
  auto* height = vtkDataArray::SafeDownCast(fieldData->GetAbstractArray("PCD Height"));
  if (width && height && width->GetNumberOfValues() == 1 && height->GetNumberOfValues() == 1)
  {
    header.Width = static_cast<std::uint64_t>(width->GetComponent(0, 0));
    header.Height = static_cast<std::uint64_t>(height->GetComponent(0, 0));
  }
  auto* viewpoint = vtkDataArray::SafeDownCast(fieldData->GetAbstractArray("PCD Viewpoint"));
  for (int k = 0; viewpoint && viewpoint->GetNumberOfValues() == 7 && k < 7; ++k)
  {
    header.Viewpoint[k] = viewpoint->GetComponent(k, 0);
  }
  auto* data = vtkStringArray::SafeDownCast(fieldData->GetAbstractArray("PCD Data"));
  for (const auto encoding : { pcbilateral::PCDEncoding::ASCII,
         pcbilateral::PCDEncoding::Binary,
         pcbilateral::PCDEncoding::BinaryCompressed })
  {
    if (data && data->GetNumberOfValues() == 1 &&
        data->GetValue(0) == pcbilateral::PCDEncodingName(encoding))
    {
      header.Encoding = encoding;
    }
  }
  return true;
}

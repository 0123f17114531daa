#include "vtkLASPointCloudFieldData.h"

#include "LASCoordinateSystem.h"
#include "LASPointFormat.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkStringArray.h"
#include "vtkType.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace
{
void AddBytes(vtkFieldData* fieldData,
  const char* name,
  const std::uint8_t* bytes,
  std::size_t size)
{
  vtkNew<vtkUnsignedCharArray> array;
  array->SetName(name);
  array->SetNumberOfValues(static_cast<vtkIdType>(size));
  std::copy(bytes, bytes + size, array->GetPointer(0));
  fieldData->AddArray(array);
}

void AddShorts(vtkFieldData* fieldData,
  const char* name,
  std::initializer_list<unsigned short> values)
{
  vtkNew<vtkUnsignedShortArray> array;
  array->SetName(name);
  for (unsigned short value : values)
  {
    array->InsertNextValue(value);
  }
  fieldData->AddArray(array);
}

void AddDoubles(vtkFieldData* fieldData, const char* name, const double values[3])
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfValues(3);
  for (int k = 0; k < 3; ++k)
  {
    array->SetValue(k, values[k]);
  }
  fieldData->AddArray(array);
}

void AddString(vtkFieldData* fieldData, const char* name, const std::string& value)
{
  vtkNew<vtkStringArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  fieldData->AddArray(array);
}

std::string GetString(vtkFieldData* fieldData, const char* name)
{
  auto* array = vtkStringArray::SafeDownCast(fieldData->GetAbstractArray(name));
  return array && array->GetNumberOfValues() > 0 ? array->GetValue(0) : std::string();
}

/// The values of a field-data array, when it has exactly `count` of them.
bool GetValues(vtkFieldData* fieldData,
  const char* name,
  std::size_t count,
  std::vector<double>& values)
{
  vtkDataArray* array = fieldData->GetArray(name);
  if (!array || array->GetNumberOfValues() != static_cast<vtkIdType>(count))
  {
    return false;
  }
  values.resize(count);
  for (std::size_t k = 0; k < count; ++k)
  {
    values[k] = array->GetComponent(static_cast<vtkIdType>(k) / array->GetNumberOfComponents(),
      static_cast<int>(k % array->GetNumberOfComponents()));
  }
  return true;
}

bool GetRecords(vtkFieldData* fieldData,
  const char* name,
  bool extended,
  std::vector<pcbilateral::LASRecord>& records)
{
  records.clear();
  auto* array = vtkUnsignedCharArray::SafeDownCast(fieldData->GetArray(name));
  if (!array)
  {
    return true;
  }
  return pcbilateral::DecodeLASRecords(
    array->GetPointer(0), static_cast<std::size_t>(array->GetNumberOfValues()), extended, records);
}
} // namespace

int vtkLASArrayType(pcbilateral::LASValueType type)
{
  using T = pcbilateral::LASValueType;
  switch (type)
  {
    case T::UInt8:
      return VTK_UNSIGNED_CHAR;
    case T::Int8:
      return VTK_SIGNED_CHAR;
    case T::UInt16:
      return VTK_UNSIGNED_SHORT;
    case T::Int16:
      return VTK_SHORT;
    case T::UInt32:
      return VTK_UNSIGNED_INT;
    case T::Int32:
      return VTK_INT;
    case T::UInt64:
      return VTK_TYPE_UINT64;
    case T::Int64:
      return VTK_TYPE_INT64;
    case T::Float32:
      return VTK_FLOAT;
    default:
      return VTK_DOUBLE;
  }
}

void vtkLASStoreFileInfo(const pcbilateral::LASFileInfo& info, vtkFieldData* fieldData)
{
  const pcbilateral::LASHeader& h = info.Header;
  const std::uint8_t version[2] = { h.VersionMajor, h.VersionMinor };
  AddBytes(fieldData, "LAS Version", version, 2);
  AddBytes(fieldData, "LAS Point Format", &h.PointFormat, 1);
  AddShorts(fieldData, "LAS Point Record Length", { h.RecordLength });
  AddDoubles(fieldData, "LAS Scale", h.Scale);
  AddDoubles(fieldData, "LAS Offset", h.Offset);
  AddShorts(fieldData, "LAS File Source Id", { h.FileSourceId });
  AddShorts(fieldData, "LAS Global Encoding", { h.GlobalEncoding });
  AddBytes(fieldData, "LAS Project Id", h.ProjectId, 16);
  AddString(fieldData, "LAS System Identifier", h.SystemIdentifier);
  AddString(fieldData, "LAS Generating Software", h.GeneratingSoftware);
  AddShorts(fieldData, "LAS Creation Day And Year", { h.CreationDay, h.CreationYear });
  const std::vector<std::uint8_t> vlrs = pcbilateral::EncodeLASRecords(info.VLRs, false);
  AddBytes(fieldData, "LAS VLRs", vlrs.data(), vlrs.size());
  if (!info.EVLRs.empty())
  {
    const std::vector<std::uint8_t> evlrs = pcbilateral::EncodeLASRecords(info.EVLRs, true);
    AddBytes(fieldData, "LAS EVLRs", evlrs.data(), evlrs.size());
  }
  // The coordinate system as text, for people (the writer uses the records themselves).
  std::string wkt;
  if (pcbilateral::FindLASCoordinateSystemWKT(info, wkt))
  {
    AddString(fieldData, "LAS CRS WKT", wkt);
  }
}

bool vtkLASLoadFileInfo(vtkFieldData* fieldData,
  pcbilateral::LASFileInfo& info,
  std::string& problem)
{
  problem.clear();
  info = pcbilateral::LASFileInfo();
  std::vector<double> version, format, length, scale, offset, values;
  if (!fieldData || !GetValues(fieldData, "LAS Point Format", 1, format))
  {
    return false;
  }
  if (!GetValues(fieldData, "LAS Version", 2, version) ||
      !GetValues(fieldData, "LAS Point Record Length", 1, length) ||
      !GetValues(fieldData, "LAS Scale", 3, scale) ||
      !GetValues(fieldData, "LAS Offset", 3, offset))
  {
    problem = "the input's LAS field data is incomplete (LAS Version, Point Record Length, "
              "Scale and Offset are needed with LAS Point Format)";
    return false;
  }
  pcbilateral::LASHeader& h = info.Header;
  if (format[0] < 0 || format[0] > 10 || length[0] < 0 || length[0] > 65535 || version[0] != 1 ||
      version[1] < 0 || version[1] > 4)
  {
    problem =
      "the input's LAS field data gives an unsupported version, point format or record length";
    return false;
  }
  h.VersionMajor = 1;
  h.VersionMinor = static_cast<std::uint8_t>(version[1]);
  h.PointFormat = static_cast<std::uint8_t>(format[0]);
  h.RecordLength = static_cast<std::uint16_t>(length[0]);
  for (int k = 0; k < 3; ++k)
  {
    h.Scale[k] = scale[k];
    h.Offset[k] = offset[k];
  }
  if (GetValues(fieldData, "LAS File Source Id", 1, values))
  {
    h.FileSourceId = static_cast<std::uint16_t>(values[0]);
  }
  if (GetValues(fieldData, "LAS Global Encoding", 1, values))
  {
    h.GlobalEncoding = static_cast<std::uint16_t>(values[0]);
  }
  if (GetValues(fieldData, "LAS Project Id", 16, values))
  {
    for (int k = 0; k < 16; ++k)
    {
      h.ProjectId[k] = static_cast<std::uint8_t>(values[k]);
    }
  }
  if (GetValues(fieldData, "LAS Creation Day And Year", 2, values))
  {
    h.CreationDay = static_cast<std::uint16_t>(values[0]);
    h.CreationYear = static_cast<std::uint16_t>(values[1]);
  }
  h.SystemIdentifier = GetString(fieldData, "LAS System Identifier");
  h.GeneratingSoftware = GetString(fieldData, "LAS Generating Software");
  if (!GetRecords(fieldData, "LAS VLRs", false, info.VLRs) ||
      !GetRecords(fieldData, "LAS EVLRs", true, info.EVLRs))
  {
    problem = "the input's LAS VLRs or EVLRs field data does not hold whole records";
    return false;
  }
  problem = pcbilateral::LASDimensionsFor(h.PointFormat,
    h.RecordLength,
    pcbilateral::LASExtraBytesRecords(info.VLRs, info.EVLRs),
    info.Dimensions);
  if (!problem.empty())
  {
    problem = "the input's LAS field data: " + problem;
    return false;
  }
  return true;
}

std::string vtkLASInformationNotHeld(vtkFieldData* fieldData)
{
  if (!fieldData || !fieldData->GetAbstractArray("LAS Scale"))
  {
    return std::string();
  }
  bool coordinateSystem = fieldData->GetAbstractArray("LAS CRS WKT") != nullptr;
  pcbilateral::LASFileInfo info;
  std::string problem;
  if (vtkLASLoadFileInfo(fieldData, info, problem))
  {
    for (const auto* records : { &info.VLRs, &info.EVLRs })
    {
      for (const pcbilateral::LASRecord& record : *records)
      {
        coordinateSystem = coordinateSystem || record.UserId == "LASF_Projection";
      }
    }
  }
  return coordinateSystem ? "the LAS file's coordinate system (CRS), scale and offset"
                          : "the LAS file's scale and offset";
}

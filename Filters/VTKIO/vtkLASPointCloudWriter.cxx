#include "vtkLASPointCloudWriter.h"

#include "LASWriter.h"
#include "vtkLASPointCloudFieldData.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkErrorCode.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

vtkStandardNewMacro(vtkLASPointCloudWriter);

namespace
{
template<typename T>
void Convert(vtkDataArray* array, double factor, std::vector<std::uint8_t>& buffer)
{
  const vtkIdType values = array->GetNumberOfValues();
  buffer.resize(static_cast<std::size_t>(values) * sizeof(T));
  T* out = reinterpret_cast<T*>(buffer.data());
  const int components = array->GetNumberOfComponents();
  for (vtkIdType k = 0; k < values; ++k)
  {
    double value = array->GetComponent(k / components, static_cast<int>(k % components)) * factor;
    if (std::numeric_limits<T>::is_integer)
    {
      // Rounded and clamped to the field's range; NaN becomes 0.
      value = std::isnan(value) ? 0.0 : std::round(value);
      value = std::min<double>(
        std::max<double>(value, static_cast<double>(std::numeric_limits<T>::lowest())),
        static_cast<double>(std::numeric_limits<T>::max()));
    }
    out[k] = static_cast<T>(value);
  }
}

/// The array's values as a packed column of the dimension's type: the array's own memory when
/// it already is one, else a converted copy in `buffer`.
const void* Column(vtkDataArray* array,
  const pcbilateral::LASDimension& dimension,
  std::vector<std::uint8_t>& buffer)
{
  const int type = vtkLASArrayType(dimension.ColumnType);
  if (array->GetDataType() == type && array->HasStandardMemoryLayout())
  {
    return array->GetVoidPointer(0);
  }
  // 8-bit colours (a PLY file's, say) take the whole 16-bit range of LAS colours.
  const double factor =
    dimension.Name == "RGB" && array->GetDataType() == VTK_UNSIGNED_CHAR ? 257.0 : 1.0;
  using T = pcbilateral::LASValueType;
  switch (dimension.ColumnType)
  {
    case T::UInt8:
      Convert<std::uint8_t>(array, factor, buffer);
      break;
    case T::Int8:
      Convert<std::int8_t>(array, factor, buffer);
      break;
    case T::UInt16:
      Convert<std::uint16_t>(array, factor, buffer);
      break;
    case T::Int16:
      Convert<std::int16_t>(array, factor, buffer);
      break;
    case T::UInt32:
      Convert<std::uint32_t>(array, factor, buffer);
      break;
    case T::Int32:
      Convert<std::int32_t>(array, factor, buffer);
      break;
    case T::UInt64:
      Convert<std::uint64_t>(array, factor, buffer);
      break;
    case T::Int64:
      Convert<std::int64_t>(array, factor, buffer);
      break;
    case T::Float32:
      Convert<float>(array, factor, buffer);
      break;
    case T::Float64:
      Convert<double>(array, factor, buffer);
      break;
  }
  return buffer.data();
}
} // namespace

vtkLASPointCloudWriter::vtkLASPointCloudWriter() = default;

vtkLASPointCloudWriter::~vtkLASPointCloudWriter()
{
  this->SetFileName(nullptr);
}

int vtkLASPointCloudWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

void vtkLASPointCloudWriter::WriteData()
{
  this->ErrorMessage.clear();
  vtkPointSet* input = vtkPointSet::SafeDownCast(this->GetInput());
  if (!this->FileName || !*this->FileName)
  {
    this->ErrorMessage = "no file name was given";
  }
  else if (!input)
  {
    this->ErrorMessage = std::string(this->FileName) + ": the input is not a point set";
  }
  const vtkIdType count = input ? input->GetNumberOfPoints() : 0;
  vtkPointData* pointData = input ? input->GetPointData() : nullptr;

  pcbilateral::LASFileInfo info;
  if (this->ErrorMessage.empty() &&
      !vtkLASLoadFileInfo(input->GetFieldData(), info, this->ErrorMessage) &&
      this->ErrorMessage.empty())
  {
    double bounds[6] = { 0, 0, 0, 0, 0, 0 };
    if (count > 0)
    {
      double vtkBounds[6];
      input->GetBounds(vtkBounds);
      for (int axis = 0; axis < 3; ++axis)
      {
        bounds[axis] = vtkBounds[2 * axis];
        bounds[3 + axis] = vtkBounds[2 * axis + 1];
      }
    }
    vtkDataArray* rgb = pointData->GetArray("RGB");
    info = pcbilateral::DefaultLASFileInfo(static_cast<std::size_t>(count),
      bounds,
      pointData->GetArray("GpsTime") != nullptr,
      rgb && rgb->GetNumberOfComponents() == 3);
  }
  else if (!this->ErrorMessage.empty() && this->FileName)
  {
    this->ErrorMessage = std::string(this->FileName) + ": " + this->ErrorMessage;
  }
  if (!this->ErrorMessage.empty())
  {
    vtkErrorMacro(<< this->ErrorMessage);
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }

  // The points in double precision, without a copy when they already are.
  vtkSmartPointer<vtkDataArray> positions;
  if (count > 0)
  {
    positions = input->GetPoints()->GetData();
    if (positions->GetDataType() != VTK_DOUBLE || !positions->HasStandardMemoryLayout())
    {
      auto copy = vtkSmartPointer<vtkDoubleArray>::New();
      copy->DeepCopy(positions);
      positions = copy;
    }
  }
  std::vector<std::vector<std::uint8_t>> buffers(info.Dimensions.size());
  std::vector<const void*> columns(info.Dimensions.size(), nullptr);
  for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
  {
    const pcbilateral::LASDimension& dimension = info.Dimensions[d];
    vtkDataArray* array = pointData->GetArray(dimension.Name.c_str());
    if (count > 0 && array && array->GetNumberOfComponents() == dimension.Components &&
        array->GetNumberOfTuples() == count)
    {
      columns[d] = Column(array, dimension, buffers[d]);
    }
  }
  const double none[3] = { 0, 0, 0 };
  this->ErrorMessage = pcbilateral::WriteLAS(this->FileName,
    info,
    static_cast<std::size_t>(count),
    count > 0 ? static_cast<const double*>(positions->GetVoidPointer(0)) : none,
    columns.data());
  if (!this->ErrorMessage.empty())
  {
    vtkErrorMacro(<< this->ErrorMessage);
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}

void vtkLASPointCloudWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}

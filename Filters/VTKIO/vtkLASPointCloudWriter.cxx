#include "vtkLASPointCloudWriter.h"

#include "LASWriter.h"
#include "vtkLASPointCloudFieldData.h"
#include "vtkPointCloudProgress.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkErrorCode.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
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
    if ((k & 0xFFFFF) == 0 && pcbilateral::ProgressPoint(0, 1))
    {
      return; // aborted (asked every million values): the write stops at its next point
    }
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

/**
 * The points' bounds as the data set's GetBounds gives them, computed a million points at a time
 * (each block's by VTK itself, through a vtkPoints viewing its memory) with the write's abort
 * asked between blocks: on 20 million points the single call took 0.6 to 0.9 s of a busy
 * machine, unasked. The blocks' bounds combine as VTK combines its threads' (a smaller minimum
 * replaces, an equal one does not). Where the points are not one packed array, or a block has
 * no valid coordinate on some axis, the data set's own GetBounds.
 */
void BoundsAskingBetweenBlocks(vtkPointSet* input, double bounds[6])
{
  vtkDataArray* data = input->GetPoints()->GetData();
  const vtkIdType count = data->GetNumberOfTuples();
  constexpr vtkIdType Block = vtkIdType(1) << 20;
  if (!data->HasStandardMemoryLayout() || data->GetNumberOfComponents() != 3 || count <= Block)
  {
    input->GetBounds(bounds);
    return;
  }
  auto* bytes = static_cast<unsigned char*>(data->GetVoidPointer(0));
  const int valueSize = data->GetDataTypeSize();
  for (vtkIdType first = 0; first < count; first += Block)
  {
    if (pcbilateral::ProgressPoint(0, 1))
    {
      return; // aborted: the write stops at its next point
    }
    const vtkIdType points = std::min(Block, count - first);
    auto view =
      vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(data->GetDataType()));
    view->SetNumberOfComponents(3);
    view->SetVoidArray(bytes + 3 * valueSize * first, 3 * points, 1);
    vtkNew<vtkPoints> block;
    block->SetData(view);
    double blockBounds[6];
    block->GetBounds(blockBounds);
    for (int axis = 0; axis < 3; ++axis)
    {
      if (!(blockBounds[2 * axis] <= blockBounds[2 * axis + 1]))
      {
        input->GetBounds(bounds);
        return;
      }
      const bool firstBlock = first == 0;
      bounds[2 * axis] = firstBlock || blockBounds[2 * axis] < bounds[2 * axis]
                           ? blockBounds[2 * axis]
                           : bounds[2 * axis];
      bounds[2 * axis + 1] = firstBlock || blockBounds[2 * axis + 1] > bounds[2 * axis + 1]
                               ? blockBounds[2 * axis + 1]
                               : bounds[2 * axis + 1];
    }
  }
}

/// The header to write: the one a LAS reader kept in the input's field data, else a default
/// one. Returns an empty string or one line naming the file.
std::string LoadFileInfo(const char* fileName,
  vtkPointSet* input,
  const vtkLASPointCloudWriter::CloudSummary& cloud,
  pcbilateral::LASFileInfo& info)
{
  std::string problem;
  if (vtkLASLoadFileInfo(input->GetFieldData(), info, problem))
  {
    return std::string();
  }
  if (!problem.empty())
  {
    return std::string(fileName) + ": " + problem;
  }
  info = pcbilateral::DefaultLASFileInfo(
    static_cast<std::size_t>(cloud.NumberOfPoints), cloud.Bounds, cloud.HasGpsTime, cloud.HasRGB);
  return std::string();
}

/// The points in double precision, without a copy when they already are; null without points.
vtkSmartPointer<vtkDataArray> DoublePositions(vtkPointSet* input)
{
  if (input->GetNumberOfPoints() == 0)
  {
    return nullptr;
  }
  vtkSmartPointer<vtkDataArray> positions = input->GetPoints()->GetData();
  if (positions->GetDataType() != VTK_DOUBLE || !positions->HasStandardMemoryLayout())
  {
    auto copy = vtkSmartPointer<vtkDoubleArray>::New();
    copy->DeepCopy(positions);
    positions = copy;
  }
  return positions;
}

/// Each record field's column: the point array of its name when it has the field's components
/// and a value per point (converted into `buffers` when needed), else null (the field is 0).
std::vector<const void*> Columns(const pcbilateral::LASFileInfo& info,
  vtkPointData* pointData,
  vtkIdType count,
  std::vector<std::vector<std::uint8_t>>& buffers)
{
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
  return columns;
}
/// The point arrays no record field takes (a PLY file's curvature, a filter's outputs...),
/// comma-separated; empty when every array is written. "Colors" is the 8-bit view the LAS
/// reader adds beside a file's 16-bit RGB, written as RGB.
std::string UnwrittenArrays(const pcbilateral::LASFileInfo& info,
  vtkPointData* pointData,
  const std::vector<const void*>& columns)
{
  std::string unwritten;
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    const char* name = pointData->GetArrayName(a) ? pointData->GetArrayName(a) : "";
    // (The 8-bit display colours come from RGB; the filter's ids of the points it kept, when it
    // removed isolated points, are not a point attribute: neither is worth a warning.)
    bool written = (std::strcmp(name, "Colors") == 0 && pointData->GetArray("RGB") != nullptr) ||
                   std::strcmp(name, "vtkOriginalPointIds") == 0;
    for (std::size_t d = 0; d < info.Dimensions.size() && !written; ++d)
    {
      written = columns[d] != nullptr && info.Dimensions[d].Name == name;
    }
    if (!written)
    {
      unwritten += (unwritten.empty() ? "" : ", ") + std::string(*name ? name : "(unnamed)");
    }
  }
  return unwritten;
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

vtkLASPointCloudWriter::CloudSummary vtkLASPointCloudWriter::MeasureCloud(vtkPointSet* input)
{
  CloudSummary cloud;
  if (!input)
  {
    return cloud;
  }
  cloud.NumberOfPoints = input->GetNumberOfPoints();
  if (cloud.NumberOfPoints > 0)
  {
    double vtkBounds[6];
    BoundsAskingBetweenBlocks(input, vtkBounds);
    for (int axis = 0; axis < 3; ++axis)
    {
      cloud.Bounds[axis] = vtkBounds[2 * axis];
      cloud.Bounds[3 + axis] = vtkBounds[2 * axis + 1];
    }
  }
  vtkPointData* pointData = input->GetPointData();
  vtkDataArray* rgb = pointData->GetArray("RGB");
  cloud.HasGpsTime = pointData->GetArray("GpsTime") != nullptr;
  cloud.HasRGB = rgb && rgb->GetNumberOfComponents() == 3;
  return cloud;
}

std::string vtkLASPointCloudWriter::WritePoints(const std::string& problem,
  const std::string& fileName,
  const pcbilateral::LASFileInfo& info,
  std::size_t count,
  const double* positions,
  const void* const* columns,
  bool compressed)
{
  if (!problem.empty())
  {
    return problem;
  }
  return (compressed ? pcbilateral::WriteLAZ : pcbilateral::WriteLAS)(
    fileName, info, count, positions, columns);
}

void vtkLASPointCloudWriter::WriteData()
{
  vtkPointCloudProgress progress(this, this->AbortExecute);
  vtkPointSet* input = vtkPointSet::SafeDownCast(this->GetInput());
  std::string problem;
  if (!this->FileName || !*this->FileName)
  {
    problem = "no file name was given";
  }
  else if (!input)
  {
    problem = std::string(this->FileName) + ": the input is not a point set";
  }
  // Measured even when the input is wrong: the parallel writer measures the whole cloud with
  // the other processes.
  const CloudSummary cloud = this->MeasureCloud(problem.empty() ? input : nullptr);
  pcbilateral::LASFileInfo info;
  if (problem.empty())
  {
    problem = LoadFileInfo(this->FileName, input, cloud, info);
  }
  const vtkIdType count = problem.empty() ? input->GetNumberOfPoints() : 0;
  // (Asked between these steps too; an abort seen here ends the write at its first point.)
  pcbilateral::ProgressPoint(0, 1);
  const vtkSmartPointer<vtkDataArray> positions =
    problem.empty() ? DoublePositions(input) : nullptr;
  pcbilateral::ProgressPoint(0, 1);
  std::vector<std::vector<std::uint8_t>> buffers(info.Dimensions.size());
  std::vector<const void*> columns(info.Dimensions.size(), nullptr);
  if (problem.empty())
  {
    columns = Columns(info, input->GetPointData(), count, buffers);
    const std::string unwritten = UnwrittenArrays(info, input->GetPointData(), columns);
    if (!unwritten.empty())
    {
      vtkWarningMacro(<< this->FileName << ": point format " << int(info.Header.PointFormat)
                      << " has no field for the point arrays " << unwritten
                      << ", which are not written");
    }
  }
  const double none[3] = { 0, 0, 0 };
  // A name ending in .laz (any case) is written compressed.
  const std::string name = this->FileName ? this->FileName : "";
  const bool compressed =
    name.size() >= 4 &&
    std::equal(name.end() - 4,
      name.end(),
      ".laz",
      [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
  this->ErrorMessage = this->WritePoints(problem,
    name,
    info,
    static_cast<std::size_t>(count),
    positions ? static_cast<const double*>(positions->GetVoidPointer(0)) : none,
    columns.data(),
    compressed);
  if (progress.StopAsked() || this->ErrorMessage == pcbilateral::AbortedMessage)
  {
    // Aborted (here, or in another process of a parallel write): no file (the formats write beside
    // it and rename), no error event.
    this->ErrorMessage = pcbilateral::AbortedMessage;
    this->SetErrorCode(vtkErrorCode::UserError);
  }
  else if (!this->ErrorMessage.empty())
  {
    vtkErrorMacro(<< this->ErrorMessage);
    this->SetErrorCode(
      problem.empty() ? vtkErrorCode::CannotOpenFileError : vtkErrorCode::UnknownError);
  }
}

void vtkLASPointCloudWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}

#include "StreamedArrays.h"

#include "LASWriter.h"
#include "OutOfCoreRun.h"
#include "PCDValues.h"
#include "PointCloudText.h"
#include "StreamedFile.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>

namespace pcbilateral
{

double StreamedArray::Value(std::size_t point, unsigned component) const
{
  const std::size_t index = point * this->Type.Count + component;
  return PCDValueAsDouble(this->Type, this->Bytes.data() + index * this->Type.Size);
}

void StreamedArrays::LeaveOutRemoved(const std::vector<std::uint8_t>& removed)
{
  std::size_t kept = 0;
  for (std::size_t i = 0; i < this->NumberOfPoints; ++i)
  {
    if (removed[i])
    {
      continue;
    }
    if (kept != i)
    {
      std::copy_n(&this->Positions[3 * i], 3, &this->Positions[3 * kept]);
      for (StreamedArray& array : this->Arrays)
      {
        const std::size_t bytes = array.Type.Bytes();
        std::copy_n(&array.Bytes[bytes * i], bytes, &array.Bytes[bytes * kept]);
      }
    }
    ++kept;
  }
  this->NumberOfPoints = kept;
  this->Positions.resize(3 * kept);
  for (StreamedArray& array : this->Arrays)
  {
    array.Bytes.resize(array.Type.Bytes() * kept);
  }
}

bool HasExtension(const std::string& path, const char* suffix)
{
  const std::size_t n = std::strlen(suffix);
  return path.size() >= n &&
         std::equal(path.end() - static_cast<std::ptrdiff_t>(n),
           path.end(),
           suffix,
           [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}

namespace
{
bool EndsWith(const std::string& path, const char* suffix)
{
  return HasExtension(path, suffix);
}

bool IsLASName(const std::string& path)
{
  return EndsWith(path, ".las") || EndsWith(path, ".laz");
}

bool IsTextName(const std::string& path)
{
  return EndsWith(path, ".txt") || EndsWith(path, ".xyz");
}

/// The first array named `name` (vtkFieldData::GetArray), or null.
const StreamedArray* FindArray(const StreamedArrays& arrays, const std::string& name)
{
  for (const StreamedArray& array : arrays.Arrays)
  {
    if (array.Name == name)
    {
      return &array;
    }
  }
  return nullptr;
}

/**
 * Each range of `input` at its filtered positions, the removed points left out:
 * `append(range)` gets each and returns an empty string or a problem, which ends the loop.
 */
template<typename Append>
std::string ForEachFilteredArrays(StreamedFile& input,
  OutOfCoreRun& run,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress,
  Append&& append)
{
  const std::uint64_t total = input.GetNumberOfPoints();
  std::string problem;
  StreamedArrays range;
  std::vector<std::uint8_t> removed;
  for (std::uint64_t first = 0; first < total && problem.empty(); first += pointsPerRange)
  {
    const auto count =
      static_cast<std::size_t>(std::min<std::uint64_t>(pointsPerRange, total - first));
    removed.assign(count, 0);
    problem = input.ReadArrays(first, count, range);
    if (problem.empty())
    {
      problem = run.ReadFiltered(first, count, range.Positions.data(), removed.data());
    }
    if (problem.empty())
    {
      range.LeaveOutRemoved(removed);
      problem = append(range);
    }
    if (progress)
    {
      progress(static_cast<double>(first + count) / static_cast<double>(total));
    }
  }
  return problem;
}

/// A LAS column type as a PCD type and size (the types StreamedArray uses).
PCDField LASColumnField(LASValueType type)
{
  static const PCDField fields[] = { { "", 'U', 1, 1 },
    { "", 'I', 1, 1 },
    { "", 'U', 2, 1 },
    { "", 'I', 2, 1 },
    { "", 'U', 4, 1 },
    { "", 'I', 4, 1 },
    { "", 'U', 8, 1 },
    { "", 'I', 8, 1 },
    { "", 'F', 4, 1 },
    { "", 'F', 8, 1 } };
  return fields[static_cast<int>(type)];
}

/// `value` in the column's type as vtkLASPointCloudWriter converts it: integers rounded half
/// away from zero and clamped, NaN as 0.
template<typename T>
void StoreLASValue(double value, std::uint8_t* out)
{
  if (std::numeric_limits<T>::is_integer)
  {
    value = std::isnan(value) ? 0.0 : std::round(value);
    value = std::min<double>(
      std::max<double>(value, static_cast<double>(std::numeric_limits<T>::lowest())),
      static_cast<double>(std::numeric_limits<T>::max()));
  }
  const T stored = static_cast<T>(value);
  std::memcpy(out, &stored, sizeof stored);
}

/// An array's values as a LAS column of `dimension` (vtkLASPointCloudWriter's Column): its bytes
/// when it has the column's type, else converted (8-bit RGB times 257).
void LASColumn(const StreamedArray& array,
  const LASDimension& dimension,
  std::size_t count,
  std::vector<std::uint8_t>& column)
{
  const PCDField type = LASColumnField(dimension.ColumnType);
  if (type.Type == array.Type.Type && type.Size == array.Type.Size)
  {
    column.assign(array.Bytes.begin(), array.Bytes.begin() + count * array.Type.Bytes());
    return;
  }
  const double factor =
    dimension.Name == "RGB" && array.Type.Type == 'U' && array.Type.Size == 1 ? 257.0 : 1.0;
  const std::size_t values = count * array.Type.Count;
  column.resize(values * type.Size);
  for (std::size_t k = 0; k < values; ++k)
  {
    const double value = array.Value(k / array.Type.Count, k % array.Type.Count) * factor;
    VisitPCDType(type,
      [&](auto kind) { StoreLASValue<decltype(kind)>(value, column.data() + k * type.Size); });
  }
}

/// The array each dimension takes (its name, its components), or null.
std::vector<const StreamedArray*> LASDimensionArrays(const LASFileInfo& info,
  const StreamedArrays& layout)
{
  std::vector<const StreamedArray*> arrays(info.Dimensions.size(), nullptr);
  for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
  {
    const StreamedArray* array = FindArray(layout, info.Dimensions[d].Name);
    if (array && static_cast<int>(array->Type.Count) == info.Dimensions[d].Components)
    {
      arrays[d] = array;
    }
  }
  return arrays;
}

/// vtkLASPointCloudWriter's header for a cloud read from no LAS file.
LASFileInfo DefaultInfoFor(const StreamedArrays& layout, std::size_t count, OutOfCoreRun& run)
{
  double bounds[6];
  run.GetFilteredBounds(bounds);
  const StreamedArray* rgb = FindArray(layout, "RGB");
  return DefaultLASFileInfo(
    count, bounds, FindArray(layout, "GpsTime") != nullptr, rgb && rgb->Type.Count == 3);
}

template<typename Writer>
std::string WriteArraysAsLAS(StreamedFile& input,
  OutOfCoreRun& run,
  Writer& writer,
  const std::string& path,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  StreamedArrays layout;
  std::string problem = input.ReadArrays(0, 0, layout);
  const auto count =
    static_cast<std::size_t>(input.GetNumberOfPoints() - run.GetNumberOfRemovedPoints());
  const LASFileInfo info = DefaultInfoFor(layout, count, run);
  problem = problem.empty() ? writer.Open(path, info, count) : problem;
  std::vector<std::vector<std::uint8_t>> columns(info.Dimensions.size());
  std::vector<const void*> pointers(info.Dimensions.size(), nullptr);
  if (problem.empty())
  {
    problem = ForEachFilteredArrays(input,
      run,
      pointsPerRange,
      progress,
      [&](const StreamedArrays& range)
      {
        const std::vector<const StreamedArray*> arrays = LASDimensionArrays(info, range);
        for (std::size_t d = 0; d < arrays.size(); ++d)
        {
          if (arrays[d])
          {
            LASColumn(*arrays[d], info.Dimensions[d], range.NumberOfPoints, columns[d]);
          }
          pointers[d] = arrays[d] ? columns[d].data() : nullptr;
        }
        return writer.Append(range.NumberOfPoints, range.Positions.data(), pointers.data());
      });
  }
  return problem.empty() ? writer.Close() : problem;
}

/// The normals array the text writer writes as columns 4-6 (-R), or null.
const StreamedArray* TextNormals(const StreamedArrays& layout, bool withNormals)
{
  for (const StreamedArray& array : layout.Arrays)
  {
    if (withNormals && array.IsNormals && array.Type.Count == 3)
    {
      return &array;
    }
  }
  return nullptr;
}

/// vtkPointCloudTextWriter's table of a range: positions, normals, every other array's
/// components as columns "name" or "name:k".
void FillTextTable(const StreamedArrays& range, bool withNormals, PointCloudTable& table)
{
  const StreamedArray* normals = TextNormals(range, withNormals);
  table.NumberOfPoints = range.NumberOfPoints;
  table.Positions = range.Positions;
  table.Normals.clear();
  table.ExtraColumns.clear();
  table.ExtraColumnNames.clear();
  for (const StreamedArray& array : range.Arrays)
  {
    for (unsigned c = 0; c < array.Type.Count; ++c)
    {
      std::vector<double> column(range.NumberOfPoints);
      for (std::size_t i = 0; i < range.NumberOfPoints; ++i)
      {
        column[i] = array.Value(i, c);
      }
      if (&array == normals)
      {
        table.Normals.resize(3 * range.NumberOfPoints);
        for (std::size_t i = 0; i < range.NumberOfPoints; ++i)
        {
          table.Normals[3 * i + c] = column[i];
        }
        continue;
      }
      table.ExtraColumns.push_back(std::move(column));
      table.ExtraColumnNames.push_back(
        array.Type.Count > 1 ? array.Name + ":" + std::to_string(c) : array.Name);
    }
  }
}

std::string WriteArraysAsText(StreamedFile& input,
  OutOfCoreRun& run,
  const std::string& path,
  bool withNormals,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  StreamedArrays layout;
  std::string problem = input.ReadArrays(0, 0, layout);
  PointCloudTable table;
  FillTextTable(layout, withNormals, table);
  PointCloudTextStreamWriter writer;
  problem = problem.empty() ? writer.Open(path, table, TextNormals(layout, withNormals) != nullptr)
                            : problem;
  if (problem.empty())
  {
    problem = ForEachFilteredArrays(input,
      run,
      pointsPerRange,
      progress,
      [&](const StreamedArrays& range)
      {
        FillTextTable(range, withNormals, table);
        return writer.Append(table);
      });
  }
  return problem.empty() ? writer.Close() : problem;
}

/// A field of a PCD output: the index of the array it comes from, and the component it takes
/// (-1: every component).
struct PCDSource
{
  std::size_t Array = 0;
  int Component = -1;
};

/// vtkPCDPointCloudWriter's fields for a cloud without a PCD layout: x y z (F4 when every
/// position written is a float), normal_x/y/z of the normals' type, then every other array of a
/// name not taken (spaces as '_'); `sources`: where each field after x y z comes from. (The
/// writer's packed colours come from 8-bit arrays named RGB, RGBA or Colors, which only a PCD or
/// LAS file's reader makes, and those have writers of their own.)
PCDHeader ArraysPCDHeader(const StreamedArrays& layout,
  bool floats,
  std::size_t count,
  std::vector<PCDSource>& sources)
{
  PCDHeader header;
  header.Width = count;
  sources.clear();
  for (const char* name : { "x", "y", "z" })
  {
    header.Fields.push_back(PCDField{ name, 'F', floats ? 4u : 8u, 1 });
  }
  const auto taken = [&](const std::string& name)
  {
    return std::any_of(header.Fields.begin(),
      header.Fields.end(),
      [&](const PCDField& field) { return field.Name == name; });
  };
  std::size_t normals = layout.Arrays.size();
  for (std::size_t a = layout.Arrays.size(); a-- > 0;)
  {
    normals = layout.Arrays[a].IsNormals && layout.Arrays[a].Type.Count == 3 ? a : normals;
  }
  for (int axis = 0; normals < layout.Arrays.size() && axis < 3; ++axis)
  {
    PCDField field = layout.Arrays[normals].Type;
    field.Name = std::string("normal_") + static_cast<char>('x' + axis);
    field.Count = 1;
    header.Fields.push_back(field);
    sources.push_back(PCDSource{ normals, axis });
  }
  for (std::size_t a = 0; a < layout.Arrays.size(); ++a)
  {
    PCDField field = layout.Arrays[a].Type;
    field.Name = layout.Arrays[a].Name;
    std::replace_if(
      field.Name.begin(), field.Name.end(), [](char c) { return c == ' ' || c == '\t'; }, '_');
    if (a != normals && !field.Name.empty() && !taken(field.Name) && !field.IsPadding())
    {
      header.Fields.push_back(field);
      sources.push_back(PCDSource{ a, -1 });
    }
  }
  return header;
}

/// A range as the PCD writer's cloud of ArraysPCDHeader's fields (the header already in
/// `cloud`).
void FillPCDRange(const StreamedArrays& range,
  const std::vector<PCDSource>& sources,
  PCDCloud& cloud)
{
  cloud.NumberOfPoints = range.NumberOfPoints;
  cloud.Positions = range.Positions;
  cloud.Columns.clear();
  for (std::size_t s = 0; s < sources.size(); ++s)
  {
    const PCDField& field = cloud.Header.Fields[3 + s];
    const StreamedArray& array = range.Arrays[sources[s].Array];
    PCDColumn column{ field, std::vector<std::uint8_t>() };
    if (sources[s].Component < 0)
    {
      column.Bytes.assign(
        array.Bytes.begin(), array.Bytes.begin() + range.NumberOfPoints * field.Bytes());
    }
    else
    {
      column.Bytes.resize(range.NumberOfPoints * field.Size);
      for (std::size_t i = 0; i < range.NumberOfPoints; ++i)
      {
        const auto component = static_cast<unsigned>(sources[s].Component);
        StorePCDValue(field, array.Value(i, component), column.Bytes.data() + i * field.Size);
      }
    }
    cloud.Columns.push_back(std::move(column));
  }
}

std::string WriteArraysAsPCD(StreamedFile& input,
  OutOfCoreRun& run,
  const std::string& path,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  StreamedArrays layout;
  std::string problem = input.ReadArrays(0, 0, layout);
  const auto count =
    static_cast<std::size_t>(input.GetNumberOfPoints() - run.GetNumberOfRemovedPoints());
  std::vector<PCDSource> sources;
  PCDCloud cloud;
  cloud.Header = ArraysPCDHeader(layout, run.AreFilteredPositionsFloats(), count, sources);
  PCDBinaryStreamWriter writer;
  problem = problem.empty() ? writer.Open(path, cloud.Header, count) : problem;
  if (problem.empty())
  {
    problem = ForEachFilteredArrays(input,
      run,
      pointsPerRange,
      progress,
      [&](const StreamedArrays& range)
      {
        FillPCDRange(range, sources, cloud);
        return writer.Append(cloud);
      });
  }
  return problem.empty() ? writer.Close() : problem;
}
} // namespace

bool IsArraysOutput(const std::string& path)
{
  return IsLASName(path) || IsTextName(path) || EndsWith(path, ".pcd");
}

std::string WriteStreamedArrays(StreamedFile& input,
  OutOfCoreRun& run,
  const std::string& path,
  bool withNormals,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  if (IsTextName(path))
  {
    return WriteArraysAsText(input, run, path, withNormals, pointsPerRange, progress);
  }
  if (EndsWith(path, ".pcd"))
  {
    return WriteArraysAsPCD(input, run, path, pointsPerRange, progress);
  }
  if (EndsWith(path, ".laz"))
  {
    LAZStreamWriter writer;
    return WriteArraysAsLAS(input, run, writer, path, pointsPerRange, progress);
  }
  LASStreamWriter writer;
  return WriteArraysAsLAS(input, run, writer, path, pointsPerRange, progress);
}

std::string StreamedArraysWarning(const StreamedArrays& layout, const std::string& path)
{
  if (!IsLASName(path))
  {
    return std::string();
  }
  // (vtkLASPointCloudWriter's warning of the arrays no dimension takes; the 8-bit display
  // colours beside RGB and the filter's ids of the points kept are not named.)
  const double bounds[6] = { 0, 0, 0, 0, 0, 0 };
  const StreamedArray* rgb = FindArray(layout, "RGB");
  const LASFileInfo info = DefaultLASFileInfo(
    0, bounds, FindArray(layout, "GpsTime") != nullptr, rgb && rgb->Type.Count == 3);
  const std::vector<const StreamedArray*> written = LASDimensionArrays(info, layout);
  std::string unwritten;
  for (const StreamedArray& array : layout.Arrays)
  {
    if ((array.Name == "Colors" && rgb) ||
        std::find(written.begin(), written.end(), &array) != written.end())
    {
      continue;
    }
    unwritten += (unwritten.empty() ? "" : ", ") + (array.Name.empty() ? "(unnamed)" : array.Name);
  }
  return unwritten.empty()
           ? std::string()
           : path + ": point format " + std::to_string(int(info.Header.PointFormat)) +
               " has no field for the point arrays " + unwritten + ", which are not written";
}

} // namespace pcbilateral

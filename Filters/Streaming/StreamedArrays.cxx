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

std::string ForEachRange(std::uint64_t total,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress,
  const std::function<std::string(std::uint64_t first, std::size_t count)>& range)
{
  std::string problem;
  for (std::uint64_t first = 0; first < total && problem.empty(); first += pointsPerRange)
  {
    const auto count =
      static_cast<std::size_t>(std::min<std::uint64_t>(pointsPerRange, total - first));
    problem = range(first, count);
    if (progress)
    {
      progress(static_cast<double>(first + count) / static_cast<double>(total));
    }
  }
  return problem;
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

bool IsLASPath(const std::string& path)
{
  return HasExtension(path, ".las") || HasExtension(path, ".laz");
}

bool IsTextPath(const std::string& path)
{
  return HasExtension(path, ".txt") || HasExtension(path, ".xyz");
}

namespace
{
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

/// What the writers read: the input, the run's results, the points of a range, the progress.
struct FilteredInput
{
  StreamedFile& Input;
  OutOfCoreRun& Run;
  std::size_t PointsPerRange;
  const std::function<void(double)>& Progress;

  /// The points written: the input's less the removed ones.
  std::size_t Written() const
  {
    return static_cast<std::size_t>(
      this->Input.GetNumberOfPoints() - this->Run.GetNumberOfRemovedPoints());
  }
};

/**
 * Each range of `input` at its filtered positions, the removed points left out, given to
 * `append(range)` (an empty string or a problem, which ends the loop), then `writer` closed:
 * an empty string or the first problem (`opened`: the writer's Open).
 */
template<typename Writer, typename Append>
std::string WriteFilteredRanges(const FilteredInput& from,
  Writer& writer,
  std::string opened,
  Append&& append)
{
  StreamedFile& input = from.Input;
  if (!opened.empty())
  {
    return opened;
  }
  StreamedArrays range;
  std::vector<std::uint8_t> removed;
  const std::string problem = ForEachRange(input.GetNumberOfPoints(),
    from.PointsPerRange,
    from.Progress,
    [&](std::uint64_t first, std::size_t count)
    {
      removed.assign(count, 0);
      std::string read = input.ReadArrays(first, count, range);
      read = read.empty()
               ? from.Run.ReadFiltered(first, count, range.Positions.data(), removed.data())
               : read;
      if (!read.empty())
      {
        return read;
      }
      range.LeaveOutRemoved(removed);
      return append(range);
    });
  return problem.empty() ? writer.Close() : problem;
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
std::string WriteArraysAsLAS(const FilteredInput& from,
  const StreamedArrays& layout,
  Writer& writer,
  const std::string& path)
{
  const LASFileInfo info = DefaultInfoFor(layout, from.Written(), from.Run);
  const std::string problem = writer.Open(path, info, from.Written());
  std::vector<std::vector<std::uint8_t>> columns(info.Dimensions.size());
  std::vector<const void*> pointers(info.Dimensions.size(), nullptr);
  return WriteFilteredRanges(from,
    writer,
    problem,
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

std::string WriteArraysAsText(const FilteredInput& from,
  const StreamedArrays& layout,
  const std::string& path,
  bool withNormals)
{
  PointCloudTable table;
  FillTextTable(layout, withNormals, table);
  PointCloudTextStreamWriter writer;
  const std::string problem = writer.Open(path, table, TextNormals(layout, withNormals) != nullptr);
  return WriteFilteredRanges(from,
    writer,
    problem,
    [&](const StreamedArrays& range)
    {
      FillTextTable(range, withNormals, table);
      return writer.Append(table);
    });
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

std::string WriteArraysAsPCD(const FilteredInput& from,
  const StreamedArrays& layout,
  const std::string& path)
{
  std::vector<PCDSource> sources;
  PCDCloud cloud;
  cloud.Header =
    ArraysPCDHeader(layout, from.Run.AreFilteredPositionsFloats(), from.Written(), sources);
  PCDBinaryStreamWriter writer;
  const std::string problem = writer.Open(path, cloud.Header, from.Written());
  return WriteFilteredRanges(from,
    writer,
    problem,
    [&](const StreamedArrays& range)
    {
      FillPCDRange(range, sources, cloud);
      return writer.Append(cloud);
    });
}
} // namespace

bool IsArraysOutput(const std::string& path)
{
  return IsLASPath(path) || IsTextPath(path) || HasExtension(path, ".pcd");
}

std::string WriteStreamedArrays(StreamedFile& input,
  OutOfCoreRun& run,
  const std::string& path,
  bool withNormals,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  StreamedArrays layout;
  const std::string problem = input.ReadArrays(0, 0, layout);
  const FilteredInput from{ input, run, pointsPerRange, progress };
  if (!problem.empty())
  {
    return problem;
  }
  if (IsTextPath(path))
  {
    return WriteArraysAsText(from, layout, path, withNormals);
  }
  if (HasExtension(path, ".pcd"))
  {
    return WriteArraysAsPCD(from, layout, path);
  }
  if (HasExtension(path, ".laz"))
  {
    LAZStreamWriter writer;
    return WriteArraysAsLAS(from, layout, writer, path);
  }
  LASStreamWriter writer;
  return WriteArraysAsLAS(from, layout, writer, path);
}

std::string StreamedArraysWarning(const StreamedArrays& layout, const std::string& path)
{
  if (!IsLASPath(path))
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

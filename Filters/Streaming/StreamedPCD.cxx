#include "StreamedPCD.h"

#include "PCDValues.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace pcbilateral
{

namespace
{
/// Records between checkpoints.
constexpr std::uint64_t CheckpointRecords = 4096;

bool IsGatheredNormal(const PCDHeader& header, const PCDField& field)
{
  // vtkPCDPointCloudReader gathers normal_x, normal_y and normal_z of one type, one value
  // each, into "Normals"; the writer scatters them back through doubles.
  if (field.Name.size() != 8 || field.Name.compare(0, 7, "normal_") != 0 || field.Count != 1)
  {
    return false;
  }
  int found = 0;
  for (const PCDField& other : header.Fields)
  {
    for (const char* axis : { "normal_x", "normal_y", "normal_z" })
    {
      found += other.Name == axis && other.Count == 1 && other.Type == field.Type &&
               other.Size == field.Size;
    }
  }
  return found == 3 && field.Name[7] >= 'x' && field.Name[7] <= 'z';
}

/// The values of the cursor's line into a record (binary layout), as DecodePCD parses them: an
/// empty string or its message.
std::string ParseRecordLine(const PCDHeader& header, PCDTextCursor& cursor, std::uint8_t* record)
{
  for (const PCDField& field : header.Fields)
  {
    for (unsigned c = 0; c < field.Count; ++c, record += field.Size)
    {
      std::string problem = cursor.ParseValue(field, record);
      if (!problem.empty())
      {
        return problem;
      }
    }
  }
  return cursor.AtLineEnd()
           ? std::string()
           : "line " + std::to_string(cursor.Line) + ": more values than the fields take";
}

/// A value of a field other than x y z and padding as the run in memory writes it back: rgb's
/// alpha byte as 255 (read as RGB, packed again), normals through doubles.
void RewriteValue(const PCDHeader& header, const PCDField& field, std::uint8_t* value)
{
  if (IsPCDPackedColour(field) && field.Name == "rgb")
  {
    const std::uint32_t packed = LoadPCDValue<std::uint32_t>(value) | 0xFF000000u;
    std::memcpy(value, &packed, 4);
  }
  else if (IsGatheredNormal(header, field))
  {
    StorePCDValue(field, PCDValueAsDouble(field, value), value);
  }
}

/// A range of records as the writer's cloud: the filtered positions, then every field that is
/// not x y z or padding, converted as the run in memory's VTK round trip converts it.
PCDCloud RangeAsWritten(const PCDHeader& header,
  const std::vector<std::uint8_t>& records,
  const std::vector<std::uint8_t>& removed,
  std::vector<double>& positions)
{
  const std::size_t stride = header.PointBytes();
  const std::size_t count = records.size() / stride;
  PCDCloud cloud;
  cloud.Header = header;
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (!removed[i])
    {
      kept.push_back(i);
      cloud.Positions.insert(cloud.Positions.end(), &positions[3 * i], &positions[3 * i + 3]);
    }
  }
  cloud.NumberOfPoints = kept.size();
  std::size_t offset = 0;
  for (const PCDField& field : header.Fields)
  {
    const std::size_t bytes = field.Bytes();
    if (!field.IsCoordinate() && !field.IsPadding())
    {
      PCDColumn column{ field, std::vector<std::uint8_t>(kept.size() * bytes) };
      for (std::size_t k = 0; k < kept.size(); ++k)
      {
        const std::uint8_t* value = records.data() + kept[k] * stride + offset;
        if (IsGatheredNormal(header, field))
        {
          StorePCDValue(field, PCDValueAsDouble(field, value), column.Bytes.data() + k * bytes);
        }
        else
        {
          std::copy_n(value, bytes, column.Bytes.data() + k * bytes);
        }
      }
      if (IsPCDPackedColour(field))
      {
        // Read as RGB (or RGBA) channels, written packed again: rgb's alpha byte becomes 255.
        const int channels = field.Name == "rgba" ? 4 : 3;
        column = PackPCDColours(field, UnpackPCDColours(column).data(), channels, kept.size());
      }
      cloud.Columns.push_back(std::move(column));
    }
    offset += bytes;
  }
  return cloud;
}
/// vtkPCDPointCloudReader's arrays of `count` records (binary layout).
void ArraysOfRecords(const PCDHeader& header,
  const std::uint8_t* records,
  std::size_t count,
  std::vector<StreamedArray>& arrays)
{
  arrays.clear();
  const std::size_t stride = header.PointBytes();
  const auto column = [&](std::size_t offset, std::size_t bytes, std::uint8_t* out)
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      std::copy_n(records + i * stride + offset, bytes, out + i * bytes);
    }
  };
  std::size_t offset = 0;
  for (const PCDField& field : header.Fields)
  {
    if (IsGatheredNormal(header, field))
    {
      if (arrays.empty() || !arrays.front().IsNormals)
      {
        arrays.insert(arrays.begin(), StreamedArray{ "Normals", field, true, {} });
        arrays.front().Type.Count = 3;
        arrays.front().Bytes.resize(count * 3 * field.Size);
      }
      std::vector<std::uint8_t> values(count * field.Size);
      column(offset, field.Size, values.data());
      for (std::size_t i = 0; i < count; ++i)
      {
        std::copy_n(&values[i * field.Size],
          field.Size,
          &arrays.front().Bytes[(3 * i + (field.Name[7] - 'x')) * field.Size]);
      }
    }
    else if (IsPCDPackedColour(field))
    {
      PCDColumn packed{ field, std::vector<std::uint8_t>(count * field.Bytes()) };
      column(offset, field.Bytes(), packed.Bytes.data());
      const bool alpha = field.Name == "rgba";
      arrays.push_back(StreamedArray{
        alpha ? "RGBA" : "RGB", PCDField{ "", 'U', 1, alpha ? 4u : 3u }, false, {} });
      arrays.back().Bytes = UnpackPCDColours(packed);
    }
    else if (!field.IsCoordinate() && !field.IsPadding())
    {
      arrays.push_back(StreamedArray{ field.Name, field, false, {} });
      arrays.back().Bytes.resize(count * field.Bytes());
      column(offset, field.Bytes(), arrays.back().Bytes.data());
    }
    offset += field.Bytes();
  }
}

/// The name VTK gives the type of the array vtkPCDPointCloudReader makes of a field of `type`.
std::string VTKTypeName(const PCDField& type)
{
  const bool isSigned = type.Type == 'I';
  switch (type.Type == 'F' ? -static_cast<int>(type.Size) : static_cast<int>(type.Size))
  {
    case -4:
      return "float";
    case -8:
      return "double";
    case 1:
      return isSigned ? "signed char" : "unsigned char";
    case 2:
      return isSigned ? "short" : "unsigned short";
    case 4:
      return isSigned ? "int" : "unsigned int";
    default:
      return isSigned ? "long long" : "unsigned long long";
  }
}
} // namespace

std::string PCDPointSource::ReadArrays(std::uint64_t first,
  std::size_t count,
  StreamedArrays& range)
{
  std::vector<std::uint8_t> records;
  const std::string problem = this->ReadRecords(first, count, records);
  range.NumberOfPoints = count;
  range.Positions.resize(3 * count);
  for (std::size_t i = 0; i < count && problem.empty(); ++i)
  {
    this->RecordPosition(records.data() + i * this->Stride, &range.Positions[3 * i]);
  }
  ArraysOfRecords(this->Header, records.data(), count, range.Arrays);
  return problem;
}

std::string PCDPointSource::WriteWarning(const std::string& path) const
{
  StreamedArrays layout;
  ArraysOfRecords(this->Header, nullptr, 0, layout.Arrays);
  return StreamedArraysWarning(layout, path);
}

std::string PCDLayoutProblem(const PCDHeader& header)
{
  for (const PCDField& field : header.Fields)
  {
    for (const char* name : { "RGB", "RGBA", "Colors", "Normals", "vtkOriginalPointIds" })
    {
      if (field.Name == name)
      {
        return "--memory-limit: a PCD field named '" + field.Name +
               "' is not streamed (the run in memory gives its name to another array)";
      }
    }
  }
  return std::string();
}

void PCDPointSource::Release()
{
  this->Mapped.Release();
}

void PCDPointSource::RecordPosition(const std::uint8_t* record, double* position) const
{
  for (int axis = 0; axis < 3; ++axis)
  {
    position[axis] =
      PCDValueAsDouble(this->CoordinateFields[axis], record + this->CoordinateOffsets[axis]);
  }
}

bool PCDPointSource::IsKept(const std::uint8_t* record) const
{
  if (this->KeepNaN)
  {
    return true;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    if (!std::isfinite(
          PCDValueAsDouble(this->CoordinateFields[axis], record + this->CoordinateOffsets[axis])))
    {
      return false;
    }
  }
  return true;
}

std::string PCDPointSource::Open(const std::string& path, bool withNormals, bool keepNaN)
{
  this->Path = path;
  this->WithNormals = withNormals;
  this->KeepNaN = keepNaN;
  if (!this->Mapped.Open(path).empty())
  {
    return path + ": cannot be opened";
  }
  std::string problem = ParsePCDHeader(
    reinterpret_cast<const char*>(this->Mapped.Data()), this->Mapped.Size(), path, this->Header);
  if (problem.empty() && this->Header.NumberOfPoints > std::numeric_limits<std::size_t>::max() / 64)
  {
    problem = path + ": the header announces more points than the file can hold";
  }
  if (problem.empty())
  {
    problem = PCDLayoutProblem(this->Header);
  }
  if (problem.empty())
  {
    problem = this->CheckData();
  }
  this->Release();
  return problem;
}

void PCDPointSource::FindCoordinates()
{
  this->Stride = this->Header.PointBytes();
  std::size_t offset = 0;
  for (const PCDField& field : this->Header.Fields)
  {
    if (field.IsCoordinate())
    {
      this->CoordinateFields[field.Name[0] - 'x'] = field;
      this->CoordinateOffsets[field.Name[0] - 'x'] = offset;
    }
    offset += field.Bytes();
  }
}

std::string PCDPointSource::CheckSize()
{
  const std::size_t blockSize = this->Mapped.Size() - this->Header.DataOffset;
  const std::uint64_t count = this->Header.NumberOfPoints;
  if (this->Header.Encoding == PCDEncoding::Binary && count > blockSize / this->Stride)
  {
    return this->Path + ": the binary data holds " + std::to_string(blockSize / this->Stride) +
           " points, the header announces " + std::to_string(count);
  }
  std::size_t valuesPerPoint = 0;
  for (const PCDField& field : this->Header.Fields)
  {
    valuesPerPoint += field.Count;
  }
  if (this->Header.Encoding == PCDEncoding::ASCII && count > 0 &&
      count > (blockSize + 1) / valuesPerPoint)
  {
    return this->Path + ": the ascii data holds fewer than the " + std::to_string(count) +
           " points the header announces";
  }
  if (this->Header.Encoding == PCDEncoding::BinaryCompressed)
  {
    const std::string problem = this->Decompress();
    if (!problem.empty())
    {
      return problem;
    }
  }
  return std::string();
}

std::string PCDPointSource::CheckData()
{
  this->FindCoordinates();
  const auto* block = reinterpret_cast<const char*>(this->Mapped.Data()) + this->Header.DataOffset;
  const std::size_t blockSize = this->Mapped.Size() - this->Header.DataOffset;
  const std::uint64_t count = this->Header.NumberOfPoints;
  this->FirstLine = 1 + static_cast<std::size_t>(std::count(
                          reinterpret_cast<const char*>(this->Mapped.Data()), block, '\n'));
  const std::string problem = this->CheckSize();
  if (!problem.empty())
  {
    return problem;
  }
  // One pass over every record: the checkpoints, the points kept, and (ascii) every value
  // parsed, so that a damaged line is found before anything is written.
  std::vector<std::uint8_t> records;
  this->Kept = 0;
  this->Checkpoints.clear();
  PCDTextCursor cursor{ block, block + blockSize, this->FirstLine };
  for (std::uint64_t first = 0; first < count; first += CheckpointRecords)
  {
    Checkpoint checkpoint;
    checkpoint.Record = first;
    checkpoint.KeptBefore = this->Kept;
    checkpoint.Offset = static_cast<std::size_t>(cursor.At - block);
    checkpoint.Line = cursor.Line;
    this->Checkpoints.push_back(checkpoint);
    const auto n = static_cast<std::size_t>(std::min(CheckpointRecords, count - first));
    records.resize(n * this->Stride);
    if (this->Header.Encoding != PCDEncoding::ASCII)
    {
      for (std::size_t i = 0; i < n; ++i)
      {
        this->CopyRecord(first + i, records.data() + i * this->Stride);
      }
    }
    else
    {
      for (std::size_t i = 0; i < n; ++i)
      {
        std::uint8_t* record = records.data() + i * this->Stride;
        if (!cursor.NextLine())
        {
          return this->Path + ": the ascii data holds " + std::to_string(first + i) +
                 " points, the header announces " + std::to_string(count);
        }
        const std::string problem = ParseRecordLine(this->Header, cursor, record);
        if (!problem.empty())
        {
          return this->Path + ": " + problem;
        }
      }
    }
    for (std::size_t i = 0; i < n; ++i)
    {
      this->Kept += this->IsKept(records.data() + i * this->Stride);
    }
    if (this->Checkpoints.size() % 256 == 0)
    {
      this->Release(); // (the pages read so far: the pass holds a range, not the file)
    }
  }
  if (this->Header.Encoding == PCDEncoding::ASCII && cursor.NextLine())
  {
    return this->Path + ": line " + std::to_string(cursor.Line) +
           ": more points than the header announces (" + std::to_string(count) + ")";
  }
  return std::string();
}

std::string PCDPointSource::Decompress()
{
  const std::uint64_t count = this->Header.NumberOfPoints;
  const std::uint8_t* block = this->Mapped.Data() + this->Header.DataOffset;
  const std::size_t blockSize = this->Mapped.Size() - this->Header.DataOffset;
  const std::string problem = DecompressPCDFields(
    block, blockSize, this->Header, static_cast<std::size_t>(count), this->Fields);
  this->Release(); // (the compressed pages: the decompressed fields are what the run holds)
  if (!problem.empty())
  {
    return this->Path + ": " + problem;
  }
  std::size_t start = 0;
  for (const PCDField& field : this->Header.Fields)
  {
    this->FieldStarts.push_back(start);
    start += static_cast<std::size_t>(count) * field.Bytes();
  }
  return std::string();
}

void PCDPointSource::CopyRecord(std::uint64_t record, std::uint8_t* out) const
{
  if (this->Header.Encoding == PCDEncoding::Binary)
  {
    std::copy_n(
      this->Mapped.Data() + this->Header.DataOffset + record * this->Stride, this->Stride, out);
    return;
  }
  for (std::size_t f = 0; f < this->Header.Fields.size(); ++f)
  {
    const std::size_t bytes = this->Header.Fields[f].Bytes();
    out = std::copy_n(this->Fields.data() + this->FieldStarts[f] + record * bytes, bytes, out);
  }
}

std::string PCDPointSource::ReadRecords(std::uint64_t first,
  std::size_t count,
  std::vector<std::uint8_t>& records)
{
  records.resize(count * this->Stride);
  if (count == 0)
  {
    return std::string();
  }
  const auto after = std::upper_bound(this->Checkpoints.begin(),
    this->Checkpoints.end(),
    first,
    [](std::uint64_t kept, const Checkpoint& c) { return kept < c.KeptBefore; });
  const Checkpoint& start = *(after - 1);
  // Binary search lands on the last checkpoint with KeptBefore <= first; earlier checkpoints
  // with the same count (all their points NaN) hold none of the range.
  const auto* block = reinterpret_cast<const char*>(this->Mapped.Data()) + this->Header.DataOffset;
  const std::size_t blockSize = this->Mapped.Size() - this->Header.DataOffset;
  PCDTextCursor cursor{ block + start.Offset, block + blockSize, start.Line };
  std::uint64_t kept = start.KeptBefore;
  std::size_t filled = 0;
  for (std::uint64_t record = start.Record; filled < count && record < this->Header.NumberOfPoints;
       ++record)
  {
    std::uint8_t* out = records.data() + filled * this->Stride;
    if (this->Header.Encoding != PCDEncoding::ASCII)
    {
      this->CopyRecord(record, out);
    }
    else
    {
      // (Every line was checked by Open.)
      cursor.NextLine();
      ParseRecordLine(this->Header, cursor, out);
    }
    if (this->IsKept(out) && kept++ >= first)
    {
      ++filled;
    }
  }
  this->Release();
  return filled == count ? std::string() : this->Path + ": changed while it was read";
}

std::string PCDPointSource::ReadPositions(std::uint64_t first, std::size_t count, double* positions)
{
  std::vector<std::uint8_t> records;
  const std::string problem = this->ReadRecords(first, count, records);
  for (std::size_t i = 0; i < count && problem.empty(); ++i)
  {
    this->RecordPosition(records.data() + i * this->Stride, positions + 3 * i);
  }
  if (!problem.empty() || this->Classes.empty())
  {
    return problem;
  }
  std::vector<std::uint8_t> chosen(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    const std::uint8_t* value = records.data() + i * this->Stride + this->ClassOffset;
    chosen[i] = IsChosenClass(this->Classes, PCDValueAsDouble(this->ClassField, value));
  }
  this->LeaveAlone(first, count, chosen.data(), positions);
  return problem;
}

std::string PCDPointSource::ChooseClasses(const std::string& name,
  const std::vector<long long>& classes)
{
  // (The arrays the run in memory's filter looks the name up in: the reader's.)
  std::vector<StreamedArray> arrays;
  ArraysOfRecords(this->Header, nullptr, 0, arrays);
  const auto array = std::find_if(
    arrays.begin(), arrays.end(), [&](const StreamedArray& a) { return a.Name == name; });
  if (array == arrays.end())
  {
    return MissingClassArrayProblem(name);
  }
  if (array->Type.Count != 1 || array->Type.Type == 'F')
  {
    return ClassArrayTypeProblem(name, array->Type.Count, VTKTypeName(array->Type));
  }
  std::size_t offset = 0;
  for (const PCDField& field : this->Header.Fields)
  {
    if (field.Name == name)
    {
      this->ClassField = field;
      this->ClassOffset = offset;
    }
    offset += field.Bytes();
  }
  this->ClassName = name;
  this->Classes = classes;
  return std::string();
}

std::string PCDPointSource::WriteFiltered(OutOfCoreRun& run,
  const std::string& path,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  if (!HasExtension(path, ".pcd"))
  {
    return WriteStreamedArrays(*this, run, path, this->WithNormals, pointsPerRange, progress);
  }
  if (this->Header.Encoding == PCDEncoding::BinaryCompressed)
  {
    return this->WriteCompressed(run, path, pointsPerRange, progress);
  }
  PCDBinaryStreamWriter writer;
  const std::uint64_t total = this->Kept;
  std::string problem = writer.Open(path,
    this->Header,
    static_cast<std::size_t>(total - run.GetNumberOfRemovedPoints()),
    this->Header.Encoding);
  std::vector<std::uint8_t> records, removed;
  std::vector<double> positions;
  for (std::uint64_t first = 0; first < total && problem.empty(); first += pointsPerRange)
  {
    const auto count =
      static_cast<std::size_t>(std::min<std::uint64_t>(pointsPerRange, total - first));
    positions.resize(3 * count);
    removed.assign(count, 0);
    problem = this->ReadRecords(first, count, records);
    for (std::size_t i = 0; i < count && problem.empty(); ++i)
    {
      this->RecordPosition(records.data() + i * this->Stride, &positions[3 * i]);
    }
    if (problem.empty())
    {
      problem = run.ReadFiltered(first, count, positions.data(), removed.data());
    }
    if (problem.empty())
    {
      problem = writer.Append(RangeAsWritten(this->Header, records, removed, positions));
    }
    if (progress)
    {
      progress(static_cast<double>(first + count) / static_cast<double>(total));
    }
  }
  return problem.empty() ? writer.Close() : problem;
}

std::size_t PCDPointSource::MoveToFront(const std::vector<bool>& written)
{
  // Field by field: a field's values move only to places before their own, and after the
  // fields already moved, so nothing unread is overwritten.
  const auto count = static_cast<std::size_t>(std::count(written.begin(), written.end(), true));
  const std::vector<PCDField>& fields = this->Header.Fields;
  std::size_t outStart = 0;
  for (std::size_t f = 0; f < fields.size(); ++f)
  {
    const std::size_t bytes = fields[f].Bytes();
    std::size_t k = 0;
    for (std::size_t r = 0; r < written.size(); ++r)
    {
      if (written[r])
      {
        std::memmove(this->Fields.data() + outStart + k++ * bytes,
          this->Fields.data() + this->FieldStarts[f] + r * bytes,
          bytes);
      }
    }
    outStart += count * bytes;
  }
  return count;
}

std::string PCDPointSource::WriteCompressed(OutOfCoreRun& run,
  const std::string& path,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  const std::uint64_t total = this->Header.NumberOfPoints;
  const std::vector<PCDField>& fields = this->Header.Fields;
  std::vector<bool> written(static_cast<std::size_t>(total), false);
  std::vector<std::uint64_t> records;
  std::vector<double> positions;
  std::vector<std::uint8_t> removed, record(this->Stride);
  std::uint64_t first = 0;
  for (std::uint64_t next = 0; next < total || !records.empty();)
  {
    // (The positions as read: with --keep-nan the points without coordinates pass through.)
    for (positions.clear(); next < total && records.size() < pointsPerRange; ++next)
    {
      this->CopyRecord(next, record.data());
      if (this->IsKept(record.data()))
      {
        records.push_back(next);
        positions.resize(positions.size() + 3);
        this->RecordPosition(record.data(), &positions[positions.size() - 3]);
      }
    }
    removed.assign(records.size(), 0);
    std::string problem = run.ReadFiltered(first, records.size(), positions.data(), removed.data());
    if (!problem.empty())
    {
      return problem;
    }
    for (std::size_t i = 0; i < records.size(); ++i)
    {
      written[records[i]] = !removed[i];
      for (std::size_t f = 0; f < fields.size(); ++f)
      {
        std::uint8_t* value =
          this->Fields.data() + this->FieldStarts[f] + records[i] * fields[f].Bytes();
        if (fields[f].IsCoordinate())
        {
          StorePCDValue(fields[f], positions[3 * i + (fields[f].Name[0] - 'x')], value);
        }
        else if (fields[f].IsPadding())
        {
          std::fill_n(value, fields[f].Bytes(), 0);
        }
        else
        {
          RewriteValue(this->Header, fields[f], value);
        }
      }
    }
    first += records.size();
    records.clear();
    if (progress)
    {
      progress(0.9 * static_cast<double>(next) / static_cast<double>(total));
    }
  }
  const std::size_t count = this->MoveToFront(written);
  const std::string problem =
    WritePCDCompressedFields(path, this->Header, count, this->Fields.data());
  if (progress)
  {
    progress(1.0);
  }
  return problem;
}

} // namespace pcbilateral

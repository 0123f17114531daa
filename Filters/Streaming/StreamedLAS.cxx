#include "StreamedLAS.h"

#include "LASPointFormat.h"
#include "LASReader.h"
#include "LASWriter.h"
#include "LAZReader.h"
#include "PCDFile.h"
#include "PointCloudText.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

namespace pcbilateral
{

namespace
{
/// Value `i` of a column of `type`, as a double.
double ColumnValue(LASValueType type, const std::uint8_t* column, std::size_t i)
{
  auto at = [&](auto kind)
  {
    decltype(kind) value;
    std::memcpy(&value, column + i * sizeof value, sizeof value);
    return static_cast<double>(value);
  };
  switch (type)
  {
    case LASValueType::UInt8:
      return at(std::uint8_t());
    case LASValueType::Int8:
      return at(std::int8_t());
    case LASValueType::UInt16:
      return at(std::uint16_t());
    case LASValueType::Int16:
      return at(std::int16_t());
    case LASValueType::UInt32:
      return at(std::uint32_t());
    case LASValueType::Int32:
      return at(std::int32_t());
    case LASValueType::UInt64:
      return at(std::uint64_t());
    case LASValueType::Int64:
      return at(std::int64_t());
    case LASValueType::Float32:
      return at(float());
    case LASValueType::Float64:
      return at(double());
  }
  return 0.0;
}

bool EndsWith(const std::string& path, const char* suffix)
{
  return HasExtension(path, suffix);
}

bool IsLAZName(const std::string& path)
{
  return EndsWith(path, ".laz");
}

bool IsTextName(const std::string& path)
{
  return EndsWith(path, ".txt") || EndsWith(path, ".xyz");
}
} // namespace

std::string LASPointSource::Open(const std::string& path, const COPCQuery* part)
{
  this->Path = path;
  const std::string mapped = this->Mapped.Open(path);
  if (!mapped.empty())
  {
    return path + ": " + mapped;
  }
  std::string problem =
    ParseLASHeader(this->Mapped.Data(), this->Mapped.Size(), path, this->Info, true);
  if (problem.empty() && part && IsCOPC(this->Info))
  {
    problem = this->OpenCOPCPart(*part);
  }
  this->Release();
  return problem;
}

std::string LASPointSource::OpenCOPCPart(const COPCQuery& part)
{
  COPCHierarchy hierarchy;
  std::string problem =
    ReadCOPCHierarchy(this->Mapped.Data(), this->Mapped.Size(), this->Info, this->Path, hierarchy);
  this->Part = true;
  this->Query = part;
  for (const COPCNode& node : SelectCOPCNodes(hierarchy, this->Info.Header, part))
  {
    this->PartChunks.push_back(node.Chunk);
    this->PartFirst.push_back(this->PartFirst.back() + node.Chunk.Points);
  }
  for (std::size_t node = 0; node < this->PartChunks.size() && part.UseBounds; ++node)
  {
    // (The points inside the box are known once the node is decoded.)
    std::vector<std::uint8_t> records;
    problem = problem.empty() ? this->ReadPartNode(node, records) : problem;
    this->PartFirst[node + 1] =
      this->PartFirst[node] + records.size() / this->Info.Header.RecordLength;
    this->Mapped.Release();
  }
  return problem;
}

std::string LASPointSource::ReadPartNode(std::size_t node, std::vector<std::uint8_t>& records)
{
  const LASHeader& h = this->Info.Header;
  const LAZChunk& chunk = this->PartChunks[node];
  records.resize(static_cast<std::size_t>(chunk.Points) * h.RecordLength);
  const std::string problem =
    DecompressLAZChunks(this->Mapped.Data(), this->Info, this->Path, { chunk }, records.data());
  if (!problem.empty())
  {
    records.clear();
  }
  else if (this->Query.UseBounds)
  {
    const std::uint64_t inside =
      KeepCOPCPointsInside(h, this->Query.Bounds, records.data(), chunk.Points);
    records.resize(static_cast<std::size_t>(inside) * h.RecordLength);
  }
  return problem;
}

std::string LASPointSource::ReadPartRecords(std::uint64_t first, std::size_t count)
{
  const std::size_t length = this->Info.Header.RecordLength;
  this->Decompressed.resize(count * length);
  const std::vector<std::uint64_t>& starts = this->PartFirst;
  auto node = static_cast<std::size_t>(
    std::upper_bound(starts.begin(), starts.end(), first) - starts.begin());
  node = node > 0 ? node - 1 : 0;
  std::size_t done = 0;
  for (; done < count && node + 1 < starts.size(); ++node)
  {
    const std::uint64_t from = first + done - starts[node];
    if (starts[node + 1] == starts[node] || from >= starts[node + 1] - starts[node])
    {
      continue;
    }
    if (node != this->CachedNode)
    {
      const std::string problem = this->ReadPartNode(node, this->CachedRecords);
      this->CachedNode = problem.empty() ? node : static_cast<std::size_t>(-1);
      if (!problem.empty())
      {
        return problem;
      }
    }
    const auto take = static_cast<std::size_t>(
      std::min<std::uint64_t>(count - done, starts[node + 1] - starts[node] - from));
    std::copy_n(this->CachedRecords.data() + from * length,
      take * length,
      this->Decompressed.data() + done * length);
    done += take;
  }
  return done == count ? std::string()
                       : this->Path + ": points beyond the COPC part were asked for";
}

void LASPointSource::Release()
{
  this->Mapped.Release();
  std::vector<std::uint8_t>().swap(this->Decompressed);
}

std::string LASPointSource::ReadPositions(std::uint64_t first, std::size_t count, double* positions)
{
  std::vector<void*> columns(this->Info.Dimensions.size(), nullptr);
  if (this->Classes.empty())
  {
    return this->ReadPoints(first, count, positions, columns.data());
  }
  const LASDimension& dimension = this->Info.Dimensions[this->ClassDimension];
  std::vector<std::uint8_t> values(count * LASColumnBytes(dimension));
  columns[this->ClassDimension] = values.data();
  const std::string problem = this->ReadPoints(first, count, positions, columns.data());
  if (!problem.empty())
  {
    return problem;
  }
  std::vector<std::uint8_t> chosen(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    // (As the filter in memory: integers compared as doubles, exact below 2^53.)
    chosen[i] = IsChosenClass(this->Classes, ColumnValue(dimension.ColumnType, values.data(), i));
  }
  this->LeaveAlone(first, count, chosen.data(), positions);
  return problem;
}

std::string LASPointSource::ChooseClasses(const std::string& name,
  const std::vector<long long>& classes)
{
  for (std::size_t d = 0; d < this->Info.Dimensions.size(); ++d)
  {
    const LASDimension& dimension = this->Info.Dimensions[d];
    if (dimension.Name != name)
    {
      continue;
    }
    const LASValueType type = dimension.ColumnType;
    if (dimension.Components != 1 || type == LASValueType::Float32 || type == LASValueType::Float64)
    {
      // (The run in memory's words, with the names VTK gives the reader's arrays' types.)
      static const char* const typeNames[] = { "unsigned char",
        "signed char",
        "unsigned short",
        "short",
        "unsigned int",
        "int",
        "unsigned long",
        "long",
        "float",
        "double" };
      return ClassArrayTypeProblem(
        name, static_cast<unsigned>(dimension.Components), typeNames[static_cast<int>(type)]);
    }
    this->ClassDimension = d;
    this->ClassName = name;
    this->Classes = classes;
    return std::string();
  }
  return MissingClassArrayProblem(name);
}

std::string LASPointSource::ReadPoints(std::uint64_t first,
  std::size_t count,
  double* positions,
  void* const* columns)
{
  const std::uint8_t* records = this->Decompressed.data();
  const std::string problem = this->Part ? this->ReadPartRecords(first, count)
                                         : UncompressedLASRecordRange(this->Mapped.Data(),
                                             this->Mapped.Size(),
                                             this->Info,
                                             this->Path,
                                             first,
                                             count,
                                             this->Decompressed,
                                             records);
  if (this->Part)
  {
    records = this->Decompressed.data();
  }
  if (problem.empty())
  {
    DecodeLASPoints(this->Info, records, count, positions, columns);
  }
  this->Release();
  return problem;
}

std::string LASPointSource::WriteFiltered(OutOfCoreRun& run,
  const std::string& path,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  if (EndsWith(path, ".pcd"))
  {
    return WriteStreamedLASAsPCD(*this, run, path, pointsPerRange, progress);
  }
  return IsTextName(path) ? WriteStreamedLASAsText(*this, run, path, pointsPerRange, progress)
                          : WriteStreamedLAS(*this, run, path, pointsPerRange, progress);
}

std::string LASPointSource::WriteWarning(const std::string& path) const
{
  const bool pcd = EndsWith(path, ".pcd");
  if (!IsTextName(path) && !pcd)
  {
    return std::string();
  }
  bool coordinateSystem = false;
  for (const auto* records : { &this->Info.VLRs, &this->Info.EVLRs })
  {
    for (const LASRecord& record : *records)
    {
      coordinateSystem = coordinateSystem || record.UserId == "LASF_Projection";
    }
  }
  // (The run in memory's words: vtkPointCloudTextWriter and vtkPCDPointCloudWriter,
  // vtkLASInformationNotHeld.)
  return path + (pcd ? ": a PCD file cannot hold " : ": a text file cannot hold ") +
         (coordinateSystem ? "the LAS file's coordinate system (CRS), scale and offset"
                           : "the LAS file's scale and offset") +
         (pcd ? ", which are not written" : ", which are not written (the coordinates are)");
}

std::string LASPointSource::ColoursFitEightBits(bool& fit)
{
  // (Of the whole file, also for a COPC part: the run in memory's reader looks at the points it
  // did not read when those it read fit 8 bits.)
  const std::string problem = LASColoursFitEightBits(this->Mapped.Data(),
    this->Mapped.Size(),
    this->Info,
    this->Path,
    0,
    this->Info.Header.NumberOfPoints,
    fit);
  this->Release();
  return problem;
}

LASFileInfo LASInfoAsWritten(const LASFileInfo& info)
{
  LASFileInfo written;
  LASHeader& h = written.Header;
  const LASHeader& read = info.Header;
  h.VersionMajor = 1;
  h.VersionMinor = read.VersionMinor;
  h.PointFormat = read.PointFormat;
  h.RecordLength = read.RecordLength;
  std::copy_n(read.Scale, 3, h.Scale);
  std::copy_n(read.Offset, 3, h.Offset);
  h.FileSourceId = read.FileSourceId;
  h.GlobalEncoding = read.GlobalEncoding;
  std::copy_n(read.ProjectId, 16, h.ProjectId);
  h.CreationDay = read.CreationDay;
  h.CreationYear = read.CreationYear;
  h.SystemIdentifier = read.SystemIdentifier;
  h.GeneratingSoftware = read.GeneratingSoftware;
  written.VLRs = info.VLRs;
  written.EVLRs = info.EVLRs;
  LASDimensionsFor(h.PointFormat,
    h.RecordLength,
    LASExtraBytesRecords(written.VLRs, written.EVLRs),
    written.Dimensions);
  return written;
}

namespace
{
/// Whether the file's points have colours (the RGB dimension).
bool HasRGB(const LASFileInfo& info)
{
  return std::any_of(info.Dimensions.begin(),
    info.Dimensions.end(),
    [](const LASDimension& dimension) { return dimension.Name == "RGB"; });
}

/// Moves the records of the points not `removed` (--remove-isolated) to the front of the
/// positions and columns, in order; returns how many there are.
std::size_t LeaveOutRemoved(const LASFileInfo& info,
  const std::vector<std::uint8_t>& removed,
  std::vector<double>& positions,
  std::vector<std::vector<std::uint8_t>>& columns)
{
  const std::size_t count = positions.size() / 3;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (removed[i])
    {
      continue;
    }
    if (kept != i)
    {
      std::copy_n(&positions[3 * i], 3, &positions[3 * kept]);
      for (std::size_t d = 0; d < columns.size(); ++d)
      {
        const std::size_t bytes = LASColumnBytes(info.Dimensions[d]);
        std::copy_n(&columns[d][bytes * i], bytes, &columns[d][bytes * kept]);
      }
    }
    ++kept;
  }
  return kept;
}

/**
 * The records of `input`, a range at a time, at their filtered positions, the removed points
 * left out: `append(kept, positions, columns, pointers)` gets each range (its first `kept`
 * positions and column records) and returns an empty string or a problem, which ends the loop.
 */
template<typename Append>
std::string ForEachFilteredRange(LASPointSource& input,
  OutOfCoreRun& run,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress,
  Append&& append)
{
  const LASFileInfo& info = input.GetInfo();
  const std::uint64_t total = input.GetNumberOfPoints();
  std::vector<double> positions;
  std::vector<std::vector<std::uint8_t>> columns(info.Dimensions.size());
  std::vector<void*> pointers(info.Dimensions.size());
  std::vector<std::uint8_t> removed(pointsPerRange);
  return ForEachRange(total,
    pointsPerRange,
    progress,
    [&](std::uint64_t first, std::size_t count)
    {
      positions.resize(3 * count);
      for (std::size_t d = 0; d < columns.size(); ++d)
      {
        columns[d].resize(count * LASColumnBytes(info.Dimensions[d]));
        pointers[d] = columns[d].data();
      }
      std::string problem = input.ReadPoints(first, count, positions.data(), pointers.data());
      if (problem.empty())
      {
        problem = run.ReadFiltered(first, count, positions.data(), removed.data());
      }
      if (problem.empty())
      {
        const std::size_t kept = LeaveOutRemoved(info, removed, positions, columns);
        problem = append(kept, positions, columns, pointers);
      }
      return problem;
    });
}

/// The records of `input` at their filtered positions into `writer` (a LASStreamWriter or a
/// LAZStreamWriter).
template<typename Writer>
std::string WriteRanges(LASPointSource& input,
  OutOfCoreRun& run,
  Writer& writer,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  const std::string problem = ForEachFilteredRange(input,
    run,
    pointsPerRange,
    progress,
    [&](std::size_t kept,
      std::vector<double>& positions,
      std::vector<std::vector<std::uint8_t>>&,
      std::vector<void*>& pointers)
    { return writer.Append(kept, positions.data(), pointers.data()); });
  return problem.empty() ? writer.Close() : problem;
}
} // namespace

std::string WriteStreamedLAS(LASPointSource& input,
  OutOfCoreRun& run,
  const std::string& path,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  const LASFileInfo written = LASInfoAsWritten(input.GetInfo());
  const std::uint64_t total = input.GetNumberOfPoints() - run.GetNumberOfRemovedPoints();
  if (IsLAZName(path))
  {
    LAZStreamWriter writer;
    const std::string problem = writer.Open(path, written, total);
    return problem.empty() ? WriteRanges(input, run, writer, pointsPerRange, progress) : problem;
  }
  LASStreamWriter writer;
  const std::string problem = writer.Open(path, written, total);
  return problem.empty() ? WriteRanges(input, run, writer, pointsPerRange, progress) : problem;
}

namespace
{
/// The text columns the run in memory writes for a LAS file (vtkLASPointCloudReader's arrays
/// through vtkPointCloudTextWriter): each dimension's components, named "Name" or "Name:k",
/// then, with RGB, the 8-bit display colours "Colors:0" to "Colors:2".
PointCloudTable LASTextHeader(const LASFileInfo& info, bool colours)
{
  PointCloudTable header;
  for (const LASDimension& dimension : info.Dimensions)
  {
    for (int c = 0; c < dimension.Components; ++c)
    {
      header.ExtraColumnNames.push_back(
        dimension.Components > 1 ? dimension.Name + ":" + std::to_string(c) : dimension.Name);
    }
  }
  for (int c = 0; colours && c < 3; ++c)
  {
    header.ExtraColumnNames.push_back("Colors:" + std::to_string(c));
  }
  header.ExtraColumns.resize(header.ExtraColumnNames.size());
  return header;
}

/// The first `kept` points' columns into `table` (laid out by LASTextHeader), as doubles; the
/// display colours are the RGB values' high bytes, or the values when `eightBit`.
void FillTextColumns(const LASFileInfo& info,
  const std::vector<std::vector<std::uint8_t>>& columns,
  std::size_t kept,
  bool eightBit,
  PointCloudTable& table)
{
  std::size_t next = 0;
  for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
  {
    const LASDimension& dimension = info.Dimensions[d];
    const auto components = static_cast<std::size_t>(dimension.Components);
    for (std::size_t c = 0; c < components; ++c)
    {
      std::vector<double>& column = table.ExtraColumns[next++];
      column.resize(kept);
      for (std::size_t i = 0; i < kept; ++i)
      {
        column[i] = ColumnValue(dimension.ColumnType, columns[d].data(), i * components + c);
      }
    }
    if (dimension.Name == "RGB" && next + 3 <= table.ExtraColumns.size())
    {
      for (std::size_t c = 0; c < 3; ++c)
      {
        std::vector<double>& colour = table.ExtraColumns[table.ExtraColumns.size() - 3 + c];
        colour.resize(kept);
        for (std::size_t i = 0; i < kept; ++i)
        {
          const auto value = static_cast<unsigned>(table.ExtraColumns[next - 3 + c][i]);
          colour[i] = static_cast<unsigned char>(eightBit ? value : value >> 8);
        }
      }
    }
  }
}
} // namespace

std::string WriteStreamedLASAsText(LASPointSource& input,
  OutOfCoreRun& run,
  const std::string& path,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  const LASFileInfo& info = input.GetInfo();
  const bool colours = HasRGB(info);
  bool eightBit = false;
  std::string problem = input.ColoursFitEightBits(eightBit);
  PointCloudTable table = LASTextHeader(info, colours);
  PointCloudTextStreamWriter writer;
  problem = problem.empty() ? writer.Open(path, table, false) : problem;
  if (problem.empty())
  {
    problem = ForEachFilteredRange(input,
      run,
      pointsPerRange,
      progress,
      [&](std::size_t kept,
        std::vector<double>& positions,
        std::vector<std::vector<std::uint8_t>>& columns,
        std::vector<void*>&)
      {
        table.Positions.swap(positions);
        table.NumberOfPoints = kept;
        table.Positions.resize(3 * kept);
        FillTextColumns(info, columns, kept, eightBit, table);
        const std::string appended = writer.Append(table);
        table.Positions.swap(positions);
        return appended;
      });
  }
  return problem.empty() ? writer.Close() : problem;
}

namespace
{
/// A LAS column type's PCD type and size (as vtkPCDFieldType gives them for the VTK arrays the
/// LAS reader makes).
PCDField PCDFieldOf(const LASDimension& dimension)
{
  static const struct
  {
    char Type;
    unsigned Size;
  } types[] = { { 'U', 1 },
    { 'I', 1 },
    { 'U', 2 },
    { 'I', 2 },
    { 'U', 4 },
    { 'I', 4 },
    { 'U', 8 },
    { 'I', 8 },
    { 'F', 4 },
    { 'F', 8 } };
  const auto kind = types[static_cast<int>(dimension.ColumnType)];
  PCDField field{
    dimension.Name, kind.Type, kind.Size, static_cast<unsigned>(dimension.Components)
  };
  std::replace_if(
    field.Name.begin(), field.Name.end(), [](char c) { return c == ' ' || c == '\t'; }, '_');
  return field;
}

/// The fields the run in memory writes for a LAS file (vtkPCDPointCloudWriter of the LAS
/// reader's arrays, no layout read): x y z (F4 when every position written is a float, else
/// F8), `rgb` packed from the 8-bit display colours with RGB, then each dimension whose name is
/// not taken (`written`: which are).
PCDHeader LASPCDHeader(const LASFileInfo& info,
  bool floats,
  bool colours,
  std::size_t count,
  std::vector<bool>& written)
{
  PCDHeader header;
  header.Width = count;
  for (const char* name : { "x", "y", "z" })
  {
    header.Fields.push_back(PCDField{ name, 'F', floats ? 4u : 8u, 1 });
  }
  if (colours)
  {
    header.Fields.push_back(PCDField{ "rgb", 'F', 4, 1 });
  }
  written.assign(info.Dimensions.size(), false);
  for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
  {
    const PCDField field = PCDFieldOf(info.Dimensions[d]);
    const bool taken = std::any_of(header.Fields.begin(),
      header.Fields.end(),
      [&](const PCDField& other) { return other.Name == field.Name; });
    if (!taken && !field.IsPadding())
    {
      header.Fields.push_back(field);
      written[d] = true;
    }
  }
  return header;
}

/// The first `kept` points' values into `range` (fields of LASPCDHeader).
void FillPCDColumns(const LASFileInfo& info,
  const std::vector<std::vector<std::uint8_t>>& columns,
  const std::vector<bool>& written,
  bool colours,
  bool eightBit,
  std::size_t kept,
  PCDCloud& range)
{
  range.Columns.clear();
  range.NumberOfPoints = kept;
  for (std::size_t d = 0; d < info.Dimensions.size() && colours; ++d)
  {
    if (info.Dimensions[d].Name != "RGB")
    {
      continue;
    }
    std::vector<std::uint8_t> display(3 * kept);
    for (std::size_t i = 0; i < 3 * kept; ++i)
    {
      const auto value =
        static_cast<unsigned>(ColumnValue(LASValueType::UInt16, columns[d].data(), i));
      display[i] = static_cast<std::uint8_t>(eightBit ? value : value >> 8);
    }
    range.Columns.push_back(PackPCDColours(PCDField{ "rgb", 'F', 4, 1 }, display.data(), 3, kept));
  }
  for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
  {
    if (written[d])
    {
      const std::size_t bytes = kept * LASColumnBytes(info.Dimensions[d]);
      range.Columns.push_back(PCDColumn{ PCDFieldOf(info.Dimensions[d]),
        std::vector<std::uint8_t>(columns[d].begin(), columns[d].begin() + bytes) });
    }
  }
}
} // namespace

std::string WriteStreamedLASAsPCD(LASPointSource& input,
  OutOfCoreRun& run,
  const std::string& path,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  const LASFileInfo& info = input.GetInfo();
  const bool colours = HasRGB(info);
  bool eightBit = false;
  std::string problem = input.ColoursFitEightBits(eightBit);
  const std::uint64_t total = input.GetNumberOfPoints();
  std::vector<bool> written;
  PCDCloud range;
  range.Header = LASPCDHeader(info,
    run.AreFilteredPositionsFloats(),
    colours,
    static_cast<std::size_t>(total - run.GetNumberOfRemovedPoints()),
    written);
  PCDBinaryStreamWriter writer;
  problem = problem.empty() ? writer.Open(path, range.Header, range.Header.Width) : problem;
  if (problem.empty())
  {
    problem = ForEachFilteredRange(input,
      run,
      pointsPerRange,
      progress,
      [&](std::size_t kept,
        std::vector<double>& positions,
        std::vector<std::vector<std::uint8_t>>& columns,
        std::vector<void*>&)
      {
        range.Positions.swap(positions);
        range.Positions.resize(3 * kept);
        FillPCDColumns(info, columns, written, colours, eightBit, kept, range);
        const std::string appended = writer.Append(range);
        range.Positions.swap(positions);
        return appended;
      });
  }
  return problem.empty() ? writer.Close() : problem;
}

} // namespace pcbilateral

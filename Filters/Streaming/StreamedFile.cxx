#include "StreamedFile.h"

#include "PointCloudText.h"
#include "StreamedLAS.h"
#include "StreamedPCD.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>

namespace pcbilateral
{

namespace
{
bool EndsWith(const std::string& name, const char* suffix)
{
  return HasExtension(name, suffix);
}

/// Moves the rows of the points not `removed` (--remove-isolated) to the front, in order, and
/// drops the others.
void LeaveOutRemoved(const std::vector<std::uint8_t>& removed, PointCloudTable& table)
{
  std::size_t kept = 0;
  const bool normals = !table.Normals.empty();
  for (std::size_t i = 0; i < table.NumberOfPoints; ++i)
  {
    if (removed[i])
    {
      continue;
    }
    if (kept != i)
    {
      std::copy_n(&table.Positions[3 * i], 3, &table.Positions[3 * kept]);
      if (normals)
      {
        std::copy_n(&table.Normals[3 * i], 3, &table.Normals[3 * kept]);
      }
      for (std::vector<double>& column : table.ExtraColumns)
      {
        column[kept] = column[i];
      }
    }
    ++kept;
  }
  table.NumberOfPoints = kept;
  table.Positions.resize(3 * kept);
  table.Normals.resize(normals ? 3 * kept : 0);
  for (std::vector<double>& column : table.ExtraColumns)
  {
    column.resize(kept);
  }
}

/// A text file (x y z, then further columns) read and written back a range at a time.
class TextPointSource : public StreamedFile
{
public:
  /// `orientedNormals` (-R): columns 4-6 are normals, read and written back as normals (a line
  /// with fewer than 6 columns is the run in memory's error).
  std::string Open(const std::string& path, bool orientedNormals)
  {
    this->WithNormals = orientedNormals;
    return this->Text.Open(path, orientedNormals);
  }
  std::uint64_t GetNumberOfPoints() const override { return this->Text.GetNumberOfPoints(); }
  std::string ReadPositions(std::uint64_t first, std::size_t count, double* positions) override
  {
    const std::string problem = this->Text.Read(first, count, this->Range);
    std::copy(this->Range.Positions.begin(), this->Range.Positions.end(), positions);
    return problem;
  }
  std::string WriteFiltered(OutOfCoreRun& run,
    const std::string& path,
    std::size_t pointsPerRange,
    const std::function<void(double)>& progress) override;
  std::string ReadArrays(std::uint64_t first, std::size_t count, StreamedArrays& range) override;
  /// The run in memory's error: a text file's columns are doubles, never a class array.
  std::string ChooseClasses(const std::string& name, const std::vector<long long>&) override
  {
    StreamedArrays layout;
    this->AddArrays(this->Text.GetHeader(), layout);
    for (const StreamedArray& array : layout.Arrays)
    {
      if (array.Name == name)
      {
        return ClassArrayTypeProblem(name, array.Type.Count, "double");
      }
    }
    return MissingClassArrayProblem(name);
  }
  std::string WriteWarning(const std::string& path) const override
  {
    StreamedArrays layout;
    this->AddArrays(this->Text.GetHeader(), layout);
    return StreamedArraysWarning(layout, path);
  }

private:
  /// vtkPointCloudTextReader's arrays of `table`: the normals (-R), then the extra columns,
  /// those named "name:0", "name:1"... one array of as many components.
  void AddArrays(const PointCloudTable& table, StreamedArrays& range) const;

  PointCloudTextStream Text;
  PointCloudTable Range;
  bool WithNormals = false;
};

void TextPointSource::AddArrays(const PointCloudTable& table, StreamedArrays& range) const
{
  const std::size_t count = table.NumberOfPoints;
  range.Arrays.clear();
  const auto add = [&](const std::string& name, unsigned components, bool normals)
  {
    range.Arrays.push_back(StreamedArray{ name, PCDField{ "", 'F', 8, components }, normals, {} });
    range.Arrays.back().Bytes.resize(count * components * sizeof(double));
    return reinterpret_cast<double*>(range.Arrays.back().Bytes.data());
  };
  if (this->WithNormals)
  {
    std::copy_n(table.Normals.data(), 3 * count, add("Normals", 3, true));
  }
  const std::vector<std::string>& names = this->Text.GetHeader().ExtraColumnNames;
  for (std::size_t column = 0; column < names.size();)
  {
    const std::string& first = names[column];
    unsigned components = 1;
    const bool numbered = first.size() > 2 && first.compare(first.size() - 2, 2, ":0") == 0;
    const std::string base = numbered ? first.substr(0, first.size() - 1) : first;
    while (numbered && column + components < names.size() &&
           names[column + components] == base + std::to_string(components))
    {
      ++components;
    }
    double* values =
      add(components == 1 ? first : first.substr(0, first.size() - 2), components, false);
    for (unsigned c = 0; c < components && count > 0; ++c)
    {
      for (std::size_t i = 0; i < count; ++i)
      {
        values[i * components + c] = table.ExtraColumns[column + c][i];
      }
    }
    column += components;
  }
}

std::string TextPointSource::ReadArrays(std::uint64_t first,
  std::size_t count,
  StreamedArrays& range)
{
  const std::string problem = count > 0 ? this->Text.Read(first, count, this->Range) : "";
  if (count == 0)
  {
    this->Range.NumberOfPoints = 0;
    this->Range.Positions.clear();
  }
  range.NumberOfPoints = this->Range.NumberOfPoints;
  range.Positions = this->Range.Positions;
  this->AddArrays(this->Range, range);
  return problem;
}

std::string TextPointSource::WriteFiltered(OutOfCoreRun& run,
  const std::string& path,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  if (!IsTextPath(path))
  {
    return WriteStreamedArrays(*this, run, path, this->WithNormals, pointsPerRange, progress);
  }
  PointCloudTextStreamWriter writer;
  std::string problem = writer.Open(path, this->Text.GetHeader(), this->WithNormals);
  const std::uint64_t total = this->GetNumberOfPoints();
  std::vector<std::uint8_t> removed;
  for (std::uint64_t first = 0; first < total && problem.empty(); first += pointsPerRange)
  {
    const auto count =
      static_cast<std::size_t>(std::min<std::uint64_t>(pointsPerRange, total - first));
    problem = this->Text.Read(first, count, this->Range);
    removed.resize(count);
    if (problem.empty())
    {
      problem = run.ReadFiltered(first, count, this->Range.Positions.data(), removed.data());
    }
    if (problem.empty())
    {
      LeaveOutRemoved(removed, this->Range);
      problem = writer.Append(this->Range);
    }
    if (progress)
    {
      progress(static_cast<double>(first + count) / static_cast<double>(total));
    }
  }
  return problem.empty() ? writer.Close() : problem;
}
} // namespace

bool IsChosenClass(const std::vector<long long>& classes, double value)
{
  return std::find_if(classes.begin(),
           classes.end(),
           [value](long long c) { return static_cast<double>(c) == value; }) != classes.end();
}

std::string ClassArrayTypeProblem(const std::string& name,
  unsigned components,
  const std::string& typeName)
{
  return "the class array '" + name + "' must hold one integer per point (it has " +
         std::to_string(components) + " component(s) of type " + typeName + ")";
}

std::string MissingClassArrayProblem(const std::string& name)
{
  return "classes were chosen, but the input has no point array '" + name + "'";
}

std::string StreamingFormatsProblem(const std::string& input, const std::string& output)
{
  if ((IsLASPath(input) || IsTextPath(input) || EndsWith(input, ".pcd")) && IsArraysOutput(output))
  {
    return std::string();
  }
  return "streaming reads .las, .laz, .txt, .xyz or .pcd into .las, .laz, .txt, .xyz or .pcd "
         "(not yet PLY or VTP)";
}

std::size_t StreamedRangePoints()
{
  // (For tests: ranges that cut a LAZ file's chunks on a small file.)
  const char* text = std::getenv("PCB_STREAMING_RANGE_POINTS");
  const unsigned long long points = text ? std::strtoull(text, nullptr, 10) : 0;
  return points > 0 ? static_cast<std::size_t>(points) : std::size_t(1) << 18;
}

std::unique_ptr<StreamedFile> OpenStreamedFile(const std::string& input,
  const std::string& output,
  bool orientedNormals,
  bool keepNaN,
  const COPCQuery* copcPart,
  std::string& problem)
{
  problem = StreamingFormatsProblem(input, output);
  if (!problem.empty())
  {
    return nullptr;
  }
  std::unique_ptr<StreamedFile> file;
  bool isCOPCPart = false;
  if (IsLASPath(input))
  {
    auto las = std::make_unique<LASPointSource>();
    problem = las->Open(input, copcPart);
    isCOPCPart = las->IsCOPCPart();
    file = std::move(las);
  }
  else if (EndsWith(input, ".pcd"))
  {
    auto pcd = std::make_unique<PCDPointSource>();
    problem = pcd->Open(input, orientedNormals, keepNaN);
    file = std::move(pcd);
  }
  else
  {
    auto text = std::make_unique<TextPointSource>();
    problem = text->Open(input, orientedNormals);
    file = std::move(text);
  }
  if (copcPart && !isCOPCPart)
  {
    // (The run in memory's warning, vtkPointCloudFileIO's and vtkLASPointCloudReader's.)
    file->SetReadWarning(input + ": not a COPC file: the COPC level and bounds apply to COPC "
                                 "files only; every point is read");
  }
  return problem.empty() ? std::move(file) : nullptr;
}

} // namespace pcbilateral

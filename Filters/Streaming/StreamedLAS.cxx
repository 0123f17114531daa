#include "StreamedLAS.h"

#include "LASPointFormat.h"
#include "LASReader.h"
#include "LASWriter.h"
#include "LAZReader.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <memory>
#include <vector>

namespace pcbilateral
{

namespace
{
bool IsLAZName(const std::string& path)
{
  return path.size() >= 4 &&
         std::equal(path.end() - 4,
           path.end(),
           ".laz",
           [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}
} // namespace

LASPointSource::~LASPointSource()
{
  if (this->Data != nullptr && this->Size > 0)
  {
    ::munmap(const_cast<std::uint8_t*>(this->Data), this->Size);
  }
}

std::string LASPointSource::Open(const std::string& path)
{
  this->Path = path;
  const int descriptor = ::open(path.c_str(), O_RDONLY);
  struct stat status;
  if (descriptor < 0 || ::fstat(descriptor, &status) != 0)
  {
    const std::string problem = path + ": " + std::strerror(errno);
    if (descriptor >= 0)
    {
      ::close(descriptor);
    }
    return problem;
  }
  this->Size = static_cast<std::size_t>(status.st_size);
  // Mapped, not populated: only the pages of the ranges read come in (Release gives them back).
  void* mapped = this->Size > 0 ? ::mmap(nullptr, this->Size, PROT_READ, MAP_PRIVATE, descriptor, 0)
                                : MAP_FAILED;
  ::close(descriptor);
  if (mapped == MAP_FAILED)
  {
    this->Size = 0;
    return path + ": cannot be mapped for reading (" + std::strerror(errno) + ")";
  }
  this->Data = static_cast<const std::uint8_t*>(mapped);
  const std::string problem = ParseLASHeader(this->Data, this->Size, path, this->Info, true);
  this->Release();
  return problem;
}

void LASPointSource::Release()
{
  if (this->Data != nullptr && this->Size > 0)
  {
    ::madvise(const_cast<std::uint8_t*>(this->Data), this->Size, MADV_DONTNEED);
  }
  std::vector<std::uint8_t>().swap(this->Decompressed);
}

std::string LASPointSource::ReadPositions(std::uint64_t first, std::size_t count, double* positions)
{
  const std::vector<void*> none(this->Info.Dimensions.size(), nullptr);
  return this->ReadPoints(first, count, positions, none.data());
}

std::string LASPointSource::ReadPoints(std::uint64_t first,
  std::size_t count,
  double* positions,
  void* const* columns)
{
  const std::uint8_t* records = nullptr;
  const std::string problem = UncompressedLASRecordRange(
    this->Data, this->Size, this->Info, this->Path, first, count, this->Decompressed, records);
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
  return WriteStreamedLAS(*this, run, path, pointsPerRange, progress);
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
/// The records of `input`, a range at a time, at their filtered positions, into `writer` (a
/// LASStreamWriter or a LAZStreamWriter).
template<typename Writer>
std::string WriteRanges(LASPointSource& input,
  OutOfCoreRun& run,
  Writer& writer,
  std::size_t pointsPerRange,
  const std::function<void(double)>& progress)
{
  const LASFileInfo& info = input.GetInfo();
  const std::uint64_t total = input.GetNumberOfPoints();
  std::string problem;
  std::vector<double> positions;
  std::vector<std::vector<std::uint8_t>> columns(info.Dimensions.size());
  std::vector<void*> pointers(info.Dimensions.size());
  for (std::uint64_t first = 0; first < total && problem.empty(); first += pointsPerRange)
  {
    const auto count =
      static_cast<std::size_t>(std::min<std::uint64_t>(pointsPerRange, total - first));
    positions.resize(3 * count);
    for (std::size_t d = 0; d < columns.size(); ++d)
    {
      columns[d].resize(count * LASColumnBytes(info.Dimensions[d]));
      pointers[d] = columns[d].data();
    }
    problem = input.ReadPoints(first, count, positions.data(), pointers.data());
    if (problem.empty())
    {
      problem = run.ReadFiltered(first, count, positions.data());
    }
    if (problem.empty())
    {
      problem = writer.Append(count, positions.data(), pointers.data());
    }
    if (progress)
    {
      progress(static_cast<double>(first + count) / static_cast<double>(total));
    }
  }
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
  const std::uint64_t total = input.GetNumberOfPoints();
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

} // namespace pcbilateral

// One LAS or LAZ file written by every process of a distributed run, each its own points, with
// the pieces of the formats library (LASWriteParts.h). This file only communicates: it shares
// the counts, sizes and summaries the parts need and decides every failure collectively.
//
// Every function here that communicates is collective: all processes call it in the same order,
// and a failure on one process is shared (by a reduction) before anyone acts on it, so no
// process is left waiting for another that gave up.
#include "vtkPLASPointCloudWriter.h"

#include "LASWriteParts.h"
#include "LAZWriter.h"
#include "ProgressCheck.h"
#include "ReplacingPath.h"

#include "vtkCommunicator.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>
#include <vector>

vtkStandardNewMacro(vtkPLASPointCloudWriter);
vtkCxxSetObjectMacro(vtkPLASPointCloudWriter, Controller, vtkMultiProcessController);

namespace
{
using pcbilateral::LASPartSummary;

/// Whether `here` holds on any process.
bool AnyProcess(vtkMultiProcessController* controller, bool here)
{
  const int local = here ? 1 : 0;
  int any = 0;
  controller->AllReduce(&local, &any, 1, vtkCommunicator::MAX_OP);
  return any != 0;
}

/// `text` as process 0 has it, on every process.
std::string BroadcastString(vtkMultiProcessController* controller, const std::string& text)
{
  vtkIdType length = static_cast<vtkIdType>(text.size());
  controller->Broadcast(&length, 1, 0);
  std::vector<char> bytes(text.begin(), text.end());
  bytes.resize(static_cast<std::size_t>(length) + 1);
  controller->Broadcast(bytes.data(), length + 1, 0);
  return std::string(bytes.data(), static_cast<std::size_t>(length));
}

/// Whether the processes agree on what their records are made of.
bool SameRecords(vtkMultiProcessController* controller, const pcbilateral::LASFileInfo& info)
{
  const auto& h = info.Header;
  const double local[9] = { double(h.PointFormat),
    double(h.RecordLength),
    h.Scale[0],
    h.Scale[1],
    h.Scale[2],
    h.Offset[0],
    h.Offset[1],
    h.Offset[2],
    double(info.Dimensions.size()) };
  double lowest[9], highest[9];
  controller->AllReduce(local, lowest, 9, vtkCommunicator::MIN_OP);
  controller->AllReduce(local, highest, 9, vtkCommunicator::MAX_OP);
  return std::equal(lowest, lowest + 9, highest);
}

/// Every process's value of `local`, in process order.
std::vector<long long> GatherCounts(vtkMultiProcessController* controller, long long local)
{
  std::vector<long long> all(static_cast<std::size_t>(controller->GetNumberOfProcesses()));
  controller->AllGather(&local, all.data(), 1);
  return all;
}

/// The summary of the whole file, from every process's part, merged in process order.
LASPartSummary ShareSummaries(vtkMultiProcessController* controller, const LASPartSummary& part)
{
  const int processes = controller->GetNumberOfProcesses();
  long long counts[17] = { static_cast<long long>(part.Count), part.OutOfRange ? 1 : 0 };
  for (int r = 0; r < 15; ++r)
  {
    counts[2 + r] = static_cast<long long>(part.PointsByReturn[r]);
  }
  std::vector<long long> allCounts(17 * static_cast<std::size_t>(processes));
  std::vector<double> allBounds(6 * static_cast<std::size_t>(processes));
  controller->AllGather(counts, allCounts.data(), 17);
  controller->AllGather(part.Bounds, allBounds.data(), 6);
  LASPartSummary whole;
  for (int p = 0; p < processes; ++p)
  {
    LASPartSummary other;
    const long long* c = allCounts.data() + 17 * p;
    other.Count = static_cast<std::uint64_t>(c[0]);
    other.OutOfRange = c[1] != 0;
    for (int r = 0; r < 15; ++r)
    {
      other.PointsByReturn[r] = static_cast<std::uint64_t>(c[2 + r]);
    }
    std::copy_n(allBounds.data() + 6 * p, 6, other.Bounds);
    pcbilateral::MergeLASPartSummary(whole, other);
  }
  return whole;
}

/// Writes `bytes` at byte `offset` of `file`; returns an empty string or why not.
std::string WriteAt(std::FILE* file, std::uint64_t offset, const std::vector<std::uint8_t>& bytes)
{
  errno = 0;
  if (fseeko(file, static_cast<off_t>(offset), SEEK_SET) != 0 ||
      std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size())
  {
    return std::string("write failed (") + std::strerror(errno ? errno : EIO) + ")";
  }
  return std::string();
}

/**
 * The one file every process writes: process 0 creates it beside its destination, every
 * process opens it for update and writes its part, and process 0 moves it onto the destination
 * once every process closed it without an error (or removes it).
 */
class SharedFile
{
public:
  SharedFile(vtkMultiProcessController* controller, const std::string& path)
    : Controller(controller)
    , Path(path)
  {
  }

  ~SharedFile()
  {
    if (this->File)
    {
      std::fclose(this->File);
    }
  }

  /// Collective. Returns an empty string or one line, the same on every process.
  std::string Open()
  {
    std::string problem;
    std::string temporary;
    if (this->Controller->GetLocalProcessId() == 0)
    {
      this->Destination.reset(new pcbilateral::ReplacingPath(this->Path));
      temporary = this->Destination->GetTemporaryPath();
      std::FILE* created = std::fopen(temporary.c_str(), "wb");
      problem = created ? std::string() : this->Destination->OpenError(errno);
      if (created)
      {
        std::fclose(created);
      }
    }
    problem = BroadcastString(this->Controller, problem);
    temporary = BroadcastString(this->Controller, temporary);
    if (!problem.empty())
    {
      return problem;
    }
    this->File = std::fopen(temporary.c_str(), "r+b");
    const int error = errno;
    if (AnyProcess(this->Controller, this->File == nullptr))
    {
      return this->Path + ": cannot be written by every process (" +
             (this->File ? std::string("see the other processes' errors")
                         : std::string(std::strerror(error))) +
             ")";
    }
    return std::string();
  }

  std::FILE* Get() const { return this->File; }

  /// Collective: closes the file and, when no process has a `problem`, moves it onto the
  /// destination. Returns an empty string or one line.
  std::string Close(std::string problem)
  {
    const bool closed = std::fclose(this->File) == 0;
    this->File = nullptr;
    if (!closed && problem.empty())
    {
      problem = this->Path + ": write failed (" + std::strerror(errno) + ")";
    }
    const bool anyFailed = AnyProcess(this->Controller, !problem.empty());
    std::string committed;
    if (this->Controller->GetLocalProcessId() == 0)
    {
      committed = this->Destination->Commit(!anyFailed);
    }
    committed = BroadcastString(this->Controller, committed);
    if (!problem.empty())
    {
      return problem;
    }
    return anyFailed ? this->Path + ": another process could not write its part (see its "
                                    "error); no file was written"
                     : committed;
  }

private:
  vtkMultiProcessController* Controller;
  std::string Path;
  std::unique_ptr<pcbilateral::ReplacingPath> Destination;
  std::FILE* File = nullptr;
};

/// What every process knows of the file before writing it.
struct Plan
{
  std::string Path;
  const pcbilateral::LASFileInfo* Info;
  const pcbilateral::LASPartsLayout* Layout;
  std::uint64_t Total;
  std::uint64_t First; // the points of the processes before this one
};

/// A LAS file: each process's records at the file's point data plus the points before it.
std::string WriteLASParts(vtkMultiProcessController* controller,
  const Plan& plan,
  std::size_t count,
  const double* positions,
  const void* const* columns)
{
  SharedFile file(controller, plan.Path);
  std::string problem = file.Open();
  if (!problem.empty())
  {
    return problem;
  }
  const std::uint64_t recordLength = plan.Info->Header.RecordLength;
  const std::uint64_t start = plan.Layout->PointDataOffset();
  LASPartSummary part;
  problem = pcbilateral::WriteLASPart(
    file.Get(), start + plan.First * recordLength, *plan.Info, count, positions, columns, part);
  const LASPartSummary whole = ShareSummaries(controller, part);
  if (controller->GetLocalProcessId() == 0 && problem.empty() && !whole.OutOfRange)
  {
    const std::uint64_t pointBytes = plan.Total * recordLength;
    problem = WriteAt(file.Get(), 0, plan.Layout->Head(whole, pointBytes));
    if (problem.empty())
    {
      problem = WriteAt(file.Get(), start + pointBytes, plan.Layout->Tail());
    }
  }
  return file.Close(problem.empty() ? problem : plan.Path + ": " + problem);
}

/// A LAZ file: each process compresses its points into chunks and writes them at the
/// compressed bytes before it; process 0 writes the chunk table of every process's chunks.
std::string WriteLAZParts(vtkMultiProcessController* controller,
  const Plan& plan,
  std::size_t count,
  const double* positions,
  const void* const* columns)
{
  pcbilateral::LAZPart part;
  LASPartSummary summary;
  std::string problem = pcbilateral::CompressLAZPart(
    *plan.Info, plan.Layout->Compression(), count, positions, columns, part, summary);
  const LASPartSummary whole = ShareSummaries(controller, summary);
  if (AnyProcess(controller, !problem.empty()))
  {
    return problem.empty() ? plan.Path + ": another process could not write its part (see its "
                                         "error); no file was written"
                           : plan.Path + ": " + problem;
  }
  const std::vector<long long> bytes = GatherCounts(controller, (long long)part.Bytes.size());
  const int self = controller->GetLocalProcessId();
  const std::uint64_t before = std::accumulate(bytes.begin(), bytes.begin() + self, 0ull);
  const std::uint64_t chunkBytes = std::accumulate(bytes.begin(), bytes.end(), 0ull);
  // The chunk table: two small numbers per chunk, gathered.
  const std::vector<long long> chunks =
    GatherCounts(controller, static_cast<long long>(part.ChunkBytes.size()));
  std::vector<vtkIdType> offsets(chunks.size(), 0), lengths(chunks.begin(), chunks.end());
  for (std::size_t p = 1; p < chunks.size(); ++p)
  {
    offsets[p] = offsets[p - 1] + lengths[p - 1];
  }
  const vtkIdType allChunks = offsets.back() + lengths.back();
  std::vector<vtkTypeUInt64> points(static_cast<std::size_t>(allChunks));
  std::vector<vtkTypeUInt64> sizes(static_cast<std::size_t>(allChunks));
  const std::vector<vtkTypeUInt64> ownPoints(part.ChunkPoints.begin(), part.ChunkPoints.end());
  const std::vector<vtkTypeUInt64> ownSizes(part.ChunkBytes.begin(), part.ChunkBytes.end());
  controller->AllGatherV(
    ownPoints.data(), points.data(), lengths[self], lengths.data(), offsets.data());
  controller->AllGatherV(
    ownSizes.data(), sizes.data(), lengths[self], lengths.data(), offsets.data());

  SharedFile file(controller, plan.Path);
  problem = file.Open();
  if (!problem.empty())
  {
    return problem;
  }
  const std::uint64_t start = plan.Layout->PointDataOffset();
  problem = WriteAt(file.Get(), start + 8 + before, part.Bytes);
  if (self == 0 && problem.empty())
  {
    const std::vector<std::uint8_t> table =
      pcbilateral::EncodeLAZChunkTable(std::vector<std::uint64_t>(points.begin(), points.end()),
        std::vector<std::uint64_t>(sizes.begin(), sizes.end()),
        true);
    const std::uint64_t tableOffset = start + 8 + chunkBytes;
    std::vector<std::uint8_t> where(8);
    for (int b = 0; b < 8; ++b)
    {
      where[b] = static_cast<std::uint8_t>(tableOffset >> (8 * b));
    }
    std::vector<std::uint8_t> head = plan.Layout->Head(whole, 8 + chunkBytes + table.size());
    head.insert(head.end(), where.begin(), where.end());
    std::vector<std::uint8_t> tail = table;
    const std::vector<std::uint8_t> evlrs = plan.Layout->Tail();
    tail.insert(tail.end(), evlrs.begin(), evlrs.end());
    problem = WriteAt(file.Get(), 0, head);
    problem = problem.empty() ? WriteAt(file.Get(), tableOffset, tail) : problem;
  }
  return file.Close(problem.empty() ? problem : plan.Path + ": " + problem);
}
} // namespace

vtkPLASPointCloudWriter::vtkPLASPointCloudWriter()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPLASPointCloudWriter::~vtkPLASPointCloudWriter()
{
  this->SetController(nullptr);
}

vtkTypeBool vtkPLASPointCloudWriter::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputs,
  vtkInformationVector* outputs)
{
  if (request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()) && this->Controller &&
      this->Controller->GetNumberOfProcesses() > 1)
  {
    vtkInformation* input = inputs[0]->GetInformationObject(0);
    input->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(),
      this->Controller->GetLocalProcessId());
    input->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(),
      this->Controller->GetNumberOfProcesses());
    input->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    return 1;
  }
  return this->Superclass::ProcessRequest(request, inputs, outputs);
}

vtkLASPointCloudWriter::CloudSummary vtkPLASPointCloudWriter::MeasureCloud(vtkPointSet* input)
{
  CloudSummary cloud = this->Superclass::MeasureCloud(input);
  if (!this->Controller || this->Controller->GetNumberOfProcesses() <= 1)
  {
    return cloud;
  }
  auto* controller = this->Controller;
  const long long local[3] = { cloud.NumberOfPoints, cloud.HasGpsTime, cloud.HasRGB };
  long long total[3] = { 0, 0, 0 };
  controller->AllReduce(local, total, 1, vtkCommunicator::SUM_OP);
  controller->AllReduce(local + 1, total + 1, 2, vtkCommunicator::MAX_OP);
  // A process without points must not widen the bounds.
  const bool empty = cloud.NumberOfPoints == 0;
  double lower[3], upper[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    lower[axis] = empty ? std::numeric_limits<double>::max() : cloud.Bounds[axis];
    upper[axis] = empty ? -std::numeric_limits<double>::max() : cloud.Bounds[3 + axis];
  }
  controller->AllReduce(lower, cloud.Bounds, 3, vtkCommunicator::MIN_OP);
  controller->AllReduce(upper, cloud.Bounds + 3, 3, vtkCommunicator::MAX_OP);
  cloud.NumberOfPoints = static_cast<vtkIdType>(total[0]);
  cloud.HasGpsTime = total[1] != 0;
  cloud.HasRGB = total[2] != 0;
  if (cloud.NumberOfPoints == 0)
  {
    std::fill_n(cloud.Bounds, 6, 0.0);
  }
  return cloud;
}

std::string vtkPLASPointCloudWriter::WritePoints(const std::string& problem,
  const std::string& fileName,
  const pcbilateral::LASFileInfo& info,
  std::size_t count,
  const double* positions,
  const void* const* columns,
  bool compressed)
{
  vtkMultiProcessController* controller = this->Controller;
  if (!controller || controller->GetNumberOfProcesses() <= 1)
  {
    return this->Superclass::WritePoints(
      problem, fileName, info, count, positions, columns, compressed);
  }
  // An abort is agreed on first, where every process meets; the parts are then written whole
  // (an abort within them would leave the other processes waiting).
  if (AnyProcess(controller, this->GetAbortExecute() != 0))
  {
    return pcbilateral::AbortedMessage;
  }
  if (AnyProcess(controller, !problem.empty()))
  {
    return problem.empty() ? fileName + ": another process could not write its part (see its "
                                        "error); no file was written"
                           : problem;
  }
  pcbilateral::ProgressScope noAbortWithin(
    [this](double fraction) { this->UpdateProgress(fraction); }, nullptr);
  if (!SameRecords(controller, info))
  {
    return fileName + ": the processes' points have different LAS point formats, record "
                      "lengths, scales or offsets; they cannot share one file";
  }
  const std::vector<long long> counts = GatherCounts(controller, static_cast<long long>(count));
  const int self = controller->GetLocalProcessId();
  Plan plan;
  plan.Path = fileName;
  plan.Info = &info;
  plan.First = std::accumulate(counts.begin(), counts.begin() + self, 0ull);
  plan.Total = std::accumulate(counts.begin(), counts.end(), 0ull);
  const pcbilateral::LASPartsLayout layout(info, plan.Total, compressed);
  if (!layout.Problem().empty())
  {
    return fileName + ": " + layout.Problem();
  }
  plan.Layout = &layout;
  return compressed ? WriteLAZParts(controller, plan, count, positions, columns)
                    : WriteLASParts(controller, plan, count, positions, columns);
}

void vtkPLASPointCloudWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
}

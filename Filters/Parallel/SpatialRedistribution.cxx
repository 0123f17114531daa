// Every exchange here is one all-to-all step in N - 1 rounds: in round k each process sends to
// the process k after it and receives from the one k before it, so every send meets its receive
// in the same round and large messages (which MPI may not buffer) cannot deadlock.
#include "SpatialRedistribution.h"

#include "vtkCommunicator.h"
#include "vtkMPICommunicator.h"
#include "vtkMPIController.h"

#include <algorithm>
#include <limits>

namespace pcbilateral
{
namespace
{
using Buffers = ExchangedBuffers;

/// Below MPI's smallest guaranteed tag bound (32767), and used by nothing else here.
constexpr int ExchangeTag = 2727;
/// MPI counts are int: longer buffers go in several messages.
constexpr std::size_t MessageLength = std::size_t(1) << 26;
/// The histogram's resolution: the regions' counts differ by at most one bin's points.
constexpr long long HistogramBins = 1LL << 18;

/// For each point of the share, the process whose slab holds it (non-finite points: this one).
std::vector<int> AssignRegions(vtkMPIController* controller,
  const PointCloudView& share,
  const CloudExtent& whole)
{
  const int processes = controller->GetNumberOfProcesses();
  const int self = controller->GetLocalProcessId();
  std::vector<int> region(share.NumberOfPoints, self);
  int axis = 0;
  for (int a = 1; a < 3; ++a)
  {
    if (whole.Max[a] - whole.Min[a] > whole.Max[axis] - whole.Min[axis])
    {
      axis = a;
    }
  }
  const double lower = whole.Min[axis];
  const double extent = whole.Max[axis] - lower;
  if (whole.NumberOfFinitePoints == 0 || !(extent > 0.0) || !std::isfinite(extent))
  {
    return region; // all finite points coincide: any split will do, so none moves
  }
  // Every process computes the same bin for the same coordinate: the same operations on the
  // same doubles.
  auto binOf = [&](const double* p)
  {
    const double t = (p[axis] - lower) / extent * static_cast<double>(HistogramBins);
    return std::min(HistogramBins - 1, static_cast<long long>(t));
  };
  std::vector<long long> localCounts(HistogramBins, 0), counts(HistogramBins, 0);
  for (std::size_t i = 0; i < share.NumberOfPoints; ++i)
  {
    const double* p = share.Positions + 3 * i;
    if (IsFinitePoint(p))
    {
      ++localCounts[binOf(p)];
    }
  }
  controller->AllReduce(localCounts.data(), counts.data(), HistogramBins, vtkCommunicator::SUM_OP);
  long long total = 0;
  for (long long count : counts)
  {
    total += count;
  }
  // A bin goes to the region k where the points before it reach k/N of all of them.
  std::vector<int> regionOfBin(HistogramBins);
  long long before = 0;
  for (long long b = 0; b < HistogramBins; ++b)
  {
    regionOfBin[b] =
      static_cast<int>(std::min<long long>(processes - 1, before * processes / total));
    before += counts[b];
  }
  for (std::size_t i = 0; i < share.NumberOfPoints; ++i)
  {
    const double* p = share.Positions + 3 * i;
    if (IsFinitePoint(p))
    {
      region[i] = regionOfBin[binOf(p)];
    }
  }
  return region;
}

/// Whether any process has this: the arrays that travel must be the same everywhere.
bool AnyProcess(vtkMPIController* controller, bool here)
{
  const int local = here ? 1 : 0;
  int any = 0;
  controller->AllReduce(&local, &any, 1, vtkCommunicator::MAX_OP);
  return any != 0;
}
} // namespace

ExchangedBuffers ExchangeBuffers(vtkMPIController* controller, ExchangedBuffers outgoing)
{
  const int processes = controller->GetNumberOfProcesses();
  const int self = controller->GetLocalProcessId();
  std::vector<vtkIdType> lengths(processes),
    allLengths(static_cast<std::size_t>(processes) * static_cast<std::size_t>(processes));
  for (int p = 0; p < processes; ++p)
  {
    lengths[p] = static_cast<vtkIdType>(outgoing[p].size());
  }
  controller->AllGather(lengths.data(), allLengths.data(), processes);
  ExchangedBuffers incoming(processes);
  incoming[self] = std::move(outgoing[self]);
  for (int round = 1; round < processes; ++round)
  {
    const int to = (self + round) % processes;
    const int from = (self - round + processes) % processes;
    const std::vector<double>& data = outgoing[to];
    std::vector<vtkMPICommunicator::Request> requests(
      (data.size() + MessageLength - 1) / MessageLength);
    for (std::size_t offset = 0, k = 0; offset < data.size(); offset += MessageLength, ++k)
    {
      const int length = static_cast<int>(std::min(MessageLength, data.size() - offset));
      controller->NoBlockSend(data.data() + offset, length, to, ExchangeTag, requests[k]);
    }
    std::vector<double>& received = incoming[from];
    received.resize(static_cast<std::size_t>(
      allLengths[static_cast<std::size_t>(from) * static_cast<std::size_t>(processes) +
                 static_cast<std::size_t>(self)]));
    for (std::size_t offset = 0; offset < received.size(); offset += MessageLength)
    {
      const vtkIdType length =
        static_cast<vtkIdType>(std::min(MessageLength, received.size() - offset));
      controller->Receive(received.data() + offset, length, from, ExchangeTag);
    }
    if (!requests.empty())
    {
      controller->WaitAll(static_cast<int>(requests.size()), requests.data());
    }
    std::vector<double>().swap(outgoing[to]);
  }
  return incoming;
}

SpatialRedistribution::SpatialRedistribution(vtkMPIController* controller,
  const PointCloudView& share,
  const CloudExtent& whole)
  : Controller(controller)
  , NumberOfProcesses(controller->GetNumberOfProcesses())
{
  this->HasOrientation = AnyProcess(controller, share.OrientationNormals != nullptr);
  this->Destination = AssignRegions(controller, share, whole);
  const std::size_t width = this->HasOrientation ? 6 : 3;
  std::vector<std::size_t> sending(this->NumberOfProcesses, 0);
  for (int destination : this->Destination)
  {
    ++sending[destination];
  }
  Buffers outgoing(this->NumberOfProcesses);
  for (int p = 0; p < this->NumberOfProcesses; ++p)
  {
    outgoing[p].reserve(width * sending[p]);
  }
  const double none[3] = { 0.0, 0.0, 0.0 }; // a process whose input has no orientation array
  for (std::size_t i = 0; i < share.NumberOfPoints; ++i)
  {
    std::vector<double>& out = outgoing[this->Destination[i]];
    out.insert(out.end(), share.Positions + 3 * i, share.Positions + 3 * i + 3);
    if (this->HasOrientation)
    {
      const double* n = share.OrientationNormals ? share.OrientationNormals + 3 * i : none;
      out.insert(out.end(), n, n + 3);
    }
  }
  Buffers incoming = ExchangeBuffers(controller, std::move(outgoing));
  std::size_t held = 0;
  this->ReceivedCounts.resize(this->NumberOfProcesses);
  for (int p = 0; p < this->NumberOfProcesses; ++p)
  {
    this->ReceivedCounts[p] = incoming[p].size() / width;
    held += this->ReceivedCounts[p];
  }
  this->Positions.reserve(3 * held);
  this->Orientation.reserve(this->HasOrientation ? 3 * held : 0);
  for (std::vector<double>& from : incoming)
  {
    for (std::size_t i = 0; i < from.size(); i += width)
    {
      this->Positions.insert(this->Positions.end(), &from[i], &from[i] + 3);
      if (this->HasOrientation)
      {
        this->Orientation.insert(this->Orientation.end(), &from[i + 3], &from[i + 3] + 3);
      }
    }
    std::vector<double>().swap(from);
  }
}

PointCloudView SpatialRedistribution::View() const
{
  PointCloudView view;
  view.NumberOfPoints = this->Positions.size() / 3;
  view.Positions = this->Positions.data();
  view.OrientationNormals = this->HasOrientation ? this->Orientation.data() : nullptr;
  return view;
}

BilateralResult SpatialRedistribution::ReturnResult(BilateralResult regionResult) const
{
  const std::size_t held = this->Positions.size() / 3;
  // A run that failed before copying its input has no positions: the points stay where they
  // were.
  const std::vector<double>& positions =
    regionResult.Positions.size() == 3 * held ? regionResult.Positions : this->Positions;
  const bool hasNormals = AnyProcess(this->Controller, !regionResult.Normals.empty());
  const bool hasRadius = AnyProcess(this->Controller, !regionResult.PointRadius.empty());
  const std::size_t width = 3 + (hasNormals ? 3 : 0) + 1 + (hasRadius ? 1 : 0);
  Buffers outgoing(this->NumberOfProcesses);
  std::size_t i = 0;
  for (int p = 0; p < this->NumberOfProcesses; ++p)
  {
    std::vector<double>& out = outgoing[p];
    out.reserve(width * this->ReceivedCounts[p]);
    for (std::size_t end = i + this->ReceivedCounts[p]; i < end; ++i)
    {
      out.insert(out.end(), &positions[3 * i], &positions[3 * i] + 3);
      if (hasNormals)
      {
        const bool has = regionResult.Normals.size() == 3 * held;
        for (int c = 0; c < 3; ++c)
        {
          out.push_back(has ? regionResult.Normals[3 * i + c] : 0.0);
        }
      }
      out.push_back(regionResult.Removed.size() == held ? regionResult.Removed[i] : 0.0);
      if (hasRadius)
      {
        out.push_back(regionResult.PointRadius.size() == held ? regionResult.PointRadius[i] : 0.0);
      }
    }
  }
  BilateralResult result = std::move(regionResult);
  std::vector<double>().swap(result.Positions);
  std::vector<double>().swap(result.Normals);
  std::vector<std::uint8_t>().swap(result.Removed);
  std::vector<double>().swap(result.PointRadius);
  const Buffers incoming = ExchangeBuffers(this->Controller, std::move(outgoing));

  const std::size_t n = this->Destination.size();
  result.Positions.resize(3 * n);
  result.Normals.resize(hasNormals ? 3 * n : 0);
  result.Removed.resize(n);
  result.PointRadius.resize(hasRadius ? n : 0);
  std::vector<std::size_t> cursor(this->NumberOfProcesses, 0);
  for (std::size_t j = 0; j < n; ++j)
  {
    const int p = this->Destination[j];
    const double* in = incoming[p].data() + width * cursor[p]++;
    std::copy(in, in + 3, &result.Positions[3 * j]);
    in += 3;
    if (hasNormals)
    {
      std::copy(in, in + 3, &result.Normals[3 * j]);
      in += 3;
    }
    result.Removed[j] = static_cast<std::uint8_t>(*in++);
    if (hasRadius)
    {
      result.PointRadius[j] = *in;
    }
  }
  return result;
}

} // namespace pcbilateral

// pcb_abort_latency: how long Abort takes to stop a run, phase by phase (issue 28). Built with the
// project, run by hand (docs/speed.md); a shared machine is too noisy for a timed test.
//
//   pcb_abort_latency INPUT OUTPUT.las [--samples K] [--iterations N] [--radius R]
//                     [--filter-until T]
//
// The pipeline is the GUI's: the plugin's reader for INPUT (vtkPointCloudFileIO::NewReader), the
// filter (automatic parameters unless --radius, N iterations, default 1), the LAS writer. A first
// run times each algorithm. Then each runs again K times (default 3; the filter 4K times) while
// another thread sets its AbortExecute flag, as ParaView's Abort button does, at evenly spread
// moments of its run (the filter's first T seconds only with --filter-until); the latency is the
// time from that moment to the algorithm's return. Each abort is counted in the phase that was
// running at its moment, followed by the filter's events: measuring (from its start to its
// ParametersChosenEvent), octree (to its first progress past 0), kernel (to its progress of 1),
// output (to its end); reading and writing are the reader's and the writer's runs. Prints a
// Markdown table: per phase, the aborts that landed in it, the largest and the mean latency, and
// whether an aborted write left a file at OUTPUT.
#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkLASPointCloudWriter.h"
#include "vtkNew.h"
#include "vtkPointCloudBilateralFilter.h"
#include "vtkPointCloudFileIO.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

double SecondsBetween(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

/// Calls a function on an algorithm's events (the callback command owns nothing).
void Observe(vtkAlgorithm* algorithm, unsigned long event, std::function<void()>* what)
{
  vtkNew<vtkCallbackCommand> command;
  command->SetClientData(what);
  command->SetCallback([](vtkObject*, unsigned long, void* data, void*)
    { (*static_cast<std::function<void()>*>(data))(); });
  algorithm->AddObserver(event, command);
}

struct Phase
{
  const char* Name;
  std::vector<double> Latencies;
  int EndedFirst = 0; // runs that ended before the abort's moment
  int LeftFiles = 0;
};

enum PhaseIndex
{
  Reading,
  Measuring,
  Octree,
  Kernel,
  Output,
  Writing
};

/**
 * Runs `update` with another thread setting the algorithm's abort flag `delay` seconds after its
 * StartEvent; returns the seconds from that moment to the return of `update` (or from the
 * return to the moment, negative, when the run ended first).
 */
/// When the filter's core last returned: its progress of 1, reported after RunOnChosen.
Clock::time_point CoreReturned;
/// When the last abort was asked.
Clock::time_point LastAbort;

double AbortAfter(vtkAlgorithm* algorithm,
  double delay,
  const std::function<void()>& update,
  const std::atomic<int>& phaseNow,
  int& phaseAtAbort)
{
  std::atomic<bool> started{ false };
  std::atomic<bool> done{ false };
  Clock::time_point start;
  std::function<void()> onStart = [&]()
  {
    start = Clock::now();
    started = true;
  };
  vtkNew<vtkCallbackCommand> command;
  command->SetClientData(&onStart);
  command->SetCallback([](vtkObject*, unsigned long, void* data, void*)
    { (*static_cast<std::function<void()>*>(data))(); });
  const unsigned long tag = algorithm->AddObserver(vtkCommand::StartEvent, command);
  Clock::time_point aborted = Clock::time_point::max();
  std::thread aborter(
    [&]()
    {
      while (!started && !done)
      {
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
      if (done)
      {
        return;
      }
      const auto when =
        start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(delay));
      while (Clock::now() < when && !done)
      {
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
      aborted = Clock::now();
      LastAbort = aborted;
      phaseAtAbort = phaseNow;
      algorithm->SetAbortExecute(1);
    });
  update();
  const Clock::time_point returned = Clock::now();
  done = true;
  aborter.join();
  algorithm->RemoveObserver(tag);
  algorithm->SetAbortExecute(0);
  return aborted == Clock::time_point::max() ? -1.0 : SecondsBetween(aborted, returned);
}

int Fail(const char* message)
{
  std::fprintf(stderr, "pcb_abort_latency: %s\n", message);
  return 1;
}
}

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    return Fail("usage: pcb_abort_latency INPUT OUTPUT.las [--samples K] [--iterations N] "
                "[--radius R] [--filter-until T]");
  }
  const char* input = argv[1];
  const std::string output = argv[2];
  int samples = 3;
  int iterations = 1;
  double radius = 0.0;
  double filterUntil = 0.0; // the filter's aborts spread over its first seconds only
  for (int i = 3; i + 1 < argc; i += 2)
  {
    if (std::strcmp(argv[i], "--samples") == 0)
      samples = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--iterations") == 0)
      iterations = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--filter-until") == 0)
      filterUntil = std::atof(argv[i + 1]);
    else if (std::strcmp(argv[i], "--radius") == 0)
      radius = std::atof(argv[i + 1]);
    else
      return Fail("unknown option");
  }
  vtkSmartPointer<vtkAlgorithm> reader;
  reader.TakeReference(vtkPointCloudFileIO::NewReader(input));
  if (!reader)
  {
    return Fail("no reader for the input's extension");
  }
  vtkNew<vtkPointCloudBilateralFilter> filter;
  filter->SetInputConnection(reader->GetOutputPort());
  filter->SetNumberOfIterations(iterations);
  filter->SetRadius(radius);
  vtkNew<vtkLASPointCloudWriter> writer;
  writer->SetInputConnection(filter->GetOutputPort());
  writer->SetFileName(output.c_str());

  // The filter's phase as it runs (read by the aborting thread).
  std::atomic<int> phaseNow{ Measuring };
  std::function<void()> onFilterStart = [&]() { phaseNow = Measuring; };
  std::function<void()> onChosen = [&]() { phaseNow = Octree; };
  std::function<void()> onProgress = [&]()
  {
    const double progress = filter->GetProgress();
    if (phaseNow == Octree && progress > 0.0)
    {
      phaseNow = Kernel;
    }
    else if (phaseNow == Kernel && progress >= 1.0)
    {
      phaseNow = Output;
    }
    if (progress >= 1.0)
    {
      CoreReturned = Clock::now();
    }
  };
  Observe(filter, vtkCommand::StartEvent, &onFilterStart);
  Observe(filter, vtkPointCloudBilateralFilter::ParametersChosenEvent, &onChosen);
  Observe(filter, vtkCommand::ProgressEvent, &onProgress);

  // The reference runs, twice (the first one's times include one-time set-up).
  double seconds[3] = { 0.0, 0.0, 0.0 };
  for (int run = 0; run < 2; ++run)
  {
    reader->Modified();
    Clock::time_point t0 = Clock::now();
    reader->Update();
    seconds[0] = SecondsBetween(t0, Clock::now());
    t0 = Clock::now();
    filter->Update();
    seconds[1] = SecondsBetween(t0, Clock::now());
    t0 = Clock::now();
    writer->Write();
    seconds[2] = SecondsBetween(t0, Clock::now());
  }
  std::printf("%s: %lld points, %d iteration(s), radius %g; reading %.3f s, filter %.3f s, "
              "writing %.3f s\n\n",
    input,
    static_cast<long long>(vtkDataSet::SafeDownCast(filter->GetOutput())->GetNumberOfPoints()),
    filter->GetNumberOfIterationsUsed(),
    filter->GetRadiusUsed(),
    seconds[0],
    seconds[1],
    seconds[2]);

  std::vector<Phase> phases = {
    { "reading" }, { "measuring" }, { "octree" }, { "kernel" }, { "output" }, { "writing" }
  };
  const std::atomic<int> readingNow{ Reading }, writingNow{ Writing };
  const auto record = [&](double latency, int phase)
  {
    if (latency < 0.0)
      ++phases[phase].EndedFirst;
    else
      phases[phase].Latencies.push_back(latency);
  };
  for (int k = 1; k <= samples; ++k)
  {
    int phase = Reading;
    reader->Modified();
    record(
      AbortAfter(
        reader, seconds[0] * k / (samples + 1), [&]() { reader->Update(); }, readingNow, phase),
      Reading);
    unlink(output.c_str());
    phase = Writing;
    const double latency = AbortAfter(
      writer, seconds[2] * k / (samples + 1), [&]() { writer->Write(); }, writingNow, phase);
    record(latency, Writing);
    phases[Writing].LeftFiles += latency >= 0.0 && access(output.c_str(), F_OK) == 0;
  }
  reader->Update();
  double largestCleanUp = 0.0; // from the core's return to the filter's
  for (int k = 1; k <= 4 * samples; ++k)
  {
    int phase = Measuring;
    filter->Modified();
    const double latency = AbortAfter(
      filter,
      (filterUntil > 0.0 ? filterUntil : seconds[1]) * k / (4 * samples + 1),
      [&]() { filter->Update(); },
      phaseNow,
      phase);
    record(latency, latency < 0.0 ? Output : phase);
    if (latency >= 0.0)
    {
      const double core = SecondsBetween(LastAbort, CoreReturned);
      std::printf("abort in %s: the core returned %.3f s after it, the filter %.3f s\n",
        phases[phase].Name,
        core,
        latency);
      largestCleanUp = std::max(largestCleanUp, latency - core);
    }
  }
  std::printf("(the filter's clean-up once its core returned: %.3f s at most)\n\n", largestCleanUp);
  std::printf("| phase | aborts in it | largest latency (s) | mean latency (s) | notes |\n"
              "| --- | ---: | ---: | ---: | --- |\n");
  for (const Phase& phase : phases)
  {
    double largest = 0.0, sum = 0.0;
    for (double latency : phase.Latencies)
    {
      largest = std::max(largest, latency);
      sum += latency;
    }
    std::string notes = phase.EndedFirst > 0 ? std::to_string(phase.EndedFirst) +
                                                 " run(s) ended before the abort's moment. "
                                             : std::string();
    if (&phase == &phases[Writing])
    {
      notes += phase.LeftFiles == 0
                 ? "no file after an aborted write"
                 : std::to_string(phase.LeftFiles) + " aborted write(s) left the file";
    }
    std::printf("| %s | %zu | %.3f | %.3f | %s |\n",
      phase.Name,
      phase.Latencies.size(),
      largest,
      phase.Latencies.empty() ? 0.0 : sum / phase.Latencies.size(),
      notes.c_str());
  }
  return 0;
}

// pcb_abort_latency: how long Abort takes to stop a run, phase by phase (issue 28). Built with the
// project, run by hand (docs/speed.md); a shared machine is too noisy for a timed test.
//
//   pcb_abort_latency INPUT OUTPUT.las [--samples K] [--iterations N] [--radius R]
//
// The pipeline is the GUI's: the plugin's reader for INPUT (vtkPointCloudFileIO::NewReader), the
// filter (automatic parameters unless --radius, N iterations, default 1), the LAS writer. A first
// run finds when each phase runs: reading (the reader), measuring (the filter's start to its
// ParametersChosenEvent), octree (to its first progress past 0), kernel (to its last progress
// event), output (to its end), writing (the writer). Then each algorithm runs again K times per
// phase (default 3), and another thread sets its AbortExecute flag, as ParaView's Abort button
// does, at 1/(K+1), 2/(K+1)... of the phase; the latency is the time from that moment to the
// algorithm's return. Prints one row per phase: its length, the largest and the mean latency,
// and whether the aborted writes left no file at OUTPUT.
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
  double Begin = 0.0; // seconds after the algorithm's StartEvent
  double End = 0.0;
  std::vector<double> Latencies;
  int LeftFiles = 0;
};

/**
 * Runs `update` with another thread setting the algorithm's abort flag `delay` seconds after its
 * StartEvent; returns the seconds from that moment to the return of `update` (or from the
 * return to the moment, negative, when the run ended first).
 */
double AbortAfter(vtkAlgorithm* algorithm, double delay, const std::function<void()>& update)
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
                "[--radius R]");
  }
  const char* input = argv[1];
  const std::string output = argv[2];
  int samples = 3;
  int iterations = 1;
  double radius = 0.0;
  for (int i = 3; i + 1 < argc; i += 2)
  {
    if (std::strcmp(argv[i], "--samples") == 0)
      samples = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--iterations") == 0)
      iterations = std::atoi(argv[i + 1]);
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

  // The reference run: when each phase runs.
  Clock::time_point filterStart, chosen, kernelStart, lastProgress, filterEnd;
  std::function<void()> onFilterStart = [&]() { filterStart = Clock::now(); };
  std::function<void()> onChosen = [&]() { chosen = Clock::now(); };
  std::function<void()> onProgress = [&]()
  {
    const Clock::time_point now = Clock::now();
    if (chosen != Clock::time_point() && kernelStart == Clock::time_point() &&
        filter->GetProgress() > 0.0)
    {
      kernelStart = now;
    }
    if (filter->GetProgress() < 1.0)
    {
      lastProgress = now;
    }
  };
  std::function<void()> onFilterEnd = [&]() { filterEnd = Clock::now(); };
  Observe(filter, vtkCommand::StartEvent, &onFilterStart);
  Observe(filter, vtkPointCloudBilateralFilter::ParametersChosenEvent, &onChosen);
  Observe(filter, vtkCommand::ProgressEvent, &onProgress);
  Observe(filter, vtkCommand::EndEvent, &onFilterEnd);
  // Twice: the second run's times (the first one's include one-time set-up).
  double readSeconds = 0.0, writeSeconds = 0.0;
  for (int run = 0; run < 2; ++run)
  {
    reader->Modified();
    kernelStart = Clock::time_point();
    chosen = Clock::time_point();
    Clock::time_point t0 = Clock::now();
    reader->Update();
    readSeconds = SecondsBetween(t0, Clock::now());
    filter->Update();
    t0 = Clock::now();
    writer->Write();
    writeSeconds = SecondsBetween(t0, Clock::now());
  }
  const auto offset = [&](Clock::time_point t) { return SecondsBetween(filterStart, t); };
  std::vector<Phase> phases = { { "reading", 0.0, readSeconds },
    { "measuring", 0.0, offset(chosen) },
    { "octree", offset(chosen), offset(kernelStart) },
    { "kernel", offset(kernelStart), offset(lastProgress) },
    { "output", offset(lastProgress), offset(filterEnd) },
    { "writing", 0.0, writeSeconds } };
  std::printf("%s: %lld points, %d iteration(s), radius %g\n",
    input,
    static_cast<long long>(vtkDataSet::SafeDownCast(filter->GetOutput())->GetNumberOfPoints()),
    filter->GetNumberOfIterationsUsed(),
    filter->GetRadiusUsed());

  for (Phase& phase : phases)
  {
    for (int k = 1; k <= samples; ++k)
    {
      const double delay = phase.Begin + (phase.End - phase.Begin) * k / (samples + 1);
      if (std::strcmp(phase.Name, "reading") == 0)
      {
        reader->Modified();
        phase.Latencies.push_back(AbortAfter(reader, delay, [&]() { reader->Update(); }));
      }
      else if (std::strcmp(phase.Name, "writing") == 0)
      {
        unlink(output.c_str());
        const double latency = AbortAfter(writer, delay, [&]() { writer->Write(); });
        phase.Latencies.push_back(latency);
        phase.LeftFiles += latency >= 0.0 && access(output.c_str(), F_OK) == 0;
      }
      else
      {
        filter->Modified();
        phase.Latencies.push_back(AbortAfter(filter, delay, [&]() { filter->Update(); }));
      }
    }
  }
  std::printf("| phase | length (s) | largest latency (s) | mean latency (s) | notes |\n"
              "| --- | ---: | ---: | ---: | --- |\n");
  for (const Phase& phase : phases)
  {
    double largest = 0.0, sum = 0.0;
    int measured = 0;
    for (double latency : phase.Latencies)
    {
      if (latency >= 0.0) // else the run had ended before the abort
      {
        largest = std::max(largest, latency);
        sum += latency;
        ++measured;
      }
    }
    std::string notes =
      measured < static_cast<int>(phase.Latencies.size())
        ? std::to_string(phase.Latencies.size() - measured) + " run(s) ended before the abort. "
        : std::string();
    if (std::strcmp(phase.Name, "writing") == 0)
    {
      notes += phase.LeftFiles == 0
                 ? "no file after an aborted write"
                 : std::to_string(phase.LeftFiles) + " aborted write(s) left the file";
    }
    std::printf("| %s | %.3f | %.3f | %.3f | %s |\n",
      phase.Name,
      phase.End - phase.Begin,
      largest,
      measured ? sum / measured : 0.0,
      notes.c_str());
  }
  return 0;
}

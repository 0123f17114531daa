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
#include "AbortTools.h"

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

struct Phase
{
  const char* Name;
  std::vector<double> Latencies;
  int EndedFirst = 0; // runs that ended before the abort's moment
  int LeftFiles = 0;
};

using namespace pcbilateral_testing; // the phases (Reading, Measuring...), Observe

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

struct Options
{
  const char* Input = nullptr;
  std::string Output;
  int Samples = 3;
  int Iterations = 1;
  double Radius = 0.0;
  double FilterUntil = 0.0; // the filter's aborts spread over its first seconds only
};

bool ParseOptions(int argc, char* argv[], Options& options)
{
  if (argc < 3)
  {
    return false;
  }
  options.Input = argv[1];
  options.Output = argv[2];
  for (int i = 3; i + 1 < argc; i += 2)
  {
    if (std::strcmp(argv[i], "--samples") == 0)
      options.Samples = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--iterations") == 0)
      options.Iterations = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--filter-until") == 0)
      options.FilterUntil = std::atof(argv[i + 1]);
    else if (std::strcmp(argv[i], "--radius") == 0)
      options.Radius = std::atof(argv[i + 1]);
    else
      return false;
  }
  return true;
}

/// The GUI's pipeline, the filter's phase as it runs, and the aborts' latencies by phase.
struct Bench
{
  Options Settings;
  vtkSmartPointer<vtkAlgorithm> Reader;
  vtkNew<vtkPointCloudBilateralFilter> Filter;
  vtkNew<vtkLASPointCloudWriter> Writer;
  std::atomic<int> PhaseNow{ Measuring }; // read by the aborting thread
  std::function<void()> OnStart, OnChosen, OnProgress;
  double Seconds[3] = { 0.0, 0.0, 0.0 }; // reading, filter, writing
  std::vector<Phase> Phases = { { PhaseNames[Reading] },
    { PhaseNames[Measuring] },
    { PhaseNames[Octree] },
    { PhaseNames[Kernel] },
    { PhaseNames[Output] },
    { PhaseNames[Writing] } };

  bool SetUp()
  {
    this->Reader.TakeReference(vtkPointCloudFileIO::NewReader(this->Settings.Input));
    if (!this->Reader)
    {
      return false;
    }
    this->Filter->SetInputConnection(this->Reader->GetOutputPort());
    this->Filter->SetNumberOfIterations(this->Settings.Iterations);
    this->Filter->SetRadius(this->Settings.Radius);
    this->Writer->SetInputConnection(this->Filter->GetOutputPort());
    this->Writer->SetFileName(this->Settings.Output.c_str());
    this->OnStart = [this]() { this->PhaseNow = Measuring; };
    this->OnChosen = [this]() { this->PhaseNow = Octree; };
    this->OnProgress = [this]()
    {
      const double progress = this->Filter->GetProgress();
      if (this->PhaseNow == Octree && progress > 0.0)
        this->PhaseNow = Kernel;
      else if (this->PhaseNow == Kernel && progress >= 1.0)
        this->PhaseNow = Output;
      if (progress >= 1.0)
        CoreReturned = Clock::now();
    };
    Observe(this->Filter, vtkCommand::StartEvent, &this->OnStart);
    Observe(this->Filter, vtkPointCloudBilateralFilter::ParametersChosenEvent, &this->OnChosen);
    Observe(this->Filter, vtkCommand::ProgressEvent, &this->OnProgress);
    return true;
  }

  /// Twice: the first run's times include one-time set-up.
  void TimeRuns()
  {
    for (int run = 0; run < 2; ++run)
    {
      this->Reader->Modified();
      Clock::time_point t0 = Clock::now();
      this->Reader->Update();
      this->Seconds[0] = SecondsBetween(t0, Clock::now());
      t0 = Clock::now();
      this->Filter->Update();
      this->Seconds[1] = SecondsBetween(t0, Clock::now());
      t0 = Clock::now();
      this->Writer->Write();
      this->Seconds[2] = SecondsBetween(t0, Clock::now());
    }
    std::printf("%s: %lld points, %d iteration(s), radius %g; reading %.3f s, filter %.3f s, "
                "writing %.3f s\n\n",
      this->Settings.Input,
      static_cast<long long>(
        vtkDataSet::SafeDownCast(this->Filter->GetOutput())->GetNumberOfPoints()),
      this->Filter->GetNumberOfIterationsUsed(),
      this->Filter->GetRadiusUsed(),
      this->Seconds[0],
      this->Seconds[1],
      this->Seconds[2]);
  }

  void Record(double latency, int phase)
  {
    if (latency < 0.0)
      ++this->Phases[phase].EndedFirst;
    else
      this->Phases[phase].Latencies.push_back(latency);
  }

  void AbortReadsAndWrites()
  {
    const std::atomic<int> readingNow{ Reading }, writingNow{ Writing };
    const int samples = this->Settings.Samples;
    for (int k = 1; k <= samples; ++k)
    {
      int phase = Reading;
      this->Reader->Modified();
      this->Record(AbortAfter(
                     this->Reader,
                     this->Seconds[0] * k / (samples + 1),
                     [this]() { this->Reader->Update(); },
                     readingNow,
                     phase),
        Reading);
    }
    // The writes are of the whole filtered cloud: an aborted read left an empty one.
    this->Reader->Modified();
    this->Filter->Update();
    for (int k = 1; k <= samples; ++k)
    {
      unlink(this->Settings.Output.c_str());
      int phase = Writing;
      const double latency = AbortAfter(
        this->Writer,
        this->Seconds[2] * k / (samples + 1),
        [this]() { this->Writer->Write(); },
        writingNow,
        phase);
      this->Record(latency, Writing);
      this->Phases[Writing].LeftFiles +=
        latency >= 0.0 && access(this->Settings.Output.c_str(), F_OK) == 0;
    }
  }

  void AbortFilterRuns()
  {
    this->Reader->Modified(); // (read whole again: the last read may have been aborted)
    this->Reader->Update();
    const int runs = 4 * this->Settings.Samples;
    const double span =
      this->Settings.FilterUntil > 0.0 ? this->Settings.FilterUntil : this->Seconds[1];
    double largestCleanUp = 0.0; // from the core's return to the filter's
    for (int k = 1; k <= runs; ++k)
    {
      int phase = Measuring;
      this->Filter->Modified();
      const double latency = AbortAfter(
        this->Filter,
        span * k / (runs + 1),
        [this]() { this->Filter->Update(); },
        this->PhaseNow,
        phase);
      this->Record(latency, latency < 0.0 ? Output : phase);
      if (latency >= 0.0)
      {
        const double core = SecondsBetween(LastAbort, CoreReturned);
        std::printf("abort in %s: the core returned %.3f s after it, the filter %.3f s\n",
          this->Phases[phase].Name,
          core,
          latency);
        largestCleanUp = std::max(largestCleanUp, latency - core);
      }
    }
    std::printf(
      "(the filter's clean-up once its core returned: %.3f s at most)\n\n", largestCleanUp);
  }

  void PrintTable() const
  {
    std::printf("| phase | aborts in it | largest latency (s) | mean latency (s) | notes |\n"
                "| --- | ---: | ---: | ---: | --- |\n");
    for (const Phase& phase : this->Phases)
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
      if (&phase == &this->Phases[Writing])
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
  }
};
}

int main(int argc, char* argv[])
{
  Bench bench;
  if (!ParseOptions(argc, argv, bench.Settings))
  {
    return Fail("usage: pcb_abort_latency INPUT OUTPUT.las [--samples K] [--iterations N] "
                "[--radius R] [--filter-until T]");
  }
  if (!bench.SetUp())
  {
    return Fail("no reader for the input's extension");
  }
  bench.TimeRuns();
  bench.AbortReadsAndWrites();
  bench.AbortFilterRuns();
  bench.PrintTable();
  return 0;
}

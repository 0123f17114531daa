// pcb_abort_gaps: where a run goes without asking whether to stop (issue 28). Built with the
// project, run by hand (docs/speed.md); a shared machine is too noisy for a timed test.
//
//   pcb_abort_gaps INPUT OUTPUT.las [--iterations N] [--radius R] [--threshold S] [--top K]
//
// Runs the GUI's pipeline once (the LAS reader, the filter with automatic parameters unless
// --radius, the LAS writer), each algorithm's GetAbortExecute overridden to note the moment it is
// asked. An abort asked just after one question is seen at the next, so the largest gap between
// two questions (or from the algorithm's start to its first question, or from its last to its
// return) is the largest latency an abort can have there, whenever it comes: unlike
// pcb_abort_latency, which aborts at chosen moments, nothing is left to chance. While a gap lasts
// past a few milliseconds, another thread samples the running thread's stack (SIGPROF), so each
// gap longer than the threshold (default 0.1 s) is printed with the functions it was spent in.
// Per phase (the filter's as pcb_abort_latency counts them), prints the largest gap.
#include "AbortTools.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkLASPointCloudReader.h"
#include "vtkLASPointCloudWriter.h"
#include "vtkNew.h"
#include "vtkPointCloudBilateralFilter.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <execinfo.h>
#include <functional>
#include <map>
#include <pthread.h>
#include <string>
#include <thread>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

std::int64_t NowNs()
{
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch())
    .count();
}

using namespace pcbilateral_testing; // PhaseIndex, PhaseNames, Observe

/// A stack taken while a gap lasted; `GapStart` names the gap (the last question's moment).
struct Sample
{
  std::int64_t GapStart;
  int Depth;
  void* Frames[40];
};
constexpr int MaxSamples = 60000;
Sample Samples[MaxSamples];
std::atomic<int> SampleCount{ 0 };
std::atomic<std::int64_t> LastQuestion{ 0 }; // 0: no algorithm running
std::atomic<int> PhaseNow{ Reading };
pthread_t Runner;

void TakeSample(int)
{
  const int k = SampleCount.fetch_add(1, std::memory_order_relaxed);
  if (k < MaxSamples)
  {
    Samples[k].GapStart = LastQuestion.load(std::memory_order_relaxed);
    Samples[k].Depth = backtrace(Samples[k].Frames, 40);
  }
}

struct Gap
{
  int Phase;
  std::int64_t Start;
  double Seconds;
  const char* EndedBy;
};
std::vector<Gap> Gaps;
double Threshold = 0.1;
std::int64_t RunStart = 0;
int PhaseAtQuestion = Reading;

/// A question (or the algorithm's return): closes the gap since the last one.
void Asked(const char* endedBy)
{
  const std::int64_t now = NowNs();
  const std::int64_t last = LastQuestion.load(std::memory_order_relaxed);
  if (last != 0)
  {
    const double seconds = 1e-9 * static_cast<double>(now - last);
    if (seconds > Threshold)
    {
      Gaps.push_back({ PhaseAtQuestion, last, seconds, endedBy });
    }
  }
  PhaseAtQuestion = PhaseNow;
  LastQuestion.store(now, std::memory_order_relaxed);
}

/// Each algorithm's question, noted when asked on the running thread (the others' questions stop
/// nothing by themselves: the running thread's return does).
template<typename Base>
class Traced : public Base
{
public:
  static Traced* Make()
  {
    auto* made = new Traced;
    made->InitializeObjectBase();
    return made;
  }
  vtkTypeBool GetAbortExecute() override
  {
    if (pthread_equal(pthread_self(), Runner))
    {
      Asked("a question");
    }
    return Base::GetAbortExecute();
  }
};

/// Samples the running thread's stack every 5 ms once a gap has lasted 10 ms.
void Watch(const std::atomic<bool>& done)
{
  while (!done)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const std::int64_t last = LastQuestion.load(std::memory_order_relaxed);
    if (last != 0 && NowNs() - last > 10000000)
    {
      pthread_kill(Runner, SIGPROF);
    }
  }
}

/// "function" for each address, through addr2line on the object it is in.
std::map<void*, std::string> Symbolize(const std::vector<void*>& addresses)
{
  std::map<std::string, std::vector<std::pair<void*, std::uintptr_t>>> byObject;
  for (void* address : addresses)
  {
    Dl_info info;
    if (dladdr(address, &info) != 0 && info.dli_fname != nullptr)
    {
      const auto base = reinterpret_cast<std::uintptr_t>(info.dli_fbase);
      // (Return addresses: the call is the byte before.)
      byObject[info.dli_fname].push_back(
        { address, reinterpret_cast<std::uintptr_t>(address) - base - 1 });
    }
  }
  std::map<void*, std::string> names;
  for (const auto& object : byObject)
  {
    std::string command = "addr2line -f -C -e '" + object.first + "'";
    for (const auto& entry : object.second)
    {
      char offset[32];
      std::snprintf(
        offset, sizeof offset, " 0x%llx", static_cast<unsigned long long>(entry.second));
      command += offset;
    }
    FILE* pipe = popen(command.c_str(), "r");
    char line[4096];
    for (const auto& entry : object.second)
    {
      std::string name = "?";
      if (pipe != nullptr && std::fgets(line, sizeof line, pipe) != nullptr)
      {
        name = line;
        name.erase(name.find_last_not_of('\n') + 1);
        std::fgets(line, sizeof line, pipe); // the file and line
      }
      if (name.size() > 90)
      {
        name = name.substr(0, 87) + "...";
      }
      names[entry.first] = name;
    }
    if (pipe != nullptr)
    {
      pclose(pipe);
    }
  }
  return names;
}

/// A gap's stacks, most frequent first, each as its innermost frames.
void PrintStacks(const Gap& gap, std::map<void*, std::string>& names)
{
  std::map<std::string, int> stacks;
  int taken = 0;
  for (int k = 0; k < std::min(SampleCount.load(), MaxSamples); ++k)
  {
    if (Samples[k].GapStart != gap.Start)
    {
      continue;
    }
    ++taken;
    std::string stack;
    int shown = 0;
    // Frames 0 and 1 are the handler and the signal's return.
    for (int f = 2; f < Samples[k].Depth && shown < 7; ++f)
    {
      const std::string& name = names[Samples[k].Frames[f]];
      if (name == "?" || name.empty())
      {
        continue;
      }
      stack += (shown++ == 0 ? "" : " < ") + name;
    }
    ++stacks[stack];
  }
  std::vector<std::pair<int, std::string>> sorted;
  for (const auto& entry : stacks)
  {
    sorted.push_back({ entry.second, entry.first });
  }
  std::sort(sorted.rbegin(), sorted.rend());
  for (std::size_t s = 0; s < sorted.size() && s < 4; ++s)
  {
    std::printf("    %d/%d samples: %s\n", sorted[s].first, taken, sorted[s].second.c_str());
  }
}

void Report(int top)
{
  std::vector<void*> addresses;
  for (int k = 0; k < std::min(SampleCount.load(), MaxSamples); ++k)
  {
    addresses.insert(addresses.end(), Samples[k].Frames, Samples[k].Frames + Samples[k].Depth);
  }
  std::sort(addresses.begin(), addresses.end());
  addresses.erase(std::unique(addresses.begin(), addresses.end()), addresses.end());
  std::map<void*, std::string> names = Symbolize(addresses);
  std::vector<Gap> sorted = Gaps;
  std::sort(
    sorted.begin(), sorted.end(), [](const Gap& a, const Gap& b) { return a.Seconds > b.Seconds; });
  std::printf("Gaps longer than %.3f s, longest first:\n", Threshold);
  for (std::size_t g = 0; g < sorted.size() && static_cast<int>(g) < top; ++g)
  {
    const Gap& gap = sorted[g];
    std::printf("%s: %.3f s from %.3f s (steady clock %.6f), ended by %s\n",
      PhaseNames[gap.Phase],
      gap.Seconds,
      1e-9 * static_cast<double>(gap.Start - RunStart),
      1e-9 * static_cast<double>(gap.Start),
      gap.EndedBy);
    PrintStacks(gap, names);
  }
  std::printf("\n| phase | largest gap between questions (s) |\n| --- | ---: |\n");
  for (int phase = Reading; phase <= Writing; ++phase)
  {
    double largest = 0.0;
    for (const Gap& gap : Gaps)
    {
      largest = gap.Phase == phase ? std::max(largest, gap.Seconds) : largest;
    }
    std::printf("| %s | %s |\n",
      PhaseNames[phase],
      largest > 0.0 ? std::to_string(largest).substr(0, 5).c_str() : "below the threshold");
  }
}
/// The events that open and close each algorithm's gaps and follow the filter's phases.
void ObservePhases(vtkAlgorithm* reader,
  vtkPointCloudBilateralFilter* filter,
  vtkAlgorithm* writer,
  std::function<void()>& onStart,
  std::function<void()>& onEnd,
  std::function<void()>& onChosen,
  std::function<void()>& onProgress)
{
  onStart = []() { Asked("the start"); };
  onEnd = []()
  {
    Asked("the return");
    LastQuestion = 0;
  };
  onChosen = []() { PhaseNow = Octree; };
  onProgress = [filter]()
  {
    const double progress = filter->GetProgress();
    if (PhaseNow == Octree && progress > 0.0)
      PhaseNow = Kernel;
    else if (PhaseNow == Kernel && progress >= 1.0)
      PhaseNow = Output;
  };
  for (vtkAlgorithm* algorithm : { reader, static_cast<vtkAlgorithm*>(filter), writer })
  {
    Observe(algorithm, vtkCommand::StartEvent, &onStart);
    Observe(algorithm, vtkCommand::EndEvent, &onEnd);
  }
  Observe(filter, vtkPointCloudBilateralFilter::ParametersChosenEvent, &onChosen);
  Observe(filter, vtkCommand::ProgressEvent, &onProgress);
}
}

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::fprintf(stderr,
      "usage: pcb_abort_gaps INPUT.las OUTPUT.las [--iterations N] [--radius R] "
      "[--threshold S] [--top K]\n");
    return 1;
  }
  int iterations = 1, top = 12;
  double radius = 0.0;
  for (int i = 3; i + 1 < argc; i += 2)
  {
    if (std::strcmp(argv[i], "--iterations") == 0)
      iterations = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--radius") == 0)
      radius = std::atof(argv[i + 1]);
    else if (std::strcmp(argv[i], "--threshold") == 0)
      Threshold = std::atof(argv[i + 1]);
    else if (std::strcmp(argv[i], "--top") == 0)
      top = std::atoi(argv[i + 1]);
  }
  Runner = pthread_self();
  void* warm[4];
  backtrace(warm, 4); // (loads the unwinder before any signal)
  std::signal(SIGPROF, TakeSample);
  auto reader =
    vtkSmartPointer<Traced<vtkLASPointCloudReader>>::Take(Traced<vtkLASPointCloudReader>::Make());
  auto filter = vtkSmartPointer<Traced<vtkPointCloudBilateralFilter>>::Take(
    Traced<vtkPointCloudBilateralFilter>::Make());
  auto writer =
    vtkSmartPointer<Traced<vtkLASPointCloudWriter>>::Take(Traced<vtkLASPointCloudWriter>::Make());
  reader->SetFileName(argv[1]);
  filter->SetInputConnection(reader->GetOutputPort());
  filter->SetNumberOfIterations(iterations);
  filter->SetRadius(radius);
  writer->SetInputConnection(filter->GetOutputPort());
  writer->SetFileName(argv[2]);

  std::function<void()> onStart, onEnd, onChosen, onProgress;
  ObservePhases(reader, filter, writer, onStart, onEnd, onChosen, onProgress);
  std::atomic<bool> done{ false };
  std::thread watcher(Watch, std::cref(done));
  RunStart = NowNs();
  PhaseNow = Reading;
  reader->Update();
  const double read = 1e-9 * static_cast<double>(NowNs() - RunStart);
  PhaseNow = Measuring;
  filter->Update();
  const double filtered = 1e-9 * static_cast<double>(NowNs() - RunStart);
  PhaseNow = Writing;
  writer->Write();
  const double written = 1e-9 * static_cast<double>(NowNs() - RunStart);
  done = true;
  watcher.join();
  std::printf("%s: reading %.3f s, filter %.3f s (r %g, N %d), writing %.3f s; %d stack "
              "samples\n\n",
    argv[1],
    read,
    filtered - read,
    filter->GetRadiusUsed(),
    filter->GetNumberOfIterationsUsed(),
    written - filtered,
    SampleCount.load());
  Report(top);
  return 0;
}

#include "ProgressCheck.h"

#include <algorithm>
#include <cstdlib>
#include <utility>

namespace pcbilateral
{
namespace
{
/// Each thread's innermost open scope.
thread_local ProgressScope* InnermostScope = nullptr;
/// 50 ms, or PCB_PROGRESS_INTERVAL_US from the environment when first asked (for tests: each
/// library that links this one statically, a VTK module say, has its own copy of the setting).
std::atomic<std::int64_t>& ReportIntervalMicroseconds()
{
  static std::atomic<std::int64_t> interval{ []
    {
      const char* given = std::getenv("PCB_PROGRESS_INTERVAL_US");
      return given != nullptr ? std::strtoll(given, nullptr, 10) : 50000ll;
    }() };
  return interval;
}
}

std::chrono::microseconds ProgressScope::GetReportInterval()
{
  return std::chrono::microseconds(ReportIntervalMicroseconds().load(std::memory_order_relaxed));
}

void ProgressScope::SetReportInterval(std::chrono::microseconds interval)
{
  ReportIntervalMicroseconds().store(interval.count(), std::memory_order_relaxed);
}

ProgressScope::ProgressScope(ProgressFunction progress, AbortFunction shouldAbort)
  : Progress(std::move(progress))
  , ShouldAbort(std::move(shouldAbort))
  , Enclosing(InnermostScope)
  , Owner(std::this_thread::get_id())
{
  InnermostScope = this;
}

ProgressScope::~ProgressScope()
{
  InnermostScope = this->Enclosing;
}

ProgressScope* ProgressScope::Current()
{
  return InnermostScope;
}

bool ProgressScope::Check(double fraction)
{
  if (this->StopAsked() || std::this_thread::get_id() != this->Owner)
  {
    return this->StopAsked();
  }
  const auto now = std::chrono::steady_clock::now();
  if (this->Checked && now < this->NextCheck && fraction < 1.0)
  {
    return false;
  }
  this->Checked = true;
  this->NextCheck = now + GetReportInterval();
  if (this->Progress)
  {
    const double clamped = fraction < 0.0 ? 0.0 : (fraction > 1.0 ? 1.0 : fraction);
    this->Progress(this->StageBegin + this->StageShare * clamped);
  }
  return this->CheckNow();
}

bool ProgressScope::CheckNow()
{
  if (std::this_thread::get_id() == this->Owner && !this->StopAsked() && this->ShouldAbort &&
      this->ShouldAbort())
  {
    this->Stopped.store(true, std::memory_order_relaxed);
  }
  return this->StopAsked();
}

void ParallelProgress::WaitForOthers()
{
  if (this->Scope == nullptr || !this->Scope->CalledByOwner())
  {
    return;
  }
  while (this->Ended.load(std::memory_order_acquire) < this->Total)
  {
    const std::uint64_t done = this->Count.load(std::memory_order_relaxed);
    this->Scope->Check(
      static_cast<double>(done) / static_cast<double>(std::max<std::uint64_t>(this->Total, 1)));
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

bool ProgressPoint(std::uint64_t done, std::uint64_t total)
{
  ProgressScope* scope = InnermostScope;
  return scope != nullptr &&
         scope->Check(total == 0 ? 1.0 : static_cast<double>(done) / static_cast<double>(total));
}

void SetProgressStage(double begin, double end)
{
  if (InnermostScope != nullptr)
  {
    InnermostScope->SetStage(begin, end);
  }
}

bool ProgressStopAsked()
{
  return InnermostScope != nullptr && InnermostScope->StopAsked();
}

} // namespace pcbilateral

// Progress and abort, checked at the same points of every phase of a run: reading, measuring,
// building the octree, filtering, writing. Plain C++17.
#ifndef pcbilateral_ProgressCheck_h
#define pcbilateral_ProgressCheck_h

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <thread>

namespace pcbilateral
{

/**
 * The progress and abort hooks of one phase, opened by a front end around it (a VTK reader's
 * RequestData, the command line's write, the filter's measurement) and found by the loops deep
 * inside it through the calling thread, so that the formats and the core need no extra
 * parameter on each of their functions:
 *
 *   ProgressScope scope(progress, shouldAbort);  // around the phase, on the calling thread
 *   ...
 *   for (each block of about a millisecond of work)
 *     if (ProgressPoint(done, total)) return;     // the phase's loops: stop when true
 *   if (scope.StopAsked()) ...                     // the front end: the phase was aborted
 *
 * The hooks are called only from the thread that opened the scope: at the first point of the
 * phase, then at most every GetReportInterval() (a clock read per point, nothing else), so a point
 * costs nothing measurable at a block of a few thousand points, and an abort is seen within
 * interval plus one block. Inside a parallel loop the calling thread is thread 0; the
 * other threads ask StopAsked() of the scope (Current(), taken before the loop). Scopes nest:
 * an inner one hides the outer one until it closes. Without a scope, ProgressPoint is false.
 */
class ProgressScope
{
public:
  using ProgressFunction = std::function<void(double)>;
  using AbortFunction = std::function<bool()>;

  /// How often, at most, the hooks are called: 50 ms. Tests set 0, to see every point of a
  /// phase on small clouds (through the environment variable PCB_PROGRESS_INTERVAL_US for the
  /// copies of this library linked into the VTK modules).
  static std::chrono::microseconds GetReportInterval();
  static void SetReportInterval(std::chrono::microseconds interval);

  /// Either hook may be empty.
  ProgressScope(ProgressFunction progress, AbortFunction shouldAbort);
  ~ProgressScope();
  ProgressScope(const ProgressScope&) = delete;
  ProgressScope& operator=(const ProgressScope&) = delete;

  /// The innermost open scope of the calling thread, or null.
  static ProgressScope* Current();

  /// Reports `fraction` of the phase and asks whether to stop, when due (the first call, then
  /// every GetReportInterval(), and at a fraction of 1) and called from the thread that opened the
  /// scope (from another thread: StopAsked()). Returns whether the phase is to stop (once true,
  /// always true).
  bool Check(double fraction);

  /// The stage of the phase the next points belong to: their fractions 0 to 1 are reported as
  /// `begin` to `end` of the phase (a reader's decompression, then its decoding).
  void SetStage(double begin, double end)
  {
    this->StageBegin = begin;
    this->StageShare = end - begin;
  }

  /// Any thread: whether the phase was asked to stop (no hook called).
  bool StopAsked() const { return this->Stopped.load(std::memory_order_relaxed); }

  /// The thread that opened the scope: asks the abort hook now, whatever the clock says.
  bool CheckNow();

  /// Whether the calling thread opened the scope (the one whose Check calls the hooks).
  bool CalledByOwner() const { return std::this_thread::get_id() == this->Owner; }

private:
  ProgressFunction Progress;
  AbortFunction ShouldAbort;
  ProgressScope* Enclosing;
  std::thread::id Owner;
  std::atomic<bool> Stopped{ false };
  bool Checked = false;
  double StageBegin = 0.0;
  double StageShare = 1.0;
  std::chrono::steady_clock::time_point NextCheck;
};

/**
 * Progress and abort in a parallel loop over `total` items of a phase: each thread calls Done
 * after a block of its items, and skips the rest of its blocks once it returns true. The thread
 * that opened the scope reports the items all threads have done and asks whether to stop; the
 * others see the stop. Taken on the calling thread, before the loop.
 */
class ParallelProgress
{
public:
  explicit ParallelProgress(std::uint64_t total)
    : Scope(ProgressScope::Current())
    , Total(total)
  {
  }

  /// After `items` more items done: whether to stop.
  bool Done(std::uint64_t items)
  {
    if (this->Scope == nullptr)
    {
      return false;
    }
    this->Ended.fetch_add(items, std::memory_order_release);
    const std::uint64_t done = this->Count.fetch_add(items, std::memory_order_relaxed) + items;
    return this->Scope->Check(
      this->Total == 0 ? 1.0 : static_cast<double>(done) / static_cast<double>(this->Total));
  }

  /// Whether the phase was asked to stop (any thread; no hook called).
  bool StopAsked() const { return this->Scope != nullptr && this->Scope->StopAsked(); }

  /// After `items` more items skipped, once a stop was seen (for WaitForOthers).
  void Skipped(std::uint64_t items) { this->Ended.fetch_add(items, std::memory_order_release); }

  /**
   * Called by each thread once out of items in a loop without a barrier at its end (`omp for
   * nowait`), every item then Done or Skipped: the thread that opened the scope keeps asking
   * whether to stop, every millisecond, until all items have ended; the others return at once.
   * Without it, that thread waited for the others' last items in the loop's barrier, asking
   * nothing: 0.8 s of a 20-million-point read on a busy machine, whose other thread was
   * clearing fresh pages.
   */
  void WaitForOthers();

private:
  ProgressScope* Scope;
  std::uint64_t Total;
  std::atomic<std::uint64_t> Count{ 0 };
  std::atomic<std::uint64_t> Ended{ 0 };
};

/// In the calling thread's innermost scope (if any): `done` of `total` units of the phase done.
/// Returns whether to stop. Call it from the thread that opened the scope.
bool ProgressPoint(std::uint64_t done, std::uint64_t total);

/// In the calling thread's innermost scope (if any): ProgressScope::SetStage.
void SetProgressStage(double begin, double end);

/// Whether the calling thread's innermost scope (if any) was asked to stop.
bool ProgressStopAsked();

/// The one-line message a format's reader or writer returns when its phase was aborted.
constexpr const char* AbortedMessage = "aborted";

} // namespace pcbilateral

#endif

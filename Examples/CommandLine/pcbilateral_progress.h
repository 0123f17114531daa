// What pcbilateral prints while it runs: each summary line as soon as it is known, and the
// progress of each phase (reading, measuring, each iteration, writing, the slabs of a streamed
// run). On a terminal a bar per phase with the time left, redrawn at most four times a second
// (and at least once a second while the phase reports) and erased before anything else is
// printed; otherwise plain lines: one when a phase ends, and one every ten seconds within a long
// one. --quiet prints neither.
#ifndef pcbilateral_progress_h
#define pcbilateral_progress_h

#include <chrono>
#include <string>

namespace pcbilateral_cli
{

class ProgressLines
{
public:
  /// Quiet: nothing at all. Bar: a terminal's bar (else plain lines).
  void Configure(bool quiet, bool bar);
  bool IsQuiet() const { return this->Quiet; }
  bool ShowsBar() const { return this->ShowBar; }

  /// `fraction` of `phase` ("reading", "iteration 2 of 3") done. A new phase ends the last one.
  void Phase(const std::string& phase, double fraction);
  /// Ends the current phase (its plain line, or its bar erased), if any; a phase that did not
  /// complete (a file that could not be read or written) gets no "done" line.
  void EndPhase(bool completed = true);
  /// Erases the bar, if shown (before a line is printed).
  void ClearBar();

private:
  void DrawBar(double fraction, double elapsed);

  bool Quiet = false;
  bool ShowBar = false;
  bool BarShown = false;
  std::string Current;
  std::chrono::steady_clock::time_point Start, LastDrawn;
};

/// The program's one display.
ProgressLines& Screen();

/// printf to the standard output, unless --quiet; the bar erased first, the line out at once.
void Say(const char* format, ...);

} // namespace pcbilateral_cli

#endif

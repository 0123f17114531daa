// What pcbilateral says about options that cannot do what they ask with these files, judged
// from the file names and the machine before anything is read: a thread count beyond the
// hardware, -R and --keep-nan where they have no effect, --keep-nan into a format that cannot
// hold the points it keeps.
#ifndef pcbilateral_checks_h
#define pcbilateral_checks_h

#include <string>
#include <vector>

namespace pcbilateral_cli
{

/// The warning for -t `requested` when it is more than the hardware threads this process may
/// run on (the result is the same, only slower), or empty (0 and unknown hardware included).
std::string ThreadsWarning(int requested, int hardwareThreads);

/// One warning per option that has no effect on reading `input` and writing `output`, with
/// why: -R (`orientedNormals`) on LAS or LAZ input, or with neither file a text file;
/// --keep-nan (`keepNaN`) on any input but PCD.
std::vector<std::string> NoEffectWarnings(const std::string& input,
  const std::string& output,
  bool orientedNormals,
  bool keepNaN);

/// Why the points --keep-nan keeps cannot be written to `output` (a PCD input into LAS or LAZ,
/// whose integer coordinates cannot be NaN), or empty.
std::string KeepNaNOutputProblem(const std::string& input, const std::string& output, bool keepNaN);

/// Why `output` cannot take a cloud with `nonFinitePoints` points without finite coordinates
/// (LAS or LAZ), or empty.
std::string NonFiniteOutputProblem(const std::string& output, unsigned long long nonFinitePoints);

} // namespace pcbilateral_cli

#endif

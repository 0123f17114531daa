#include "pcbilateral_progress.h"

#include <cstdarg>
#include <cstdio>

namespace pcbilateral_cli
{
namespace
{
/// "phase:" padded to the summary's column (15), with at least one space after it.
std::string Label(const std::string& phase)
{
  const std::string label = phase + ":";
  return label + std::string(label.size() < 15 ? 15 - label.size() : 1, ' ');
}
}

void ProgressLines::Configure(bool quiet, bool bar)
{
  this->Quiet = quiet;
  this->ShowBar = !quiet && bar;
}

void ProgressLines::ClearBar()
{
  if (this->BarShown)
  {
    std::fputs("\r\033[K", stdout);
    std::fflush(stdout);
    this->BarShown = false;
  }
}

void ProgressLines::DrawBar(double fraction, double elapsed)
{
  constexpr int Width = 30;
  const int filled = static_cast<int>(fraction * Width);
  char left[32] = "";
  if (fraction > 0.02 && fraction < 1.0)
  {
    std::snprintf(left, sizeof left, ", %.0f s left", elapsed * (1.0 - fraction) / fraction);
  }
  const std::string label = Label(this->Current);
  std::printf("\r%s[%s%s] %3.0f%%%s\033[K",
    label.c_str(),
    std::string(static_cast<std::size_t>(filled), '#').c_str(),
    std::string(static_cast<std::size_t>(Width - filled), '.').c_str(),
    100.0 * fraction,
    left);
  std::fflush(stdout);
  this->BarShown = true;
}

void ProgressLines::Phase(const std::string& phase, double fraction)
{
  if (this->Quiet)
  {
    return;
  }
  const auto now = std::chrono::steady_clock::now();
  if (phase != this->Current)
  {
    this->EndPhase();
    this->Current = phase;
    this->Start = now;
    this->LastDrawn = now;
    if (this->ShowBar)
    {
      this->DrawBar(fraction, 0.0);
    }
    return;
  }
  const double elapsed = std::chrono::duration<double>(now - this->Start).count();
  const auto interval = this->ShowBar ? std::chrono::milliseconds(250) : std::chrono::seconds(10);
  if (now - this->LastDrawn < interval)
  {
    return;
  }
  this->LastDrawn = now;
  if (this->ShowBar)
  {
    this->DrawBar(fraction, elapsed);
  }
  else if (fraction > 0.0)
  {
    const std::string label = Label(this->Current);
    std::printf("%s%.0f%%, %.0f s left\n",
      label.c_str(),
      100.0 * fraction,
      elapsed * (1.0 - fraction) / fraction);
    std::fflush(stdout);
  }
}

void ProgressLines::EndPhase(bool completed)
{
  if (this->Current.empty())
  {
    return;
  }
  this->ClearBar();
  if (completed && !this->ShowBar && !this->Quiet)
  {
    const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
    std::printf("%sdone, %.3f s\n", Label(this->Current).c_str(), elapsed);
    std::fflush(stdout);
  }
  this->Current.clear();
}

ProgressLines& Screen()
{
  static ProgressLines lines;
  return lines;
}

void Say(const char* format, ...)
{
  ProgressLines& screen = Screen();
  if (screen.IsQuiet())
  {
    return;
  }
  screen.ClearBar();
  va_list arguments;
  va_start(arguments, format);
  std::vprintf(format, arguments);
  va_end(arguments);
  std::fflush(stdout);
}

} // namespace pcbilateral_cli

#include "pcbilateral_checks.h"

#include "StreamedArrays.h"

namespace pcbilateral_cli
{
namespace
{
/// "a text file", "a PLY file", ... by the path's extension, for the messages.
std::string KindOf(const std::string& path)
{
  if (pcbilateral::IsTextPath(path))
  {
    return "a text file";
  }
  if (pcbilateral::HasExtension(path, ".ply"))
  {
    return "a PLY file";
  }
  if (pcbilateral::HasExtension(path, ".vtp"))
  {
    return "a VTP file";
  }
  return "this file";
}
} // namespace

std::string ThreadsWarning(int requested, int hardwareThreads)
{
  if (hardwareThreads <= 0 || requested <= hardwareThreads)
  {
    return std::string();
  }
  return "-t " + std::to_string(requested) + " asks for more threads than the " +
         std::to_string(hardwareThreads) +
         " hardware threads this process can run on: the result is the same, only slower";
}

std::vector<std::string> NoEffectWarnings(const std::string& input,
  const std::string& output,
  bool orientedNormals,
  bool keepNaN)
{
  std::vector<std::string> warnings;
  const bool lasInput = pcbilateral::IsLASPath(input);
  if (orientedNormals && lasInput)
  {
    warnings.push_back("-R has no effect on " + input +
                       ": a LAS file has no normals to read, orient by or write back");
  }
  else if (orientedNormals && !pcbilateral::IsTextPath(input) && !pcbilateral::IsTextPath(output))
  {
    warnings.push_back("-R has no effect here: it reads normals from a text input and writes "
                       "normals to a text output, and neither " +
                       input + " nor " + output + " is a text file");
  }
  if (keepNaN && lasInput)
  {
    warnings.push_back(
      "--keep-nan has no effect on " + input + ": LAS coordinates are integers and cannot be NaN");
  }
  else if (keepNaN && !pcbilateral::HasExtension(input, ".pcd"))
  {
    warnings.push_back("--keep-nan has no effect on " + input + ": " + KindOf(input) +
                       "'s points with NaN coordinates are always kept (only PCD input "
                       "leaves them out)");
  }
  return warnings;
}

std::string KeepNaNOutputProblem(const std::string& input, const std::string& output, bool keepNaN)
{
  if (!keepNaN || !pcbilateral::HasExtension(input, ".pcd") || !pcbilateral::IsLASPath(output))
  {
    return std::string();
  }
  return "--keep-nan: " + output +
         ": a LAS file cannot hold the points without coordinates (NaN) it keeps; leave "
         "--keep-nan out (they are then left out) or write a .pcd file";
}

std::string NonFiniteOutputProblem(const std::string& output, unsigned long long nonFinitePoints)
{
  if (nonFinitePoints == 0 || !pcbilateral::IsLASPath(output))
  {
    return std::string();
  }
  return output + ": a LAS file cannot hold the input's " + std::to_string(nonFinitePoints) +
         " point(s) with NaN or infinite coordinates (LAS coordinates are integers); write a "
         ".pcd, .txt, .xyz, .ply or .vtp file";
}

} // namespace pcbilateral_cli

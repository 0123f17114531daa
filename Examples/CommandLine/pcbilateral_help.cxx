#include "pcbilateral_help.h"

#include "AutomaticRule.h"
#include "BilateralParameters.h"
#include "EdgeAwareRule.h"

#include <cstdio>
#include <sstream>
#include <string>

namespace pcbilateral_cli
{
namespace
{
// The help's fixed text; the automatic rule and the paper's heuristic are the core's own words
// (AutomaticRule.h), inserted by HelpText.
const char* const UsageHead =
  "usage: pcbilateral INPUT OUTPUT [-r R] [-n RN] [-N ITER] [--paper] [-R] [-t THREADS]\n"
  "                   [--remove-isolated] [--edge-aware] [--keep-nan] [-q]\n"
  "                   [--classes LIST [--class-array NAME]]\n"
  "                   [--copc-level N] [--copc-bounds xmin,xmax,ymin,ymax,zmin,zmax]\n"
  "                   [--memory-limit SIZE]\n"
  "\n"
  "Denoises a point cloud with the bilateral filter (Digne & de Franchis, IPOL 2017).\n"
  "INPUT and OUTPUT: .txt or .xyz (x y z [nx ny nz] [more columns]), .las (LiDAR),\n"
  ".laz (compressed LiDAR), .pcd (PCL's), .ply or .vtp. A text file is written as the\n"
  "text input was: the same columns in the same order, a header line only if it had\n"
  "one, spaces or tabs.\n"
  "\n"
  "  -r R               neighbourhood radius\n"
  "  -n RN              normal radius, the tolerance to the tangent plane\n"
  "  -N ITER            number of iterations\n";
const char* const AutomaticLead =
  "Each is automatic when not given (or 0): chosen from the cloud's measured point spacing "
  "and noise sigma";
const char* const PaperLead =
  "parameters not given follow the paper's heuristic instead, as the authors' program:";
const char* const UsageTail =
  "  -R                 text files carry oriented normals in columns 4-6; the estimated\n"
  "                     normals are oriented by them and they are written back (a text\n"
  "                     output gets the normals of a PCD, PLY or VTP input; LAS and LAZ\n"
  "                     have no normals: a warning says it has no effect there)\n";
const char* const ThreadsText =
  "threads (default 0: all cores), at most %d; the result does not depend on it, and more "
  "than the machine's hardware threads only slow the run (a warning says so)";
const char* const UsageOptions =
  "  --remove-isolated  remove points with fewer than 5 neighbours, as the authors' program\n"
  "                     does (default: they stay where they are)\n"
  "  --edge-aware       edge-aware mode, beyond the paper: normals filtered bilaterally\n"
  "                     before the displacement, for sharp edges under strong noise\n"
  "                     (default: the paper's filter)\n"
  "  --classes LIST     filter only the points of these classes (integers, comma-separated,\n"
  "                     e.g. 2,6 for LAS ground and buildings); the others keep their exact\n"
  "                     coordinates and are no one's neighbours (default: every point)\n"
  "  --class-array NAME the integer point array that holds the class (default\n"
  "                     Classification, as LAS files name it)\n"
  "  --keep-nan         PCD input: keep the points without coordinates (NaN) of an\n"
  "                     organised frame in place, never as neighbours, so that a .pcd\n"
  "                     output keeps the frame's WIDTH and HEIGHT (default: left out);\n"
  "                     a warning says it has no effect on other input (LAS coordinates\n"
  "                     cannot be NaN; text, PLY and VTP keep such points anyway), and\n"
  "                     it is refused with a .las or .laz output, which cannot hold them\n"
  "  --copc-level N     COPC input: read only the octree levels 0 to N (a level of detail;\n"
  "                     default -1: every point)\n"
  "  --copc-bounds B    COPC input: read only the points inside the box B =\n"
  "                     xmin,xmax,ymin,ymax,zmin,zmax (the file's coordinates)\n"
  "  --memory-limit SIZE  filter the file in slabs within SIZE of memory (e.g. 512M, 2G),\n"
  "                     temporary files in TMPDIR or beside the output; the same output\n"
  "                     file as in memory. LAS, LAZ, text or PCD into any of them;\n"
  "                     --edge-aware, --remove-isolated, -R, --keep-nan.\n"
  "                     Default: in memory, or streamed within 80% of the available\n"
  "                     memory when the cloud needs more (said). A SIZE without a unit\n"
  "                     is in bytes; one below a megabyte is refused before reading\n"
  "  -q, --quiet        print nothing but warnings and errors (default: what was read,\n"
  "                     measured, chosen and written, each line as soon as it is known, and\n"
  "                     on a terminal a progress bar with the time left for reading,\n"
  "                     measuring, each iteration and writing)\n"
  "  -p                 accepted for compatibility and ignored: the filter always runs in "
  "parallel\n"
  "  -h, --help         this text\n";

/// The help's option descriptions start in this column and wrap before this width.
constexpr std::size_t DescriptionColumn = 21;
constexpr std::size_t HelpWidth = 86;

/// `label` padded to the description column, then `text` wrapped at word boundaries, each
/// continuation line indented to that column.
std::string OptionParagraph(const std::string& label, const std::string& text)
{
  std::string paragraph = label + std::string(DescriptionColumn - label.size(), ' ');
  std::size_t lineLength = DescriptionColumn;
  std::istringstream words(text);
  std::string word;
  while (words >> word)
  {
    const bool lineStarted = lineLength > DescriptionColumn;
    if (lineStarted && lineLength + 1 + word.size() > HelpWidth)
    {
      paragraph += "\n" + std::string(DescriptionColumn, ' ');
      lineLength = DescriptionColumn;
    }
    else if (lineStarted)
    {
      paragraph += ' ';
      ++lineLength;
    }
    paragraph += word;
    lineLength += word.size();
  }
  return paragraph + "\n";
}

/// The -t paragraph, with the core's limit.
std::string ThreadsParagraph()
{
  char text[256];
  std::snprintf(text, sizeof text, ThreadsText, pcbilateral::limits::MaximumThreads);
  return text;
}

} // namespace

std::string HelpText()
{
  return UsageHead +
         OptionParagraph("",
           std::string(AutomaticLead) + " (" + pcbilateral::DescribeAutomaticRule() + "; " +
             pcbilateral::DescribeEdgeAwareRule() + ")") +
         OptionParagraph(
           "  --paper", std::string(PaperLead) + " " + pcbilateral::DescribePaperRule()) +
         UsageTail + OptionParagraph("  -t THREADS", ThreadsParagraph()) + UsageOptions;
}

} // namespace pcbilateral_cli

// Build tool: writes the proxy XML with the automatic rule's words filled in from the one place
// the rule is written (Filters/Core/Measurement/AutomaticRule.h), so that ParaView's help can
// never state another rule than the filter runs.
//   FillRuleText IN OUT    replaces {{AUTOMATIC_RULE}}, {{PAPER_RULE}} and {{EDGE_AWARE_RULE}}
//   FillRuleText --print   prints the three texts, one per line (for the documentation test)
#include "AutomaticRule.h"
#include "EdgeAwareRule.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace
{
void ReplaceAll(std::string& text, const std::string& placeholder, const std::string& value)
{
  for (std::size_t at = text.find(placeholder); at != std::string::npos;
       at = text.find(placeholder, at + value.size()))
  {
    text.replace(at, placeholder.size(), value);
  }
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc == 2 && std::string(argv[1]) == "--print")
  {
    std::printf("%s\n%s\n%s\n",
      pcbilateral::DescribeAutomaticRule().c_str(),
      pcbilateral::DescribePaperRule(),
      pcbilateral::DescribeEdgeAwareRule().c_str());
    return 0;
  }
  if (argc != 3)
  {
    std::fprintf(stderr, "usage: FillRuleText IN OUT\n");
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in)
  {
    std::fprintf(stderr, "FillRuleText: cannot read %s\n", argv[1]);
    return 1;
  }
  std::string xml = text.str();
  ReplaceAll(xml, "{{AUTOMATIC_RULE}}", pcbilateral::DescribeAutomaticRule());
  ReplaceAll(xml, "{{PAPER_RULE}}", pcbilateral::DescribePaperRule());
  ReplaceAll(xml, "{{EDGE_AWARE_RULE}}", pcbilateral::DescribeEdgeAwareRule());
  std::ofstream out(argv[2], std::ios::binary | std::ios::trunc);
  out << xml;
  if (!out.flush())
  {
    std::fprintf(stderr, "FillRuleText: cannot write %s\n", argv[2]);
    return 1;
  }
  return 0;
}

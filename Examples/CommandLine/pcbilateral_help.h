// The text of pcbilateral -h: the options, their defaults and limits; the automatic rule and the
// paper's heuristic in the core's own words (AutomaticRule.h), the limits from the core's
// (BilateralParameters.h).
#ifndef pcbilateral_help_h
#define pcbilateral_help_h

#include <string>

namespace pcbilateral_cli
{

/// What pcbilateral -h prints.
std::string HelpText();

} // namespace pcbilateral_cli

#endif

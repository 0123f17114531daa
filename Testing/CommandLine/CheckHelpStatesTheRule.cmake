# pcbilateral's help states the automatic rule and the paper's heuristic in the words of the
# rule's own code (Filters/Core/Measurement/AutomaticRule.h), which RULE_PROGRAM prints, one per
# line; the help may wrap them, so spaces and line breaks are compared as one space.
#   cmake -DPROGRAM=<pcbilateral> -DRULE_PROGRAM=<pcb_fill_rule_text> -P CheckHelpStatesTheRule.cmake
cmake_minimum_required(VERSION 3.16)
execute_process(COMMAND "${PROGRAM}" --help OUTPUT_VARIABLE help ERROR_VARIABLE help_errors
  RESULT_VARIABLE status)
execute_process(COMMAND "${RULE_PROGRAM}" --print OUTPUT_VARIABLE rules RESULT_VARIABLE rule_status)
if (NOT rule_status EQUAL 0)
  message(FATAL_ERROR "${RULE_PROGRAM} --print failed")
endif ()
# (The texts' semicolons would split CMake's lists: they are compared as "<semicolon>".)
string(REPLACE ";" "<semicolon>" help "${help}${help_errors}")
string(REPLACE ";" "<semicolon>" rules "${rules}")
string(REGEX REPLACE "[ \t\r\n]+" " " help "${help}")
string(REGEX REPLACE "\n$" "" rules "${rules}")
string(REPLACE "\n" ";" rules "${rules}")
foreach (rule IN LISTS rules)
  string(FIND "${help}" "${rule}" at)
  if (at LESS 0)
    message(FATAL_ERROR "the help does not state: ${rule}")
  endif ()
  message(STATUS "stated: ${rule}")
endforeach ()

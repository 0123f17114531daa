// A PLY file's header checked against the file before a reader sees it: VTK's PLY reader does
// not stop at a damaged file (one cut short reads as made-up points with thousands of
// warnings; one announcing more vertices than it holds aborts the program).
#ifndef pcbilateral_PLYFileCheck_h
#define pcbilateral_PLYFileCheck_h

#include <string>

namespace pcbilateral
{

/**
 * Checks that the file starts with a PLY header of a known format and property types, whose
 * vertices have x, y and z properties, and that the data after it holds as many records as it
 * announces (bytes for binary files; lines, each with a value per property, for ASCII ones).
 * Returns an empty string, or one line: "PATH: problem".
 */
std::string CheckPLYFile(const std::string& path);

} // namespace pcbilateral

#endif

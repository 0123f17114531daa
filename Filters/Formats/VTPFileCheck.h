// A VTK XML file checked before a reader sees it: VTK's XML reader does not stop at a file cut
// short.
#ifndef pcbilateral_VTPFileCheck_h
#define pcbilateral_VTPFileCheck_h

#include <string>

namespace pcbilateral
{

/// Checks that the file starts as a VTK XML file (a <VTKFile> element in its first 512 bytes)
/// and ends with </VTKFile>. Returns an empty string, or one line: "PATH: problem".
std::string CheckVTPFile(const std::string& path);

} // namespace pcbilateral

#endif

// The checks that look at a PLY or VTP file before VTK's readers do (PLYFileCheck.h,
// VTPFileCheck.h): each message, on a small file made for it, and no message on good files.
#include "CoreTesting.h"

#include "PLYFileCheck.h"
#include "VTPFileCheck.h"

#include <cstdio>
#include <string>

namespace
{
using pcbilateral_testing::WriteFileContents;

/// A check's message for a file of `bytes`: "" or the problem after "NAME: ".
template<typename Check>
void Expect(Check check,
  const std::string& name,
  const std::string& bytes,
  const std::string& problem)
{
  const std::string path = WriteFileContents(name, bytes);
  const std::string expected = problem.empty() ? problem : path + ": " + problem;
  const std::string found = check(path);
  PCB_CHECK(found == expected,
    "%s: \"%s\" instead of \"%s\"",
    name.c_str(),
    found.c_str(),
    expected.c_str());
  std::remove(path.c_str());
}

void ExpectPLY(const std::string& name, const std::string& bytes, const std::string& problem)
{
  Expect(pcbilateral::CheckPLYFile, name + ".ply", bytes, problem);
}

const std::string XYZ = "property float x\nproperty float y\nproperty float z\n";

/// Binary little-endian PLY of `vertices` records of three floats, with `bytes` bytes of data.
std::string BinaryPLY(int vertices, std::size_t bytes)
{
  return "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(vertices) + "\n" +
         XYZ + "end_header\n" + std::string(bytes, '\0');
}

void GoodPLYFiles()
{
  ExpectPLY(
    "ascii", "ply\nformat ascii 1.0\nelement vertex 2\n" + XYZ + "end_header\n0 0 0\n1 1 1\n", "");
  // Blank lines between records, CR LF line ends, more values than properties.
  ExpectPLY("crlf",
    "ply\r\nformat ascii 1.0\r\nelement vertex 2\r\n" + XYZ +
      "end_header\r\n0 0 0 7\r\n\r\n1 1 1\r\n",
    "");
  ExpectPLY("binary", BinaryPLY(10, 120), "");
  // Faces: lists count as their count's bytes at least.
  ExpectPLY("faces",
    "ply\nformat binary_big_endian 1.0\nelement vertex 1\n" + XYZ +
      "element face 2\nproperty list uchar int vertex_indices\nend_header\n" +
      std::string(14, '\0'),
    "");
}

void DamagedPLYHeaders()
{
  ExpectPLY("text", "0 0 0\n1 1 1\n", "not a PLY file (it does not start with 'ply')");
  ExpectPLY("plywood", "plywood\n", "not a PLY file (it does not start with 'ply')");
  ExpectPLY("count",
    "ply\nformat ascii 1.0\nelement vertex 3x\n" + XYZ + "end_header\n",
    "the PLY header gives element 'vertex' the count '3x', not a whole number");
  ExpectPLY("orphan",
    "ply\nformat ascii 1.0\nproperty float x\nend_header\n",
    "the PLY header has a property before any element");
  ExpectPLY("type",
    "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
    "the PLY header has a property of unknown type 'float128'");
  ExpectPLY("list-type",
    "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar quad vertex_indices\nend_header\n",
    "the PLY header has a property of unknown type 'quad'");
  ExpectPLY("no-end",
    "ply\nformat ascii 1.0\nelement vertex 1\n" + XYZ,
    "the PLY header has no end_header line in its first 64 KB");
  ExpectPLY("end-without-newline",
    "ply\nformat ascii 1.0\nelement vertex 0\n" + XYZ + "end_header",
    "the PLY header has no end_header line in its first 64 KB");
  ExpectPLY("long-header",
    "ply\n" + std::string(1 << 16, '\n') + "end_header\n",
    "the PLY header has no end_header line in its first 64 KB");
  ExpectPLY("format",
    "ply\nformat binary_middle_endian 1.0\nelement vertex 0\n" + XYZ + "end_header\n",
    "the PLY header gives an unknown format 'binary_middle_endian'");
  ExpectPLY("no-format",
    "ply\nelement vertex 0\n" + XYZ + "end_header\n",
    "the PLY header gives an unknown format ''");
  ExpectPLY("no-vertex",
    "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int i\nend_header\n",
    "the PLY file has no vertex element");
  ExpectPLY("no-yz",
    "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n",
    "the PLY vertices have no y, z property (x, y and z are needed)");
}

void DamagedPLYData()
{
  ExpectPLY("cut-binary",
    BinaryPLY(10, 119),
    "truncated: the PLY header announces 10 vertex records of at least 12 bytes, the file holds "
    "119 bytes after its header");
  ExpectPLY("cut-faces",
    "ply\nformat binary_little_endian 1.0\nelement vertex 1\n" + XYZ +
      "element face 3\nproperty list uchar int vertex_indices\nend_header\n" +
      std::string(14, '\0'),
    "truncated: the PLY header announces 3 face records of at least 1 bytes, the file holds 14 "
    "bytes after its header");
  ExpectPLY("cut-ascii",
    "ply\nformat ascii 1.0\nelement vertex 3\n" + XYZ + "end_header\n0 0 0\n\n1 1 1\n",
    "truncated: the PLY header announces 3 vertex lines, the file holds 2");
  ExpectPLY("short-line",
    "ply\nformat ascii 1.0\nelement vertex 2\n" + XYZ + "end_header\n0 0 0\n1 1\n",
    "vertex 2 has 2 values, the PLY header announces 3");
  ExpectPLY("empty", std::string(), "not a PLY file (it does not start with 'ply')");
}

void MissingFiles()
{
  for (const auto check : { pcbilateral::CheckPLYFile, pcbilateral::CheckVTPFile })
  {
    const std::string found = check("missing.file");
    PCB_CHECK(found == "missing.file: No such file or directory", "%s", found.c_str());
  }
}

void VTPFiles()
{
  const auto check = pcbilateral::CheckVTPFile;
  const std::string head = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\">\n";
  Expect(check, "good.vtp", head + "<PolyData/>\n</VTKFile>\n\n  \n", "");
  Expect(check,
    "cut.vtp",
    head + "<PolyData/>\n</VTKFi",
    "truncated: the VTK XML file does not end with </VTKFile>");
  Expect(
    check, "small.vtp", "<VTKFile", "truncated: the VTK XML file does not end with </VTKFile>");
  Expect(check,
    "text.vtp",
    "0 0 0\n</VTKFile>\n",
    "not a VTK XML file (no <VTKFile> element at its start)");
  Expect(check,
    "late.vtp",
    std::string(600, ' ') + head + "</VTKFile>\n",
    "not a VTK XML file (no <VTKFile> element at its start)");
}
} // namespace

int main(int argc, char* argv[])
{
  return RunNamedCase(argc,
    argv,
    { { "ply-good", GoodPLYFiles },
      { "ply-header", DamagedPLYHeaders },
      { "ply-data", DamagedPLYData },
      { "vtp", VTPFiles },
      { "missing", MissingFiles } });
}

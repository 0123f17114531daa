// PCL's PCD format in the formats library: the files of PCL's data repository (three encodings,
// packed colours, padding, an organised frame with NaN pixels), every field type written and
// read back in every encoding, NaN points dropped or kept, and damaged files refused in one line.
#include "CoreTesting.h"

#include "PCDFile.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>

using namespace pcbilateral;
using namespace pcbilateral_testing;

namespace
{
std::string DataFolder;

const PCDEncoding Encodings[] = { PCDEncoding::ASCII,
  PCDEncoding::Binary,
  PCDEncoding::BinaryCompressed };

/// Whether two clouds hold the same points and fields, bit for bit.
bool SameCloud(const PCDCloud& a, const PCDCloud& b)
{
  if (a.NumberOfPoints != b.NumberOfPoints || !SameBits(a.Positions, b.Positions) ||
      a.Columns.size() != b.Columns.size() || a.Header.Fields.size() != b.Header.Fields.size())
  {
    return false;
  }
  for (std::size_t k = 0; k < a.Columns.size(); ++k)
  {
    const PCDField& f = a.Columns[k].Field;
    const PCDField& g = b.Columns[k].Field;
    if (f.Name != g.Name || f.Type != g.Type || f.Size != g.Size || f.Count != g.Count ||
        a.Columns[k].Bytes != b.Columns[k].Bytes)
    {
      return false;
    }
  }
  return true;
}

/// Writes `cloud` in each encoding and reads it back: the same cloud each time.
void CheckRoundTrips(const PCDCloud& cloud, const std::string& name, bool keepNaN)
{
  for (const PCDEncoding encoding : Encodings)
  {
    const std::string path = name + "." + PCDEncodingName(encoding) + ".pcd";
    const std::string error = WritePCD(path, cloud, encoding);
    PCB_CHECK(error.empty(), "%s", error.c_str());
    PCDCloud back;
    PCDReadOptions options;
    options.KeepNaNPoints = keepNaN;
    const std::string readError = ReadPCD(path, options, back);
    PCB_CHECK(readError.empty(), "%s", readError.c_str());
    PCB_CHECK(SameCloud(cloud, back),
      "%s: not the same cloud in %s",
      name.c_str(),
      PCDEncodingName(encoding));
    PCB_CHECK(back.Header.Encoding == encoding, "%s", path.c_str());
  }
}

struct SharedFile
{
  const char* Name;
  std::size_t Points;
  std::size_t Dropped;
  PCDEncoding Encoding;
  const char* Fields;
};

/// The shared files (their README): points, encoding and fields as read.
void SharedFiles()
{
  const SharedFile files[] = {
    { "lamppost.pcd", 1771, 0, PCDEncoding::ASCII, "x y z" },
    { "object_template_0.pcd", 1397, 0, PCDEncoding::ASCII, "x y z _" },
    { "face_model.pcd", 100000, 0, PCDEncoding::Binary, "x y z" },
    { "samp21_utm_ground.pcd", 10085, 0, PCDEncoding::BinaryCompressed, "x y z" },
    { "milk.pcd", 12575, 0, PCDEncoding::BinaryCompressed, "x y z rgba" },
    { "region_growing_tutorial.pcd", 108104, 0, PCDEncoding::BinaryCompressed, "x y z rgb" },
    { "capture0001.pcd", 249647, 57553, PCDEncoding::BinaryCompressed, "x y z" },
  };
  for (const SharedFile& file : files)
  {
    PCDCloud cloud;
    const std::string error = ReadPCD(DataFolder + "/" + file.Name, PCDReadOptions(), cloud);
    PCB_CHECK(error.empty(), "%s", error.c_str());
    std::string fields;
    for (const PCDField& field : cloud.Header.Fields)
    {
      fields += (fields.empty() ? "" : " ") + field.Name;
    }
    PCB_CHECK(cloud.NumberOfPoints == file.Points && cloud.NumberOfDroppedPoints == file.Dropped,
      "%s: %zu points, %zu dropped",
      file.Name,
      cloud.NumberOfPoints,
      cloud.NumberOfDroppedPoints);
    PCB_CHECK(cloud.Header.Encoding == file.Encoding && fields == file.Fields,
      "%s: %s",
      file.Name,
      fields.c_str());
    CheckRoundTrips(cloud, file.Name, false);
  }
}

/// The organised frame with its NaN pixels kept: WIDTH x HEIGHT points, NaN where there was
/// no depth, and the same frame written back (WIDTH, HEIGHT and VIEWPOINT too).
void SharedFrameKept()
{
  PCDReadOptions keep;
  keep.KeepNaNPoints = true;
  PCDCloud frame;
  const std::string error = ReadPCD(DataFolder + "/capture0001.pcd", keep, frame);
  PCB_CHECK(error.empty(), "%s", error.c_str());
  PCB_CHECK(frame.NumberOfPoints == 640 * 480 && frame.NumberOfDroppedPoints == 0 &&
              frame.Header.Width == 640 && frame.Header.Height == 480,
    "%zu points",
    frame.NumberOfPoints);
  std::size_t nan = 0;
  for (std::size_t i = 0; i < frame.NumberOfPoints; ++i)
  {
    nan += std::isnan(frame.Positions[3 * i]) ? 1 : 0;
  }
  PCB_CHECK(nan == 57553, "%zu NaN points", nan);
  CheckRoundTrips(frame, "frame", true);
  PCDCloud back;
  ReadPCD("frame.binary.pcd", keep, back);
  PCB_CHECK(back.Header.Width == 640 && back.Header.Height == 480 &&
              std::memcmp(
                back.Header.Viewpoint, frame.Header.Viewpoint, sizeof frame.Header.Viewpoint) == 0,
    "the frame's layout was not written back");
}

/// One field of every type, a field of 3 values, padding and packed colours, with extreme
/// values, in every encoding.
void EveryType()
{
  PCDCloud cloud;
  cloud.NumberOfPoints = 3;
  cloud.Positions = { 0.5, -1.25, 1e300, std::nan(""), 2.0, 3.0, -0.0, 1e-300, 7.0 };
  cloud.Header.Fields = { { "x", 'F', 8, 1 }, { "y", 'F', 8, 1 }, { "z", 'F', 8, 1 } };
  cloud.Header.Width = 3;
  const std::int64_t i8[] = {
    std::numeric_limits<std::int64_t>::min(), -1, std::numeric_limits<std::int64_t>::max()
  };
  const std::uint64_t u8[] = { 0, 1, std::numeric_limits<std::uint64_t>::max() };
  const float f4[] = {
    0.1f, std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::infinity()
  };
  const std::int8_t i1[] = { -128, 0, 127 };
  const std::uint16_t u2x3[] = { 1, 2, 3, 65535, 0, 7, 8, 9, 10 };
  const std::uint32_t rgb[] = {
    0xFF80FF00u, 0x00000005u, 0x7F123456u
  }; // a NaN's bits, a denormal's
  auto add = [&cloud](const PCDField& field, const void* values)
  {
    PCDColumn column{ field, std::vector<std::uint8_t>(cloud.NumberOfPoints * field.Bytes()) };
    std::memcpy(column.Bytes.data(), values, column.Bytes.size());
    cloud.Header.Fields.push_back(field);
    cloud.Columns.push_back(column);
  };
  add({ "big", 'I', 8, 1 }, i8);
  add({ "huge", 'U', 8, 1 }, u8);
  cloud.Header.Fields.push_back({ "_", 'U', 1, 3 });
  add({ "f", 'F', 4, 1 }, f4);
  add({ "small", 'I', 1, 1 }, i1);
  add({ "triple", 'U', 2, 3 }, u2x3);
  add({ "rgb", 'F', 4, 1 }, rgb);
  add({ "rgba", 'U', 4, 1 }, rgb);
  CheckRoundTrips(cloud, "types", true);
  // Packed colours: rgb gives R G B, rgba R G B A, from 0xAARRGGBB.
  const std::vector<std::uint8_t> colours = UnpackPCDColours(cloud.Columns[5]);
  const std::vector<std::uint8_t> withAlpha = UnpackPCDColours(cloud.Columns[6]);
  PCB_CHECK(colours.size() == 9 && colours[0] == 0x80 && colours[1] == 0xFF && colours[2] == 0,
    "rgb unpacked wrongly");
  PCB_CHECK(withAlpha.size() == 12 && withAlpha[3] == 0xFF && withAlpha[11] == 0x7F,
    "rgba unpacked wrongly");
  PCB_CHECK(
    PackPCDColours(cloud.Columns[6].Field, withAlpha.data(), 4, 3).Bytes == cloud.Columns[6].Bytes,
    "rgba packed wrongly");
  // ascii writes a packed rgb as its bits' integer (PCL's way: they can be a NaN).
  const std::string text = FileContents("types.ascii.pcd");
  PCB_CHECK(text.find(" 4286643968 ") != std::string::npos, "rgb not written as an integer");
}

/// ascii as other writers write it: rgb as a float, CR LF, blank lines, '+' signs, COLUMNS and
/// no COUNT (PCD 0.5), comments.
void OtherWriters()
{
  const float red = []
  {
    const std::uint32_t bits = 0x00FF0000u;
    float value;
    std::memcpy(&value, &bits, 4);
    return value;
  }();
  char redText[32];
  std::snprintf(redText, sizeof redText, "%.9g", red);
  const std::string file =
    "# written elsewhere\r\nVERSION .5\r\nCOLUMNS x y z rgb\r\nSIZE 4 4 4 4\r\n"
    "TYPE F F F F\r\nWIDTH 2\r\nHEIGHT 1\r\nPOINTS 2\r\nDATA ascii\r\n"
    "1 2 +3 " +
    std::string(redText) + "\r\n\r\n  4 5 6 16711680\r\n";
  PCDCloud cloud;
  const std::string error = DecodePCD(file.data(), file.size(), "other", PCDReadOptions(), cloud);
  PCB_CHECK(error.empty(), "%s", error.c_str());
  PCB_CHECK(
    cloud.NumberOfPoints == 2 && cloud.Positions[2] == 3.0 && cloud.Positions[5] == 6.0, "points");
  const std::vector<std::uint8_t> colours =
    cloud.Columns.empty() ? std::vector<std::uint8_t>() : UnpackPCDColours(cloud.Columns[0]);
  PCB_CHECK(colours == std::vector<std::uint8_t>({ 255, 0, 0, 255, 0, 0 }),
    "rgb as a float and as an integer");
}

/// A small organised frame of 3 x 2 with two NaN pixels: dropped and counted, or kept.
void OrganisedNaN()
{
  const std::string file =
    "VERSION 0.7\nFIELDS x y z i\nSIZE 4 4 4 2\nTYPE F F F U\nCOUNT 1 1 1 1\n"
    "WIDTH 3\nHEIGHT 2\nVIEWPOINT 1 2 3 0 1 0 0\nPOINTS 6\nDATA ascii\n"
    "0 0 1 10\nnan nan nan 11\n2 0 1 12\n0 1 1 13\n1 1 nan 14\n2 1 1 15\n";
  PCDCloud dropped;
  std::string error = DecodePCD(file.data(), file.size(), "frame", PCDReadOptions(), dropped);
  PCB_CHECK(error.empty(), "%s", error.c_str());
  PCB_CHECK(dropped.NumberOfPoints == 4 && dropped.NumberOfDroppedPoints == 2,
    "%zu points",
    dropped.NumberOfPoints);
  std::uint16_t ids[4];
  std::memcpy(ids, dropped.Columns[0].Bytes.data(), 8);
  PCB_CHECK(ids[0] == 10 && ids[1] == 12 && ids[2] == 13 && ids[3] == 15,
    "the fields of the dropped points stayed");
  error = WritePCD("dropped.pcd", dropped, PCDEncoding::ASCII);
  PCB_CHECK(
    FileContents("dropped.pcd").find("WIDTH 4\nHEIGHT 1\nVIEWPOINT 1 2 3 0 1 0 0\nPOINTS 4\n") !=
      std::string::npos,
    "a frame with points dropped is not written as a frame");
  PCDReadOptions keep;
  keep.KeepNaNPoints = true;
  PCDCloud kept;
  error = DecodePCD(file.data(), file.size(), "frame", keep, kept);
  PCB_CHECK(
    kept.NumberOfPoints == 6 && std::isnan(kept.Positions[3]) && std::isnan(kept.Positions[14]),
    "NaN points not kept in place");
  error = WritePCD("kept.pcd", kept, PCDEncoding::ASCII);
  PCB_CHECK(FileContents("kept.pcd")
                .find("WIDTH 3\nHEIGHT 2\nVIEWPOINT 1 2 3 0 1 0 0\nPOINTS 6\nDATA ascii\n0 0 1 "
                      "10\nnan nan nan 11\n") != std::string::npos,
    "the frame is not written back as it was");
}

/// A header of x y z floats and a U2 field for `points` points.
std::string Header(const std::string& points,
  const std::string& data,
  const std::string& size = "4 4 4 2",
  const std::string& type = "F F F U",
  const std::string& width = "")
{
  return "VERSION 0.7\nFIELDS x y z i\nSIZE " + size + "\nTYPE " + type +
         "\nCOUNT 1 1 1 1\nWIDTH " + (width.empty() ? points : width) + "\nHEIGHT 1\nPOINTS " +
         points + "\nDATA " + data + "\n";
}

/// The file of a cloud of `count` points written in `encoding`.
std::string ValidFile(PCDEncoding encoding, std::size_t count)
{
  PCDCloud cloud;
  cloud.NumberOfPoints = count;
  cloud.Header.Width = count;
  cloud.Header.Fields = {
    { "x", 'F', 4, 1 }, { "y", 'F', 4, 1 }, { "z", 'F', 4, 1 }, { "i", 'U', 2, 1 }
  };
  cloud.Columns.push_back({ cloud.Header.Fields[3], std::vector<std::uint8_t>(2 * count, 7) });
  for (std::size_t i = 0; i < count; ++i)
  {
    cloud.Positions.insert(cloud.Positions.end(), { 0.25 * i, 0.5 * (i % 7), 1.0 });
  }
  WritePCD("valid.pcd", cloud, encoding);
  return FileContents("valid.pcd");
}

/// Each damaged file: one line naming the file and the problem, an empty cloud.
void Damaged()
{
  const std::string binary = ValidFile(PCDEncoding::Binary, 100);
  const std::string compressed = ValidFile(PCDEncoding::BinaryCompressed, 100);
  const std::size_t sizes = compressed.find("DATA binary_compressed\n") + 23;
  std::string lyingCompressed = compressed, lyingUncompressed = compressed, corrupt = compressed;
  lyingCompressed[sizes + 1] = 0x7F; // compressed size beyond the file
  lyingUncompressed[sizes + 4] = 1;  // uncompressed size other than the points'
  for (std::size_t k = sizes + 8; k < corrupt.size(); k += 3)
  {
    corrupt[k] = static_cast<char>(0xE0); // long back-references before any data
  }
  const std::pair<std::string, std::string> cases[] = {
    { binary.substr(0, binary.size() - 1),
      "the binary data holds 99 points, the header announces 100" },
    { Header("5", "binary", "4 4 4 2", "F F F U", "4"), "POINTS 5 is not WIDTH x HEIGHT (4 x 1)" },
    { Header("1", "binary", "4 4 4") + std::string(14, '\0'),
      "FIELDS, SIZE, TYPE and COUNT do not have one value per field each" },
    { Header("1", "binary", "4 4 4 2", "F F F Q") + std::string(14, '\0'),
      "field 'i' has an unknown type 'Q' of 2 bytes" },
    { Header("1", "binary", "4 4 4 2", "F F F F") + std::string(14, '\0'),
      "field 'i' has an unknown type 'F' of 2 bytes" },
    { Header("1", "binary", "4 4 4 3") + std::string(15, '\0'),
      "field 'i' has an unknown type 'U' of 3 bytes" },
    { Header("1", "binary_lz4"), "unknown DATA encoding 'binary_lz4'" },
    { compressed.substr(0, compressed.size() - 5), "do not match the file" },
    { lyingCompressed, "do not match the file" },
    { lyingUncompressed, "the compressed data announces" },
    { corrupt, "the compressed data is damaged" },
    { Header("3", "ascii") + "1 2 3 4\n5 6 7 8\n",
      "the ascii data holds 2 points, the header announces 3" },
    { Header("2", "ascii") + "1 2 3 4\n5 6 7\n", "line 11: fewer values than the fields take" },
    { Header("2", "ascii") + "1 2 3 4\n5 6 7 8 9\n", "line 11: more values than the fields take" },
    { Header("1", "ascii") + "1 2 3 4\n5 6 7 8\n",
      "line 11: more points than the header announces (1)" },
    { Header("1", "ascii") + "1 2 3 70000\n", "line 10: '70000' is not a value of field 'i' (U2)" },
    { Header("1", "ascii") + "1 2 x 4\n", "line 10: 'x' is not a value of field 'z' (F4)" },
    { Header("18446744073709551615", "binary", "4 4 4 2", "F F F U", "18446744073709551615"),
      "the header announces more points than the file can hold" },
    { "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 4294967296\nHEIGHT "
      "4294967296\nDATA binary\n",
      "WIDTH x HEIGHT is too large" },
    { "VERSION 0.7\nFIELDS a b\nSIZE 4 4\nTYPE F F\nWIDTH 1\nDATA binary\n", "no x y z fields" },
    { "VERSION 0.7\nFIELDS x y z x\nSIZE 4 4 4 4\nTYPE F F F F\nWIDTH 1\nDATA binary\n",
      "field 'x' is named twice" },
    { "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\n", "no DATA line" },
    { std::string("\x89PNG\r\n\x1a\n", 8), "not a PCD file" },
    { "", "the file is empty" },
  };
  for (const auto& [bytes, expected] : cases)
  {
    PCDCloud cloud;
    const std::string path = WriteFileContents("damaged.pcd", bytes);
    const std::string error = ReadPCD(path, PCDReadOptions(), cloud);
    PCB_CHECK(error.compare(0, path.size() + 2, path + ": ") == 0 &&
                error.find('\n') == std::string::npos && error.find(expected) != std::string::npos,
      "expected '%s', got '%s'",
      expected.c_str(),
      error.c_str());
    PCB_CHECK(cloud.NumberOfPoints == 0 && cloud.Positions.empty() && cloud.Columns.empty(),
      "%s: a cloud",
      expected.c_str());
  }
}
} // namespace

int main(int argc, char* argv[])
{
  DataFolder = argc > 2 ? argv[2] : "";
  return RunNamedCase(argc,
    argv,
    { { "shared-files", SharedFiles },
      { "shared-frame-kept", SharedFrameKept },
      { "every-type", EveryType },
      { "other-writers", OtherWriters },
      { "organised-nan", OrganisedNaN },
      { "damaged", Damaged } });
}

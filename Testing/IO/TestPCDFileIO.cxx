// PCD through vtkPointCloudFileIO and the VTK reader and writer: fields as typed point arrays
// (normals, packed colours, padding skipped), the file's layout written back, clouds from
// elsewhere, an organised frame's NaN points kept through the filter (never neighbours, still
// NaN, the same bits for the others as without them), the warning for what PCD cannot hold,
// and PCL's depth frame against the same frame as PLY.
#include "CoreTesting.h"
#include "VTKTesting.h"

#include "PCDFile.h"
#include "vtkPCDPointCloudReader.h"
#include "vtkPCDPointCloudWriter.h"
#include "vtkPointCloudFileIO.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <cmath>
#include <cstring>

using namespace pcbilateral_testing;

namespace
{
std::string DataFolder, OtherFolder;

/// A PCD file of 4 points with normals, colours, an intensity, a 3-value histogram and padding.
void WriteFieldsFile(const std::string& path)
{
  const std::string text = "VERSION 0.7\n"
                           "FIELDS x y z normal_x normal_y normal_z rgb intensity hist _\n"
                           "SIZE 4 4 4 4 4 4 4 2 4 1\nTYPE F F F F F F F U F U\n"
                           "COUNT 1 1 1 1 1 1 1 1 3 2\nWIDTH 2\nHEIGHT 2\n"
                           "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\n"
                           "0 0 0 0 0 1 16711680 7 1 2 3 0 0\n"
                           "1 0 0 0 0 1 65280 8 4 5 6 0 0\n"
                           "0 1 0 0 0 1 255 9 7 8 9 0 0\n"
                           "1 1 0.5 0 1 0 16777215 10 1.5 2.5 3.5 0 0\n";
  WriteFileContents(path, text);
}

/// Typed arrays from the fields, and the file's layout written back.
void Fields()
{
  WriteFieldsFile("fields.pcd");
  vtkNew<vtkPointCloudFileIO> io;
  vtkNew<vtkPolyData> cloud;
  PCB_CHECK(io->Read("fields.pcd", cloud), "%s", io->GetErrorMessage());
  vtkPointData* pd = cloud->GetPointData();
  vtkDataArray* normals = pd->GetNormals();
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(pd->GetArray("RGB"));
  vtkDataArray* intensity = pd->GetArray("intensity");
  vtkDataArray* hist = pd->GetArray("hist");
  PCB_CHECK(
    cloud->GetNumberOfPoints() == 4 && cloud->GetPoints()->GetDataType() == VTK_DOUBLE, "points");
  PCB_CHECK(normals && normals->GetDataType() == VTK_FLOAT && normals->GetComponent(3, 1) == 1.0,
    "normals");
  PCB_CHECK(rgb && rgb->GetNumberOfComponents() == 3 && rgb->GetValue(0) == 255 &&
              rgb->GetValue(4) == 255 && rgb->GetValue(8) == 255 && rgb->GetValue(3) == 0,
    "colours");
  PCB_CHECK(intensity && intensity->GetDataType() == VTK_UNSIGNED_SHORT &&
              intensity->GetComponent(3, 0) == 10,
    "intensity");
  PCB_CHECK(hist && hist->GetNumberOfComponents() == 3 && hist->GetComponent(3, 2) == 3.5, "hist");
  PCB_CHECK(
    pd->GetNumberOfArrays() == 4 && !pd->GetArray("_"), "%d arrays", pd->GetNumberOfArrays());
  // Written back: the same fields, in their order, and the same values.
  PCB_CHECK(io->Write(cloud, "back.pcd"), "%s", io->GetErrorMessage());
  pcbilateral::PCDCloud original, back;
  pcbilateral::ReadPCD("fields.pcd", pcbilateral::PCDReadOptions(), original);
  pcbilateral::ReadPCD("back.pcd", pcbilateral::PCDReadOptions(), back);
  std::string fields;
  for (const pcbilateral::PCDField& field : back.Header.Fields)
  {
    fields +=
      field.Name + field.Type + std::to_string(field.Size) + std::to_string(field.Count) + " ";
  }
  PCB_CHECK(fields == "xF41 yF41 zF41 normal_xF41 normal_yF41 normal_zF41 rgbF41 intensityU21 "
                      "histF43 _U12 ",
    "%s",
    fields.c_str());
  PCB_CHECK(SameBits(original.Positions, back.Positions) && back.Columns.size() == 6 &&
              back.Header.Width == 2 && back.Header.Height == 2 &&
              back.Header.Encoding == pcbilateral::PCDEncoding::ASCII,
    "not written back as read");
  for (std::size_t k = 0; k < back.Columns.size(); ++k)
  {
    // rgb's alpha byte is written as 255 (PCL's opaque colour); the file had 0.
    const bool colours = back.Columns[k].Field.Name == "rgb";
    PCB_CHECK(colours ? pcbilateral::UnpackPCDColours(back.Columns[k]) ==
                          pcbilateral::UnpackPCDColours(original.Columns[k])
                      : back.Columns[k].Bytes == original.Columns[k].Bytes,
      "field %s changed",
      back.Columns[k].Field.Name.c_str());
  }
}

/// A cloud not read from PCD: float coordinates as F4 when exact, else F8; normals, 8-bit
/// colours and other arrays as fields; not vtkOriginalPointIds; the encoding asked for.
void FromElsewhere()
{
  vtkSmartPointer<vtkPolyData> cloud = MakeCloud({ 0.5, 1, 2, 3, 4, 5 });
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("Colors");
  colours->SetNumberOfComponents(3);
  for (const unsigned char value : { 1, 2, 3, 4, 5, 6 })
  {
    colours->InsertNextValue(value);
  }
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("vtkOriginalPointIds");
  ids->InsertNextValue(0);
  ids->InsertNextValue(1);
  vtkNew<vtkDoubleArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  for (const double value : { 0, 0, 1, 0, 1, 0 })
  {
    normals->InsertNextValue(value);
  }
  vtkNew<vtkDoubleArray> weight;
  weight->SetName("my weight");
  weight->InsertNextValue(0.25);
  weight->InsertNextValue(0.75);
  cloud->GetPointData()->AddArray(colours);
  cloud->GetPointData()->AddArray(ids);
  cloud->GetPointData()->AddArray(weight);
  cloud->GetPointData()->SetNormals(normals);
  vtkNew<vtkPointCloudFileIO> io;
  PCB_CHECK(io->Write(cloud, "floats.pcd"), "%s", io->GetErrorMessage());
  const std::string text = FileContents("floats.pcd");
  PCB_CHECK(
    text.find("FIELDS x y z normal_x normal_y normal_z rgb my_weight\nSIZE 4 4 4 8 8 8 4 8\n"
              "TYPE F F F F F F F F\n") != std::string::npos &&
      text.find("DATA binary\n") != std::string::npos,
    "%s",
    text.substr(0, 300).c_str());
  cloud->GetPoints()->SetPoint(1, 3.1, 4, 5); // not a float
  vtkNew<vtkPCDPointCloudWriter> writer;
  writer->SetInputData(cloud);
  writer->SetFileName("doubles.pcd");
  writer->SetDataEncoding(vtkPCDPointCloudWriter::BINARY_COMPRESSED);
  PCB_CHECK(writer->Write() == 1, "%s", writer->GetErrorMessage());
  const std::string doubles = FileContents("doubles.pcd");
  PCB_CHECK(doubles.find("SIZE 8 8 8 ") != std::string::npos &&
              doubles.find("DATA binary_compressed\n") != std::string::npos,
    "%s",
    doubles.substr(0, 300).c_str());
  vtkNew<vtkPolyData> back;
  PCB_CHECK(io->Read("doubles.pcd", back) && back->GetPoint(1)[0] == 3.1, "coordinates not exact");
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(back->GetPointData()->GetArray("RGB"));
  PCB_CHECK(rgb && rgb->GetValue(5) == 6, "colours not written");
}

/// A LAS file's two colour arrays, 8-bit `Colors` and 16-bit `RGB`, written to PCD as the
/// packed `rgb` and a field `RGB`: both read back (the packed one had been read as "RGB" too, and
/// the field replaced it).
void ColoursBesideRGBField()
{
  vtkSmartPointer<vtkPolyData> cloud = MakeCloud({ 0.5, 1, 2, 3, 4, 5 });
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("Colors");
  colours->SetNumberOfComponents(3);
  vtkNew<vtkUnsignedShortArray> wide;
  wide->SetName("RGB");
  wide->SetNumberOfComponents(3);
  for (const unsigned char value : { 1, 2, 3, 4, 5, 6 })
  {
    colours->InsertNextValue(value);
    wide->InsertNextValue(static_cast<unsigned short>(value * 257));
  }
  cloud->GetPointData()->AddArray(colours);
  cloud->GetPointData()->AddArray(wide);
  vtkNew<vtkPointCloudFileIO> io;
  vtkNew<vtkPolyData> back;
  PCB_CHECK(io->Write(cloud, "two-colours.pcd") && io->Read("two-colours.pcd", back),
    "%s",
    io->GetErrorMessage());
  auto* eight = vtkUnsignedCharArray::SafeDownCast(back->GetPointData()->GetArray("Colors"));
  auto* sixteen = vtkUnsignedShortArray::SafeDownCast(back->GetPointData()->GetArray("RGB"));
  PCB_CHECK(eight && eight->GetNumberOfComponents() == 3 && eight->GetValue(5) == 6,
    "the 8-bit colours were lost");
  PCB_CHECK(sixteen && sixteen->GetNumberOfComponents() == 3 && sixteen->GetValue(5) == 6 * 257,
    "the 16-bit RGB field was lost");
}

/// A frame of 40 x 30 pixels on a noisy plane, every 7th pixel without depth (NaN).
std::string WriteFrame()
{
  pcbilateral::PCDCloud frame;
  frame.Header.Width = 40;
  frame.Header.Height = 30;
  frame.Header.Viewpoint[0] = 0.5;
  frame.NumberOfPoints = 1200;
  frame.Header.Fields = { { "x", 'F', 4, 1 }, { "y", 'F', 4, 1 }, { "z", 'F', 4, 1 } };
  for (std::size_t i = 0; i < 1200; ++i)
  {
    const double noise = 0.002 * std::sin(12.9898 * static_cast<double>(i));
    const double z =
      i % 7 == 3 ? std::nan("") : 1.0 + 0.1 * static_cast<double>(i % 40) / 40 + noise;
    frame.Positions.insert(frame.Positions.end(),
      { static_cast<float>(0.01 * static_cast<double>(i % 40)),
        static_cast<float>(0.01 * static_cast<double>(i / 40)),
        static_cast<float>(z) });
  }
  const std::string error =
    pcbilateral::WritePCD("frame.pcd", frame, pcbilateral::PCDEncoding::BinaryCompressed);
  PCB_CHECK(error.empty(), "%s", error.c_str());
  return "frame.pcd";
}

/// Kept NaN points go through the filter unchanged and are never neighbours: the other points
/// get the bits they get without them, and the frame is written back as a frame.
void KeptThroughFilter()
{
  const std::string path = WriteFrame();
  vtkNew<vtkPointCloudFileIO> io;
  vtkNew<vtkPolyData> dropped, kept;
  PCB_CHECK(io->Read(path.c_str(), dropped) && io->GetNumberOfDroppedPoints() == 171,
    "%lld dropped",
    static_cast<long long>(io->GetNumberOfDroppedPoints()));
  io->KeepNaNPointsOn();
  PCB_CHECK(io->Read(path.c_str(), kept) && kept->GetNumberOfPoints() == 1200 &&
              io->GetNumberOfDroppedPoints() == 0,
    "not kept");
  for (const bool automatic : { false, true })
  {
    auto setup = [automatic](vtkPointCloudBilateralFilter* filter)
    {
      filter->SetRadius(automatic ? 0.0 : 0.03);
      filter->SetNormalRadius(automatic ? 0.0 : 0.01);
      filter->SetNumberOfIterations(2);
    };
    const FilterRun fromDropped = RunFilter(dropped, setup);
    const FilterRun fromKept = RunFilter(kept, setup);
    PCB_CHECK(fromKept.Errors == 0 && fromKept.Output->GetNumberOfPoints() == 1200,
      "%s",
      fromKept.Messages.c_str());
    vtkIdType next = 0;
    bool same = true, nan = true;
    for (vtkIdType id = 0; id < 1200; ++id)
    {
      const double* p = fromKept.Output->GetPoint(id);
      if (id % 7 == 3)
      {
        nan = nan && std::isnan(p[2]);
        continue;
      }
      const double* q = fromDropped.Output->GetPoint(next++);
      same = same && std::memcmp(p, q, 3 * sizeof(double)) == 0;
    }
    PCB_CHECK(same && nan,
      "automatic %d: kept NaN points changed the others (%d) or were moved (%d)",
      automatic,
      same,
      nan);
    PCB_CHECK(io->Write(fromKept.Output, "filtered.pcd"), "%s", io->GetErrorMessage());
    const std::string text = FileContents("filtered.pcd");
    PCB_CHECK(
      text.find(
        "WIDTH 40\nHEIGHT 30\nVIEWPOINT 0.5 0 0 1 0 0 0\nPOINTS 1200\nDATA binary_compressed\n") !=
        std::string::npos,
      "not written back as a frame");
  }
}

/// A cloud read from LAS, written to PCD: one warning saying what is not written; none for
/// PCD to PCD.
void LASWarning()
{
  vtkSmartPointer<vtkPolyData> cloud = MakeCloud({ 10, 20, 30, 11, 21, 31, 12, 22, 33 });
  vtkNew<vtkPointCloudFileIO> io;
  vtkNew<vtkPolyData> las, pcd;
  PCB_CHECK(
    io->Write(cloud, "cloud.las") && io->Read("cloud.las", las), "%s", io->GetErrorMessage());
  PCB_CHECK(io->Write(las, "from-las.pcd") && io->GetNumberOfWarnings() == 1,
    "%d warnings",
    io->GetNumberOfWarnings());
  const std::string warning = io->GetNumberOfWarnings() == 1 ? io->GetWarning(0) : "";
  PCB_CHECK(
    warning ==
      "from-las.pcd: a PCD file cannot hold the LAS file's scale and offset, which are not written",
    "%s",
    warning.c_str());
  PCB_CHECK(
    io->Read("from-las.pcd", pcd) && io->Write(pcd, "again.pcd") && io->GetNumberOfWarnings() == 0,
    "a warning for PCD to PCD");
  // PLY loses the LAS arrays and the scale and offset: one warning that names both; VTP keeps all.
  PCB_CHECK(
    io->Write(las, "from-las.ply") && io->GetNumberOfWarnings() == 1 &&
      std::string(io->GetWarning(0)).find("the point arrays Intensity, ") != std::string::npos &&
      std::string(io->GetWarning(0)).find("; the LAS file's scale and offset are not") !=
        std::string::npos,
    "LAS to PLY: %d warnings (%s)",
    io->GetNumberOfWarnings(),
    io->GetNumberOfWarnings() > 0 ? io->GetWarning(0) : "");
  PCB_CHECK(io->Write(las, "from-las.vtp") && io->GetNumberOfWarnings() == 0, "a warning for VTP");
  // Text keeps the arrays as columns, not the scale and offset.
  PCB_CHECK(io->Write(las, "from-las.txt") && io->GetNumberOfWarnings() == 1 &&
              std::string(io->GetWarning(0)) ==
                "from-las.txt: a text file cannot hold the LAS file's scale and offset, which are "
                "not written (the coordinates are)",
    "LAS to text: %d warnings (%s)",
    io->GetNumberOfWarnings(),
    io->GetNumberOfWarnings() > 0 ? io->GetWarning(0) : "");
}

/// A LAS file with a coordinate system (the shared autzen_trim.las): the warning names it.
void LASCoordinateSystemWarning()
{
  vtkNew<vtkPointCloudFileIO> io;
  vtkNew<vtkPolyData> las;
  PCB_CHECK(io->Read((OtherFolder + "/autzen_trim.las").c_str(), las), "%s", io->GetErrorMessage());
  PCB_CHECK(io->Write(las, "autzen.pcd") && io->GetNumberOfWarnings() == 1 &&
              std::string(io->GetWarning(0)).find("coordinate system (CRS), scale and offset") !=
                std::string::npos,
    "no warning about the coordinate system");
  vtkNew<vtkPolyData> back;
  PCB_CHECK(io->Read("autzen.pcd", back) && back->GetNumberOfPoints() == las->GetNumberOfPoints() &&
              back->GetPoint(1000)[0] == las->GetPoint(1000)[0],
    "the coordinates changed");
}

/// PCL's depth frame, its NaN points dropped, is the shared PLY of the same frame, point for
/// point.
void CaptureMatchesPLY()
{
  vtkNew<vtkPointCloudFileIO> io;
  vtkNew<vtkPolyData> pcd, ply;
  PCB_CHECK(io->Read((DataFolder + "/capture0001.pcd").c_str(), pcd), "%s", io->GetErrorMessage());
  PCB_CHECK(io->GetNumberOfDroppedPoints() == 57553,
    "%lld dropped",
    static_cast<long long>(io->GetNumberOfDroppedPoints()));
  PCB_CHECK(
    io->Read((OtherFolder + "/kinect_capture0001.ply").c_str(), ply), "%s", io->GetErrorMessage());
  bool same = pcd->GetNumberOfPoints() == ply->GetNumberOfPoints();
  for (vtkIdType id = 0; same && id < pcd->GetNumberOfPoints(); ++id)
  {
    const double* p = pcd->GetPoint(id);
    const double* q = ply->GetPoint(id);
    same = p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
  }
  PCB_CHECK(same,
    "%lld and %lld points, not the same",
    static_cast<long long>(pcd->GetNumberOfPoints()),
    static_cast<long long>(ply->GetNumberOfPoints()));
}
} // namespace

int main(int argc, char* argv[])
{
  DataFolder = argc > 2 ? argv[2] : "";
  OtherFolder = argc > 3 ? argv[3] : "";
  return RunNamedCase(argc,
    argv,
    { { "fields", Fields },
      { "from-elsewhere", FromElsewhere },
      { "colours-beside-rgb-field", ColoursBesideRGBField },
      { "kept-through-filter", KeptThroughFilter },
      { "las-warning", LASWarning },
      { "las-crs-warning", LASCoordinateSystemWarning },
      { "capture-matches-ply", CaptureMatchesPLY } });
}

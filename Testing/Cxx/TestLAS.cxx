// The LAS reader and writer: every point format 0-10 written, read back and written again
// (same values, same point records byte for byte), written into a mapping of the file and in
// chunks (the same bytes; a file beyond the size limit gives one error and no file), extra
// bytes named by their record, the header chosen for points from elsewhere, and damaged files
// through the VTK reader (one error, an empty output).
#include "CoreTesting.h"
#include "FileSizeLimit.h"

#include "vtkLASPointCloudReader.h"
#include "vtkLASPointCloudWriter.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

namespace
{
std::vector<char> FileBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

template<typename T>
T At(const std::vector<char>& bytes, std::size_t offset)
{
  T value{};
  if (offset + sizeof(T) <= bytes.size())
  {
    std::memcpy(&value, bytes.data() + offset, sizeof(T));
  }
  return value;
}

/// The point records of a LAS file, as the file's header places them.
std::vector<char> PointRecords(const std::vector<char>& bytes)
{
  const auto offset = At<std::uint32_t>(bytes, 96);
  const auto length = At<std::uint16_t>(bytes, 105);
  std::uint64_t count = At<std::uint32_t>(bytes, 107);
  if (bytes.size() > 255 && bytes[25] >= 4)
  {
    count = At<std::uint64_t>(bytes, 247);
  }
  const std::size_t end = offset + count * length;
  return end <= bytes.size() ? std::vector<char>(bytes.begin() + offset, bytes.begin() + end)
                             : std::vector<char>();
}

void AddFieldValues(vtkFieldData* fieldData, const char* name, int type, std::vector<double> values)
{
  auto array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(type));
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t k = 0; k < values.size(); ++k)
  {
    array->SetTuple1(static_cast<vtkIdType>(k), values[k]);
  }
  fieldData->AddArray(array);
}

/// A cloud whose every field gets values that fill its bits, deterministically.
vtkSmartPointer<vtkPolyData> MakeCloud(int format, vtkIdType count)
{
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (vtkIdType i = 0; i < count; ++i)
  {
    // On the 0.001 grid of the header below, so they read back exactly.
    points->InsertNextPoint(
      1000.0 + 0.001 * (i * 7919 % 100003), 2000.0 - 0.001 * i, -5.0 + 0.001 * (i % 977));
  }
  cloud->SetPoints(points);
  vtkFieldData* fieldData = cloud->GetFieldData();
  AddFieldValues(fieldData, "LAS Version", VTK_UNSIGNED_CHAR, { 1, 4 });
  AddFieldValues(fieldData, "LAS Point Format", VTK_UNSIGNED_CHAR, { double(format) });
  const int standard[] = { 20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67 };
  AddFieldValues(
    fieldData, "LAS Point Record Length", VTK_UNSIGNED_SHORT, { double(standard[format]) });
  AddFieldValues(fieldData, "LAS Scale", VTK_DOUBLE, { 0.001, 0.001, 0.001 });
  AddFieldValues(fieldData, "LAS Offset", VTK_DOUBLE, { 1000, 2000, 0 });
  return cloud;
}

/// Fills every point array of `like` (a cloud read from a LAS file) in `cloud` with
/// pseudo-random values within each field's range.
void FillArraysLike(vtkPolyData* like, vtkPolyData* cloud)
{
  const vtkIdType count = cloud->GetNumberOfPoints();
  vtkPointData* from = like->GetPointData();
  for (int a = 0; a < from->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* model = from->GetArray(a);
    if (!model || std::strcmp(model->GetName(), "Colors") == 0)
    {
      continue;
    }
    auto array = vtkSmartPointer<vtkDataArray>::Take(model->NewInstance());
    array->SetName(model->GetName());
    array->SetNumberOfComponents(model->GetNumberOfComponents());
    array->SetNumberOfTuples(count);
    const std::string name = model->GetName();
    double range = 255;
    if (name == "ReturnNumber" || name == "NumberOfReturns")
    {
      range = cloud->GetFieldData()->GetArray("LAS Point Format")->GetTuple1(0) > 5 ? 15 : 7;
    }
    else if (name == "Classification")
    {
      range = cloud->GetFieldData()->GetArray("LAS Point Format")->GetTuple1(0) > 5 ? 255 : 31;
    }
    else if (name == "ScannerChannel")
    {
      range = 3;
    }
    else if (name == "Synthetic" || name == "KeyPoint" || name == "Withheld" || name == "Overlap" ||
             name == "ScanDirectionFlag" || name == "EdgeOfFlightLine")
    {
      range = 1;
    }
    else if (array->GetDataType() == VTK_SIGNED_CHAR)
    {
      range = 127;
    }
    else if (array->GetDataTypeSize() >= 2)
    {
      range = 30000;
    }
    for (vtkIdType i = 0; i < count; ++i)
    {
      for (int c = 0; c < array->GetNumberOfComponents(); ++c)
      {
        double value =
          static_cast<double>((i * 2654435761u + c * 40503u) % 1000003u) / 1000003.0 * (range + 1);
        value = std::floor(value);
        if (name == "ScanAngle")
        {
          // Degrees, on the grid of the stored integers (0.006 degree), as the reader gives
          // them: a float of the stored value times 0.006.
          value = static_cast<float>(static_cast<double>(i * 7 % 60001 - 30000) * 0.006);
        }
        else if (array->GetDataType() == VTK_DOUBLE || array->GetDataType() == VTK_FLOAT)
        {
          value = 0.25 * i + c; // exact in float too for these sizes
        }
        array->SetComponent(i, c, value);
      }
    }
    cloud->GetPointData()->AddArray(array);
  }
}

struct ErrorCounter
{
  int Errors = 0;
  vtkNew<vtkCallbackCommand> Command;
  void Observe(vtkObject* object)
  {
    this->Command->SetClientData(this);
    this->Command->SetCallback([](vtkObject*, unsigned long, void* self, void*)
      { ++static_cast<ErrorCounter*>(self)->Errors; });
    object->AddObserver(vtkCommand::ErrorEvent, this->Command);
  }
};

vtkSmartPointer<vtkPolyData> Read(const std::string& path, std::string* error = nullptr)
{
  vtkNew<vtkLASPointCloudReader> reader;
  ErrorCounter errors;
  errors.Observe(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  if (error)
  {
    *error = reader->GetErrorMessage();
  }
  PCB_CHECK(errors.Errors == (reader->GetErrorMessage()[0] ? 1 : 0),
    "%s: %d errors reported",
    path.c_str(),
    errors.Errors);
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->ShallowCopy(reader->GetOutput());
  return cloud;
}

bool Write(vtkPolyData* cloud, const std::string& path)
{
  vtkNew<vtkLASPointCloudWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(cloud);
  writer->Write();
  PCB_CHECK(writer->GetErrorMessage()[0] == '\0', "%s", writer->GetErrorMessage());
  return writer->GetErrorMessage()[0] == '\0';
}

template<typename T>
void Put(std::vector<char>& bytes, std::size_t offset, T value)
{
  std::memcpy(bytes.data() + offset, &value, sizeof(T));
}

/// A LAS file made byte by byte here (not by the writer under test): LAS 1.2, or 1.4 for the
/// formats beyond 5, with one VLR when `vlr` is not empty, and `records` as the point records.
std::vector<char> HandMadeLAS(int format,
  std::uint16_t recordLength,
  const std::vector<char>& vlr,
  const std::vector<char>& records)
{
  const bool wide = format > 5;
  const std::size_t headerSize = wide ? 375 : 227;
  const std::size_t count = records.size() / recordLength;
  std::vector<char> bytes(headerSize, 0);
  std::memcpy(bytes.data(), "LASF", 4);
  bytes[24] = 1;
  bytes[25] = wide ? 4 : 2;
  Put<std::uint16_t>(bytes, 94, static_cast<std::uint16_t>(headerSize));
  Put<std::uint32_t>(bytes, 96, static_cast<std::uint32_t>(headerSize + vlr.size()));
  Put<std::uint32_t>(bytes, 100, vlr.empty() ? 0u : 1u);
  bytes[104] = static_cast<char>(format);
  Put<std::uint16_t>(bytes, 105, recordLength);
  Put<std::uint32_t>(bytes, 107, wide ? 0u : static_cast<std::uint32_t>(count));
  for (int axis = 0; axis < 3; ++axis)
  {
    Put<double>(bytes, 131 + 8 * axis, 0.01);
  }
  if (wide)
  {
    Put<std::uint64_t>(bytes, 247, count);
  }
  bytes.insert(bytes.end(), vlr.begin(), vlr.end());
  bytes.insert(bytes.end(), records.begin(), records.end());
  return bytes;
}

void WriteBytes(const std::string& path, const std::vector<char>& bytes)
{
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// The extra-bytes VLR (record 4 of LASF_Spec) for `descriptors` of 192 bytes each.
std::vector<char> ExtraBytesVLR(const std::vector<std::vector<char>>& descriptors)
{
  std::vector<char> vlr(54, 0);
  std::memcpy(vlr.data() + 2, "LASF_Spec", 9);
  vlr[18] = 4;
  Put<std::uint16_t>(vlr, 20, static_cast<std::uint16_t>(192 * descriptors.size()));
  for (const std::vector<char>& descriptor : descriptors)
  {
    vlr.insert(vlr.end(), descriptor.begin(), descriptor.end());
  }
  return vlr;
}

std::vector<char> Descriptor(int dataType,
  int options,
  const char* name,
  std::vector<double> scales,
  std::vector<double> offsets,
  std::int64_t noData = 0)
{
  std::vector<char> descriptor(192, 0);
  descriptor[2] = static_cast<char>(dataType);
  descriptor[3] = static_cast<char>(options);
  std::memcpy(descriptor.data() + 4, name, std::strlen(name));
  for (std::size_t c = 0; c < scales.size(); ++c)
  {
    Put<std::int64_t>(descriptor, 40 + 8 * c, noData);
    Put<double>(descriptor, 112 + 8 * c, scales[c]);
    Put<double>(descriptor, 136 + 8 * c, offsets[c]);
  }
  return descriptor;
}

/// Reads `path`, writes it back unchanged to `again`: the point records must be the same.
void CheckRecordsWrittenBack(const std::string& path, vtkPolyData* read, const std::string& again)
{
  if (Write(read, again))
  {
    const std::vector<char> first = PointRecords(FileBytes(path));
    const std::vector<char> second = PointRecords(FileBytes(again));
    PCB_CHECK(
      !first.empty() && first == second, "%s: the point records written back differ", path.c_str());
  }
}

/// Writes `cloud` into a mapping of the file (where the file system allows it) and in chunks
/// with fwrite (PCB_LAS_WRITE_MAPPED=0, as where it does not): the same bytes.
void CheckMappedAndChunked(vtkPolyData* cloud, const std::string& name)
{
  unsetenv("PCB_LAS_WRITE_MAPPED");
  const bool mapped = Write(cloud, name + "-mapped.las");
  setenv("PCB_LAS_WRITE_MAPPED", "0", 1);
  const bool chunked = Write(cloud, name + "-chunked.las");
  unsetenv("PCB_LAS_WRITE_MAPPED");
  if (mapped && chunked)
  {
    const std::vector<char> bytes = FileBytes(name + "-mapped.las");
    PCB_CHECK(bytes.size() > 227 && bytes == FileBytes(name + "-chunked.las"),
      "%s: the mapped and the chunked writes differ",
      name.c_str());
  }
}

/// A file larger than the process may write (RLIMIT_FSIZE, as a full file system): one error,
/// and neither the file nor its temporary file left.
void CheckWriteBeyondLimit(vtkPolyData* cloud, const std::string& path)
{
  vtkNew<vtkLASPointCloudWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(cloud);
  {
    // Within the second chunk of the fwrite path (4.5 MB each).
    const pcbilateral_testing::FileSizeLimit sizeLimit(6000000);
    writer->Write();
  }
  const std::string expected = path + ": write failed (" + std::strerror(EFBIG) + ")";
  PCB_CHECK(expected == writer->GetErrorMessage(),
    "%s: \"%s\" instead of \"%s\"",
    path.c_str(),
    writer->GetErrorMessage(),
    expected.c_str());
  PCB_CHECK(access(path.c_str(), F_OK) != 0 && access((path + ".partial").c_str(), F_OK) != 0,
    "%s: a file was left after the failed write",
    path.c_str());
}

/// An empty file of the format, written and read back: the reader's arrays tell its fields.
vtkSmartPointer<vtkPolyData> FormatModel(int format, const std::string& name)
{
  vtkSmartPointer<vtkPolyData> empty = MakeCloud(format, 0);
  return Write(empty, name + "-empty.las") ? Read(name + "-empty.las") : nullptr;
}

void TestEveryPointFormat()
{
  const vtkIdType count = 20000; // more than two blocks of the parallel coder
  for (int format = 0; format <= 10; ++format)
  {
    const std::string name = "format" + std::to_string(format);
    vtkSmartPointer<vtkPolyData> model = FormatModel(format, name);
    if (!model)
    {
      continue;
    }
    vtkSmartPointer<vtkPolyData> cloud = MakeCloud(format, count);
    // The points alone: every other field has no column and must be zeros either way.
    CheckMappedAndChunked(cloud, name + "-points");
    FillArraysLike(model, cloud);
    CheckMappedAndChunked(cloud, name);
    if (!Write(cloud, name + ".las"))
    {
      continue;
    }
    vtkSmartPointer<vtkPolyData> read = Read(name + ".las");
    PCB_CHECK(read->GetNumberOfPoints() == count,
      "%s: %lld points",
      name.c_str(),
      static_cast<long long>(read->GetNumberOfPoints()));
    PCB_CHECK(read->GetNumberOfVerts() == count, "%s: one vertex per point", name.c_str());
    PCB_CHECK(read->GetPoints()->GetDataType() == VTK_DOUBLE, "%s: double points", name.c_str());
    if (read->GetNumberOfPoints() != count)
    {
      continue;
    }
    double worst = 0;
    for (vtkIdType i = 0; i < count; ++i)
    {
      double a[3], b[3];
      cloud->GetPoint(i, a);
      read->GetPoint(i, b);
      for (int k = 0; k < 3; ++k)
      {
        worst = std::max(worst, std::abs(a[k] - b[k]));
      }
    }
    PCB_CHECK(worst < 1e-9, "%s: points moved by %g", name.c_str(), worst);
    for (int a = 0; a < cloud->GetPointData()->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* written = cloud->GetPointData()->GetArray(a);
      vtkDataArray* back = read->GetPointData()->GetArray(written->GetName());
      PCB_CHECK(back != nullptr, "%s: no array %s", name.c_str(), written->GetName());
      if (!back)
      {
        continue;
      }
      PCB_CHECK(back->GetDataType() == written->GetDataType() &&
                  back->GetNumberOfComponents() == written->GetNumberOfComponents(),
        "%s: %s changed type",
        name.c_str(),
        written->GetName());
      bool same = true;
      for (vtkIdType i = 0; i < count && same; ++i)
      {
        for (int c = 0; c < written->GetNumberOfComponents(); ++c)
        {
          same = same && written->GetComponent(i, c) == back->GetComponent(i, c);
        }
      }
      PCB_CHECK(same, "%s: the values of %s changed", name.c_str(), written->GetName());
    }
    // Read, then written again without a change: the same point records, byte for byte.
    CheckRecordsWrittenBack(name + ".las", read, name + "-again.las");
    PCB_CHECK(FileBytes(name + ".las")[104] == format,
      "%s: written as format %d",
      name.c_str(),
      FileBytes(name + ".las")[104]);
  }
}

void TestChunksAndSizeLimit()
{
  vtkSmartPointer<vtkPolyData> model = FormatModel(3, "limited");
  if (!model)
  {
    return;
  }
  // More than two chunks of the fwrite path (131072 points each), 37 blocks of 8192 points.
  vtkSmartPointer<vtkPolyData> cloud = MakeCloud(3, 300000);
  FillArraysLike(model, cloud);
  CheckMappedAndChunked(cloud, "chunks");
  CheckWriteBeyondLimit(cloud, "limited.las");
  setenv("PCB_LAS_WRITE_MAPPED", "0", 1);
  CheckWriteBeyondLimit(cloud, "limited-chunked.las");
  unsetenv("PCB_LAS_WRITE_MAPPED");
}

void TestDefaultHeader()
{
  // Float points from elsewhere, with GPS times and 8-bit colours: LAS 1.2 format 3, colours
  // scaled to 16 bits, the precision of the points kept.
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  vtkNew<vtkDoubleArray> times;
  times->SetName("GpsTime");
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("RGB");
  colours->SetNumberOfComponents(3);
  for (int i = 0; i < 100; ++i)
  {
    points->InsertNextPoint(0.01f * i, 1.0f - 0.01f * i, 0.5f);
    times->InsertNextValue(1e5 + i);
    colours->InsertNextTuple3(i, 2 * i, 255);
  }
  cloud->SetPoints(points);
  cloud->GetPointData()->AddArray(times);
  cloud->GetPointData()->AddArray(colours);
  if (!Write(cloud, "default.las"))
  {
    return;
  }
  const std::vector<char> bytes = FileBytes("default.las");
  PCB_CHECK(bytes[24] == 1 && bytes[25] == 2 && bytes[104] == 3,
    "LAS %d.%d format %d",
    bytes[24],
    bytes[25],
    bytes[104]);
  vtkSmartPointer<vtkPolyData> read = Read("default.las");
  PCB_CHECK(read->GetNumberOfPoints() == 100,
    "%lld points",
    static_cast<long long>(read->GetNumberOfPoints()));
  double worst = 0;
  for (vtkIdType i = 0; i < read->GetNumberOfPoints(); ++i)
  {
    double a[3], b[3];
    cloud->GetPoint(i, a);
    read->GetPoint(i, b);
    for (int k = 0; k < 3; ++k)
    {
      worst = std::max(worst, std::abs(a[k] - b[k]));
    }
  }
  PCB_CHECK(worst < 1e-8, "points moved by %g", worst);
  auto* rgb = vtkUnsignedShortArray::SafeDownCast(read->GetPointData()->GetArray("RGB"));
  PCB_CHECK(rgb && rgb->GetComponent(10, 1) == 20 * 257 && rgb->GetComponent(10, 2) == 65535,
    "8-bit colours scaled to 16 bits");
  vtkDataArray* display = read->GetPointData()->GetArray("Colors");
  PCB_CHECK(
    display && display->GetDataType() == VTK_UNSIGNED_CHAR && display->GetComponent(10, 1) == 20,
    "8-bit display colours");
  PCB_CHECK(read->GetPointData()->GetArray("GpsTime")->GetComponent(7, 0) == 1e5 + 7, "GPS time");
}

void TestExtraBytes()
{
  // A record of format 0 with 12 extra bytes: a described float "Height", a described
  // unsigned short "Label", and 6 bytes no descriptor names.
  vtkSmartPointer<vtkPolyData> cloud = MakeCloud(0, 10);
  vtkFieldData* fieldData = cloud->GetFieldData();
  fieldData->RemoveArray("LAS Point Record Length");
  AddFieldValues(fieldData, "LAS Point Record Length", VTK_UNSIGNED_SHORT, { 20 + 12 });
  const std::vector<char> vlr = ExtraBytesVLR({
    Descriptor(9, 0, "Height", { 1.0 }, { 0.0 }), // float
    Descriptor(3, 0, "Label", { 1.0 }, { 0.0 }),  // unsigned short
  });
  vtkNew<vtkUnsignedCharArray> vlrs;
  vlrs->SetName("LAS VLRs");
  for (char byte : vlr)
  {
    vlrs->InsertNextValue(static_cast<unsigned char>(byte));
  }
  fieldData->AddArray(vlrs);
  vtkNew<vtkFloatArray> height;
  height->SetName("Height");
  vtkNew<vtkUnsignedShortArray> label;
  label->SetName("Label");
  for (int i = 0; i < 10; ++i)
  {
    height->InsertNextValue(0.5f * i);
    label->InsertNextValue(static_cast<unsigned short>(1000 + i));
  }
  cloud->GetPointData()->AddArray(height);
  cloud->GetPointData()->AddArray(label);
  if (!Write(cloud, "extra.las"))
  {
    return;
  }
  vtkSmartPointer<vtkPolyData> read = Read("extra.las");
  vtkDataArray* h = read->GetPointData()->GetArray("Height");
  vtkDataArray* l = read->GetPointData()->GetArray("Label");
  vtkDataArray* rest = read->GetPointData()->GetArray("ExtraBytes");
  PCB_CHECK(h && h->GetDataType() == VTK_FLOAT && h->GetComponent(3, 0) == 1.5, "Height");
  PCB_CHECK(l && l->GetDataType() == VTK_UNSIGNED_SHORT && l->GetComponent(9, 0) == 1009, "Label");
  PCB_CHECK(rest && rest->GetNumberOfComponents() == 6, "the undescribed bytes");
}

// Format 0 with 4 + 2 + 6 + 4 + 1 extra bytes: "Height", an int32 with a scale and an offset;
// "Temperature", a uint16 with a scale, an offset and a no-data value; "Shift", a deprecated
// array of 3 int16 with a scale and an offset per component; "Ratio", a float with a scale
// (floats keep their stored values); "Flags", a uint8 with neither (kept as it is).
constexpr std::uint16_t ScaledExtraBytesLength = 20 + 4 + 2 + 6 + 4 + 1;
constexpr int ScaledExtraBytesCount = 10;
const std::vector<double> ShiftScales = { 0.5, 0.25, 2.0 };
const std::vector<double> ShiftOffsets = { 1.0, -2.0, 1000.0 };

/// The records of the scaled extra bytes' file; point 3's temperature is the no-data value.
std::vector<char> ScaledExtraBytesRecords()
{
  const std::uint16_t length = ScaledExtraBytesLength;
  std::vector<char> records(static_cast<std::size_t>(length) * ScaledExtraBytesCount, 0);
  for (int i = 0; i < ScaledExtraBytesCount; ++i)
  {
    const std::size_t at = static_cast<std::size_t>(i) * length;
    Put<std::int32_t>(records, at, 100 * i);
    Put<std::int32_t>(records, at + 20, static_cast<std::int32_t>(-2000000000LL + 400000000LL * i));
    Put<std::uint16_t>(
      records, at + 24, static_cast<std::uint16_t>(i == 3 ? 65535 : 6000 + 37 * i));
    for (int c = 0; c < 3; ++c)
    {
      Put<std::int16_t>(
        records, at + 26 + 2 * c, static_cast<std::int16_t>((c + 1) * (i - 5) * 1000));
    }
    Put<float>(records, at + 32, 0.5f * i);
    records[at + 36] = static_cast<char>(200 + i);
  }
  return records;
}

/// Point i's extra bytes as read: the stored values scaled and offset, or as stored.
void CheckScaledValues(vtkPointData* data, int i)
{
  vtkDataArray* height = data->GetArray("Height");
  vtkDataArray* temperature = data->GetArray("Temperature");
  vtkDataArray* shift = data->GetArray("Shift");
  const double expectedHeight = (-2000000000.0 + 400000000.0 * i) * 0.001 + 100.0;
  PCB_CHECK(height->GetComponent(i, 0) == expectedHeight,
    "point %d: Height %.17g, expected %.17g",
    i,
    height->GetComponent(i, 0),
    expectedHeight);
  if (i == 3)
  {
    PCB_CHECK(std::isnan(temperature->GetComponent(i, 0)), "the no-data value reads as NaN");
  }
  else
  {
    const double expected = (6000 + 37 * i) * 0.01 - 40.0;
    PCB_CHECK(temperature->GetComponent(i, 0) == expected,
      "point %d: Temperature %.17g, "
      "expected %.17g",
      i,
      temperature->GetComponent(i, 0),
      expected);
  }
  for (int c = 0; c < 3; ++c)
  {
    const double expected = (c + 1) * (i - 5) * 1000 * ShiftScales[c] + ShiftOffsets[c];
    PCB_CHECK(shift->GetComponent(i, c) == expected,
      "point %d: Shift[%d] %g, expected %g",
      i,
      c,
      shift->GetComponent(i, c),
      expected);
  }
  PCB_CHECK(data->GetArray("Ratio")->GetComponent(i, 0) == 0.5 * i &&
              data->GetArray("Flags")->GetComponent(i, 0) == 200 + i,
    "point %d: Ratio and Flags as stored",
    i);
}

/// Values changed (as a filter would) are stored rounded to the nearest step.
void CheckChangedValuesRounded(vtkPolyData* read)
{
  read->GetPointData()->GetArray("Temperature")->SetComponent(0, 0, 20.004);
  read->GetPointData()->GetArray("Temperature")->SetComponent(1, 0, std::nan(""));
  read->GetPointData()->GetArray("Height")->SetComponent(0, 0, 100.0006);
  if (Write(read, "scaled-extra-changed.las"))
  {
    const std::vector<char> changed = PointRecords(FileBytes("scaled-extra-changed.las"));
    PCB_CHECK(At<std::uint16_t>(changed, 24) == 6000 &&
                At<std::uint16_t>(changed, ScaledExtraBytesLength + 24) == 65535 &&
                At<std::int32_t>(changed, 20) == 1,
      "changed values stored as %u, %u and %d",
      At<std::uint16_t>(changed, 24),
      At<std::uint16_t>(changed, ScaledExtraBytesLength + 24),
      At<std::int32_t>(changed, 20));
  }
}

void TestScaledExtraBytes()
{
  const std::vector<char> vlr = ExtraBytesVLR({
    Descriptor(6, 8 | 16, "Height", { 0.001 }, { 100.0 }),
    Descriptor(3, 1 | 2 | 4 | 8 | 16, "Temperature", { 0.01 }, { -40.0 }, 65535),
    Descriptor(24, 8 | 16, "Shift", ShiftScales, ShiftOffsets),
    Descriptor(9, 8, "Ratio", { 10.0 }, { 0.0 }),
    Descriptor(1, 0, "Flags", { 1.0 }, { 0.0 }),
  });
  WriteBytes(
    "scaled-extra.las", HandMadeLAS(0, ScaledExtraBytesLength, vlr, ScaledExtraBytesRecords()));
  vtkSmartPointer<vtkPolyData> read = Read("scaled-extra.las");
  vtkPointData* data = read->GetPointData();
  vtkDataArray* height = data->GetArray("Height");
  vtkDataArray* temperature = data->GetArray("Temperature");
  vtkDataArray* shift = data->GetArray("Shift");
  vtkDataArray* ratio = data->GetArray("Ratio");
  vtkDataArray* flags = data->GetArray("Flags");
  const int count = ScaledExtraBytesCount;
  PCB_CHECK(read->GetNumberOfPoints() == count,
    "%lld points",
    static_cast<long long>(read->GetNumberOfPoints()));
  PCB_CHECK(height && height->GetDataType() == VTK_DOUBLE && temperature &&
              temperature->GetDataType() == VTK_DOUBLE && shift &&
              shift->GetDataType() == VTK_DOUBLE && shift->GetNumberOfComponents() == 3,
    "the scaled extra bytes are doubles");
  PCB_CHECK(ratio && ratio->GetDataType() == VTK_FLOAT && flags &&
              flags->GetDataType() == VTK_UNSIGNED_CHAR,
    "unscaled extra bytes keep their types");
  if (!height || !temperature || !shift || !ratio || !flags || read->GetNumberOfPoints() != count)
  {
    return;
  }
  for (int i = 0; i < count; ++i)
  {
    CheckScaledValues(data, i);
  }
  CheckRecordsWrittenBack("scaled-extra.las", read, "scaled-extra-again.las");
  CheckChangedValuesRounded(read);
}

void TestScanAngle()
{
  // Format 6 stores the scan angle in units of 0.006 degree; it reads in degrees.
  const std::int16_t stored[] = { -32768, -30000, -12345, -1, 0, 1, 2, 15000, 30000, 32767 };
  const int count = 10;
  std::vector<char> records(static_cast<std::size_t>(30) * count, 0);
  for (int i = 0; i < count; ++i)
  {
    Put<std::int16_t>(records, static_cast<std::size_t>(i) * 30 + 18, stored[i]);
  }
  WriteBytes("scan-angle.las", HandMadeLAS(6, 30, {}, records));
  vtkSmartPointer<vtkPolyData> read = Read("scan-angle.las");
  vtkDataArray* angle = read->GetPointData()->GetArray("ScanAngle");
  PCB_CHECK(angle && (angle->GetDataType() == VTK_FLOAT || angle->GetDataType() == VTK_DOUBLE),
    "ScanAngle is a floating-point array");
  if (!angle || read->GetNumberOfPoints() != count)
  {
    return;
  }
  for (int i = 0; i < count; ++i)
  {
    PCB_CHECK(std::abs(angle->GetComponent(i, 0) - stored[i] * 0.006) < 1e-5,
      "ScanAngle %g degrees, stored %d",
      angle->GetComponent(i, 0),
      stored[i]);
  }
  PCB_CHECK(angle->GetComponent(8, 0) == static_cast<float>(180.0), "30000 steps: 180 degrees");
  CheckRecordsWrittenBack("scan-angle.las", read, "scan-angle-again.las");
}

void TestExtraBytesNamedColors()
{
  // Format 2 (RGB) with 3 extra bytes named "Colors" (3 unsigned bytes, type 21): the reader's
  // display colours, also "Colors", must not replace them.
  const std::vector<char> vlr = ExtraBytesVLR({ Descriptor(21, 0, "Colors", {}, {}) });
  const int count = 5;
  std::vector<char> records(static_cast<std::size_t>(29) * count, 0);
  for (int i = 0; i < count; ++i)
  {
    const std::size_t at = static_cast<std::size_t>(i) * 29;
    for (int c = 0; c < 3; ++c)
    {
      Put<std::uint16_t>(records, at + 20 + 2 * c, static_cast<std::uint16_t>(1000 * (c + 1)));
      records[at + 26 + c] = static_cast<char>(10 * i + c);
    }
  }
  WriteBytes("extra-colors.las", HandMadeLAS(2, 29, vlr, records));
  vtkSmartPointer<vtkPolyData> read = Read("extra-colors.las");
  vtkDataArray* extra = read->GetPointData()->GetArray("Colors_2");
  PCB_CHECK(extra && extra->GetNumberOfComponents() == 3 && extra->GetComponent(4, 2) == 42,
    "the extra bytes named Colors are read as Colors_2");
  vtkDataArray* display = read->GetPointData()->GetArray("Colors");
  PCB_CHECK(display && display->GetComponent(4, 2) == 3000 / 256, "the display colours");
  CheckRecordsWrittenBack("extra-colors.las", read, "extra-colors-again.las");
}

void TestDamagedFiles()
{
  vtkSmartPointer<vtkPolyData> cloud = MakeCloud(6, 1000);
  if (!Write(cloud, "whole.las"))
  {
    return;
  }
  const std::vector<char> whole = FileBytes("whole.las");
  auto damaged = [&](const char* name, std::vector<char> bytes, const char* expected)
  {
    WriteBytes(name, bytes);
    std::string error;
    vtkSmartPointer<vtkPolyData> read = Read(name, &error);
    PCB_CHECK(error.find(expected) != std::string::npos && error.find(name) != std::string::npos &&
                error.find('\n') == std::string::npos,
      "%s: the error is '%s', expected '%s'",
      name,
      error.c_str(),
      expected);
    PCB_CHECK(read->GetNumberOfPoints() == 0,
      "%s: %lld points read from a damaged file",
      name,
      static_cast<long long>(read->GetNumberOfPoints()));
  };
  damaged("cut.las", std::vector<char>(whole.begin(), whole.end() - 1), "truncated");
  damaged("header-only.las", std::vector<char>(whole.begin(), whole.begin() + 100), "truncated");
  damaged("empty.las", {}, "not a LAS file");
  std::vector<char> bytes = whole;
  bytes[104] = static_cast<char>(0x86);
  damaged("compressed.las", bytes, "compressed (LAZ)");
  bytes = whole;
  bytes[104] = 42;
  damaged("format42.las", bytes, "point format 42 is not supported");
  bytes = whole;
  bytes[105] = 10; // record length 10, shorter than format 6 needs
  bytes[106] = 0;
  damaged("short-records.las", bytes, "shorter than point format 6 needs");
  bytes = whole;
  std::memset(bytes.data() + 247, 0xff, 8); // 2^64 - 1 points
  damaged("count.las", bytes, "truncated: the header announces 18446744073709551615 points");
  bytes = whole;
  std::memset(bytes.data() + 131, 0, 8); // x scale 0
  damaged("scale.las", bytes, "scale or offset of x");
  bytes = whole;
  bytes[25] = 9;
  damaged("version.las", bytes, "unsupported LAS version 1.9");
  damaged("missing.las", {}, "not a LAS file");
  std::remove("missing.las");
  std::string error;
  Read("missing.las", &error);
  PCB_CHECK(error.find("No such file") != std::string::npos, "missing file: %s", error.c_str());
}
} // namespace

int main(int argc, char* argv[])
{
  const std::map<std::string, std::function<void()>> cases = {
    { "every-point-format", TestEveryPointFormat },
    { "chunks-and-size-limit", TestChunksAndSizeLimit },
    { "default-header", TestDefaultHeader },
    { "extra-bytes", TestExtraBytes },
    { "scaled-extra-bytes", TestScaledExtraBytes },
    { "scan-angle", TestScanAngle },
    { "extra-bytes-named-colors", TestExtraBytesNamedColors },
    { "damaged-files", TestDamagedFiles },
  };
  return RunNamedCase(argc, argv, cases);
}

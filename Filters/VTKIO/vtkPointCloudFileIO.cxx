#include "vtkPointCloudFileIO.h"

#include "vtkLASPointCloudReader.h"
#include "vtkLASPointCloudWriter.h"
#include "vtkPointCloudTextReader.h"
#include "vtkPointCloudTextWriter.h"

#include "ReplacingPath.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPLYReader.h"
#include "vtkPLYWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkWriter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkXMLWriter.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

vtkStandardNewMacro(vtkPointCloudFileIO);

namespace
{
std::string Extension(const char* path)
{
  std::string extension = std::filesystem::path(path ? path : "").extension().string();
  std::transform(extension.begin(),
    extension.end(),
    extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

bool IsText(const std::string& extension)
{
  return extension == ".txt" || extension == ".xyz";
}

bool IsLAS(const std::string& extension)
{
  return extension == ".las" || extension == ".laz";
}

/// "PATH: unsupported file type '.ext' (use ...)".
std::string UnsupportedType(const char* path)
{
  return std::string(path ? path : "") + ": unsupported file type '" + Extension(path) + "' (use " +
         vtkPointCloudFileIO::GetSupportedExtensions() + ")";
}

/// Up to `count` bytes of a file from `offset`.
std::string ReadBytes(const std::string& path, std::uintmax_t offset, std::size_t count)
{
  std::ifstream file(path, std::ios::binary);
  file.seekg(static_cast<std::streamoff>(offset));
  std::string bytes(count, '\0');
  file.read(&bytes[0], static_cast<std::streamsize>(count));
  bytes.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, file.gcount())));
  return bytes;
}

struct PLYElement
{
  std::string Name;
  unsigned long long Count = 0;
  std::size_t FixedBytes = 0; // scalar properties, and the count of each list
  std::size_t Properties = 0; // values on an ASCII line at least
  std::vector<std::string> Names;
};

std::size_t PLYTypeSize(const std::string& type)
{
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8")
  {
    return 1;
  }
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16")
  {
    return 2;
  }
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
      type == "float32")
  {
    return 4;
  }
  if (type == "double" || type == "float64")
  {
    return 8;
  }
  return 0;
}

/// The PLY header against the file: one line, or an empty string.
std::string CheckPLY(const std::string& path, std::uintmax_t size)
{
  constexpr std::size_t MaximumHeader = 1 << 16;
  const std::string head = ReadBytes(path, 0, MaximumHeader);
  if (head.compare(0, 3, "ply") != 0 || head.size() < 4 || (head[3] != '\n' && head[3] != '\r'))
  {
    return "not a PLY file (it does not start with 'ply')";
  }
  std::istringstream lines(head);
  std::string line;
  std::string format;
  std::vector<PLYElement> elements;
  std::size_t headerBytes = 0;
  bool ended = false;
  while (std::getline(lines, line))
  {
    headerBytes += line.size() + 1;
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "end_header")
    {
      ended = !lines.eof();
      break;
    }
    if (keyword == "format")
    {
      words >> format;
    }
    else if (keyword == "element")
    {
      PLYElement element;
      std::string count;
      words >> element.Name >> count;
      const auto parsed = std::from_chars(count.data(), count.data() + count.size(), element.Count);
      if (parsed.ec != std::errc() || parsed.ptr != count.data() + count.size())
      {
        return "the PLY header gives element '" + element.Name + "' the count '" + count +
               "', not a whole number";
      }
      elements.push_back(element);
    }
    else if (keyword == "property")
    {
      if (elements.empty())
      {
        return "the PLY header has a property before any element";
      }
      std::string type, name;
      words >> type;
      if (type == "list")
      {
        std::string countType, itemType;
        words >> countType >> itemType >> name;
        type = countType;
        if (PLYTypeSize(itemType) == 0)
        {
          type = itemType;
        }
      }
      else
      {
        words >> name;
      }
      if (PLYTypeSize(type) == 0)
      {
        return "the PLY header has a property of unknown type '" + type + "'";
      }
      elements.back().FixedBytes += PLYTypeSize(type);
      elements.back().Properties += 1;
      elements.back().Names.push_back(name);
    }
  }
  if (!ended)
  {
    return "the PLY header has no end_header line in its first 64 KB";
  }
  if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
  {
    return "the PLY header gives an unknown format '" + format + "'";
  }
  const PLYElement* vertices = nullptr;
  for (const PLYElement& element : elements)
  {
    vertices = element.Name == "vertex" ? &element : vertices;
  }
  if (!vertices)
  {
    return "the PLY file has no vertex element";
  }
  std::string missing;
  for (const char* axis : { "x", "y", "z" })
  {
    if (std::find(vertices->Names.begin(), vertices->Names.end(), axis) == vertices->Names.end())
    {
      missing += missing.empty() ? axis : std::string(", ") + axis;
    }
  }
  if (!missing.empty())
  {
    return "the PLY vertices have no " + missing + " property (x, y and z are needed)";
  }

  const std::uintmax_t dataBytes = size - std::min<std::uintmax_t>(size, headerBytes);
  if (format != "ascii")
  {
    // Lists hold at least their count: the smallest size the announced elements can take.
    std::uintmax_t needed = 0;
    for (const PLYElement& element : elements)
    {
      if (element.FixedBytes > 0 && element.Count > (dataBytes - needed) / element.FixedBytes)
      {
        return "truncated: the PLY header announces " + std::to_string(element.Count) + " " +
               element.Name + " records of at least " + std::to_string(element.FixedBytes) +
               " bytes, the file holds " + std::to_string(dataBytes) + " bytes after its header";
      }
      needed += element.Count * element.FixedBytes;
    }
    return std::string();
  }
  // ASCII: one line per record, each with at least as many values as the element's properties.
  std::ifstream file(path, std::ios::binary);
  file.seekg(static_cast<std::streamoff>(headerBytes));
  for (const PLYElement& element : elements)
  {
    for (unsigned long long k = 0; k < element.Count; ++k)
    {
      do
      {
        if (!std::getline(file, line))
        {
          return "truncated: the PLY header announces " + std::to_string(element.Count) + " " +
                 element.Name + " lines, the file holds " + std::to_string(k);
        }
      } while (line.find_first_not_of(" \t\r") == std::string::npos);
      std::istringstream words(line);
      std::string word;
      std::size_t values = 0;
      while (words >> word)
      {
        ++values;
      }
      if (values < element.Properties)
      {
        return element.Name + " " + std::to_string(k + 1) + " has " + std::to_string(values) +
               " values, the PLY header announces " + std::to_string(element.Properties);
      }
    }
  }
  return std::string();
}

std::string CheckVTP(const std::string& path, std::uintmax_t size)
{
  const std::string head = ReadBytes(path, 0, 512);
  if (head.find("<VTKFile") == std::string::npos)
  {
    return "not a VTK XML file (no <VTKFile> element at its start)";
  }
  std::string tail = ReadBytes(path, size > 64 ? size - 64 : 0, 64);
  while (!tail.empty() && std::isspace(static_cast<unsigned char>(tail.back())))
  {
    tail.pop_back();
  }
  const std::string closing = "</VTKFile>";
  if (tail.size() < closing.size() ||
      tail.compare(tail.size() - closing.size(), closing.size(), closing) != 0)
  {
    return "truncated: the VTK XML file does not end with </VTKFile>";
  }
  return std::string();
}

/// Keeps the first error (and warning) an algorithm reports, without VTK's object prefix.
struct MessageCatcher
{
  std::string Error;
  std::string Path;
  vtkNew<vtkCallbackCommand> Command;

  void Observe(vtkObject* object)
  {
    this->Command->SetClientData(this);
    this->Command->SetCallback(
      [](vtkObject*, unsigned long, void* clientData, void* callData)
      {
        auto* self = static_cast<MessageCatcher*>(clientData);
        if (self->Error.empty() && callData)
        {
          self->Error = self->Clean(static_cast<const char*>(callData));
        }
      });
    object->AddObserver(vtkCommand::ErrorEvent, this->Command);
  }

  /// The event's message, starting with the path (once).
  std::string Clean(const char* callData) const
  {
    std::string message = vtkPointCloudFileIO::EventMessage(callData);
    if (message.compare(0, this->Path.size(), this->Path) != 0)
    {
      message = this->Path + ": " + message;
    }
    return message;
  }
};

/// The cloud as the PLY writer stores it: float normals (the only ones PLY stores), and the
/// 8-bit colours named to the writer.
vtkSmartPointer<vtkPolyData> InputForPLY(vtkPolyData* data, vtkPLYWriter* ply)
{
  vtkSmartPointer<vtkPolyData> input = data;
  vtkDataArray* normals = data->GetPointData()->GetNormals();
  if (normals && normals->GetDataType() != VTK_FLOAT)
  {
    input = vtkSmartPointer<vtkPolyData>::New();
    input->ShallowCopy(data);
    vtkNew<vtkFloatArray> floatNormals;
    floatNormals->DeepCopy(normals);
    input->GetPointData()->SetNormals(floatNormals);
  }
  // 8-bit colours only; a LAS file's 16-bit "RGB" has 8-bit "Colors" beside it.
  for (const char* colours : { "Colors", "RGBA", "RGB" })
  {
    vtkDataArray* array = input->GetPointData()->GetArray(colours);
    if (array && array->GetDataType() == VTK_UNSIGNED_CHAR)
    {
      ply->SetArrayName(colours);
    }
  }
  return input;
}

/// Runs a writer of NewWriter(): whether it reported success.
bool RunWriter(vtkAlgorithm* writer)
{
  if (auto* xml = vtkXMLWriter::SafeDownCast(writer))
  {
    return xml->Write() == 1;
  }
  return vtkWriter::SafeDownCast(writer)->Write() == 1;
}

/// Runs VTK's PLY or XML writer on a temporary file beside `path`, moved onto it only when the
/// writer succeeded. Returns an empty string or one line naming `path` (VTK's messages name the
/// temporary file).
std::string WriteReplacing(vtkAlgorithm* writer,
  const std::string& path,
  const MessageCatcher& messages)
{
  // The PLY writer appends ".ply" to a name without it: the extension stays last.
  pcbilateral::ReplacingPath destination(
    path, pcbilateral::ReplacingPath::TemporaryName::ExtensionLast);
  const char* temporary = destination.GetTemporaryPath().c_str();
  if (auto* ply = vtkPLYWriter::SafeDownCast(writer))
  {
    ply->SetFileName(temporary);
  }
  else
  {
    vtkXMLWriter::SafeDownCast(writer)->SetFileName(temporary);
  }
  errno = 0;
  const bool written = RunWriter(writer) && messages.Error.empty();
  return destination.Commit(written, errno);
}
} // namespace

vtkPointCloudFileIO::vtkPointCloudFileIO() = default;
vtkPointCloudFileIO::~vtkPointCloudFileIO() = default;

std::string vtkPointCloudFileIO::EventMessage(const char* callData)
{
  std::string message = callData ? callData : "";
  // "ERROR: In file.cxx, line N\n" (or "Warning: ...") before the object, in VTK 9.2.
  if (message.compare(0, 10, "ERROR: In ") == 0 || message.compare(0, 12, "Warning: In ") == 0)
  {
    const std::size_t lineEnd = message.find('\n');
    message = lineEnd == std::string::npos ? std::string() : message.substr(lineEnd + 1);
  }
  const std::size_t prefix = message.find("): ");
  if (message.compare(0, 3, "vtk") == 0 && prefix != std::string::npos &&
      prefix < message.find('\n'))
  {
    message = message.substr(prefix + 3);
  }
  message = message.substr(0, message.find('\n'));
  while (!message.empty() && (message.back() == ' ' || message.back() == '\r'))
  {
    message.pop_back();
  }
  return message;
}

const char* vtkPointCloudFileIO::GetSupportedExtensions()
{
  return ".txt, .xyz, .las, .ply or .vtp";
}

bool vtkPointCloudFileIO::IsSupported(const char* path)
{
  const std::string extension = Extension(path);
  return IsText(extension) || IsLAS(extension) || extension == ".ply" || extension == ".vtp";
}

vtkAlgorithm* vtkPointCloudFileIO::NewReader(const char* path)
{
  const std::string extension = Extension(path);
  if (IsText(extension))
  {
    auto* reader = vtkPointCloudTextReader::New();
    reader->SetFileName(path);
    return reader;
  }
  if (IsLAS(extension))
  {
    auto* reader = vtkLASPointCloudReader::New();
    reader->SetFileName(path);
    return reader;
  }
  if (extension == ".ply")
  {
    auto* reader = vtkPLYReader::New();
    reader->SetFileName(path);
    return reader;
  }
  if (extension == ".vtp")
  {
    auto* reader = vtkXMLPolyDataReader::New();
    reader->SetFileName(path);
    return reader;
  }
  return nullptr;
}

std::string vtkPointCloudFileIO::CheckFileName(const char* path, bool forWriting)
{
  const std::string name = path ? path : "";
  if (!IsSupported(path))
  {
    return UnsupportedType(path);
  }
  if (forWriting && Extension(path) == ".laz")
  {
    return name + ": compressed LAS (LAZ) is not written: write .las (then compress it with "
                  "laszip if needed)";
  }
  return std::string();
}

bool vtkPointCloudFileIO::IsTextFormat(const char* path)
{
  return IsText(Extension(path));
}

vtkAlgorithm* vtkPointCloudFileIO::NewWriter(const char* path)
{
  const std::string extension = Extension(path);
  if (IsText(extension))
  {
    auto* writer = vtkPointCloudTextWriter::New();
    writer->SetFileName(path);
    return writer;
  }
  if (extension == ".las")
  {
    auto* writer = vtkLASPointCloudWriter::New();
    writer->SetFileName(path);
    return writer;
  }
  if (extension == ".ply")
  {
    auto* writer = vtkPLYWriter::New();
    writer->SetFileName(path);
    writer->SetFileTypeToBinary();
    return writer;
  }
  if (extension == ".vtp")
  {
    auto* writer = vtkXMLPolyDataWriter::New();
    writer->SetFileName(path);
    return writer;
  }
  return nullptr;
}

std::string vtkPointCloudFileIO::CheckInputFile(const char* path)
{
  const std::string name = path ? path : "";
  std::error_code error;
  const auto status = std::filesystem::status(name, error);
  if (!std::filesystem::exists(status))
  {
    return name + ": " + std::strerror(ENOENT);
  }
  if (std::filesystem::is_directory(status))
  {
    return name + ": is a directory, not a point file";
  }
  const std::string extension = Extension(path);
  if (!IsSupported(path))
  {
    return UnsupportedType(path);
  }
  const std::uintmax_t size = std::filesystem::file_size(name, error);
  if (error)
  {
    return name + ": " + error.message();
  }
  std::string problem;
  if (extension == ".ply")
  {
    problem = CheckPLY(name, size);
  }
  else if (extension == ".vtp")
  {
    problem = CheckVTP(name, size);
  }
  return problem.empty() ? problem : name + ": " + problem;
}

bool vtkPointCloudFileIO::Read(const char* path, vtkPolyData* output)
{
  output->Initialize();
  this->ErrorMessage = CheckInputFile(path);
  if (!this->ErrorMessage.empty())
  {
    return false;
  }
  vtkSmartPointer<vtkAlgorithm> reader = vtkSmartPointer<vtkAlgorithm>::Take(NewReader(path));
  if (auto* text = vtkPointCloudTextReader::SafeDownCast(reader))
  {
    text->SetHasNormals(this->OrientedNormals);
  }
  MessageCatcher messages;
  messages.Path = path;
  messages.Observe(reader);
  reader->Update();
  auto* cloud = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (messages.Error.empty() && !cloud)
  {
    messages.Error = std::string(path) + ": the reader gave no point cloud";
  }
  this->ErrorMessage = messages.Error;
  if (!this->ErrorMessage.empty())
  {
    return false;
  }
  output->ShallowCopy(cloud);
  return true;
}

bool vtkPointCloudFileIO::Write(vtkPolyData* data, const char* path)
{
  const std::string name = path ? path : "";
  vtkSmartPointer<vtkAlgorithm> writer = vtkSmartPointer<vtkAlgorithm>::Take(NewWriter(path));
  if (!writer)
  {
    this->ErrorMessage = UnsupportedType(path);
    return false;
  }
  MessageCatcher messages;
  messages.Path = name;
  messages.Observe(writer);
  vtkSmartPointer<vtkPolyData> input = data;
  if (auto* text = vtkPointCloudTextWriter::SafeDownCast(writer))
  {
    text->SetWriteNormals(this->OrientedNormals);
  }
  else if (auto* ply = vtkPLYWriter::SafeDownCast(writer))
  {
    input = InputForPLY(data, ply);
  }
  writer->SetInputDataObject(input);
  if (vtkPLYWriter::SafeDownCast(writer) || vtkXMLWriter::SafeDownCast(writer))
  {
    this->ErrorMessage = WriteReplacing(writer, name, messages);
    return this->ErrorMessage.empty();
  }
  // The text and LAS writers replace the file themselves (pcbilateral::ReplacingFile).
  if (!RunWriter(writer) && messages.Error.empty())
  {
    messages.Error = name + ": cannot be written";
  }
  this->ErrorMessage = messages.Error;
  return this->ErrorMessage.empty();
}

void vtkPointCloudFileIO::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OrientedNormals: " << this->OrientedNormals << "\n";
}

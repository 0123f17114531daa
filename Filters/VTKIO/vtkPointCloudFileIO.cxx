#include "vtkPointCloudFileIO.h"
#include "vtkLASPointCloudFieldData.h"

#include "vtkLASPointCloudReader.h"
#include "vtkLASPointCloudWriter.h"
#include "vtkPCDPointCloudReader.h"
#include "vtkPCDPointCloudWriter.h"
#include "vtkPointCloudTextReader.h"
#include "vtkPointCloudTextWriter.h"

#include "PLYFileCheck.h"
#include "ReplacingPath.h"
#include "VTPFileCheck.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkErrorCode.h"
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
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <utility>

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

/// The formats read and written, by extension (any case).
enum class FileType
{
  Unsupported,
  Text,
  LAS,
  LAZ,
  PCD,
  PLY,
  VTP
};

FileType TypeOf(const char* path)
{
  static const std::pair<const char*, FileType> Extensions[] = { { ".txt", FileType::Text },
    { ".xyz", FileType::Text },
    { ".las", FileType::LAS },
    { ".laz", FileType::LAZ },
    { ".pcd", FileType::PCD },
    { ".ply", FileType::PLY },
    { ".vtp", FileType::VTP } };
  const std::string extension = Extension(path);
  for (const auto& [known, type] : Extensions)
  {
    if (extension == known)
    {
      return type;
    }
  }
  return FileType::Unsupported;
}

/// "PATH: unsupported file type '.ext' (use ...)".
std::string UnsupportedType(const char* path)
{
  return std::string(path ? path : "") + ": unsupported file type '" + Extension(path) + "' (use " +
         vtkPointCloudFileIO::GetSupportedExtensions() + ")";
}

/// A new reader or writer with its file name set.
template<typename Algorithm>
Algorithm* WithFileName(Algorithm* algorithm, const char* path)
{
  algorithm->SetFileName(path);
  return algorithm;
}

/// Keeps the first error an algorithm reports, without VTK's object prefix.
struct MessageCatcher
{
  std::string Error;
  std::string Path;
  std::vector<std::string> Warnings;
  vtkNew<vtkCallbackCommand> Command;

  void Observe(vtkObject* object)
  {
    this->Command->SetClientData(this);
    this->Command->SetCallback(
      [](vtkObject*, unsigned long event, void* clientData, void* callData)
      {
        auto* self = static_cast<MessageCatcher*>(clientData);
        if (event == vtkCommand::WarningEvent && callData)
        {
          self->Warnings.push_back(self->Clean(static_cast<const char*>(callData)));
        }
        else if (self->Error.empty() && callData)
        {
          self->Error = self->Clean(static_cast<const char*>(callData));
        }
      });
    object->AddObserver(vtkCommand::ErrorEvent, this->Command);
    object->AddObserver(vtkCommand::WarningEvent, this->Command);
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

/// What a PLY file written by vtkPLYWriter loses of `data` (its point arrays but the normals and
/// the colours named to the writer, a LAS file's scale, offset and coordinate system), in
/// words; empty when nothing.
std::string NotHeldByPLY(vtkPolyData* data, vtkPLYWriter* ply)
{
  std::string arrays;
  vtkPointData* pointData = data->GetPointData();
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = pointData->GetAbstractArray(a);
    const char* name = array->GetName() ? array->GetName() : "";
    if (array == pointData->GetNormals() ||
        (ply->GetArrayName() && std::strcmp(name, ply->GetArrayName()) == 0))
    {
      continue;
    }
    arrays += (arrays.empty() ? "" : ", ") + std::string(*name ? name : "(unnamed)");
  }
  std::string notHeld = arrays.empty() ? "" : "the point arrays " + arrays;
  const std::string las = vtkLASInformationNotHeld(data->GetFieldData());
  if (!las.empty())
  {
    notHeld += (notHeld.empty() ? "" : "; ") + las;
  }
  return notHeld;
}

/// Passes the algorithm's progress events on as `files`' own, for whoever watches the reads and
/// writes (pcbilateral's progress bar).
void ForwardProgress(vtkAlgorithm* algorithm, vtkObject* files)
{
  vtkNew<vtkCallbackCommand> forward;
  forward->SetClientData(files);
  forward->SetCallback([](vtkObject*, unsigned long, void* client, void* callData)
    { static_cast<vtkObject*>(client)->InvokeEvent(vtkCommand::ProgressEvent, callData); });
  algorithm->AddObserver(vtkCommand::ProgressEvent, forward);
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
/// whole file was written. Returns an empty string or one line naming `path` (VTK's messages name
/// the temporary file).
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
  // The XML writer runs out of disk space with a success and an error code alone.
  bool written =
    RunWriter(writer) && writer->GetErrorCode() == vtkErrorCode::NoError && messages.Error.empty();
  const int failure = errno;
  // The PLY writer does not check its writes at all (a cut file and a success): its file is
  // checked as a reader would check it.
  if (written && vtkPLYWriter::SafeDownCast(writer))
  {
    written = pcbilateral::CheckPLYFile(destination.GetTemporaryPath()).empty();
  }
  return destination.Commit(written, failure);
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
  return ".txt, .xyz, .las, .laz, .pcd, .ply or .vtp";
}

bool vtkPointCloudFileIO::IsSupported(const char* path)
{
  return TypeOf(path) != FileType::Unsupported;
}

vtkAlgorithm* vtkPointCloudFileIO::NewReader(const char* path)
{
  switch (TypeOf(path))
  {
    case FileType::Text:
      return WithFileName(vtkPointCloudTextReader::New(), path);
    case FileType::LAS:
    case FileType::LAZ:
      return WithFileName(vtkLASPointCloudReader::New(), path);
    case FileType::PCD:
      return WithFileName(vtkPCDPointCloudReader::New(), path);
    case FileType::PLY:
      return WithFileName(vtkPLYReader::New(), path);
    case FileType::VTP:
      return WithFileName(vtkXMLPolyDataReader::New(), path);
    case FileType::Unsupported:
      break;
  }
  return nullptr;
}

std::string vtkPointCloudFileIO::CheckFileName(const char* path, bool forWriting)
{
  (void)forWriting; // every extension read is written too (LAZ since it is compressed here)
  const FileType type = TypeOf(path);
  if (type == FileType::Unsupported)
  {
    return UnsupportedType(path);
  }
  return std::string();
}

std::string vtkPointCloudFileIO::CheckOutputPath(const char* output, const char* input)
{
  const std::string name = output ? output : "";
  const std::filesystem::path path(name);
  std::filesystem::path folder = path.parent_path();
  if (folder.empty())
  {
    folder = ".";
  }
  std::error_code error;
  const auto folderStatus = std::filesystem::status(folder, error);
  if (!std::filesystem::exists(folderStatus))
  {
    return name + ": cannot be written (its folder " + folder.string() + " does not exist)";
  }
  if (!std::filesystem::is_directory(folderStatus))
  {
    return name + ": cannot be written (" + folder.string() + " is not a folder)";
  }
  if (input && std::filesystem::equivalent(path, std::filesystem::path(input), error))
  {
    return name + ": is the input file; write the result to another file";
  }
  return std::string();
}

bool vtkPointCloudFileIO::IsTextFormat(const char* path)
{
  return TypeOf(path) == FileType::Text;
}

vtkAlgorithm* vtkPointCloudFileIO::NewWriter(const char* path)
{
  switch (TypeOf(path))
  {
    case FileType::Text:
      return WithFileName(vtkPointCloudTextWriter::New(), path);
    case FileType::LAS:
    case FileType::LAZ:
      return WithFileName(vtkLASPointCloudWriter::New(), path);
    case FileType::PCD:
      return WithFileName(vtkPCDPointCloudWriter::New(), path);
    case FileType::PLY:
    {
      auto* writer = WithFileName(vtkPLYWriter::New(), path);
      writer->SetFileTypeToBinary();
      return writer;
    }
    case FileType::VTP:
      return WithFileName(vtkXMLPolyDataWriter::New(), path);
    case FileType::Unsupported:
      break;
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
  const FileType type = TypeOf(path);
  if (type == FileType::Unsupported)
  {
    return UnsupportedType(path);
  }
  // What cannot be measured (a special file, say) is not read.
  if (std::filesystem::file_size(name, error) == static_cast<std::uintmax_t>(-1))
  {
    return name + ": " + error.message();
  }
  // VTK's PLY and XML readers do not stop at damaged files: they are checked first.
  return type == FileType::PLY   ? pcbilateral::CheckPLYFile(name)
         : type == FileType::VTP ? pcbilateral::CheckVTPFile(name)
                                 : std::string();
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
  auto* pcd = vtkPCDPointCloudReader::SafeDownCast(reader);
  if (pcd)
  {
    pcd->SetKeepNaNPoints(this->KeepNaNPoints);
  }
  this->NumberOfDroppedPoints = 0;
  this->Warnings.clear();
  if (auto* las = vtkLASPointCloudReader::SafeDownCast(reader))
  {
    las->SetCOPCMaxLevel(this->COPCMaxLevel);
    las->SetCOPCUseBounds(this->COPCUseBounds);
    las->SetCOPCBounds(this->COPCBounds);
  }
  else if (this->COPCMaxLevel >= 0 || this->COPCUseBounds)
  {
    this->Warnings.push_back(
      std::string(path) +
      ": not a COPC file: the COPC level and bounds apply to COPC files only; every point is "
      "read");
  }
  MessageCatcher messages;
  messages.Path = path;
  messages.Observe(reader);
  ForwardProgress(reader, this);
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
  this->NumberOfDroppedPoints = pcd ? pcd->GetNumberOfDroppedPoints() : 0;
  this->Warnings.insert(this->Warnings.end(), messages.Warnings.begin(), messages.Warnings.end());
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
  this->Warnings.clear();
  MessageCatcher messages;
  messages.Path = name;
  messages.Observe(writer);
  ForwardProgress(writer, this);
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
  const FileType type = TypeOf(path);
  if (type == FileType::PLY || type == FileType::VTP)
  {
    this->ErrorMessage = WriteReplacing(writer, name, messages);
    this->Warnings = messages.Warnings;
    const std::string notHeld =
      type == FileType::PLY ? NotHeldByPLY(input, vtkPLYWriter::SafeDownCast(writer)) : "";
    if (this->ErrorMessage.empty() && !notHeld.empty())
    {
      // (Only points, normals and 8-bit colours are PLY properties here.)
      this->Warnings.push_back(name + ": a PLY file written here holds points, normals and " +
                               "8-bit colours only: " + notHeld + " are not written");
    }
    return this->ErrorMessage.empty();
  }
  // The text, LAS and PCD writers replace the file themselves (pcbilateral::ReplacingFile).
  if (!RunWriter(writer) && messages.Error.empty())
  {
    messages.Error = name + ": cannot be written";
  }
  this->Warnings = messages.Warnings;
  this->ErrorMessage = messages.Error;
  return this->ErrorMessage.empty();
}

void vtkPointCloudFileIO::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OrientedNormals: " << this->OrientedNormals << "\n";
  os << indent << "KeepNaNPoints: " << this->KeepNaNPoints << "\n";
  os << indent << "COPCMaxLevel: " << this->COPCMaxLevel << "\n";
  os << indent << "COPCUseBounds: " << this->COPCUseBounds << "\n";
}

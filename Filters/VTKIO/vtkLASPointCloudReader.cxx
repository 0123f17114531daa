#include "vtkLASPointCloudReader.h"

#include "COPC.h"
#include "LASHeader.h"
#include "LASReader.h"
#include "LAZReader.h"
#include "PointPieces.h"
#include "vtkLASPointCloudFieldData.h"
#include "vtkPointCloudProgress.h"
#include "vtkPointCloudVertices.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkLASPointCloudReader);

namespace
{
/// 8-bit colours for display: the 16-bit values' high bytes, unless the file stored 8-bit
/// values in its 16-bit fields (`eightBit`).
vtkSmartPointer<vtkUnsignedCharArray> DisplayColours(vtkUnsignedShortArray* rgb, bool eightBit)
{
  const vtkIdType values = rgb->GetNumberOfValues();
  const unsigned short* in = rgb->GetPointer(0);
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetName("Colors");
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(rgb->GetNumberOfTuples());
  unsigned char* out = colours->GetPointer(0);
  for (vtkIdType i = 0; i < values; ++i)
  {
    out[i] = static_cast<unsigned char>(eightBit ? in[i] : in[i] >> 8);
  }
  return colours;
}
} // namespace

vtkLASPointCloudReader::vtkLASPointCloudReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkLASPointCloudReader::~vtkLASPointCloudReader()
{
  this->SetFileName(nullptr);
}

int vtkLASPointCloudReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  // Each piece reads its own share of the points (PieceOfPoints).
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkLASPointCloudReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->ErrorMessage.clear();
  vtkPointCloudProgress progress(this, this->AbortExecute);
  pcbilateral::LASFileBytes file;
  pcbilateral::LASFileInfo info;
  if (!this->FileName || !*this->FileName)
  {
    this->ErrorMessage = "no file name was given";
  }
  else
  {
    this->ErrorMessage = file.Open(this->FileName);
  }
  if (this->ErrorMessage.empty())
  {
    this->ErrorMessage =
      pcbilateral::ParseLASHeader(file.Data(), file.Size(), this->FileName, info, true);
  }
  std::vector<std::uint8_t> decompressed;
  const std::uint8_t* records = nullptr;
  std::uint64_t count = 0;
  pcbilateral::PointRange share;
  if (this->ErrorMessage.empty())
  {
    // Decompressing takes most of a LAZ file's read.
    progress.SetStage(0.0, pcbilateral::IsLAZ(file.Data(), file.Size()) ? 0.8 : 0.0);
    this->ErrorMessage = this->ReadShare(file,
      info,
      outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()),
      outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()),
      decompressed,
      records,
      count,
      share);
  }
  if (this->ErrorMessage.empty())
  {
    progress.SetStage(pcbilateral::IsLAZ(file.Data(), file.Size()) ? 0.8 : 0.0, 1.0);
    this->ErrorMessage = this->DecodePoints(info, records, count, output);
  }
  if (this->ErrorMessage.empty())
  {
    this->ErrorMessage = this->AddDisplayColours(file.Data(), file.Size(), info, share, output);
  }
  if (progress.StopAsked())
  {
    // Aborted: an empty output and no error event; GetErrorMessage() says "aborted", which a
    // distributed read takes as this piece's failure, so that every process stops.
    output->Initialize();
    this->ErrorMessage = pcbilateral::AbortedMessage;
    return 1;
  }
  if (!this->ErrorMessage.empty())
  {
    // One error and an empty output: a failed request would add the pipeline's own report.
    output->Initialize();
    vtkErrorMacro(<< this->ErrorMessage);
    return 1;
  }
  vtkLASStoreFileInfo(info, output->GetFieldData());
  return 1;
}

std::string vtkLASPointCloudReader::DecodePoints(const pcbilateral::LASFileInfo& info,
  const std::uint8_t* records,
  std::uint64_t numberOfPoints,
  vtkPolyData* output)
{
  const auto count = static_cast<vtkIdType>(numberOfPoints);
  vtkNew<vtkDoubleArray> positions;
  positions->SetNumberOfComponents(3);
  positions->SetNumberOfTuples(count);
  std::vector<vtkSmartPointer<vtkDataArray>> arrays;
  std::vector<void*> columns;
  for (const pcbilateral::LASDimension& dimension : info.Dimensions)
  {
    auto array = vtkSmartPointer<vtkDataArray>::Take(
      vtkDataArray::CreateDataArray(vtkLASArrayType(dimension.ColumnType)));
    array->SetName(dimension.Name.c_str());
    array->SetNumberOfComponents(dimension.Components);
    array->SetNumberOfTuples(count);
    arrays.push_back(array);
    columns.push_back(array->GetVoidPointer(0));
  }
  if (!pcbilateral::DecodeLASPoints(
        info, records, static_cast<std::size_t>(count), positions->GetPointer(0), columns.data()))
  {
    return pcbilateral::AbortedMessage;
  }

  // (The cells are built once the records are decoded: asked as the decoding's end.)
  const vtkSmartPointer<vtkCellArray> vertices =
    vtkPointCloudVertices(count, []() { return pcbilateral::ProgressPoint(999, 1000); });
  if (!vertices)
  {
    return pcbilateral::AbortedMessage;
  }
  vtkNew<vtkPoints> points;
  points->SetData(positions);
  output->SetPoints(points);
  output->SetVerts(vertices);
  for (const auto& array : arrays)
  {
    output->GetPointData()->AddArray(array);
  }
  return std::string();
}

std::string vtkLASPointCloudReader::AddDisplayColours(const std::uint8_t* data,
  std::size_t size,
  const pcbilateral::LASFileInfo& info,
  const pcbilateral::PointRange& share,
  vtkPolyData* output)
{
  auto* rgb = vtkUnsignedShortArray::SafeDownCast(output->GetPointData()->GetArray("RGB"));
  if (!rgb)
  {
    return std::string();
  }
  const unsigned short* values = rgb->GetPointer(0);
  bool eightBit = std::all_of(
    values, values + rgb->GetNumberOfValues(), [](unsigned short v) { return v <= 255; });
  // Whether the file holds 8-bit colours is a property of the whole file: a piece whose own
  // colours all fit 8 bits looks at the other points' (up to the first larger value), so that
  // every piece shows the colours the whole file would.
  const std::uint64_t total = info.Header.NumberOfPoints;
  const std::uint64_t end = share.First + share.Count;
  std::string problem;
  if (eightBit && share.First > 0)
  {
    problem = pcbilateral::LASColoursFitEightBits(
      data, size, info, this->FileName, 0, share.First, eightBit);
  }
  if (problem.empty() && eightBit && end < total)
  {
    problem = pcbilateral::LASColoursFitEightBits(
      data, size, info, this->FileName, end, total - end, eightBit);
  }
  if (problem.empty())
  {
    output->GetPointData()->AddArray(DisplayColours(rgb, eightBit));
  }
  return problem;
}

std::string vtkLASPointCloudReader::ReadShare(const pcbilateral::LASFileBytes& file,
  const pcbilateral::LASFileInfo& info,
  int piece,
  int pieces,
  std::vector<std::uint8_t>& decompressed,
  const std::uint8_t*& records,
  std::uint64_t& count,
  pcbilateral::PointRange& colourShare)
{
  const bool partAsked = this->COPCMaxLevel >= 0 || this->COPCUseBounds;
  if (partAsked && pcbilateral::IsCOPC(info))
  {
    pcbilateral::COPCQuery query;
    query.MaxLevel = this->COPCMaxLevel;
    query.UseBounds = this->COPCUseBounds;
    std::copy(this->COPCBounds, this->COPCBounds + 6, query.Bounds);
    query.Piece = piece;
    query.NumberOfPieces = pieces;
    const std::string problem = pcbilateral::ReadCOPCPoints(
      file.Data(), file.Size(), info, this->FileName, query, decompressed, count);
    records = decompressed.data();
    colourShare = pcbilateral::PointRange();
    return problem;
  }
  if (partAsked)
  {
    vtkWarningMacro(<< this->FileName
                    << ": not a COPC file: the COPC level and bounds apply to COPC files only; "
                       "every point is read");
  }
  // A LAZ file's records of the share are decompressed first (in parallel, by chunk); a LAS
  // file's are read where they lie.
  colourShare = pcbilateral::PieceOfPoints(info.Header.NumberOfPoints, piece, pieces);
  count = colourShare.Count;
  return pcbilateral::UncompressedLASRecordRange(file.Data(),
    file.Size(),
    info,
    this->FileName,
    colourShare.First,
    colourShare.Count,
    decompressed,
    records);
}

void vtkLASPointCloudReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "COPCMaxLevel: " << this->COPCMaxLevel << "\n";
  os << indent << "COPCUseBounds: " << this->COPCUseBounds << "\n";
  os << indent << "COPCBounds: " << this->COPCBounds[0] << " " << this->COPCBounds[1] << " "
     << this->COPCBounds[2] << " " << this->COPCBounds[3] << " " << this->COPCBounds[4] << " "
     << this->COPCBounds[5] << "\n";
}

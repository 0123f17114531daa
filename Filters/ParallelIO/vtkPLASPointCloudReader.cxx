#include "vtkPLASPointCloudReader.h"

#include "vtkPointCloudPieceStatus.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

vtkStandardNewMacro(vtkPLASPointCloudReader);
vtkCxxSetObjectMacro(vtkPLASPointCloudReader, Controller, vtkMultiProcessController);

vtkPLASPointCloudReader::vtkPLASPointCloudReader()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPLASPointCloudReader::~vtkPLASPointCloudReader()
{
  this->SetController(nullptr);
}

int vtkPLASPointCloudReader::RequestData(vtkInformation* request,
  vtkInformationVector** inputs,
  vtkInformationVector* outputs)
{
  const int read = this->Superclass::RequestData(request, inputs, outputs);
  if (!vtkIsDistributedRead(this->Controller, outputs->GetInformationObject(0)))
  {
    return read;
  }
  const bool readHere = read != 0 && this->ErrorMessage.empty();
  if (vtkEveryPieceRead(this->Controller, readHere, this->FileName, this->ErrorMessage))
  {
    return 1;
  }
  vtkPolyData::GetData(outputs)->Initialize();
  if (readHere)
  {
    vtkErrorMacro(<< this->ErrorMessage);
  }
  return 0;
}

void vtkPLASPointCloudReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
}

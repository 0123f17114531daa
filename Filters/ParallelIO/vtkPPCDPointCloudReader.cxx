#include "vtkPPCDPointCloudReader.h"

#include "vtkPointCloudPieceStatus.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

vtkStandardNewMacro(vtkPPCDPointCloudReader);
vtkCxxSetObjectMacro(vtkPPCDPointCloudReader, Controller, vtkMultiProcessController);

vtkPPCDPointCloudReader::vtkPPCDPointCloudReader()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPPCDPointCloudReader::~vtkPPCDPointCloudReader()
{
  this->SetController(nullptr);
}

int vtkPPCDPointCloudReader::RequestData(vtkInformation* request,
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

void vtkPPCDPointCloudReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
}

#include "vtkPPCDPointCloudReader.h"

#include "vtkPointCloudPieceStatus.h"

#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"

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
  return vtkFinishPieceRead(this,
    this->Controller,
    this->Superclass::RequestData(request, inputs, outputs),
    this->FileName,
    this->ErrorMessage,
    outputs);
}

void vtkPPCDPointCloudReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
}

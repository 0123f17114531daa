#include "vtkPLASPointCloudReader.h"

#include "vtkPointCloudPieceStatus.h"

#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"

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
  return vtkFinishPieceRead(this,
    this->Controller,
    this->Superclass::RequestData(request, inputs, outputs),
    this->FileName,
    this->ErrorMessage,
    outputs);
}

void vtkPLASPointCloudReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
}

#include "vtkPPointCloudTextReader.h"

#include "vtkPointCloudPieceStatus.h"

#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkPPointCloudTextReader);
vtkCxxSetObjectMacro(vtkPPointCloudTextReader, Controller, vtkMultiProcessController);

vtkPPointCloudTextReader::vtkPPointCloudTextReader()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPPointCloudTextReader::~vtkPPointCloudTextReader()
{
  this->SetController(nullptr);
}

int vtkPPointCloudTextReader::RequestData(vtkInformation* request,
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

void vtkPPointCloudTextReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
}

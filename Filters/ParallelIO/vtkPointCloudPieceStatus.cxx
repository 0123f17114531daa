#include "vtkPointCloudPieceStatus.h"

#include "vtkAlgorithm.h"
#include "vtkCommunicator.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

bool vtkIsDistributedRead(vtkMultiProcessController* controller, vtkInformation* outInfo)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (!controller || controller->GetNumberOfProcesses() <= 1 || !outInfo)
  {
    return false;
  }
  return outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES()) == controller->GetNumberOfProcesses() &&
         outInfo->Get(SDDP::UPDATE_PIECE_NUMBER()) == controller->GetLocalProcessId();
}

bool vtkEveryPieceRead(vtkMultiProcessController* controller,
  bool readHere,
  const char* fileName,
  std::string& message)
{
  const int failedHere = readHere ? 0 : 1;
  int failures = 0;
  controller->AllReduce(&failedHere, &failures, 1, vtkCommunicator::SUM_OP);
  if (failures > 0 && readHere)
  {
    message = std::string(fileName ? fileName : "") +
              ": another process could not read its piece (see its error); no piece is output";
  }
  return failures == 0;
}

int vtkFinishPieceRead(vtkAlgorithm* reader,
  vtkMultiProcessController* controller,
  int read,
  const char* fileName,
  std::string& message,
  vtkInformationVector* outputs)
{
  if (!vtkIsDistributedRead(controller, outputs->GetInformationObject(0)))
  {
    return read;
  }
  const bool readHere = read != 0 && message.empty();
  if (vtkEveryPieceRead(controller, readHere, fileName, message))
  {
    return 1;
  }
  vtkPolyData::GetData(outputs)->Initialize();
  if (readHere)
  {
    vtkErrorWithObjectMacro(reader, << message);
  }
  return 0;
}

// The formats' progress and abort (pcbilateral::ProgressScope) mapped to a VTK algorithm's, for
// the readers and writers of this module and their parallel subclasses. Internal, not wrapped.
#ifndef vtkPointCloudProgress_h
#define vtkPointCloudProgress_h

#include "ProgressCheck.h"

#include "vtkAlgorithm.h"

/**
 * Open for the whole of a reader's RequestData or a writer's WriteData: the formats' loops then
 * report through UpdateProgress (ProgressEvent, ParaView's progress bar) and stop once the
 * algorithm's AbortExecute flag is set (ParaView's Abort button, or another thread). The caller
 * clears a flag left from an earlier run first (VTK 9.2 never clears it).
 */
class vtkPointCloudProgress : public pcbilateral::ProgressScope
{
public:
  explicit vtkPointCloudProgress(vtkAlgorithm* algorithm)
    : ProgressScope([algorithm](double fraction) { algorithm->UpdateProgress(fraction); },
        [algorithm]() { return algorithm->GetAbortExecute() != 0; })
  {
  }
};

#endif

// The formats' progress and abort (pcbilateral::ProgressScope) mapped to a VTK algorithm's, for
// the readers and writers of this module and their parallel subclasses. Internal, not wrapped.
#ifndef vtkPointCloudProgress_h
#define vtkPointCloudProgress_h

#include "ProgressCheck.h"

#include "vtkAlgorithm.h"

#include <functional>

/**
 * Open for the whole of a reader's RequestData or a writer's WriteData: the formats' loops then
 * report through UpdateProgress (ProgressEvent, ParaView's progress bar) and stop once the
 * algorithm's AbortExecute flag is set (ParaView's Abort button, or another thread). The flag
 * is cleared when the scope closes, at the end of the run it stopped (VTK 9.2 never clears it,
 * and every later run would stop at once); not when the run starts, since VTK's executive
 * reports progress before RequestData, and an abort asked then belongs to this run. It is
 * cleared directly, as the filter clears its own: SetAbortExecute would mark the algorithm
 * modified from within its run.
 */
class vtkPointCloudProgress : public pcbilateral::ProgressScope
{
public:
  /// `abortFlag`: the algorithm's AbortExecute member (atomic or not, by VTK version).
  template<typename Flag>
  vtkPointCloudProgress(vtkAlgorithm* algorithm, Flag& abortFlag)
    : ProgressScope([algorithm](double fraction) { algorithm->UpdateProgress(fraction); },
        [algorithm]() { return algorithm->GetAbortExecute() != 0; })
    , ClearFlag([&abortFlag]() { abortFlag = 0; })
  {
  }

  ~vtkPointCloudProgress() { this->ClearFlag(); }

  vtkPointCloudProgress(const vtkPointCloudProgress&) = delete;
  vtkPointCloudProgress& operator=(const vtkPointCloudProgress&) = delete;

private:
  std::function<void()> ClearFlag;
};

#endif

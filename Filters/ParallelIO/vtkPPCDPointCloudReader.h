/**
 * @class   vtkPPCDPointCloudReader
 * @brief   vtkPCDPointCloudReader reading its piece of a file together with the other processes of
 * an MPI run
 *
 * Under `mpirun pvbatch` or pvserver (ParaView's reader proxy uses this class when VTK has
 * MPI), each process reads its piece of the file, as vtkPCDPointCloudReader does. Damage inside the
 * data (a malformed ascii line) is found only by the process whose piece holds it; this class then
 * fails the read on every process: that one reports the damage, the others that another process
 * could not read its piece, and none outputs points (rather than leaving the others to wait for it
 * in the next distributed step, or to go on without its points). The check is one reduction, made
 * only when the request is this process's piece of as many as there are processes; a read of
 * another piece, or with a single process, is vtkPCDPointCloudReader's.
 *
 * @sa
 * vtkPCDPointCloudReader vtkPPointCloudBilateralFilter vtkPLASPointCloudWriter
 */
#ifndef vtkPPCDPointCloudReader_h
#define vtkPPCDPointCloudReader_h

#include "vtkIOParallelPointCloudBilateralModule.h" // For export macro
#include "vtkPCDPointCloudReader.h"

class vtkMultiProcessController;

class VTKIOPARALLELPOINTCLOUDBILATERAL_EXPORT vtkPPCDPointCloudReader
  : public vtkPCDPointCloudReader
{
public:
  static vtkPPCDPointCloudReader* New();
  vtkTypeMacro(vtkPPCDPointCloudReader, vtkPCDPointCloudReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The processes reading the file together; by default the global controller.
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

protected:
  vtkPPCDPointCloudReader();
  ~vtkPPCDPointCloudReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkMultiProcessController* Controller = nullptr;

private:
  vtkPPCDPointCloudReader(const vtkPPCDPointCloudReader&) = delete;
  void operator=(const vtkPPCDPointCloudReader&) = delete;
};

#endif

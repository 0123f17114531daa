/**
 * @class   vtkPLASPointCloudReader
 * @brief   vtkLASPointCloudReader reading its piece of a file together with the other processes of
 * an MPI run
 *
 * Under `mpirun pvbatch` or pvserver (ParaView's reader proxy uses this class when VTK has
 * MPI), each process reads its piece of the file, as vtkLASPointCloudReader does. Damage inside the
 * data (a LAZ chunk) is found only by the process whose piece holds it; this class then fails the
 * read on every process: that one reports the damage, the others that another process could not
 * read its piece, and none outputs points (rather than leaving the others to wait for it in
 * the next distributed step, or to go on without its points). The check is one reduction,
 * made only when the request is this process's piece of as many as there are processes; a
 * read of another piece, or with a single process, is vtkLASPointCloudReader's.
 *
 * @sa
 * vtkLASPointCloudReader vtkPPointCloudBilateralFilter vtkPLASPointCloudWriter
 */
#ifndef vtkPLASPointCloudReader_h
#define vtkPLASPointCloudReader_h

#include "vtkIOParallelPointCloudBilateralModule.h" // For export macro
#include "vtkLASPointCloudReader.h"

class vtkMultiProcessController;

class VTKIOPARALLELPOINTCLOUDBILATERAL_EXPORT vtkPLASPointCloudReader
  : public vtkLASPointCloudReader
{
public:
  static vtkPLASPointCloudReader* New();
  vtkTypeMacro(vtkPLASPointCloudReader, vtkLASPointCloudReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The processes reading the file together; by default the global controller.
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

protected:
  vtkPLASPointCloudReader();
  ~vtkPLASPointCloudReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkMultiProcessController* Controller = nullptr;

private:
  vtkPLASPointCloudReader(const vtkPLASPointCloudReader&) = delete;
  void operator=(const vtkPLASPointCloudReader&) = delete;
};

#endif

/**
 * @class   vtkPLASPointCloudWriter
 * @brief   write one LAS or LAZ file from a point cloud split across the processes of an MPI run
 *
 * vtkPLASPointCloudWriter is vtkLASPointCloudWriter for a cloud whose points are split over
 * processes (`mpirun pvbatch`, pvserver: ParaView's LAS writer proxy uses this class when VTK
 * has MPI). Every process writes its own points into the one file, rank after rank: the file
 * holds the points of process 0, then those of process 1, and so on, each in its order, which
 * is the file's order when the processes read a file's pieces and filtered them with
 * vtkPPointCloudBilateralFilter. No process gathers the cloud: each encodes its records and
 * writes them at its place (an exclusive prefix sum of the point counts, or for LAZ of the
 * compressed bytes), only counts, bounds and a LAZ file's chunk sizes are exchanged, and the
 * first process writes the header, the VLRs and (LAZ) the chunk table. A LAS file is, byte for
 * byte, what vtkLASPointCloudWriter writes in one process from the same points; a LAZ file
 * holds the same records, in chunks that end where each process's points end (the LASzip
 * record says the chunks' sizes vary).
 *
 * The header is made as vtkLASPointCloudWriter makes it, from the whole cloud: the processes
 * must agree on the point format, record length, scales and offsets (a LAS file's field data
 * is the same on every piece of it), or the write fails on all of them. Every process must
 * call Write() together; a failure on one (bad input, a full disk) fails the write on all of
 * them with a one-line message, and no file is left. With no controller or a single process,
 * it is vtkLASPointCloudWriter.
 *
 * @sa
 * vtkLASPointCloudWriter vtkPPointCloudBilateralFilter
 */
#ifndef vtkPLASPointCloudWriter_h
#define vtkPLASPointCloudWriter_h

#include "vtkIOParallelPointCloudBilateralModule.h" // For export macro
#include "vtkLASPointCloudWriter.h"

class vtkMultiProcessController;

class VTKIOPARALLELPOINTCLOUDBILATERAL_EXPORT vtkPLASPointCloudWriter
  : public vtkLASPointCloudWriter
{
public:
  static vtkPLASPointCloudWriter* New();
  vtkTypeMacro(vtkPLASPointCloudWriter, vtkLASPointCloudWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The processes sharing the cloud; by default the global controller.
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

protected:
  vtkPLASPointCloudWriter();
  ~vtkPLASPointCloudWriter() override;

  /// Asks the input for this process's piece (one per process).
  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inputs,
    vtkInformationVector* outputs) override;

  CloudSummary MeasureCloud(vtkPointSet* input) override;

  std::string WritePoints(const std::string& problem,
    const std::string& fileName,
    const pcbilateral::LASFileInfo& info,
    std::size_t count,
    const double* positions,
    const void* const* columns,
    bool compressed) override;

  vtkMultiProcessController* Controller = nullptr;

private:
  vtkPLASPointCloudWriter(const vtkPLASPointCloudWriter&) = delete;
  void operator=(const vtkPLASPointCloudWriter&) = delete;
};

#endif

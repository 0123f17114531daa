// A distributed read fails on every process or on none: a piece's damage (a LAZ chunk, a
// malformed text or PCD ascii line) is seen only by the process that reads it, and processes
// that went on without it would wait for it in the next collective step (the distributed
// filter's, the parallel writer's) for ever. Private to the parallel readers.
#ifndef vtkPointCloudPieceStatus_h
#define vtkPointCloudPieceStatus_h

#include <string>

class vtkAlgorithm;
class vtkInformation;
class vtkInformationVector;
class vtkMultiProcessController;

/**
 * Whether the request `outInfo` asks this process for its own piece of a read split over the
 * processes of `controller` (piece = rank, pieces = number of processes > 1): only then do all
 * the processes read together.
 */
bool vtkIsDistributedRead(vtkMultiProcessController* controller, vtkInformation* outInfo);

/**
 * Collective, for a distributed read: whether every process read its piece (`readHere` on
 * every one). When one did not, `message` becomes, on the processes that did, "FILE: another
 * process could not read its piece (see its error); no piece is output".
 */
bool vtkEveryPieceRead(vtkMultiProcessController* controller,
  bool readHere,
  const char* fileName,
  std::string& message);

/**
 * The end of a parallel reader's RequestData, after its serial reader's (which returned `read`
 * and left `message` empty on success): for a distributed read, every process learns whether
 * every piece was read; when one was not, each process's output is emptied, `reader` reports
 * the error on the processes whose own piece was read (the one that failed reported its
 * damage already), and 0 is returned everywhere. Other reads return `read` unchanged.
 */
int vtkFinishPieceRead(vtkAlgorithm* reader,
  vtkMultiProcessController* controller,
  int read,
  const char* fileName,
  std::string& message,
  vtkInformationVector* outputs);

#endif

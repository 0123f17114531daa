// A distributed read fails on every process or on none: a piece's damage (a LAZ chunk, a
// malformed text or PCD ascii line) is seen only by the process that reads it, and processes
// that went on without it would wait for it in the next collective step (the distributed
// filter's, the parallel writer's) for ever. Private to the parallel readers.
#ifndef vtkPointCloudPieceStatus_h
#define vtkPointCloudPieceStatus_h

#include <string>

class vtkInformation;
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

#endif

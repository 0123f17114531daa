// One vertex cell per point, the cells every reader and filter of this module gives its point
// clouds so that ParaView's Surface and Points representations show them. Internal: not
// wrapped, not installed.
#ifndef vtkPointCloudVertices_h
#define vtkPointCloudVertices_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

class vtkCellArray;

/// Vertex cells 0, 1, ..., numberOfPoints - 1, built from two arrays without a per-cell call.
vtkSmartPointer<vtkCellArray> vtkPointCloudVertices(vtkIdType numberOfPoints);

#endif

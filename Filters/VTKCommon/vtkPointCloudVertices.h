// One vertex cell per point, the cells every reader and filter of this project gives its point
// clouds so that ParaView's Surface and Points representations show them. Internal: not
// wrapped, not installed; header-only, shared by the VTK filter and IO modules.
#ifndef vtkPointCloudVertices_h
#define vtkPointCloudVertices_h

#include "vtkCellArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <numeric>

/// Vertex cells 0, 1, ..., numberOfPoints - 1, built from two arrays without a per-cell call.
inline vtkSmartPointer<vtkCellArray> vtkPointCloudVertices(vtkIdType numberOfPoints)
{
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(numberOfPoints + 1);
  std::iota(offsets->GetPointer(0), offsets->GetPointer(0) + numberOfPoints + 1, vtkIdType(0));
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(numberOfPoints);
  std::iota(
    connectivity->GetPointer(0), connectivity->GetPointer(0) + numberOfPoints, vtkIdType(0));
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, connectivity);
  return cells;
}

#endif

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

#include <algorithm>
#include <functional>
#include <numeric>

/// Vertex cells 0, 1, ..., numberOfPoints - 1, built from two arrays without a per-cell call.
/// `stop`, when given, is asked every million cells (a run's abort: the arrays of 20 million
/// points are 320 MB, a tenth of a second or more); when it says stop, the result is null.
inline vtkSmartPointer<vtkCellArray> vtkPointCloudVertices(vtkIdType numberOfPoints,
  const std::function<bool()>& stop = nullptr)
{
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(numberOfPoints + 1);
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(numberOfPoints);
  constexpr vtkIdType Block = vtkIdType(1) << 20;
  for (vtkIdType first = 0; first <= numberOfPoints; first += Block)
  {
    if (stop && stop())
    {
      return nullptr;
    }
    const vtkIdType end = std::min(numberOfPoints + 1, first + Block);
    std::iota(offsets->GetPointer(first), offsets->GetPointer(0) + end, first);
    std::iota(connectivity->GetPointer(0) + first,
      connectivity->GetPointer(0) + std::min(numberOfPoints, end),
      first);
  }
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, connectivity);
  return cells;
}

#endif

#include "vtkPointCloudVertices.h"

#include "vtkCellArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"

#include <numeric>

vtkSmartPointer<vtkCellArray> vtkPointCloudVertices(vtkIdType numberOfPoints)
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

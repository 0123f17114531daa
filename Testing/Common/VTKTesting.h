// Helpers for the tests of the VTK module: clouds as vtkPolyData, and one way to run the filter
// and see what it said.
#ifndef pcbilateral_VTKTesting_h
#define pcbilateral_VTKTesting_h

#include "vtkPointCloudBilateralFilter.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <functional>
#include <string>
#include <vector>

namespace pcbilateral_testing
{

/// A point cloud (no cells) from interleaved xyz, with points of the given VTK type.
inline vtkSmartPointer<vtkPolyData> MakeCloud(const std::vector<double>& xyz,
  int pointType = VTK_DOUBLE)
{
  vtkNew<vtkPoints> points;
  points->SetDataType(pointType);
  points->SetNumberOfPoints(static_cast<vtkIdType>(xyz.size() / 3));
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    points->SetPoint(i, &xyz[3 * i]);
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  return cloud;
}

/// What an update of the filter gave and said.
struct FilterRun
{
  vtkSmartPointer<vtkPolyData> Output;
  int Errors = 0;
  int Warnings = 0;
  /// The messages, one after the other.
  std::string Messages;
  int ProgressEvents = 0;
  double RadiusUsed = 0.0;
  double NormalRadiusUsed = 0.0;
};

/// Updates a vtkPointCloudBilateralFilter on `input` after `setup` set its properties, counting
/// its errors (its executive's too), warnings and progress events instead of printing them.
inline FilterRun RunFilter(vtkDataObject* input,
  const std::function<void(vtkPointCloudBilateralFilter*)>& setup)
{
  FilterRun run;
  vtkNew<vtkCallbackCommand> messages;
  messages->SetClientData(&run);
  messages->SetCallback(
    [](vtkObject*, unsigned long event, void* client, void* text)
    {
      auto* counts = static_cast<FilterRun*>(client);
      if (event == vtkCommand::ProgressEvent)
      {
        ++counts->ProgressEvents;
        return;
      }
      (event == vtkCommand::ErrorEvent ? counts->Errors : counts->Warnings) += 1;
      counts->Messages += text ? static_cast<const char*>(text) : "";
    });
  vtkNew<vtkPointCloudBilateralFilter> filter;
  for (const unsigned long event :
    { vtkCommand::ErrorEvent, vtkCommand::WarningEvent, vtkCommand::ProgressEvent })
  {
    filter->AddObserver(event, messages);
  }
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, messages);
  filter->SetInputDataObject(input);
  if (setup)
  {
    setup(filter);
  }
  filter->Update();
  run.Output = vtkSmartPointer<vtkPolyData>::New();
  run.Output->ShallowCopy(filter->GetOutput());
  run.RadiusUsed = filter->GetRadiusUsed();
  run.NormalRadiusUsed = filter->GetNormalRadiusUsed();
  return run;
}

} // namespace pcbilateral_testing

#endif

// What the image tests share: reading a sample, filtering it, and drawing clouds side by side
// with one camera, points as lit spheres.
#ifndef pcbilateral_RenderingScene_h
#define pcbilateral_RenderingScene_h

#include "VTKTesting.h"
#include "vtkPointCloudBilateralFilter.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCoordinate.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkVertexGlyphFilter.h"

#include <string>
#include <vector>

namespace pcbilateral_rendering
{
inline vtkSmartPointer<vtkPolyData> ReadSample(const std::string& name)
{
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName((std::string(PCB_DATA_DIR) + "/" + name).c_str());
  // PLY clouds have no vertex cells, which points need to be drawn.
  vtkNew<vtkVertexGlyphFilter> vertices;
  vertices->SetInputConnection(reader->GetOutputPort());
  vertices->Update();
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->ShallowCopy(vertices->GetOutput());
  return cloud;
}

/// The filtered cloud, with the displacement length the scenes colour by.
inline vtkSmartPointer<vtkPolyData> Filter(vtkPolyData* input, double r, double rn, int iterations)
{
  return pcbilateral_testing::RunFilter(input,
    [&](vtkPointCloudBilateralFilter* filter)
    {
      filter->SetRadius(r);
      filter->SetNormalRadius(rn);
      filter->SetNumberOfIterations(iterations);
      filter->GenerateDisplacementLengthOn();
    })
    .Output;
}

/// The points with low <= z <= high: a cross-section that shows edges and corners in profile.
inline vtkSmartPointer<vtkPolyData> Slab(vtkPolyData* cloud, double low, double high)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> vertices;
  for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
  {
    double p[3];
    cloud->GetPoint(i, p);
    if (p[2] >= low && p[2] <= high)
    {
      const vtkIdType id = points->InsertNextPoint(p);
      vertices->InsertNextCell(1, &id);
    }
  }
  auto slab = vtkSmartPointer<vtkPolyData>::New();
  slab->SetPoints(points);
  slab->SetVerts(vertices);
  return slab;
}

struct Panel
{
  vtkSmartPointer<vtkPolyData> Cloud;
  std::string Caption;
};

/// Draws the panels left to right in a window of panel size width x height each.
inline void Show(vtkRenderWindow* window,
  const std::vector<Panel>& panels,
  vtkCamera* camera,
  int width,
  int height)
{
  window->SetSize(width * static_cast<int>(panels.size()), height);
  window->SetMultiSamples(0);
  for (std::size_t i = 0; i < panels.size(); ++i)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(panels[i].Cloud);
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetPointSize(2.0);
    actor->GetProperty()->SetRenderPointsAsSpheres(true);
    actor->GetProperty()->SetColor(0.93, 0.80, 0.55);
    vtkNew<vtkTextActor> caption;
    caption->SetInput(panels[i].Caption.c_str());
    caption->GetTextProperty()->SetFontSize(14);
    caption->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
    caption->GetPositionCoordinate()->SetValue(0.03, 0.04);
    vtkNew<vtkRenderer> renderer;
    renderer->SetViewport(
      static_cast<double>(i) / panels.size(), 0.0, static_cast<double>(i + 1) / panels.size(), 1.0);
    renderer->SetBackground(0.16, 0.18, 0.22);
    renderer->AddActor(actor);
    renderer->AddViewProp(caption);
    renderer->SetActiveCamera(camera);
    window->AddRenderer(renderer);
  }
  window->Render();
}
} // namespace pcbilateral_rendering

#endif

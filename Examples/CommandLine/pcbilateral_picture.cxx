// pcbilateral_picture: renders two point clouds side by side into a PNG, to show what the
// bilateral filter did.
//
//   pcbilateral_picture BEFORE AFTER OUTPUT.png [--caption-after TEXT] [--view X Y Z] [--zoom Z]
//
// BEFORE and AFTER: .txt, .xyz, .las, .pcd, .ply or .vtp. Both are drawn the same way (points as
// lit spheres, same camera), so differences are the filter's. --view sets the direction the camera
// looks from (default 1 0.7 0.45), --zoom magnifies (default 1). Needs an X display (xvfb-run on a
// headless machine).
#include "vtkPointCloudFileIO.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkCamera.h"
#include "vtkCoordinate.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkVertexGlyphFilter.h"
#include "vtkWindowToImageFilter.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
vtkSmartPointer<vtkPolyData> Read(const std::string& path)
{
  // The same choice of reader, and the same checks of damaged files, as pcbilateral's.
  vtkNew<vtkPointCloudFileIO> files;
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  if (!files->Read(path.c_str(), cloud))
  {
    std::fprintf(stderr, "pcbilateral_picture: error: %s\n", files->GetErrorMessage());
    std::exit(EXIT_FAILURE);
  }
  if (cloud->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "pcbilateral_picture: error: %s: no points read\n", path.c_str());
    std::exit(EXIT_FAILURE);
  }
  return cloud;
}

vtkSmartPointer<vtkRenderer> View(vtkPolyData* cloud,
  const std::string& caption,
  double left,
  double right,
  vtkCamera* camera)
{
  // Points need vertex cells to be drawn, and PLY clouds have none.
  vtkNew<vtkVertexGlyphFilter> vertices;
  vertices->SetInputData(cloud);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(vertices->GetOutputPort());
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetRepresentationToPoints();
  actor->GetProperty()->SetRenderPointsAsSpheres(true);
  actor->GetProperty()->SetPointSize(2.5);
  actor->GetProperty()->SetColor(0.93, 0.80, 0.55);
  actor->GetProperty()->SetSpecular(0.3);

  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetViewport(left, 0.0, right, 1.0);
  renderer->SetBackground(0.16, 0.18, 0.22);
  renderer->AddActor(actor);
  renderer->SetActiveCamera(camera);

  vtkNew<vtkTextActor> text;
  text->SetInput(caption.c_str());
  text->GetTextProperty()->SetFontSize(22);
  text->GetTextProperty()->SetColor(1, 1, 1);
  text->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  text->GetPositionCoordinate()->SetValue(0.03, 0.04);
  renderer->AddViewProp(text);
  return renderer;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 4)
  {
    std::fprintf(stderr,
      "usage: pcbilateral_picture BEFORE AFTER OUTPUT.png [--caption-after TEXT] [--view X Y Z] "
      "[--zoom Z]\n");
    return EXIT_FAILURE;
  }
  std::string captionAfter = "bilateral filter";
  double view[3] = { 1.0, 0.7, 0.45 };
  double zoom = 1.0;
  for (int i = 4; i < argc; ++i)
  {
    const std::string option = argv[i];
    if (option == "--caption-after" && i + 1 < argc)
    {
      captionAfter = argv[++i];
    }
    else if (option == "--view" && i + 3 < argc)
    {
      for (double& component : view)
      {
        component = std::atof(argv[++i]);
      }
    }
    else if (option == "--zoom" && i + 1 < argc)
    {
      zoom = std::atof(argv[++i]);
    }
    else
    {
      std::fprintf(stderr, "pcbilateral_picture: error: unknown option '%s'\n", argv[i]);
      return EXIT_FAILURE;
    }
  }
  auto before = Read(argv[1]);
  auto after = Read(argv[2]);

  double bounds[6];
  before->GetBounds(bounds);
  const double centre[3] = {
    0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])
  };
  vtkNew<vtkCamera> camera;
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0] + view[0], centre[1] + view[1], centre[2] + view[2]);
  camera->SetViewUp(0, 0, 1);
  camera->ParallelProjectionOn();

  vtkNew<vtkRenderWindow> window;
  window->SetSize(1400, 700);
  window->SetMultiSamples(8);
  window->OffScreenRenderingOn();
  auto left = View(before, "noisy input", 0.0, 0.5, camera);
  auto right = View(after, captionAfter, 0.5, 1.0, camera);
  window->AddRenderer(left);
  window->AddRenderer(right);
  left->ResetCamera(bounds);
  camera->Zoom(zoom > 0 ? zoom : 1.0);
  window->Render();

  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(window);
  capture->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(argv[3]);
  writer->SetInputConnection(capture->GetOutputPort());
  writer->Write();
  std::printf("picture:       %s\n", argv[3]);
  return EXIT_SUCCESS;
}

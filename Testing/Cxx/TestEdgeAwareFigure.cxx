// The edge-aware mode against the paper's filter (the figure of docs/edge-aware.md): the bundled
// noisy sharp edge (noise 0.5% of the diagonal), then the paper's filter and the edge-aware mode
// with the same r, rn and N, seen along the ridge and close to it. The edge-aware mode keeps the
// ridge sharper and the faces thinner.
#include "RenderingScene.h"

#include "vtkRegressionTestImage.h"

int TestEdgeAwareFigure(int argc, char* argv[])
{
  using namespace pcbilateral_rendering;
  auto noisy = ReadSample("sharp_edge_noise0.5.ply");
  auto filter = [&](bool edgeAware)
  {
    return pcbilateral_testing::RunFilter(noisy,
      [&](vtkPointCloudBilateralFilter* bilateral)
      {
        bilateral->SetRadius(0.12);
        bilateral->SetNormalRadius(0.047);
        bilateral->SetNumberOfIterations(2);
        bilateral->SetEdgeAware(edgeAware);
        bilateral->GenerateDisplacementLengthOn();
      })
      .Output;
  };
  vtkNew<vtkCamera> camera;
  camera->SetFocalPoint(0.0, 0.0, -0.05);
  camera->SetPosition(0.0, -3.0, -0.05);
  camera->SetViewUp(0.0, 0.0, 1.0);
  camera->ParallelProjectionOn();
  camera->SetParallelScale(0.07);
  vtkNew<vtkRenderWindow> window;
  Show(window,
    { { noisy, "noisy" },
      { filter(false), "paper: r 0.12, rn 0.047, N 2" },
      { filter(true), "edge-aware, same" } },
    camera,
    320,
    260);
  // As for Figure 6: sparse points on a dark background, so keep the threshold low.
  const int result = vtkRegressionTestImageThreshold(window, 0.01);
  return result == vtkRegressionTester::FAILED;
}

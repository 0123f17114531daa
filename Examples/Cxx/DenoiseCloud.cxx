// DenoiseCloud: the filter in a C++ program of a few lines: read a PLY cloud, denoise it, write
// a VTP file that keeps every point array.
//
//   DenoiseCloud INPUT.ply OUTPUT.vtp [RADIUS [NORMAL_RADIUS [ITERATIONS]]]
//
// Each defaults to 0: automatic, from the cloud's measured spacing and noise. Built with the
// project (build/bin/DenoiseCloud) and, from outside it, by Examples/Cxx/External.
#include "vtkPointCloudBilateralFilter.h"

#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <cstdio>
#include <cstdlib>

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::fprintf(
      stderr, "usage: %s INPUT.ply OUTPUT.vtp [RADIUS [NORMAL_RADIUS [ITERATIONS]]]\n", argv[0]);
    return EXIT_FAILURE;
  }

  vtkNew<vtkPLYReader> reader;
  reader->SetFileName(argv[1]);

  vtkNew<vtkPointCloudBilateralFilter> bilateral;
  bilateral->SetInputConnection(reader->GetOutputPort());
  if (argc > 3)
  {
    bilateral->SetRadius(std::atof(argv[3]));
  }
  if (argc > 4)
  {
    bilateral->SetNormalRadius(std::atof(argv[4]));
  }
  if (argc > 5)
  {
    bilateral->SetNumberOfIterations(std::atoi(argv[5]));
  }

  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputConnection(bilateral->GetOutputPort());
  writer->SetFileName(argv[2]);
  if (writer->Write() != 1 || bilateral->GetOutput()->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "%s: nothing was written (see the messages above)\n", argv[2]);
    return EXIT_FAILURE;
  }
  std::printf("%lld points denoised with radius %g and normal radius %g, written to %s\n",
    static_cast<long long>(bilateral->GetOutput()->GetNumberOfPoints()),
    bilateral->GetRadiusUsed(),
    bilateral->GetNormalRadiusUsed(),
    argv[2]);
  return EXIT_SUCCESS;
}

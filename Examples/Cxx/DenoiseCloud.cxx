// DenoiseCloud: the filter in a C++ program of a few lines: read a PLY cloud, denoise it, write
// a VTP file that keeps every point array.
//
//   DenoiseCloud INPUT.ply OUTPUT.vtp [RADIUS [NORMAL_RADIUS [ITERATIONS]]]
//
// RADIUS and NORMAL_RADIUS default to 0 (automatic), ITERATIONS to 1. Built with the project
// (build/bin/DenoiseCloud) and, from outside it, by Examples/Cxx/External.
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
  bilateral->SetRadius(argc > 3 ? std::atof(argv[3]) : 0.0);
  bilateral->SetNormalRadius(argc > 4 ? std::atof(argv[4]) : 0.0);
  bilateral->SetNumberOfIterations(argc > 5 ? std::atoi(argv[5]) : 1);

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

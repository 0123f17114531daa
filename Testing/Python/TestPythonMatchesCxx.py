"""The wrapped filter in a plain vtkmodules pipeline gives the same points, bit for bit, as the
C++ filter (run through the pcbilateral program) on the same input.

    PYTHONPATH=<build>/lib/python3/dist-packages /usr/bin/python3 TestPythonMatchesCxx.py \
        PCBILATERAL INPUT.ply SCRATCH_FOLDER
"""
import os
import subprocess
import sys

import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from pointcloudbilateral import vtkPointCloudBilateralFilter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pcb_testing import check, finish  # noqa: E402

program, input_path, scratch = sys.argv[1:4]
os.makedirs(scratch, exist_ok=True)
cxx_path = os.path.join(scratch, "cxx.vtp")
subprocess.run([program, input_path, cxx_path, "-r", "0.06", "-n", "0.02", "-N", "2"],
               check=True, stdout=subprocess.DEVNULL)
cxx_reader = vtkXMLPolyDataReader()
cxx_reader.SetFileName(cxx_path)
cxx_reader.Update()
cxx = dsa.WrapDataObject(cxx_reader.GetOutput())

reader = vtkPLYReader()
reader.SetFileName(input_path)
bilateral = vtkPointCloudBilateralFilter()
bilateral.SetInputConnection(reader.GetOutputPort())
bilateral.SetRadius(0.06)
bilateral.SetNormalRadius(0.02)
bilateral.SetNumberOfIterations(2)
bilateral.Update()
python = dsa.WrapDataObject(bilateral.GetOutput())

ours, theirs = np.asarray(python.Points), np.asarray(cxx.Points)
original = dsa.WrapDataObject(reader.GetOutput()).Points
check(ours.dtype == theirs.dtype == np.float32, f"point types {ours.dtype} and {theirs.dtype}")
check(ours.shape == theirs.shape, f"{len(ours)} and {len(theirs)} points")
check(np.array_equal(ours, theirs), "the same points, bit for bit")
check(np.max(np.abs(ours - original)) > 1e-3, "the points moved")

# The edge-aware mode: the same property in Python and on the command line, and other points.
paper = np.array(ours)
subprocess.run([program, input_path, cxx_path, "-r", "0.06", "-n", "0.02", "-N", "2",
                "--edge-aware"], check=True, stdout=subprocess.DEVNULL)
cxx_reader.Modified()
cxx_reader.Update()
check(not bilateral.GetEdgeAware(), "the edge-aware mode is off by default")
bilateral.EdgeAwareOn()
bilateral.Update()
aware = np.asarray(dsa.WrapDataObject(bilateral.GetOutput()).Points)
check(np.array_equal(aware, np.asarray(dsa.WrapDataObject(cxx_reader.GetOutput()).Points)),
      "edge-aware: the same points, bit for bit")
check(not np.array_equal(aware, paper), "edge-aware: other points than the paper's filter")

# The automatic mode (the default) from Python: the same measurement and choice as the program.
automatic_path = os.path.join(scratch, "cxx-automatic.vtp")
printed = subprocess.run([program, input_path, automatic_path], check=True, capture_output=True,
                         text=True).stdout
automatic = vtkPointCloudBilateralFilter()
automatic.SetInputConnection(reader.GetOutputPort())
check(automatic.GetRadius() == 0 and automatic.GetNumberOfIterations() == 0
      and automatic.GetAutomaticParameters() == vtkPointCloudBilateralFilter.MEASURED,
      "the defaults are automatic")
automatic.Update()
said = f"radius:        {automatic.GetRadiusUsed():.9g} (automatic"
check(said in printed and automatic.GetNoiseSigma() > 0
      and f"noise sigma {automatic.GetNoiseSigma():.6g}" in printed,
      f"Python used radius {automatic.GetRadiusUsed():.9g} and measured noise "
      f"{automatic.GetNoiseSigma():.6g}; the program printed:\n{printed}")
automatic.SetAutomaticParametersToPaper()
automatic.Update()
check(automatic.GetNumberOfIterationsUsed() == 1
      and automatic.GetNormalRadiusUsed() == automatic.GetRadiusUsed()
      and automatic.GetLastRunSummary().endswith("(paper's rule)"),
      f"the paper's rule by name: {automatic.GetLastRunSummary()}")
finish()

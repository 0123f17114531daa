"""Run inside the ParaView GUI (paraview --script=... --test-script=PanelChecks.xml) by
TestPanel.sh: sets up what PanelChecks.xml then checks in the widgets themselves.
- A filter with a radius far too small for the cloud: its error in the Output Messages window;
- one with given values (radius 0.06, 2 iterations), left as the active source, so that the
  Properties panel shows its information properties (Number Of Iterations Used, Radius Used,
  Last Run) after its run;
- a LAS file, panel.las in the test directory, for PanelChecks.xml to open with File > Open
  (TestPanel.sh then checks that nothing printed GDAL's "ERROR 4")."""
import os

from paraview import simple

data = os.path.join(os.environ["PCB_SOURCE_DIR"], "Data", "sharp_edge_noise0.5.ply")
reader = simple.PLYReader(FileNames=[data])
failing = simple.PointCloudBilateralFilter(Input=reader, Radius=1e-9, NumberOfIterations=1)
simple.Show(failing)
simple.Render()
simple.Hide(failing)
given = simple.PointCloudBilateralFilter(Input=reader, Radius=0.06, NormalRadius=0.02,
                                         NumberOfIterations=2)
simple.Show(given)
simple.Render()
simple.SetActiveSource(given)
# The LAS file that PanelChecks.xml opens with File > Open (in ParaView's test directory).
simple.SaveData(os.path.join(os.environ["PCB_SCRATCH"], "panel.las"), proxy=reader)

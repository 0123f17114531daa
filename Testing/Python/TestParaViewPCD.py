"""PCL's PCD files in ParaView: File > Open offers them (the reader factory lists *.pcd) and
OpenDataFile picks the plugin's reader, the depth frame's NaN points are dropped or, with Keep
NaN Points, kept through the filter and saved back (File > Save Data lists *.pcd) as the
640 x 480 frame; a damaged file gives one error and no points.

    pvpython TestParaViewPCD.py PLUGIN PCD_FOLDER SCRATCH_FOLDER

Exits with 77 (skipped) when PCD_FOLDER has no capture0001.pcd.
"""
import os
import sys

from paraview import servermanager, simple

# The wrapped classes, so that the reader's own methods are reachable from Python.
import pointcloudbilateral  # noqa: F401
from pcb_testing import check, finish, shared_file_or_skip

plugin, folder, scratch = sys.argv[1], sys.argv[2], sys.argv[3]
capture = shared_file_or_skip(folder, "capture0001.pcd", "PCB_PCD_DATA_DIR")
os.makedirs(scratch, exist_ok=True)

simple.LoadPlugin(plugin, remote=False, ns=vars(simple))
manager = servermanager.vtkSMProxyManager.GetProxyManager()
session = servermanager.ActiveConnection.Session
readers = manager.GetReaderFactory().GetSupportedFileTypes(session)
check("PCD point cloud (PCL) (*.pcd)" in readers, "File > Open lists PCD files")

reader = simple.OpenDataFile(capture)
check(reader is not None and reader.GetXMLName() == "PCDPointCloudReader",
      f"OpenDataFile picks the PCD reader: {reader.GetXMLName() if reader else None}")
reader.UpdatePipeline()
reader.UpdatePropertyInformation()
check(reader.GetDataInformation().GetNumberOfPoints() == 249647 and
      reader.NumberOfDroppedPoints == 57553, "the NaN points dropped and counted")
writers = manager.GetWriterFactory().GetSupportedFileTypes(reader.SMProxy, 0)
check("PCD point cloud (PCL)(*.pcd )" in writers, "File > Save Data lists PCD files")

reader.KeepNaNPoints = 1
reader.UpdatePipeline()
check(reader.GetDataInformation().GetNumberOfPoints() == 307200, "kept: the whole frame")
bilateral = simple.PointCloudBilateralFilter(Input=reader)
out = os.path.join(scratch, "capture_filtered.pcd")
simple.SaveData(out, proxy=bilateral)
with open(out, "rb") as written:
    header = written.read(300)
check(b"WIDTH 640\nHEIGHT 480\n" in header and b"POINTS 307200\nDATA binary_compressed\n" in header,
      "saved back as the frame, in its encoding")
again = simple.OpenDataFile(out)
again.KeepNaNPoints = 1
again.UpdatePipeline()
check(again.GetDataInformation().GetNumberOfPoints() == 307200, "and read back")

damaged = os.path.join(scratch, "cut.pcd")
with open(capture, "rb") as whole, open(damaged, "wb") as cut:
    cut.write(whole.read()[:5000])
bad = simple.OpenDataFile(damaged)
bad.UpdatePipeline()
check(bad.GetDataInformation().GetNumberOfPoints() == 0, "a cut file gives no points")
message = bad.GetClientSideObject().GetErrorMessage()
check("do not match the file" in message and "\n" not in message, f"and one error: {message}")

finish()
print("all checks passed")

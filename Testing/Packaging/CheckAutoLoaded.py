"""Run by TestDebianPackage.sh inside a ParaView program (pvpython, pvbatch, or the GUI with
--script) started from the unpacked package's usr/bin, with no Load Plugin step: writes
"ok: ..." / "FAILED: ..." lines to PCB_LOG (or prints them). Checks that the plugin was loaded at
start-up from the package (under PCB_ROOT, the unpacked tree, or installed), that its filter is defined in the Filters menu's group
with its menu category, that ParaView's open and save dialogs list its readers' and writers'
extensions, and that the filter runs. With PCB_EXPECT_ABSENT=1 it checks the opposite: the
plugin is not loaded (a program started from a folder without the package's paraview.conf)."""
import os
import sys

from paraview import servermanager, simple

root = os.environ.get("PCB_ROOT", "")  # "" for the installed package
expect_absent = os.environ.get("PCB_EXPECT_ABSENT") == "1"
lines = []


def check(condition, message):
    lines.append(("ok:     " if condition else "FAILED: ") + message)


mapped = sorted({line.split()[-1] for line in open("/proc/self/maps")
                 if line.rstrip().endswith("/PointCloudBilateral.so")})
definitions = servermanager.ProxyManager().SMProxyManager.GetProxyDefinitionManager()
defined = definitions.HasDefinition("filters", "PointCloudBilateralFilter")
if expect_absent:
    check(not defined and not mapped,
          f"without the package's paraview.conf the plugin is not loaded ({mapped})")
else:
    check(len(mapped) == 1 and mapped[0].startswith(root + "/"),
          f"the plugin loaded at start-up from the package: {mapped}")
    check(defined, "the filter's proxy is defined (Filters menu)")
    hints = definitions.GetProxyDefinition(
        "filters", "PointCloudBilateralFilter") if defined else None
    menu = hints.FindNestedElementByName("Hints").FindNestedElementByName("ShowInMenu") \
        if hints is not None and hints.FindNestedElementByName("Hints") is not None else None
    check(menu is not None and menu.GetAttribute("category") == "Point Cloud",
          "the filter is in the Filters menu's Point Cloud category")
    session = servermanager.ActiveConnection.Session
    # What File > Open and File > Save Data list (pqLoadDataReaction, pqSaveDataReaction).
    reader_factory = servermanager.vtkSMProxyManager.GetProxyManager().GetReaderFactory()
    reader_factory.UpdateAvailableReaders()
    readers = reader_factory.GetSupportedFileTypes(session)
    check(all(f"*.{extension}" in readers for extension in ("las", "laz", "pcd", "xyz")),
          "the open dialog lists *.las, *.laz, *.pcd and *.xyz")
    sphere = simple.Sphere()
    writer_factory = servermanager.vtkSMProxyManager.GetProxyManager().GetWriterFactory()
    writer_factory.UpdateAvailableWriters()
    writers = writer_factory.GetSupportedFileTypes(sphere.SMProxy, 0)
    check(all(f"*.{extension}" in writers for extension in ("las", "laz", "pcd", "xyz")),
          "the save dialog lists *.las, *.laz, *.pcd and *.xyz")
    points = simple.PointSource(NumberOfPoints=500, Radius=1.0)
    bilateral = simple.PointCloudBilateralFilter(Input=points)
    bilateral.UpdatePipeline()
    count = bilateral.GetDataInformation().GetNumberOfPoints()
    check(count == 500, f"the filter runs ({count} points out)")

log = os.environ.get("PCB_LOG")
if log:
    with open(log, "w") as out:
        out.write("\n".join(lines) + "\n")
else:
    print("\n".join(lines))
    sys.exit(1 if any(line.startswith("FAILED") for line in lines) else 0)

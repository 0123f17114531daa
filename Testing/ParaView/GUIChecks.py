"""Run inside the ParaView GUI (paraview --script=... --exit) by TestGUIScript.sh; checks what the
plugin's GUI part sets up, and writes "ok: ..." or "FAILED: ..." lines to PCB_LOG:
- after the filter has run, the arrays its display offers for colouring: the field arrays
  Bilateral* (the parameters used and the measured scales, for the Information panel and
  scripts) must not be among them; DisplacementLength must;
- the default reader of .xyz files (what File > Open uses without asking) is the Point Cloud
  Text Reader, not PLOT3D's;
- a LAS file with colours, and the filter's output of it, are shown in those colours, also when
  the output was first shown empty (a bad radius, then a good one)."""
import os

from paraview import servermanager, simple

data = os.path.join(os.environ["PCB_SOURCE_DIR"], "Data", "sharp_edge_noise0.5.ply")
reader = simple.PLYReader(FileNames=[data])
reader_display = simple.Show(reader)  # (the GUI picks its representation when first shown)
bilateral = simple.PointCloudBilateralFilter(Input=reader, OutputDisplacementLength=1)
display = simple.Show(bilateral)
simple.Render()
domain = display.GetProperty("ColorArrayName").SMProperty.FindDomain("vtkSMArrayListDomain")
offered = [domain.GetString(i) for i in range(domain.GetNumberOfStrings())]
field = [array.GetName() for array in bilateral.FieldData]
with open(os.environ["PCB_LOG"], "w") as log_file:
    def check(condition, message):
        log_file.write(("ok:     " if condition else "FAILED: ") + message + "\n")
    recorded = ["BilateralRadius", "BilateralNormalRadius", "BilateralNumberOfIterations",
                "BilateralPointSpacing", "BilateralNoiseSigma",
                "BilateralNearestNeighbourDistances", "BilateralSpacingSpread", "BilateralMode"]
    check(all(name in field for name in recorded),
          f"the output's field data has the parameters used and the scales measured: {field}")
    check("DisplacementLength" in offered, f"colour-by offers {offered}")
    # Before and after look alike: the filter's output is shown as the GUI's Apply shows a PLY
    # cloud of points without cells (Point Gaussian; a scripted Show of the PLY reader may keep
    # Surface, so its representation is printed, not compared).
    check(display.Representation == "Point Gaussian" and
          display.PointSize == reader_display.PointSize,
          f"output shown as {display.Representation} (the PLY input, shown by a script: "
          f"{reader_display.Representation}), point size {display.PointSize}")
    check(not any(name.startswith("Bilateral") for name in offered),
          f"colour-by does not offer the recorded parameters ({offered})")

    # A LAS file (the project's small one, written here): its point attributes are offered,
    # the header values kept in field data ("LAS Scale"...) are not.
    las_path = os.path.join(os.environ.get("PCB_LOG") + ".las")
    simple.SaveData(las_path, proxy=reader)
    las = simple.OpenDataFile(las_path)
    las_display = simple.Show(las)
    check(las_display.Representation == "Point Gaussian",
          f"a LAS file is shown as a PLY one ({las_display.Representation})")
    simple.Render()
    las_domain = las_display.GetProperty("ColorArrayName").SMProperty.FindDomain(
        "vtkSMArrayListDomain")
    las_offered = [las_domain.GetString(i) for i in range(las_domain.GetNumberOfStrings())]
    las_field = [array.GetName() for array in las.FieldData]
    check(any(name.startswith("LAS ") for name in las_field) and "Intensity" in las_offered
          and not any(name.startswith("LAS ") for name in las_offered),
          f"a LAS file's colour-by offers {las_offered}, not its header ({las_field})")

    # A LAS file with colours is shown in them (the reader's "Colors", not mapped), and so is
    # the filter's output of it: both were plain grey.
    painted = simple.ProgrammableFilter(Input=reader)
    painted.Script = ("import numpy\n"
                      "rgb = numpy.zeros((inputs[0].GetNumberOfPoints(), 3), numpy.uint16)\n"
                      "rgb[:, 0] = 65535\n"
                      "output.ShallowCopy(inputs[0].VTKObject)\n"
                      "output.PointData.append(rgb, 'RGB')")
    colour_path = os.path.join(os.environ.get("PCB_LOG") + ".colours.las")
    simple.SaveData(colour_path, proxy=painted)
    coloured = simple.OpenDataFile(colour_path)
    coloured_display = simple.Show(coloured)
    simple.Render()
    coloured_filter = simple.PointCloudBilateralFilter(Input=coloured)
    coloured_filter_display = simple.Show(coloured_filter)
    simple.Render()
    for what, shown in (("a LAS file", coloured_display), ("its filtered output",
                                                         coloured_filter_display)):
        check(list(shown.ColorArrayName) == ["POINTS", "Colors"] and shown.MapScalars == 0,
              f"{what} with colours is shown in them ({shown.ColorArrayName}, "
              f"map scalars {shown.MapScalars})")
    # First shown on an empty output (a bad radius: an error), then run with a good radius: the
    # display is set up as one first shown with points (it stayed a plain white surface).
    late = simple.PointCloudBilateralFilter(Input=coloured, Radius=-1.0)
    late_display = simple.Show(late)
    simple.Render()
    empty = late.GetDataInformation().GetNumberOfPoints()
    late.Radius = 0.0
    simple.Render()
    check(empty == 0 and late.GetDataInformation().GetNumberOfPoints() > 0 and
          list(late_display.ColorArrayName) == ["POINTS", "Colors"] and
          late_display.MapScalars == 0 and late_display.Representation == "Point Gaussian" and
          late_display.GaussianRadius > 0,
          f"an output first shown empty ({empty} points), then filled, is shown as the others: "
          f"{late_display.Representation}, radius {late_display.GaussianRadius}, coloured by "
          f"{late_display.ColorArrayName}, map scalars {late_display.MapScalars}")
    check(not las_display.ColorArrayName[1],
          f"a LAS file without colours is not coloured ({las_display.ColorArrayName})")

    # Class Array: Classification on a LAS file, "(none)" on a cloud without integer point arrays
    # (the PLY sample), never a name the input lacks (the panel showed "Classification (?)").
    las_filter = simple.PointCloudBilateralFilter(Input=las)
    for proxy, expected in ((bilateral, "(none)"), (las_filter, "Classification")):
        class_domain = proxy.GetProperty("ClassArray").SMProperty.FindDomain("vtkSMArrayListDomain")
        choices = [class_domain.GetString(i) for i in range(class_domain.GetNumberOfStrings())]
        check(proxy.ClassArray == expected and expected in choices and "GpsTime" not in choices,
              f"Class Array is {proxy.ClassArray!r} among the integer point arrays {choices}")

    # ParaView's open dialog (pqLoadDataReaction) reads this setting: pattern, description,
    # reader name, three strings per entry, the last matching entry first.
    settings = servermanager.vtkSMSettings.GetInstance()
    key = ".settings.RepresentedArrayListSettings.ReaderDetails"
    entries = [settings.GetSettingAsString(key, i, "")
               for i in range(settings.GetSettingNumberOfElements(key))]
    readers = {entries[i]: entries[i + 2] for i in range(0, len(entries) - 2, 3)}
    check(readers.get("*.xyz") == "ASCIIPointCloudTextReader",
          f"the default reader of *.xyz is the Point Cloud Text Reader ({readers})")

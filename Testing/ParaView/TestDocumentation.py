"""The documentation behind ParaView's "?" button: the plugin's compiled Qt help file (built
with XML_DOCUMENTATION ON and embedded in the plugin) has a page for each proxy, with the
proxy's long help and its properties' documentation. The filter's page states the automatic
rule and the paper's heuristic in the words of the rule's own code (AutomaticRule.h), which the
build tool prints.

    python3 TestDocumentation.py PointCloudBilateral.qch FILL_RULE_TEXT_PROGRAM
"""
import sqlite3
import subprocess
import sys
import zlib

rules = subprocess.run([sys.argv[2], "--print"], check=True, capture_output=True,
                       text=True).stdout.splitlines()

pages = {}
with sqlite3.connect(sys.argv[1]) as help_file:  # a .qch is an SQLite database
    for name, data in help_file.execute(
            "SELECT n.Name, d.Data FROM FileNameTable n JOIN FileDataTable d ON n.FileId = d.Id"):
        if data:  # Qt's qCompress: a 4-byte length, then a zlib stream
            pages[name] = zlib.decompress(bytes(data)[4:]).decode()

failures = 0
for page, expected in [
        ("filters.PointCloudBilateralFilter.html",
         ["Digne and C. de Franchis", "Neighbourhood radius r", "Number of iterations N"] + rules),
        ("sources.ASCIIPointCloudTextReader.html", ["Has Normals", "lines starting with #"]),
        ("writers.PointCloudTextWriter.html", ["one line per point"])]:
    text = " ".join(pages.get(page, "").split())
    missing = [phrase for phrase in expected if phrase not in text]
    print(("ok:     " if not missing else "FAILED: ") + f"{page}: {len(text)} characters" +
          (f", missing {missing}" if missing else ""))
    failures += bool(missing)

# Each property's row is headed by its label in the panel ("Number Of Iterations"), never by its
# internal name ("NumberOfIterations"); the input's row asks for no array the filter does not
# need (its array choosers once put "must contain a field array with 3 component(s)" there).
import re  # noqa: E402
for page, text in sorted(pages.items()):
    headers = re.findall(r"<th>(.*?)</th>", text)
    internal = [h for h in headers if re.fullmatch(r"[A-Z][a-z]+(?:[A-Z][a-z]+)+", h)]
    print(("ok:     " if not internal else "FAILED: ") + f"{page}: row headers {headers[1:]}")
    failures += bool(internal)
filter_page = pages.get("filters.PointCloudBilateralFilter.html", "")
asks = "must contain a field array" in filter_page
print(("FAILED: " if asks else "ok:     ") + "the filter's input asks for no particular array")
failures += asks
sys.exit(1 if failures else 0)

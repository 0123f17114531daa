"""The checks of TestAbort.sh filter (Abort during a long run of the filter, AbortSession.py):
CheckAbortFilter.py LOG CLICKS, where CLICKS holds the time of the click on Abort."""
import sys
lines = [line.split() for line in open(sys.argv[1])]
clicked = float(open(sys.argv[2]).read().split()[0])
times = {}
for line in lines:
    times.setdefault(line[1], []).append(float(line[0]))
failures = []
def check(condition, message):
    print(("ok:     " if condition else "FAILED: ") + message)
    if not condition:
        failures.append(message)
start = times["start"][0]
end = times.get("end", [float("inf")])[0]
returned = times.get("returned", [float("inf")])[0]
progress = [start] + [t for t in times.get("progress", []) if t <= clicked]
gaps = [b - a for a, b in zip(progress, progress[1:])]
warning = times.get("warning", [float("inf")])[0]
points = [line[2] for line in lines if line[1] == "end"]
print(f"measured: the filter returned {returned - clicked:.3f} s after the click, the Apply "
      f"ended after {end - clicked:.3f} s; {len(progress) - 1} progress events "
      f"in the {clicked - start:.2f} s before it, largest gap {max(gaps, default=0):.3f} s; "
      f"warning {warning - start:.3f} s after the start")
check(returned - clicked < 5.0, f"the filter returned {returned - clicked:.3f} s after Abort was clicked")
check(points == ["0"], f"an aborted run has an empty output ({points})")
check("aborted-message" in times, "the Output Messages window says the run was aborted")
texts = {" ".join(line[3:]) for line in lines if line[1] == "progress"}
ours = {text for text in texts if "ilateral" in text}
check(ours == {"Point Cloud Bilateral Filter"},
      f"the progress bar names the filter by its label, not its class ({sorted(texts)})")
again = [line[2] for line in lines if line[1] == "again"]
check(again == ["40000", "40000"], f"the two Applies after the abort ran to the end ({again})")
check(len(progress) > 3 and max(gaps) < 2.0, "progress reaches the GUI while the run goes on")
check(warning < clicked, "the warning about the radius arrived while the run went on")
sys.exit(1 if failures else 0)

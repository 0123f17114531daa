"""The checks of TestAbort.sh read-write (AbortReadWriteSession.py): CheckAbortReadWrite.py LOG
CLICKS, where CLICKS holds the times of the three clicks on Abort (during the read, the reload
and the write). Prints the abort latencies measured (the reader's or writer's return after the
click), which are not checked against a bound tighter than 5 s: the machine may be busy."""
import sys

lines = [line.split() for line in open(sys.argv[1])]
clicks = [float(value) for value in open(sys.argv[2]).read().split()]
failures = []


def check(condition, message):
    print(("ok:     " if condition else "FAILED: ") + message)
    if not condition:
        failures.append(message)


def first(what, name, after=0.0):
    """The time of the first line "what name" after `after` (infinity if none)."""
    return min((float(line[0]) for line in lines
                if line[1:3] == [what, name] and float(line[0]) >= after), default=float("inf"))


def values(what, name):
    return [line[3:] for line in lines if line[1:3] == [what, name]]


points = [int(line[2]) for line in lines if line[1] == "points"]
check(len(points) == 1 and points[0] > 0, f"the generated LAZ file has {points} points")
total = points[0] if points else -1
check(len(clicks) == 3, f"Abort was clicked three times ({len(clicks)})")
clicks += [float("inf")] * (3 - len(clicks))
for run, clicked in zip(("read", "reload", "write"), clicks):
    start = first("start", run)
    returned = first("returned", run, clicked)
    progress = [float(line[0]) for line in lines
                if line[1] == "progress" and start <= float(line[0]) <= clicked]
    gaps = [b - a for a, b in zip([start] + progress, progress)]
    print(f"measured: {run}: the {'writer' if run == 'write' else 'reader'} returned "
          f"{returned - clicked:.3f} s after the click, {clicked - start:.2f} s after its start; "
          f"{len(progress)} progress events before the click, largest gap "
          f"{max(gaps, default=0):.3f} s")
    check(start < clicked < first("end", run), f"Abort was clicked during the {run}")
    check(returned - clicked < 5.0,
          f"the {run} returned {returned - clicked:.3f} s after Abort was clicked")
    check(len(progress) >= 1, f"the progress bar moved during the {run} ({len(progress)} events)")
# The progress bar names each run by its reader's or writer's label, not its class.
texts = {" ".join(line[3:]) for line in lines if line[1] == "progress"}
ours = {text for text in texts if "LAS" in text}
check(ours == {"LAS Point Cloud Reader", "LAS Point Cloud Writer"},
      f"the progress bar names the reader and the writer by their labels ({sorted(texts)})")
messages = [line[2] for line in lines if line[1] == "aborted-message"]
check(messages == ["Reader", "Reader", "Writer"],
      f"the Output Messages window says each run was aborted ({messages})")
check(values("end", "read") == [["0"]],
      f"the aborted read's output is empty ({values('end', 'read')})")
check(values("end", "reload") == [["0"]],
      f"the aborted reload's output is empty ({values('end', 'reload')})")
check(values("again", "read") == [[str(total)]],
      f"the next reload read all {total} points ({values('again', 'read')})")
check(values("end", "write") == [["0", "-"]],
      f"the aborted write left no file, complete or partial ({values('end', 'write')})")
check(values("again", "write") == [[str(total)]],
      f"the next save wrote all {total} points ({values('again', 'write')})")
camera = [[float(value) for value in line[2:4]] for line in lines if line[1] == "camera"]
check(len(camera) == 1 and all(400 < value < 600 for value in camera[0]),
      f"after the reload the camera looks at the cloud's middle ({camera}; 500 500)")
radius = [float(line[2]) for line in lines if line[1] == "radius"]
check(len(radius) == 1 and radius[0] > 0,
      f"after the reload the points have a size to be drawn with ({radius}; -0.01 was none)")
sys.exit(1 if failures else 0)

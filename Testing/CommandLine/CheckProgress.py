"""What pcbilateral prints while it runs (issue 27, item 6):
- on a terminal (run under `script`, which gives it one), each summary line as soon as it is
  known: the parameters before the iterations' progress bars reach the end; a bar per phase
  (reading, measuring, each iteration, writing) shows the percentage and the time left, and is
  erased before the next line;
- not on a terminal: the same lines and a line as each phase ends (reading, measuring,
  iteration k of N, writing), no bar, no carriage return or escape;
- with --quiet: nothing on the standard output, the same output file.

    CheckProgress.py PCBILATERAL SAMPLE SCRATCH
"""
import os
import re
import shlex
import subprocess
import sys


def main(program, sample, scratch):
    os.makedirs(scratch, exist_ok=True)
    failures = []

    def check(condition, message):
        print(("ok:     " if condition else "FAILED: ") + message)
        if not condition:
            failures.append(message)

    # Long enough for several redraws (4 a second): the edge-aware mode, many iterations.
    arguments = [sample, os.path.join(scratch, "out.ply"), "--edge-aware", "-N", "12", "-t", "1"]
    command = " ".join(shlex.quote(a) for a in [program] + arguments)
    # (Bytes: text mode would turn the bar's carriage returns into new lines.)
    on_terminal = subprocess.run(["script", "-qec", command, "/dev/null"], capture_output=True,
                                 env=dict(os.environ, TERM="xterm")).stdout.decode()
    bars = [m.start() for m in
            re.finditer(r"\riteration \d+ of 12: *\[[#.]+\] +\d+%", on_terminal)]
    phases = [phase for phase in ("reading", "measuring", "iteration 1 of 12", "iteration 12 of 12",
                                  "writing")
              if re.search("\r" + phase + r": *\[[#.]+\] +\d+%", on_terminal)]
    check(len(phases) == 5, f"on a terminal: bars for {phases}")
    left = re.search(r"\] +\d+%, \d+ s left", on_terminal)
    radius = on_terminal.find("radius:")
    finished = on_terminal.find("filtering:     ", bars[-1] + 1 if bars else 0)
    check(len(bars) >= 3 and left is not None,
          f"on a terminal: {len(bars)} redraws of the bar, time left shown: {left is not None}")
    check(0 <= radius < (bars[-1] if bars else -1),
          "the parameters are printed before the filtering ends (as soon as they are chosen)")
    check(re.search(r"filtering: +[0-9.]+ s", on_terminal[finished:]) is not None and
          "\r\033[K" in on_terminal, "the bar is erased, then the time is printed")

    plain = subprocess.run([program] + arguments, capture_output=True)
    plain.stdout = plain.stdout.decode()
    check(plain.returncode == 0 and "\r" not in plain.stdout and "\033" not in plain.stdout and
          "radius:" in plain.stdout and "output:" in plain.stdout,
          "not on a terminal: plain lines only")
    ended = re.findall(r"^(reading|measuring|iteration \d+ of 12|writing): +done, [0-9.]+ s$",
                       plain.stdout, re.MULTILINE)
    check(ended == ["reading", "measuring"] + [f"iteration {k} of 12" for k in range(1, 13)] +
          ["writing"], f"not on a terminal: a line as each phase ends: {ended}")
    # A phase that fails says so, not "done": a file that is not LAS.
    damaged = os.path.join(scratch, "not-las.las")
    with open(damaged, "w") as stream:
        stream.write("1 2 3\n")
    failed = subprocess.run([program, damaged, os.path.join(scratch, "failed.las")],
                            capture_output=True, text=True)
    check(failed.returncode == 1 and "done" not in failed.stdout and "not a LAS file" in
          failed.stderr, f"a read that failed is not said done: {failed.stdout!r}")
    quiet = subprocess.run([program] + arguments + ["--quiet"], capture_output=True, text=True)
    check(quiet.returncode == 0 and quiet.stdout == "" and
          os.path.getsize(os.path.join(scratch, "out.ply")) > 0,
          f"--quiet: nothing printed ({quiet.stdout!r}), the file written")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))

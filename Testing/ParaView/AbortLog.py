"""The log of the sessions that TestAbort.sh drives (AbortSession.py, AbortReadWriteSession.py),
written inside the ParaView GUI: each line of PCB_LOG is "<absolute time> <what> [values]",
flushed at once so that the driving script can follow the runs and click Abort. Logged for
every session:
  progress P T   the session's progress handler (what the progress bar shows) reported P percent
                 and the text T
and each warning that reaches the output window (the Output Messages window), as the session's
`warning_line` names it (None: not logged)."""
import os
import time

from paraview import servermanager
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkOutputWindow

log = open(os.environ["PCB_LOG"], "w")


def note(what):
    log.write(f"{time.time():.3f} {what}\n")
    log.flush()


def follow_progress_and_warnings(warning_line):
    handler = servermanager.ActiveConnection.Session.GetProgressHandler()
    handler.AddObserver("ProgressEvent", lambda caller, event: note(
        f"progress {caller.GetLastProgress()} {caller.GetLastProgressText()}"))

    @calldata_type(VTK_STRING)
    def on_warning(caller, event, text):
        line = warning_line(text)
        if line:
            note(line)

    vtkOutputWindow.GetInstance().AddObserver("WarningEvent", on_warning)

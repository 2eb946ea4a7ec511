"""Runs one command and measures it alone: wall time, CPU time, peak RSS."""
import os
import shlex
import subprocess
import tempfile
import time
from dataclasses import dataclass

OUTPUT_TAIL_LINES = 15


@dataclass
class Usage:
    wall_s: float
    cpu_s: float  # user + system
    peak_rss_mib: float


class CommandFailed(RuntimeError):
    """A command exited non-zero (or could not start); names it and its output's tail.

    The tail mixes stdout and stderr: hba logs its errors on stdout.
    """

    def __init__(self, argv, problem, output=""):
        tail = "\n".join(output.strip().splitlines()[-OUTPUT_TAIL_LINES:])
        super().__init__(f"command failed ({problem}): {shlex.join(argv)}" + (f"\n{tail}" if tail else ""))


def run(argv):
    """Runs argv to completion; returns (stdout, Usage).

    The child is reaped with os.wait4, whose rusage covers that child alone
    (not the harness nor earlier children). Output goes to temporary files,
    not pipes, so a chatty child can never block on a full pipe while we wait.
    """
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.monotonic()
        try:
            child = subprocess.Popen(argv, stdout=out, stderr=err, stdin=subprocess.DEVNULL)
        except OSError as error:
            raise CommandFailed(argv, str(error)) from error
        _, status, rusage = os.wait4(child.pid, 0)
        wall_s = time.monotonic() - start
        child.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        stdout = out.read().decode(errors="replace")
        stderr = err.read().decode(errors="replace")
    if child.returncode != 0:
        raise CommandFailed(argv, f"exit {child.returncode}", stdout + stderr)
    # ru_maxrss is in KiB on Linux.
    usage = Usage(wall_s, rusage.ru_utime + rusage.ru_stime, rusage.ru_maxrss / 1024.0)
    return stdout, usage

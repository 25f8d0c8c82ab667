"""Code run in a fresh interpreter, for tests of signals and child processes: forking needs
a process without other threads, and an injected signal must not reach the test runner."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

NO_CHILD_LEFT = '''
def assert_no_child_left(what):
    """No child of this process, running or unreaped."""
    import os
    try:
        child = os.waitpid(-1, os.WNOHANG)
    except ChildProcessError:
        return
    raise AssertionError(f"{what} was left: {child}")
'''


def run_fresh(code: str, *args: str, timeout_s: float = 120.0) -> str:
    """Run ``code`` (dedented; ``assert_no_child_left(what)`` defined for it) with
    ``sys.argv[1:] = args`` in a new interpreter; its stdout, or an assertion error with
    its stderr when it fails."""
    out = subprocess.run([sys.executable, "-c", NO_CHILD_LEFT + textwrap.dedent(code), *args],
                         capture_output=True, text=True, timeout=timeout_s)
    assert out.returncode == 0, out.stderr
    return out.stdout


def session_alive(pgid: int) -> list[int]:
    """Processes (not zombies) of the process group ``pgid``, from /proc."""
    alive = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as fh:
                fields = fh.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[2]) == pgid and fields[0] != "Z":
            alive.append(int(entry))
    return alive

"""The checks a command prints (``sweep``, ``load``): one line each, and the exit status."""

from __future__ import annotations

from ..reporting import FAIL


def print_findings(title: str, verdicts) -> int:
    """Print ``title`` and one line per check (``pass`` or ``FAIL`` with the margin, ``not
    judged`` with the reason); returns the exit status: 1 when a check fails (a finding,
    as the README says), else 0."""
    print(title)
    for v in verdicts:
        mark = "FAIL" if v.verdict == FAIL else v.verdict
        limit = f" (limit {v.limit})" if v.limit not in ("", "–") else ""
        why = f"; {v.reason.split(';')[0]}" if v.reason else ""  # the margin, or why not
        print(f"  {mark}: {v.check}: {v.value}{limit}{why}")
    return 1 if any(v.verdict == FAIL for v in verdicts) else 0

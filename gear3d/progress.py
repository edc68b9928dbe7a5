"""Progress on a terminal for long builds: after about 2 s, a bar naming the stage.

The pipeline marks its stages with :func:`stage` (profile, body, measure, write: a cheap
assignment). :class:`Reporter`, used by the CLI around a command, waits
:data:`DELAY` seconds in a background thread and, if the command is still running and
stderr is a terminal, shows a one-line bar of the stages with the elapsed time. Nothing is
printed when stderr is not a terminal (pipes, CI logs) or when the command finishes
first. ``GEAR3D_PROGRESS_DELAY`` (seconds) overrides the delay.
"""
from __future__ import annotations

import os
import sys
import threading

#: seconds before a bar appears
DELAY = 2.0
#: the stages a build goes through, in order
STAGES = ("profile", "body", "measure", "write")

_current = {"stage": ""}


def stage(name: str) -> None:
    """Mark the stage the build is in (one of :data:`STAGES`, or any short text)."""
    _current["stage"] = name


class Reporter:
    """Context manager: a bar on a terminal when the block runs longer than the delay."""

    def __init__(self, stream=None, delay: float | None = None):
        self.stream = stream if stream is not None else sys.stderr
        env = os.environ.get("GEAR3D_PROGRESS_DELAY")
        try:
            self.delay = float(env) if env is not None else (DELAY if delay is None else delay)
        except ValueError:
            self.delay = DELAY
        self._done = threading.Event()
        self._thread = None

    def __enter__(self):
        _current["stage"] = ""
        try:
            tty = self.stream.isatty()
        except (AttributeError, ValueError):
            tty = False
        if tty:
            self._thread = threading.Thread(target=self._run, daemon=True)
            self._thread.start()
        return self

    def __exit__(self, *exc):
        self._done.set()
        if self._thread is not None:
            self._thread.join(timeout=2.0)
        return False

    def _run(self):
        import time
        if self._done.wait(self.delay):
            return
        t0 = time.monotonic() - self.delay
        width, last = 20, 0
        try:
            while True:
                name = _current["stage"]
                n = STAGES.index(name) + 1 if name in STAGES else 0
                fill = width * n // len(STAGES)
                line = (f"gear3d: [{'#' * fill}{'-' * (width - fill)}] {n}/{len(STAGES)} stages, "
                        f"{name or 'starting'}, {time.monotonic() - t0:.1f} s")
                self.stream.write("\r" + line + " " * max(last - len(line), 0))
                self.stream.flush()
                last = len(line)
                if self._done.wait(0.2):
                    break
            self.stream.write("\r" + " " * last + "\r")     # leave the terminal clean
            self.stream.flush()
        except (OSError, ValueError):                       # the terminal went away
            pass

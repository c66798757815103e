"""The progress bar of the long commands (``map2d``): plain text on a stream, no dependency."""

from __future__ import annotations

import sys
import time

__all__ = ["Progress"]


class Progress:
    """A plain progress bar on a stream: redrawn in place on a terminal, a line every 10 % otherwise."""

    def __init__(self, total: int, label: str, stream=None, enabled: bool = True):
        self.total, self.label, self.enabled = max(int(total), 1), label, enabled
        self.stream = stream or sys.stderr
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.done, self._shown, self._last_draw, self._start = 0, -1, 0.0, time.monotonic()

    def update(self, done: int):
        self.done = min(max(int(done), self.done), self.total)
        if not self.enabled:
            return
        if self.tty:
            now = time.monotonic()
            if now - self._last_draw > 0.1 or self.done == self.total:
                self._last_draw = now
                self.stream.write("\r" + self._line())
                self.stream.flush()
        else:
            step = 10 * self.done // self.total
            if step > self._shown:
                self._shown = step
                self.stream.write(self._line() + "\n")
                self.stream.flush()

    def _line(self) -> str:
        frac = self.done / self.total
        bar = "#" * int(30 * frac)
        return f"{self.label} [{bar:<30}] {self.done}/{self.total} {time.monotonic() - self._start:5.1f} s"

    def close(self):
        self.update(self.total)
        if self.enabled and self.tty:
            self.stream.write("\n")
            self.stream.flush()

"""A dependency-free progress bar on stderr for long runs and batches."""

from __future__ import annotations

import sys
import time
from typing import TextIO


class ProgressBar:
    """``with ProgressBar(total, "solving") as bar: ... bar.update()``; silent when disabled."""

    def __init__(self, total: int, label: str = "", enabled: bool = True, file: TextIO | None = None, width: int = 30):
        self.total, self.label, self.enabled, self.width = max(int(total), 0), label, enabled, width
        self.file = file if file is not None else sys.stderr
        self.done = 0
        self.start = time.perf_counter()
        self._last = 0.0

    def update(self, k: int = 1) -> None:
        self.done += k
        now = time.perf_counter()
        if self.enabled and (now - self._last > 0.1 or self.done >= self.total):
            self._last = now
            self._draw(now)

    def _draw(self, now: float) -> None:
        frac = self.done / self.total if self.total else 1.0
        filled = int(round(self.width * frac))
        elapsed = now - self.start
        # No estimate until something is done (0 done says nothing about the rate).
        left = f", {elapsed / frac - elapsed:.1f} s left" if 0 < frac < 1 else ""
        self.file.write(f"\r{self.label} [{'#' * filled}{'.' * (self.width - filled)}] {self.done}/{self.total} "
                        f"{elapsed:.1f} s elapsed{left} ")
        self.file.flush()

    def __enter__(self) -> "ProgressBar":
        if self.enabled:
            self._draw(time.perf_counter())
        return self

    def __exit__(self, *exc) -> None:
        if self.enabled:
            self.file.write("\n")
            self.file.flush()


def run_with_progress(fn, label: str, enabled: bool = True, file: TextIO | None = None, interval: float = 0.2):
    """Runs fn() in a worker thread (the solve releases the GIL) while the calling thread shows the
    elapsed time on stderr; returns fn's result (and raises its exception)."""
    if not enabled:
        return fn()
    import concurrent.futures
    import itertools

    out = file if file is not None else sys.stderr
    start = time.perf_counter()
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        future = pool.submit(fn)
        for spin in itertools.cycle("|/-\\"):
            try:
                result = future.result(timeout=interval)
                break
            except concurrent.futures.TimeoutError:
                out.write(f"\r{label} {spin} {time.perf_counter() - start:.1f} s ")
                out.flush()
    out.write(f"\r{label} done in {time.perf_counter() - start:.2f} s\n")
    out.flush()
    return result

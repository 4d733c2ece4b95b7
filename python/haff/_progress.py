"""Progress bars for runs: tqdm (terminal or notebook) if installed, else a stderr line."""

from __future__ import annotations

import sys
from typing import Any, Callable, Optional


def _interactive() -> bool:
    if "ipykernel" in sys.modules:
        return True
    return hasattr(sys.stderr, "isatty") and sys.stderr.isatty()


class _Bar:
    """Calls from the run driver: (done, total, note) at the start and at every sample."""

    def __init__(self) -> None:
        self._bar: Any = None  # a tqdm bar, made at the first call
        self._tqdm: Any = None
        try:
            from tqdm.auto import tqdm
            self._tqdm = tqdm
        except ImportError:
            pass

    def __call__(self, done: int, total: int, note: str) -> None:
        if self._tqdm is not None:
            if self._bar is None:
                self._bar = self._tqdm(total=total, initial=done, unit="sample")
            self._bar.n = done
            if note:
                self._bar.set_postfix_str(note, refresh=False)
            self._bar.refresh()
            if done >= total:
                self._bar.close()
        else:
            sys.stderr.write(f"\rhaff: sample {done}/{total} {note}")
            if done >= total:
                sys.stderr.write("\n")
            sys.stderr.flush()


def progress_callback(progress: Optional[bool]) -> Optional[Callable[[int, int, str], None]]:
    """The callback for `progress` (True, False, or None: when interactive)."""
    if progress is None:
        progress = _interactive()
    return _Bar() if progress else None

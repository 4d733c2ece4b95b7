"""Whether a call releases the GIL: a thread that notes the time in a loop pauses only as
long as some other thread holds the GIL (the switch interval is 5 ms)."""

import threading
import time


def longest_pause_while(call):
    """(seconds the call took, longest pause of a looping thread during it)."""
    stamps = []
    stop = threading.Event()

    def note():
        while not stop.is_set():
            stamps.append(time.perf_counter())

    thread = threading.Thread(target=note)
    thread.start()
    time.sleep(0.02)
    start = time.perf_counter()
    try:
        call()
    finally:
        end = time.perf_counter()
        stop.set()
        thread.join()
    inside = [t for t in stamps if start <= t <= end]
    points = [start] + inside + [end]
    pause = max(b - a for a, b in zip(points, points[1:]))
    return end - start, pause

"""Timing for the benchmarks: the best of a few runs (the least disturbed by the rest of the machine)."""
import time


def best_of(repeats: int, work) -> float:
    best = float("inf")
    for _ in range(repeats):
        started = time.perf_counter()
        work()
        best = min(best, time.perf_counter() - started)
    return best

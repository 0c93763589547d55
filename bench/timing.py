"""Timing for the benchmarks: the best of a few runs (the least disturbed by the rest of the machine)."""
import time


def best_of(repeats: int, work, clock=time.perf_counter) -> float:
    """The least time of ``repeats`` runs of ``work()`` by ``clock`` (wall; time.process_time: CPU)."""
    best = float("inf")
    for _ in range(repeats):
        started = clock()
        work()
        best = min(best, clock() - started)
    return best

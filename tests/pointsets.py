"""Distances between point sets, for comparing two toolpaths (tests and bench/): numpy only."""
import numpy as np


def hausdorff(a: np.ndarray, b: np.ndarray) -> float:
    """Largest distance from a point of either set to the nearest point of the other."""
    worst = 0.0
    for x, y in ((a, b), (b, a)):
        for s in range(0, len(x), 500):
            d = np.sqrt(((x[s:s + 500, None, :] - y[None, :, :]) ** 2).sum(axis=-1)).min(axis=1)
            worst = max(worst, float(d.max()))
    return worst

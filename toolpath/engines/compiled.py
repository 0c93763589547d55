"""Choosing between a compiled (numba) kernel module and the numpy path, one rule for every engine.

numba is optional: "auto" falls back to numpy where the module cannot be imported or where the
environment sets KEZURI_NO_NUMBA=1; "numba" then refuses with the reason; "numpy" never tries.
"""
from __future__ import annotations

import importlib
import os

KERNELS = ("auto", "numba", "numpy")


def kernel_module(kernel: str, module: str, error, what: str):
    """The compiled module ``module`` (absolute name) for ``kernel``, or None for the numpy path.
    ``error``: the engine's InputError class; ``what``: the kernel in words, for the refusal."""
    if kernel not in KERNELS:
        raise error(f"kernel must be one of {KERNELS}, got {kernel!r}")
    if kernel == "numpy":
        return None
    if os.environ.get("KEZURI_NO_NUMBA") == "1":
        why = "KEZURI_NO_NUMBA=1 is set"
    else:
        try:
            return importlib.import_module(module)
        except (ImportError, OSError, RuntimeError) as failure:
            # OSError: llvmlite's library would not load; RuntimeError: numba finds no
            # writable place for its cache of compiled kernels
            why = f"numba cannot be used ({failure})"
    if kernel == "numba":
        raise error(f"the {what} is not available: {why}")
    return None

"""linkbox from Python: load a case, solve it, get its certified roots as arrays.

    import linkbox
    case = linkbox.load("cases/spherical/agile-eye.toml")
    result = case.solve()
    print(result.headline, result.roots)

The solver runs in this process (the C++ library is linked into the module ``_linkbox``), the
same pipeline as ``linkbox solve``: load, search, verify, and the result JSON that
``linkbox solve --json`` writes, from which :class:`Result` is built.
"""
import os

# CLP's LAPACK may be OpenBLAS, whose thread pool busy-waits for work; linkbox makes no BLAS
# call worth threading (the CLI sets the same, see papers/decisions/solve-driver.md). Read
# when OpenBLAS loads, so only when nothing loaded it before.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import _linkbox  # noqa: E402

from ._errors import CaseError, Interrupted  # noqa: E402
from .case import Case, load  # noqa: E402
from .compare import compare  # noqa: E402
from .result import CheckOutcome, Result  # noqa: E402


def interrupt() -> None:
    """Interrupts every solve in progress, from any thread, as Ctrl-C does the CLI: the search
    stops at the next box and what it found is verified (a second call skips verification).
    The interrupted solve returns its partial result (``complete`` False, ``stop_reason``
    "interrupted")."""
    _linkbox.interrupt()


__all__ = ["Case", "CaseError", "CheckOutcome", "Interrupted", "Result", "compare", "interrupt", "load"]

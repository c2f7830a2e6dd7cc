"""A loaded case and its solve."""
from __future__ import annotations

import json
import math
import os
import time
from typing import Callable, Iterable, Mapping, Optional, Union

import _linkbox

from ._errors import Interrupted
from .result import Result

Progress = Union[None, bool, Callable[[float], None]]


class Case:
    """A case loaded and formulated, ready to solve. Make one with :func:`load` or
    :meth:`Case.polynomial`."""

    def __init__(self, handle: "_linkbox.Case"):
        self._handle = handle

    @property
    def name(self) -> str:
        """The case's name (its ``name`` key)."""
        return self._handle.name

    @property
    def kind(self) -> str:
        """"polynomial", "spherical", "linkage", ..."""
        return self._handle.kind

    @property
    def file(self) -> str:
        """The file it was read from (``<polynomial>`` for :meth:`Case.polynomial`)."""
        return self._handle.file

    @property
    def variables(self) -> list[str]:
        """The output variables: the columns of ``Result.roots``."""
        return list(self._handle.variables)

    def __repr__(self) -> str:
        return f"<linkbox.Case {self.name!r} ({self.kind}, {self.file})>"

    @classmethod
    def polynomial(cls, variables: Mapping[str, tuple[float, float]], equations: Iterable, inequalities: Iterable = (),
                   name: str = "polynomial") -> "Case":
        """A polynomial system built in code, read by the same reader as a TOML case.

        variables: ``{name: (lo, hi)}``, the search domain (bounds may be ``math.inf``).
        equations: expressions that are zero at a root, as strings (``"x^2 + y^2 - 1"``) or
            sympy expressions.
        inequalities: strings such as ``"x^2 + y^2 > 0.25"`` (or sympy relations).
        Raises CaseError with ``<polynomial>:line: message`` for anything the reader refuses.
        """
        text = polynomial_toml(variables, equations, inequalities, name)
        return cls(_linkbox.load_text(text, "<polynomial>"))

    def solve(self, *, prune: Optional[str] = None, bisect: Optional[str] = None, sigma: Optional[float] = None,
              rho: Optional[float] = None, order: Optional[str] = None, lp: Optional[str] = None,
              arith: Optional[str] = None, time_limit: Optional[float] = None, max_boxes: int = 0, threads: int = 1,
              verify: bool = True, progress: Progress = None) -> Result:
        """Encloses every root in solution boxes and certifies them, as ``linkbox solve``.

        Each option is the CLI's flag of that name. None takes it from the case's ``[solve]``
        table, else the CLI's default, as a flag not given does.

        prune: contractors: "auto" (default), or a comma-separated list of {contractors};
            "/" starts a stage that runs only when the earlier ones stall, e.g. "hc4,newton/lp".
        bisect: "auto" (default), "widest", "round-robin" or "smear".
        sigma: solution box size (default 1e-4).
        rho: split when the volume ratio after a shrink exceeds rho (default 0.99 on
            spherical cases, 0.8 elsewhere).
        order: "dfs" (default) or "bfs".
        lp: LP backend: "safe" (default) or "exact".
        arith: "verified" (default) or "float": the UNVERIFIED float variant, for comparison.
        time_limit: seconds (0 = none); the search stops and keeps what it proved.
        max_boxes: processed boxes (0 = none).
        threads: sub-problems in parallel, and the boxes of each search.
        verify: False skips clustering and certification (the CLI's --no-verify).
        progress: True prints the CLI's progress lines on stderr; a callable is called with
            the elapsed seconds about once a second, on this thread.

        The GIL is released while the solver works. Ctrl-C stops the search at the next box,
        verifies what it found and raises :class:`Interrupted` (a KeyboardInterrupt) holding
        that result; :func:`linkbox.interrupt` from another thread stops it the same way and
        the partial result is returned. Raises CaseError for a bad ``[solve]`` table and
        ValueError for a bad option.
        """
        args = _linkbox.SolveArgs()
        for key, value in (("prune", prune), ("bisect", bisect), ("order", order), ("lp", lp), ("arith", arith)):
            setattr(args, key, value)
        args.sigma = _positive("sigma", sigma)
        args.rho = _positive("rho", rho)
        args.time_limit = None if time_limit is None else float(time_limit)
        if args.time_limit is not None and args.time_limit < 0:
            raise ValueError("time_limit: expected a number >= 0, got %r" % time_limit)
        if max_boxes < 0 or not 1 <= threads <= 256:
            raise ValueError("max_boxes must be >= 0 and threads in [1, 256]")
        args.max_boxes, args.threads, args.verify = int(max_boxes), int(threads), bool(verify)
        args.progress = progress is True
        text, interrupted = self._handle.solve(args, _poll(progress))
        result = Result(json.loads(text), case=self)
        if interrupted:
            raise Interrupted(result)
        return result

    def check(self, result: Result):
        """Re-checks every certificate of ``result`` against this case (``linkbox check``)."""
        return result.check(self)


Case.solve.__doc__ = Case.solve.__doc__.replace("{contractors}", _linkbox.contractor_names())


def load(path: Union[str, os.PathLike]) -> Case:
    """Loads a case file: TOML (polynomial, spherical, linkage), Minibex ``.bch`` or CuikSuite
    ``.cuik``. Raises CaseError with the CLI's ``file:line: message`` when it is bad."""
    return Case(_linkbox.load(os.fspath(path)))


def _positive(name: str, x: Optional[float]) -> Optional[float]:
    if x is not None and not x > 0:
        raise ValueError("%s: expected a number > 0, got %r" % (name, x))
    return None if x is None else float(x)


def _poll(progress: Progress) -> Callable[[], None]:
    """What the module calls ten times a second while a solve runs."""
    if not callable(progress) or progress is True:
        return lambda: None
    start, last = time.monotonic(), [time.monotonic()]

    def poll():
        now = time.monotonic()
        if now - last[0] >= 1:
            last[0] = now
            progress(now - start)
    return poll


def _expression(e) -> str:
    """A string as it is; a sympy expression in linkbox's syntax (^ for powers)."""
    if isinstance(e, str):
        return e
    rel = getattr(e, "rel_op", None)
    if rel is not None:  # a sympy relation: lhs op rhs
        return "%s %s %s" % (_expression(e.lhs), rel, _expression(e.rhs))
    return str(e).replace("**", "^")


def _bound(x: float) -> str:
    x = float(x)
    return json.dumps(("-inf" if x < 0 else "inf")) if math.isinf(x) else repr(x)


def polynomial_toml(variables: Mapping[str, tuple[float, float]], equations: Iterable, inequalities: Iterable = (),
                    name: str = "polynomial") -> str:
    """The TOML text of a polynomial case (cases/polynomial/*.toml show the format)."""
    lines = ['kind = "polynomial"', "name = " + json.dumps(name), "variables = ["]
    for var, (lo, hi) in variables.items():
        lines.append("  { name = %s, domain = [%s, %s] }," % (json.dumps(str(var)), _bound(lo), _bound(hi)))
    lines.append("]")
    for key, items in (("equations", equations), ("inequalities", inequalities)):
        items = [_expression(e) for e in items]
        if items or key == "equations":
            lines += [key + " = ["] + ["  %s," % json.dumps(e) for e in items] + ["]"]
    return "\n".join(lines) + "\n"

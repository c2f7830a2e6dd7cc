"""The result of a solve: the JSON of ``linkbox solve --json``, with arrays and a plot."""
from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from typing import Any, Optional, Union

import numpy as np


@dataclass
class CheckOutcome:
    """What :meth:`Result.check` found: true when every certificate holds."""
    checked: int
    failures: list[str] = field(default_factory=list)

    def __bool__(self) -> bool:
        return not self.failures


class Result:
    """What a solve proved. ``data`` is the result JSON (documented in README.md); the
    attributes below are views of it."""

    def __init__(self, data: dict[str, Any], case=None):
        self.data = data
        self._case = case

    @classmethod
    def from_json(cls, path: Union[str, os.PathLike]) -> "Result":
        """Reads a result written by :meth:`to_json` or ``linkbox solve --json``."""
        with open(path) as f:
            return cls(json.load(f))

    def to_json(self, path: Union[str, os.PathLike, None] = None) -> str:
        """The result JSON's text (as ``linkbox solve --json`` writes it); also written to
        ``path`` when given."""
        text = json.dumps(self.data, indent=1) + "\n"
        if path is not None:
            with open(path, "w") as f:
                f.write(text)
        return text

    @property
    def headline(self) -> str:
        """What was proved, e.g. "exactly 8 roots" (empty without verification)."""
        return self.data.get("headline", "")

    @property
    def exact(self) -> bool:
        """The count of roots is proved exact."""
        return bool(self.data.get("verification", {}).get("exact", False))

    @property
    def complete(self) -> bool:
        """The search covered the whole domain (no limit or interrupt stopped it)."""
        return bool(self.data["complete"])

    @property
    def stop_reason(self) -> str:
        """Why an incomplete search stopped ("time limit reached", "interrupted", ...)."""
        return self.data.get("stop_reason", "")

    @property
    def unrefined(self) -> int:
        """Solution boxes of a complete search that a limit left unrefined (0: none)."""
        return int(self.data.get("refinement_stopped", {}).get("boxes", 0))

    @property
    def variables(self) -> list[str]:
        """The output variables: the columns of :attr:`roots`."""
        return list(self.data["variables"])

    @property
    def certified_roots(self) -> int:
        """How many distinct roots are certified."""
        return int(self.data.get("certified_roots", 0))

    @property
    def roots(self) -> np.ndarray:
        """The certified roots' midpoints, one row per distinct root: shape (k, n)."""
        rows = [r["midpoint"] for r in self.data.get("roots", [])]
        return np.array(rows, dtype=float).reshape(len(rows), len(self.variables))

    @property
    def root_boxes(self) -> np.ndarray:
        """The certified boxes, each enclosing exactly one root: shape (k, n, 2), [lo, hi]."""
        boxes = [r["box"] for r in self.data.get("roots", [])]
        return np.array(boxes, dtype=float).reshape(len(boxes), len(self.variables), 2)

    @property
    def solution_boxes(self) -> np.ndarray:
        """The search's solution boxes in the output variables: shape (m, n, 2)."""
        boxes = [s["box"] for s in self.data.get("solutions", [])]
        return np.array(boxes, dtype=float).reshape(len(boxes), len(self.variables), 2)

    @property
    def clusters(self) -> list[dict[str, Any]]:
        """The clusters of solution boxes with their status and certificate (JSON objects)."""
        return self.data.get("clusters", [])

    @property
    def stats(self) -> dict[str, Any]:
        """The search's figures: processed, solution_boxes, empty, seconds, ..."""
        return self.data["stats"]

    def check(self, case=None) -> CheckOutcome:
        """Re-checks every certificate against the case's equations alone (``linkbox check``):
        ``case`` defaults to the one solved, else the file the result names."""
        if "clusters" not in self.data:
            raise ValueError("no certificates (was it solved with verify=False?)")
        case = case or self._case
        if case is None:
            from .case import load
            case = load(self.data["case_file"])
        checked, failures = case._handle.check(json.dumps(self.data))
        return CheckOutcome(checked, list(failures))

    def plot(self, x: Union[int, str] = 0, y: Union[int, str] = 1, ax=None, boxes: bool = True):
        """Plots the solution boxes and the certified roots in two output variables (index or
        name) with matplotlib; returns the axes."""
        import matplotlib.pyplot as plt
        from matplotlib.patches import Rectangle

        names = self.variables
        i, j = (names.index(v) if isinstance(v, str) else v for v in (x, y))
        if ax is None:
            ax = plt.figure().add_subplot()
        if boxes:
            for b in self.solution_boxes:
                ax.add_patch(Rectangle((b[i, 0], b[j, 0]), b[i, 1] - b[i, 0], b[j, 1] - b[j, 0], fill=False,
                                       edgecolor="0.6", linewidth=0.5))
        roots = self.roots
        ax.plot(roots[:, i], roots[:, j], "o", color="C3", label="certified roots (%d)" % len(roots))
        ax.autoscale_view()
        ax.set_xlabel(names[i])
        ax.set_ylabel(names[j])
        ax.set_title("%s: %s" % (self.data.get("case", ""), self.headline))
        ax.legend(loc="best")
        return ax

    def __repr__(self) -> str:
        state = "complete" if self.complete else "incomplete: " + self.stop_reason
        return "<linkbox.Result %s: %s (%s, %s processed boxes)>" % (
            self.data.get("case", "?"), self.headline or "not verified", state, self.stats.get("processed"))

"""Several strategies on one case, as a table."""
from __future__ import annotations

from typing import Any, Iterable, Mapping, Union

Strategy = Union[str, Mapping[str, Any]]


def compare(case, strategies: Iterable[Strategy] = ("auto", "hc4", "lp", "hc4,newton/lp"), **options):
    """Solves ``case`` once per strategy and returns one row per run, as a pandas DataFrame
    (a list of dicts when pandas is missing).

    case: a :class:`linkbox.Case` or a path.
    strategies: each a ``prune`` string, or a dict of :meth:`Case.solve` options
        (e.g. ``{"prune": "lp", "lp": "exact"}``).
    options: :meth:`Case.solve` options common to every run (sigma, time_limit, ...).
    Columns: strategy, strategy_run (what "auto" resolved to), complete, headline,
    certified_roots, exact, seconds (search), verify_seconds, processed, solution_boxes,
    clusters.
    """
    from .case import Case, load

    if not isinstance(case, Case):
        case = load(case)
    rows = []
    for s in strategies:
        settings = {"prune": s} if isinstance(s, str) else dict(s)
        r = case.solve(**{**options, **settings})
        rows.append({
            "strategy": s if isinstance(s, str) else ",".join("%s=%s" % kv for kv in settings.items()),
            "strategy_run": r.data.get("strategy", ""),
            "complete": r.complete,
            "headline": r.headline,
            "certified_roots": r.certified_roots,
            "exact": r.exact,
            "seconds": r.stats.get("seconds"),
            "verify_seconds": r.data.get("verification", {}).get("seconds"),
            "processed": r.stats.get("processed"),
            "solution_boxes": r.stats.get("solution_boxes"),
            "clusters": len(r.clusters),
        })
    try:
        import pandas
    except ImportError:
        return rows
    return pandas.DataFrame(rows)

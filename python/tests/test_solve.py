"""Solving from Python gives the CLI's roots, arrays, JSON that checks, comparisons and plots."""
import json
import math
import subprocess

import numpy as np
import pytest

import linkbox
from conftest import ROOT


def cli_result(cli, case, *flags):
    run = subprocess.run([cli, "solve", str(ROOT / case), "--quiet", "--json", "-", *flags], capture_output=True,
                         text=True, check=True)
    return json.loads(run.stdout)


@pytest.mark.parametrize("case,flags", [
    ("cases/spherical/agile-eye.toml", {}),
    ("cases/polynomial/circle-line.toml", {}),
    ("cases/benchmarks/kin1.bch", {}),
    ("cases/spherical/wrist.toml", {"bisect": "widest", "sigma": 1e-6}),
])
def test_roots_equal_the_clis(cli, case, flags):
    result = linkbox.load(ROOT / case).solve(**flags)
    expected = cli_result(cli, case, *[x for k, v in flags.items() for x in ("--" + k, str(v))])
    assert result.headline == expected["headline"]
    assert result.data["roots"] == expected["roots"]
    assert result.data["solutions"] == expected["solutions"]
    assert result.roots.shape == (expected["certified_roots"], len(expected["variables"]))
    assert result.root_boxes.shape == result.roots.shape + (2,)
    assert np.all(result.root_boxes[:, :, 0] <= result.roots) and np.all(result.roots <= result.root_boxes[:, :, 1])


def test_agile_eye_has_8_certified_roots():
    result = linkbox.load(ROOT / "cases/spherical/agile-eye.toml").solve()
    assert result.complete and result.exact and result.certified_roots == 8
    assert result.roots.shape == (8, len(result.variables))
    assert result.check()


def test_a_polynomial_built_in_code(tmp_path):
    case = linkbox.Case.polynomial(variables={"x": (-2, 2), "y": (-2, 2)}, equations=["x^2 + y^2 - 1", "x - y"])
    result = case.solve()
    assert result.headline == linkbox.load(ROOT / "cases/polynomial/circle-line.toml").solve().headline
    assert sorted(abs(result.roots.ravel() - 1 / math.sqrt(2)) < 1e-9) == [True] * 4 or \
        np.allclose(np.abs(result.roots), 1 / math.sqrt(2))
    clear = linkbox.Case.polynomial(variables={"x": (-2, 2), "y": (-2, 2)}, equations=["x^2 + y^2 - 1", "x - y"],
                                    inequalities=["x > 0"])
    assert clear.solve().certified_roots == 1
    assert result.check()
    path = tmp_path / "r.json"
    result.to_json(path)
    again = linkbox.Result.from_json(path)
    assert again.data == result.data and np.array_equal(again.roots, result.roots)


def test_a_polynomial_from_sympy():
    sympy = pytest.importorskip("sympy")
    x, y = sympy.symbols("x y")
    case = linkbox.Case.polynomial(variables={"x": (-2, 2), "y": (-2, 2)}, equations=[x**2 + y**2 - 1, x - y],
                                   inequalities=[x > 0])
    result = case.solve()
    assert result.certified_roots == 1 and np.allclose(result.roots, [[2 ** -0.5, 2 ** -0.5]])


def test_from_json_checks_against_the_named_case(tmp_path, cli):
    out = tmp_path / "wrist.json"
    subprocess.run([cli, "solve", str(ROOT / "cases/spherical/wrist.toml"), "--quiet", "--json", str(out)], check=True,
                   capture_output=True)
    outcome = linkbox.Result.from_json(out).check()
    assert outcome and outcome.checked > 0
    data = json.loads(out.read_text())
    data["roots"][0]["box"][0] = [0.0, 0.0]
    data["clusters"][0]["root"][0] = [0.0, 0.0]
    assert not linkbox.Result(data).check()


def test_case_settings_and_limits():
    case = linkbox.load(ROOT / "cases/spherical/four-loop.toml")
    result = case.solve(max_boxes=5)
    assert not result.complete and result.stop_reason == "box limit reached"
    sigma = linkbox.load(ROOT / "cases/linkages/cyclohexane.toml").solve(max_boxes=1, verify=False)
    assert sigma.data["parameters"]["sigma"] == 0.1 and "headline" not in sigma.data
    close = linkbox.load(ROOT / "cases/hard/close-roots.toml")
    cut = close.solve(max_boxes=40)  # the search finishes, the refinement of its boxes does not
    assert cut.complete and cut.unrefined > 0 and not cut.exact
    assert close.solve().unrefined == 0


def test_compare_gives_a_dataframe():
    frame = linkbox.compare(ROOT / "cases/polynomial/circle-line.toml", strategies=["hc4", "lp", {"prune": "lp", "lp": "exact"}])
    assert list(frame["strategy"]) == ["hc4", "lp", "prune=lp,lp=exact"]
    assert (frame["certified_roots"] == 2).all() and frame["exact"].all()


def test_plot(tmp_path):
    ax = linkbox.load(ROOT / "cases/spherical/agile-eye.toml").solve().plot("phi1", "psi1")
    ax.figure.savefig(tmp_path / "roots.png")
    assert (tmp_path / "roots.png").stat().st_size > 0


def test_progress_callback_is_called():
    seen = []
    result = linkbox.load(ROOT / "cases/benchmarks/eco11.toml").solve(time_limit=2.5, progress=seen.append)
    assert result.stop_reason == "time limit reached"
    assert seen and all(t >= 1 for t in seen)

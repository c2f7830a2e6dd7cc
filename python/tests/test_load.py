"""Every bundled case loads; bad input raises with the CLI's file:line message."""
import subprocess

import pytest

import linkbox
from conftest import ROOT

CASES = sorted(p for ext in ("toml", "bch", "cuik") for p in ROOT.glob("cases/**/*." + ext))


def test_there_are_cases():
    assert len(CASES) > 30


@pytest.mark.parametrize("path", CASES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_bundled_case_loads(path):
    case = linkbox.load(path)
    assert case.name and case.kind and case.variables
    assert case.file == str(path)


BAD = {
    "unknown-key.toml": 'kind = "polynomial"\nname = "bad"\nvariables = [{ name = "x", domain = [0, 1] }]\n'
                        'equations = ["x - 1/2"]\nsurprise = 1\n',
    "bad-equation.toml": 'kind = "polynomial"\nname = "bad"\nvariables = [{ name = "x", domain = [0, 1] }]\n'
                         'equations = [\n  "x - ",\n]\n',
    "missing.toml": None,
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_a_bad_case_raises_the_clis_message(name, tmp_path, cli):
    path = tmp_path / name
    if BAD[name] is not None:
        path.write_text(BAD[name])
    run = subprocess.run([cli, "solve", str(path), "--quiet"], capture_output=True, text=True)
    assert run.returncode == 2
    with pytest.raises(linkbox.CaseError) as raised:
        linkbox.load(path)
    assert str(raised.value) == run.stderr.strip()
    assert str(raised.value).startswith("%s:%d: " % (path, raised.value.line))
    assert raised.value.file == str(path)


def test_a_bad_polynomial_names_its_line():
    with pytest.raises(linkbox.CaseError, match=r"^<polynomial>:\d+: .*equation 2"):
        linkbox.Case.polynomial(variables={"x": (0, 1)}, equations=["x - 1/2", "x +"])
    with pytest.raises(ValueError):
        linkbox.Case.polynomial(variables={"x": (0, 1)}, equations=["x"]).solve(prune="no-such-contractor")


def test_help_documents_every_option():
    doc = linkbox.Case.solve.__doc__
    for option in ("prune", "bisect", "sigma", "rho", "order", "lp", "arith", "time_limit", "max_boxes", "threads",
                   "verify", "progress"):
        assert "\n        %s: " % option in doc, option

"""A long solve stops when interrupted from another thread, keeping what it found."""
import _thread
import threading
import time

import pytest

import linkbox
from conftest import ROOT

LONG = ROOT / "cases/benchmarks/eco11.toml"  # minutes of search


def test_interrupt_from_another_thread_returns_the_partial_result():
    timer = threading.Timer(1.0, linkbox.interrupt)
    timer.start()
    start = time.monotonic()
    result = linkbox.load(LONG).solve(threads=2)
    assert time.monotonic() - start < 30
    assert not result.complete and result.stop_reason == "interrupted"
    assert result.stats["processed"] > 0


def test_ctrl_c_raises_keyboard_interrupt_with_the_result():
    timer = threading.Timer(1.0, _thread.interrupt_main)  # as SIGINT does on the main thread
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt) as raised:
        linkbox.load(LONG).solve()
    assert time.monotonic() - start < 30
    assert isinstance(raised.value, linkbox.Interrupted)
    assert raised.value.result.stop_reason == "interrupted"


def test_a_run_after_an_interrupt_is_not_stopped():
    linkbox.interrupt()  # no run in progress: nothing to stop
    assert linkbox.load(ROOT / "cases/polynomial/circle-line.toml").solve().complete

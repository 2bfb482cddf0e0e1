"""Our renders started ahead in a serial image run: each case gets its own render, in order, one at a time,
and a failed render fails its case alone; the run's results equal those of renders made in the case."""
from __future__ import annotations

import threading
import time

import pytest

from harness.engines.base import Engine, RenderFailed, RenderResult
from harness.images.render_ahead import RenderAhead


class Slow(Engine):
    """Renders a scene name into its result after a pause, failing on "bad"; records overlap."""

    name = "slow"
    renders_elsewhere = True

    def __init__(self) -> None:
        self.order, self.running, self.most = [], 0, 0
        self.lock = threading.Lock()

    def version(self) -> str:
        return "slow"

    def render(self, scene, integrator, spp, batches, seed, params=None) -> RenderResult:
        with self.lock:
            self.running += 1
            self.most = max(self.most, self.running)
            self.order.append(scene)
        time.sleep(0.02)
        with self.lock:
            self.running -= 1
        if scene.endswith("bad") or scene.endswith("bad.xml"):
            raise RenderFailed("bad scene")
        return RenderResult(self.name, scene, integrator, spp, seed, None, {})


def _args(scene: str) -> tuple:
    return scene, "ao", 1, 1, 0, {}


def test_each_case_gets_its_own_render_and_the_next_starts_early():
    engine = Slow()
    ahead = RenderAhead(engine, [_args(s) for s in ("a", "bad", "c")])
    try:
        first = ahead.render(0)
        assert first.result().scene == "a"
        time.sleep(0.05)
        assert engine.order == ["a", "bad"]  # case 1's render began while case 0 was being compared
        with pytest.raises(RenderFailed, match="bad scene"):
            ahead.render(1).result()
        assert ahead.render(2).result().scene == "c"
    finally:
        ahead.close()
    assert engine.order == ["a", "bad", "c"] and engine.most == 1


def test_a_run_that_stops_early_leaves_no_render_running():
    engine = Slow()
    ahead = RenderAhead(engine, [_args(s) for s in "abcd"])
    ahead.render(0).result()
    ahead.close()
    assert engine.order == ["a", "b"] and engine.running == 0


def test_every_render_at_once_skips_the_cases_without_one():
    engine = Slow()
    ahead = RenderAhead(engine, [_args("a"), None, _args("c")], depth=None)
    try:
        assert ahead.render(2).result().scene == "c" and ahead.render(0).result().scene == "a"
    finally:
        ahead.close()
    assert engine.order == ["a", "c"]


def test_a_case_asks_renders_ahead_as_it_asks_any_renders():
    from pathlib import Path

    from harness.images.case_renders import CaseRenders
    from harness.images.render_ahead import RendersAhead
    from harness.images.suite import ImageCase

    engine = Slow()
    cases = [ImageCase(s, "ao") for s in ("a", "bad", "c")]
    renders = RendersAhead(engine, engine, cases, [1, 2, 3], [False] * 3)
    assert isinstance(renders, CaseRenders)
    try:
        assert Path(renders.tested(cases[0], 1).scene).stem == "a"
        time.sleep(0.05)
        assert [Path(s).stem for s in engine.order] == ["a", "bad"]  # the next case's render began ahead
        with pytest.raises(RenderFailed, match="bad scene"):
            renders.tested(cases[1], 2)
        # Another seed than the run's, or a second request, is rendered when asked, as CaseRenders renders it.
        assert Path(renders.tested(cases[0], 9).scene).stem == "a"
        assert Path(renders.tested(cases[0], 1).scene).stem == "a"
        assert Path(renders.tested(cases[2], 3).scene).stem == "c"
    finally:
        renders.close()
    assert sorted(Path(s).stem for s in engine.order) == ["a", "a", "a", "bad", "c"]

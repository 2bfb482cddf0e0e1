"""Nori's scene tests run as they are: a `<test type="ttest">` of `<scene>`s (the course's furnaces, a floor under
polygonal lights), each scene rendered by the engine under test and the luminance a camera sample receives judged
by Nori's Student's t-test against the file's reference for it (src/ttest.cpp), at the Sidak-corrected level
over the file's scenes.

Nori draws `sampleCount` camera samples through random pixels and takes their mean and variance. Here the engine
renders about as many, the same number through each pixel, in BATCHES batches: the mean is the image's, and one
sample's variance is the variance of the batch means times a batch's samples. For Nori's test scenes, one pixel
each, that is the variance Nori estimates; over several pixels it leaves out the spread between the pixels'
means, which Nori's random pixels add, and the test is the stricter for it. That estimate has BATCHES - 1
degrees of freedom, not Nori's sampleCount - 1, and the t-test takes them: a heavy-tailed estimator (path_ems
near the edges of Nori's furnace box) whose batches missed its tail would otherwise fail as a normal one.
"""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from harness.engines.base import Engine, RenderFailed
from harness.engines.nori.reader import Reader
from harness.engines.nori.test_files import NoriTest
from harness.engines.nori.to_mitsuba import NOT_COMPARED, scene_to_mitsuba
from harness.engines.nori.values import LUMINANCE
from harness.engines.scene_paths import absolute_paths
from harness.engines.written_scene import film_size
from harness.statistics.constants import sidak_level
from harness.statistics.nori_ttest import students_t_test

#: Batches each scene is rendered in: the spread of their means gives one sample's variance.
BATCHES = 32


@dataclass(frozen=True)
class SceneVerdict:
    """Nori's t-test of one `<scene>`: where it is, its integrator, the verdict (None: not run, the message says
    why), its p-value and level."""

    scene: str
    integrator: str
    passed: bool | None
    p_value: float | None
    level: float
    message: str

    def to_json(self) -> dict:
        return {"scene": self.scene, "integrator": self.integrator, "pass": self.passed, "p_value": self.p_value,
                "level": self.level, "message": self.message}


def _written(test: NoriTest, k: int, scene: ET.Element, folder: Path) -> tuple[Path | None, str, int]:
    """The scene's Mitsuba copy in `folder`, mcval's integrator for it and the film's pixels, or (None, why no
    integrator computes what the scene's does, 0)."""
    notes: list[str] = []
    root = scene_to_mitsuba(Reader(test.doc), scene, notes)
    unmatched = next((n for n in notes if NOT_COMPARED in n), None)
    if unmatched is not None:
        return None, unmatched, 0
    absolute_paths(root, test.path)
    ET.indent(root)
    file = folder / f"{test.path.stem}-scene{k + 1}.xml"
    file.write_text(ET.tostring(root, encoding="unicode") + "\n")
    width, height = film_size(root)
    return file, root.find("integrator").get("type"), width * height


def run_scene_test(test: NoriTest, engine: Engine, folder: Path, seed: int) -> list[SceneVerdict]:
    """Each scene of `test` rendered by `engine` (its copy written in `folder`) and judged as Nori judges it."""
    references = test.floats("references")
    level = sidak_level(float(test.properties["significanceLevel"]), len(references))
    wanted = int(test.properties["sampleCount"])
    out = []
    for k, (scene, reference) in enumerate(zip(test.scenes, references)):
        where = test.doc.where(scene)
        own = next((e.get("type", "") for e in scene if e.tag == "integrator"), "")
        file, integrator, pixels = _written(test, k, scene, folder)
        if file is None:
            out.append(SceneVerdict(where, own, None, None, level, f"not run: {integrator}"))
            continue
        spp = max(1, math.ceil(wanted / (BATCHES * pixels)))
        try:
            result = engine.render(str(file), integrator, spp, BATCHES, seed + k)
        except RenderFailed as e:
            out.append(SceneVerdict(where, own, False, None, level, f"render failed: {e}"))
            continue
        luminance = np.asarray(result.batches[..., :3], dtype=float) @ np.asarray(LUMINANCE)
        means = luminance.reshape(BATCHES, -1).mean(axis=1)
        per_batch = spp * pixels
        passed, p, message = students_t_test(float(means.mean()), float(means.var(ddof=1)) * per_batch, reference,
                                             per_batch * BATCHES, level, dof=BATCHES - 1)
        out.append(SceneVerdict(where, own, passed, p, level, f"{integrator} ({spp * BATCHES} spp): {message}"))
    return out

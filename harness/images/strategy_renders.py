"""The strategy check's renders: the engine under test renders a case's scene once per strategy of its integrator
(IntegratorEntry.strategies: direct's emitter sampling alone, BSDF sampling alone and MIS), each from a copy of
the scene whose <integrator> selects it, at the case's budget and with a seed of its own. evaluate() compares
them with each other (harness/comparison/strategies.py); nothing here judges.

The case's own render is the integrator at its defaults: where the scene file's <integrator> sets nothing but
`hide_emitters`, it is the strategy whose parameters are those defaults (direct's MIS), and is not rendered
twice.
"""
from __future__ import annotations

import tempfile
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from harness.engines.base import Engine
from harness.engines.scene_paths import absolute_paths
from harness.engines.written_scene import file_hide_emitters, file_parameters
from harness.images.suite import ImageCase
from harness.integrators import entry
from harness.integrators.entry import Parameter


def _expanded(path: Path) -> ET.Element:
    """The scene's root with its includes inlined and its file names absolute (a copy can go anywhere)."""
    root = ET.parse(path).getroot()
    absolute_paths(root, path)
    return root


def not_judged(case: ImageCase, engine: Engine) -> str | None:
    """Why the strategies of `case` are not compared (one line), or None where they are: its integrator has
    none, the engine takes no integrator parameters from a scene file, or the scene lights what one strategy
    cannot find (the entry's `applies`)."""
    strategies = entry(case.integrator).strategies
    if strategies is None or case.problem:
        return "no strategies" if strategies is None else case.problem
    if not engine.reads_integrator_parameters(case.integrator):
        return f"{engine.name} takes no {case.integrator} {' or '.join(sorted(_selecting(case.integrator)))} from a " \
               f"scene file"
    try:
        why = strategies.applies(_expanded(engine.scene_file(case.path)))
    except (ET.ParseError, ValueError, OSError):
        return None  # the renderer's loader reports a broken file, with its line, as the case's failure
    return f"the strategies see different light: {why}" if why else None


def _selecting(integrator: str) -> set[str]:
    """The names of the parameters that select the integrator's strategies."""
    return {name for _, parameters in entry(integrator).strategies.settings for _, name, _ in parameters}


def default_strategy(case: ImageCase, scene: Path) -> str | None:
    """The strategy that the case's own render draws (its integrator's defaults, where the scene file's
    <integrator> sets nothing but hide_emitters and the parameters no strategy sets, such as path's max_depth),
    or None."""
    e = entry(case.integrator)
    try:
        root = ET.parse(scene).getroot()
    except ET.ParseError:
        return None
    allowed = {"hide_emitters"} | ({name for _, name, _ in e.parameters} - _selecting(case.integrator))
    if any(p.get("name") not in allowed for i in root if i.tag == "integrator" for p in i):
        return None
    # The setting whose parameters all keep the integrator's defaults (direct's emitter and BSDF sample, path's mis).
    return next((name for name, parameters in e.strategies.settings if set(parameters) <= set(e.parameters)), None)


def strategy_scene(path: Path, integrator: str, parameters: tuple[Parameter, ...], out: Path) -> Path:
    """Write `path` to `out` with its <integrator> replaced by `integrator` with `parameters` (the file's
    `hide_emitters` kept, and its values of the integrator's other parameters, such as path's max_depth), its
    <default>s kept and its file names absolute."""
    root = _expanded(path)
    hide = file_hide_emitters(root)
    others = tuple(name for _, name, _ in entry(integrator).parameters if name not in {n for _, n, _ in parameters})
    kept = file_parameters(root, integrator, others)
    old = [e for e in root if e.tag == "integrator"]
    at = list(root).index(old[0]) if old else 0
    for e in old:
        root.remove(e)
    new = ET.Element("integrator", type=integrator)
    if hide is not None:
        ET.SubElement(new, "boolean", name="hide_emitters", value=hide)
    new.extend(kept)
    for tag, name, value in parameters:
        ET.SubElement(new, tag, name=name, value=value)
    root.insert(at, new)
    ET.ElementTree(root).write(out, encoding="utf-8", xml_declaration=True)
    return out


def strategy_seed(seed: int, strategy: str, case: ImageCase) -> int:
    """The seed of `strategy`'s render beside the case's render at `seed`: distinct from it and from the other
    strategies'."""
    index = [name for name, _ in entry(case.integrator).strategies.settings].index(strategy)
    return (seed + 104_729 * (index + 1)) % 2**31


@contextmanager
def strategy_file(engine: Engine, case: ImageCase, strategy: str) -> Iterator[Path]:
    """A copy of the scene the engine renders for `case` with its integrator set to `strategy`, in a temporary
    folder that lives as long as the context."""
    settings = dict(entry(case.integrator).strategies.settings)
    scene = engine.scene_file(case.path)
    with tempfile.TemporaryDirectory(prefix="mcval-strategies-") as folder:
        yield strategy_scene(scene, case.integrator, settings[strategy], Path(folder) / f"{scene.stem}-{strategy}.xml")

"""The image-validation suite: every scene with every integrator of the renderer that has a harness entry.

Two groups of scenes: our own (scenes/*.xml) and real ones (scenes/real/*.xml, Mitsuba's own files). A case
whose scene lacks what its integrator needs (simple without a point light) is not applicable: listed with the
entry's reason, never run. Budgets and Mitsuba mappings live in each integrator's entry (harness/integrators/).
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

from harness.images.user_scenes import UserScene
from harness.project import PROJECT_ROOT, missing_reason

#: The clone of mcval whose scenes/ and references/ the suite uses (harness/project.py).
ROOT = PROJECT_ROOT
SCENES_DIR = ROOT / "scenes"
REAL_SCENES_DIR = SCENES_DIR / "real"
GROUP_DIRS = {"synthetic": SCENES_DIR, "real": REAL_SCENES_DIR}
#: The group of the scenes given with --scene.
USER = "user"

def suite_integrators(available: Sequence[str] | None = None) -> tuple[str, ...]:
    """The integrators with an entry that the engine under test renders (`available`, its Engine.integrators;
    None: the default tested engine's); those that check geometry first (a scene whose normals fail has a
    camera or geometry mismatch, which the run notes on that scene's other cases)."""
    if available is None:
        from harness.engines.registry import DEFAULT_TEST, engine_integrators
        from harness.integrators import match
        found = match(engine_integrators(DEFAULT_TEST)).entries
    else:
        from harness.integrators import entries
        found = [e for name, e in entries().items() if name in available]
    return tuple(e.name for e in sorted(found, key=lambda e: not e.checks_geometry))


class _Integrators(Sequence):
    """INTEGRATORS, read from the registry when used (importing this module needs no renderer)."""

    def __getitem__(self, i):
        return suite_integrators()[i]

    def __len__(self) -> int:
        return len(suite_integrators())

    def __repr__(self) -> str:
        return repr(suite_integrators())


class _Budget(Mapping):
    """TESTED_SPP / REFERENCE_SPP: one entry field by integrator name, read from the registry when used."""

    def __init__(self, field: str) -> None:
        self._field = field

    def _values(self) -> dict[str, int]:
        from harness.integrators import entries
        return {name: getattr(e, self._field) for name, e in entries().items()}

    def __getitem__(self, name: str) -> int:
        return self._values()[name]

    def __iter__(self):
        return iter(self._values())

    def __len__(self) -> int:
        return len(self._values())

    def __repr__(self) -> str:
        return repr(self._values())


INTEGRATORS = _Integrators()
#: Cases of scenes/ whose estimators are so heavy-tailed (a point light 0.02 from a wall: 1/r^2 within a
#: pixel) that at the integrator's tested samples a 5 % bias stays below what the family-wise level detects:
#: their tested renders take this many times the samples, enough to decide them.
SPP_FACTOR = {"close_light:simple": 4, "close_light:direct": 16, "close_light:path": 16}
#: Cases of scenes/ whose estimator's own rare samples lie far above its pixels' means, with why: there the
#: firefly test (a pixel's variance against its reference neighbourhood's, harness/statistics/excess_spread.py)
#: is not made; every test of the mean and the image-wide variance ratio still are. Under path the light
#: reflected off the wall beside close_light's point light reaches pixels of mean near 1 as samples of 3000 to
#: 3800, about 1e-5 of them: a tested pixel that met one shows 70 to 3000 times the variance of a reference
#: neighbourhood that met fewer, though both engines draw such samples alike (over the image, 4096 samples a
#: pixel each: the share above 10, 100, 1000 and 3000 within 3 % of each other).
#: On materials, light reaches the floor off the mirrors and through the glass by BSDF samples alone (caustics):
#: a floor pixel of mean 0.05 meets a sample of 6 now and then. Both engines draw them alike: in 256 batches of 16
#: samples of every pixel, batch means above 1, 2 and 4 number 22473, 5183 and 2441 in ours and 22396, 5226 and
#: 2432 in Mitsuba's; on the dimmest floor (mean 0.092) 601 and 567 above 0.5.
#: In the Cornell boxes the green light on the red wall (reflectance 0.03 in G) comes from rare paths off the green
#: wall: at 16 samples a pixel our path failed the firefly test at seeds 3, 4 and 5 of cornell and 4 of
#: cornell_measured (50 to 150 times, limits 40 to 50), as the example engine file's path did at seed 2. Mitsuba
#: draws the same tail: on cornell, 256 batches of 16 samples in G, batch means above 5, 10, 20 and 40 times the
#: pixel's mean number 396, 31, 4 and 0 in ours and 361, 29, 6 and 1 in Mitsuba's.
HEAVY_TAILED = {"close_light:path": "light off the wall beside the point light reaches 1e-5 of the samples at "
                                    "thousands of times the pixel's mean",
                "materials:path": "caustics off the mirrors and through the glass reach the floor as rare samples "
                                  "100 times its pixels' mean",
                "cornell:path": "green light on the red wall comes from rare paths off the green wall, as batches "
                                "up to 40 times the pixel's mean in Mitsuba's renders too",
                "cornell_measured:path": "green light on the red wall comes from rare paths off the green wall (as "
                                         "cornell:path)"}
#: Samples per pixel per batch: the tested engine's in every run, the reference engine's for stored references.
TESTED_SPP = _Budget("tested_spp")
REFERENCE_SPP = _Budget("reference_spp")


@dataclass(frozen=True)
class ImageCase:
    """One comparison: a scene with one of our integrators."""

    scene: str        # file stem in the group's folder
    integrator: str
    group: str = "synthetic"  # "synthetic" (scenes/), "real" (scenes/real/) or "user" (--scene)
    #: Where the project's files are: ROOT, or a worker's copy of them (harness/distributed/bundle.py); for a
    #: user's scene, the folder of its prepared copy (harness/images/user_scenes.py).
    root: Path = field(default=ROOT, compare=False, repr=False)
    #: A user's scene file as given (--scene), for reports and the command that reproduces the case.
    source: str = field(default="", compare=False)
    #: Why a user's scene cannot be rendered at all (its cases fail with it), or "".
    problem: str = field(default="", compare=False)
    #: What the preparation of a user's scene left out, one line each (a Nori file's own integrator), or ().
    notes: tuple[str, ...] = field(default=(), compare=False)
    #: Samples per pixel per batch of the tested engine's render where a budget chose them (--detect-bias);
    #: None: the integrator's default (TESTED_SPP, times the case's SPP_FACTOR).
    spp: int | None = field(default=None, compare=False)
    #: The dialect of the user's scene file as given: "mitsuba", or "nori" (a reference image of it is Nori's).
    dialect: str = field(default="mitsuba", compare=False)
    #: Per line of a user's prepared copy, the line of the file as given it came from (0: none; empty: none
    #: known): an engine's error then names the user's line (harness/images/copy_lines.py).
    source_lines: tuple[int, ...] = field(default=(), compare=False, repr=False)
    #: Where an unforeseen error in preparing the copy arose (the case's `problem`), for the run's log.
    traceback: str = field(default="", compare=False, repr=False)

    @property
    def test_spp(self) -> int:
        factor = SPP_FACTOR.get(self.key, 1) if self.group == "synthetic" else 1
        return self.spp or TESTED_SPP[self.integrator] * factor

    @property
    def heavy_tail(self) -> str:
        """Why the firefly test is not made on this case (HEAVY_TAILED), or ""."""
        return HEAVY_TAILED.get(self.key, "") if self.group != USER else ""

    @property
    def key(self) -> str:
        return f"{self.scene}:{self.integrator}"

    @property
    def folder(self) -> Path:
        return self.root if self.group == USER else self.root / GROUP_DIRS[self.group].relative_to(ROOT)

    @property
    def path(self) -> Path:
        return self.folder / f"{self.scene}.xml"


def scene_names(group: str = "synthetic") -> list[str]:
    return sorted(p.stem for p in GROUP_DIRS[group].glob("*.xml") if not p.name.startswith("."))


def scene_cases(user: Sequence[UserScene] | None = None, with_suite: bool = False) -> list[ImageCase]:
    """One case per scene (its integrator left empty): the suite's, unless user scenes replace it, then the
    user's. ValueError for a user scene named as one of the suite's it runs beside, or when the suite's scenes
    are wanted and not found (an installed harness away from its clone: harness/project.py)."""
    if (not user or with_suite) and missing_reason(ROOT):
        raise ValueError(missing_reason(ROOT))
    suite = [ImageCase(s, "", group) for group in GROUP_DIRS for s in scene_names(group)] \
        if not user or with_suite else []
    taken = {c.scene for c in suite}
    for u in user or ():
        if u.name in taken:
            raise ValueError(f"--scene {u.source}: the suite has a scene called {u.name} too; rename the file "
                             "or run it without --with-suite")
    return suite + [ImageCase(u.name, "", USER, u.prepared.parent, str(u.source), u.problem, u.notes,
                              dialect=u.dialect, source_lines=u.source_lines, traceback=u.traceback)
                   for u in user or ()]


def _all_cases(integrators: Sequence[str] | None = None, user: Sequence[UserScene] | None = None,
               with_suite: bool = False) -> tuple[list[ImageCase], list[tuple[ImageCase, str]]]:
    """Every case that can run, and every one that cannot with why (the entry's scene requirement)."""
    from harness.integrators import entry

    runnable, not_applicable = [], []
    for scene in scene_cases(user, with_suite):
        for name in suite_integrators(integrators):
            case = replace(scene, integrator=name)
            # A scene that cannot be rendered fails its cases with why; whether they apply is moot.
            reason = "" if case.problem else entry(name).not_applicable(case.path)
            (not_applicable.append((case, reason)) if reason else runnable.append(case))
    return runnable, not_applicable


def _chosen(cases, only: list[str] | None, key=lambda c: c):
    return [x for x in cases if not only or key(x).key in only or key(x).scene in only or key(x).integrator in only]


def select_cases(only: list[str] | None, integrators: Sequence[str] | None = None,
                 user: Sequence[UserScene] | None = None, with_suite: bool = False) -> list[ImageCase]:
    """All runnable cases, normals first per scene; `only` takes scene names, integrator names or
    scene:integrator; `integrators`: those the engine under test renders (None: our renderer's); `user`: the
    scenes of --scene, instead of the suite's or (`with_suite`) after them.
    A case named in `only` that is not applicable is an error saying why."""
    runnable, not_applicable = _all_cases(integrators, user, with_suite)
    if not only:
        return runnable
    cases = [*runnable, *(c for c, _ in not_applicable)]
    known = {c.key for c in cases} | {c.scene for c in cases} | set(suite_integrators(integrators))
    unknown = sorted(set(only) - known)
    from harness.integrators import entries
    rendered = suite_integrators(integrators)
    for name in unknown:  # scene:normals, or normals, where the engine under test renders no normals
        integrator = name.rpartition(":")[2]
        if integrator in entries() and integrator not in rendered and name.rpartition(":")[0] in ("", *known):
            raise ValueError(f"--only {name}: the engine under test does not render {integrator} (it renders "
                             f"{', '.join(rendered) or 'none of them'})")
    if unknown:
        raise ValueError(f"unknown scene or case {', '.join(unknown)}: scenes are "
                         f"{', '.join(dict.fromkeys(c.scene for c in cases))}; integrators "
                         f"{', '.join(suite_integrators(integrators))}")
    for case, reason in not_applicable:
        if case.key in only:
            raise ValueError(f"{case.key} is not applicable: {reason} ({case.source or case.path.relative_to(ROOT)})")
    return _chosen(runnable, only)


def not_applicable_cases(only: list[str] | None, integrators: Sequence[str] | None = None,
                         user: Sequence[UserScene] | None = None,
                         with_suite: bool = False) -> list[tuple[ImageCase, str]]:
    """The cases `only` would name that cannot run, each with the entry's reason."""
    return _chosen(_all_cases(integrators, user, with_suite)[1], only, key=lambda pair: pair[0])

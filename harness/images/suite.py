"""The image-validation suite: every scene of scenes/ with every integrator, its budgets and references."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCENES_DIR = ROOT / "scenes"
INTEGRATORS = ("normals", "simple", "ao")

#: Samples per pixel per batch: ours in every run, Mitsuba's for stored references.
OUR_SPP = {"normals": 16, "simple": 32, "ao": 32}
REFERENCE_SPP = {"normals": 64, "simple": 256, "ao": 256}

#: Scenes whose Mitsuba reference is another scene file that must give the same image.
#: far_from_origin is sphere_plane scaled by 1000 and moved 1e5 from the origin: the same image,
#: rendered by Mitsuba where its ray offset ((1 + max|p|) * 9e-5) is not stretched by the distance.
MITSUBA_SCENE = {"far_from_origin": "sphere_plane"}


@dataclass(frozen=True)
class ImageCase:
    """One comparison: a scene with one of our integrators."""

    scene: str        # file stem in scenes/
    integrator: str

    @property
    def key(self) -> str:
        return f"{self.scene}:{self.integrator}"

    @property
    def path(self) -> Path:
        return SCENES_DIR / f"{self.scene}.xml"

    @property
    def mitsuba_path(self) -> Path:
        return SCENES_DIR / f"{MITSUBA_SCENE.get(self.scene, self.scene)}.xml"


def scene_names() -> list[str]:
    return sorted(p.stem for p in SCENES_DIR.glob("*.xml") if not p.name.startswith("."))


def select_cases(only: list[str] | None) -> list[ImageCase]:
    """All cases, normals first per scene; `only` takes scene names, integrator names or scene:integrator."""
    cases = [ImageCase(s, i) for s in scene_names() for i in INTEGRATORS]
    if not only:
        return cases
    chosen = [c for c in cases if c.key in only or c.scene in only or c.integrator in only]
    known = {c.key for c in cases} | set(scene_names()) | set(INTEGRATORS)
    unknown = sorted(set(only) - known)
    if unknown:
        raise ValueError(f"unknown scene or case {', '.join(unknown)}: scenes are {', '.join(scene_names())}; "
                         f"integrators {', '.join(INTEGRATORS)}")
    return chosen

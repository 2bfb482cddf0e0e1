"""The example renderer's engine file (examples/renderer/pyrender.toml) as the tests use it: optionally with one of
its planted bugs, or sampling sphere lights by area (another estimator of direct). One call a render, as the
file says: each call pays pyrender's start-up (Mitsuba's import and scene load, about half a second), and the
test processes already keep both cores busy (calls at once: tests/engines/test_command_engine.py)."""
from __future__ import annotations

from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "renderer"


def pyrender_engine(tmp_path: Path, bug: str | None = None, *, sphere_by_area: bool = False,
                    other_estimators: tuple[str, ...] = ()) -> Path:
    """examples/renderer/pyrender.toml with `--bug BUG` planted, with `--sphere-sampling area`
    where `sphere_by_area`, and declaring `other_estimators` (a copy in tmp_path)."""
    text = (EXAMPLE / "pyrender.toml").read_text().replace("{here}", str(EXAMPLE))
    words = (["--bug", bug] if bug else []) + (["--sphere-sampling", "area"] if sphere_by_area else [])
    name = "-".join(["pyrender", *([bug] if bug else []), *(["sphere-by-area"] if sphere_by_area else []),
                     *(["declared"] if other_estimators else [])])
    text = text.replace('name = "pyrender"', f'name = "{name}"')
    text = text.replace('"-o", "{output}"]', '"-o", "{output}"' + "".join(f', "{w}"' for w in words) + "]")
    if other_estimators:
        listed = ", ".join(f'"{i}"' for i in other_estimators)
        text = text.replace("[integrators]", f"other_estimators = [{listed}]\n\n[integrators]")
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    return path

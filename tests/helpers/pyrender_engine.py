"""The example renderer's engine file (examples/renderer/pyrender.toml) as the tests use it: two calls at once,
optionally with one of its planted bugs."""
from __future__ import annotations

from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "renderer"


def pyrender_engine(tmp_path: Path, bug: str | None = None) -> Path:
    """examples/renderer/pyrender.toml, two calls at once, with `--bug BUG` planted (a copy in tmp_path)."""
    text = (EXAMPLE / "pyrender.toml").read_text().replace("{here}", str(EXAMPLE))
    text = text.replace("jobs = 1", "jobs = 2")
    if bug:
        text = text.replace('name = "pyrender"', f'name = "pyrender-{bug}"')
        text = text.replace('"-o", "{output}"]', f'"-o", "{{output}}", "--bug", "{bug}"]')
    path = tmp_path / f"pyrender-{bug or 'correct'}.toml"
    path.write_text(text)
    return path

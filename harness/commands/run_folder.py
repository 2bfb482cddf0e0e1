"""A command's run folder, results/<date>-<time>/, and the one place that finishes a run: results.json,
the index page, the --json copy, and the links (results/latest, ...) that move only once the run is whole."""
from __future__ import annotations

from pathlib import Path

from harness.report.index_page import link_page
from harness.results import latest_run, new_run_dir, point_link, write_atomic, write_json


class RunFolder:
    """The run folder of one command under `out` (made by `start`), and what `latest` pointed at before."""

    def __init__(self, out: Path) -> None:
        self.out = out
        self.path: Path | None = None
        self.previous = latest_run(out)

    def start(self) -> Path:
        self.path = new_run_dir(self.out)
        return self.path

    def finish(self, payload: dict, links: tuple[str, ...] = ("latest",), index: tuple[str, str] | None = None,
               json_copy: Path | None = None, name: str = "results.json") -> None:
        """Write `payload` as `name` (and to `json_copy`), report.html as a link to `index` = (href, title)
        if given, then point each of `links` (folders beside the run) at this run."""
        assert self.path is not None, "finish() before start()"
        write_json(self.path / name, payload)
        if index is not None:
            write_atomic(self.path / "report.html", link_page(*index))
        if json_copy is not None:
            write_json(json_copy, payload)
        for link in links:
            point_link(self.out / link, self.path)

    def unfinished(self, what: str) -> str:
        """One line: where an unfinished run's partial output is, and that `latest` did not move."""
        if self.path is None:
            return what
        kept = f"{self.out / 'latest'} still points at {self.previous}" if self.previous \
            else f"{self.out / 'latest'} was not created"
        return f"{what}: partial output in {self.path}/; {kept}"

"""Where an image case's renders come from. A case task asks one CaseRenders for each of them and gets an
image or an exception; whether a render began before the case asked is the strategy's business
(harness/images/render_ahead.py), never the case's."""
from __future__ import annotations

from harness.engines.analytic import AnalyticEngine
from harness.engines.base import Engine, RenderResult
from harness.images.references import Reference, render_params, render_reference
from harness.images.strategy_renders import strategy_file, strategy_seed
from harness.images.suite import ImageCase
from harness.statistics.constants import IMAGE_BATCHES


def render_args(case: ImageCase, seed: int, params: dict[str, str]) -> tuple:
    """The arguments of the tested engine's render of `case` (Engine.render), wherever it is started."""
    return str(case.path), case.integrator, case.test_spp, IMAGE_BATCHES, seed, params


def closed_form_args(case: ImageCase, seed: int, params: dict[str, str]) -> tuple:
    """The arguments of the analytic engine's render of `case`: its own samples and seed beside the tested
    engine's."""
    spp = AnalyticEngine.samples_for(case.integrator, case.test_spp)
    return str(case.path), case.integrator, spp, IMAGE_BATCHES, seed + 1, params


class CaseRenders:
    """The renders of image cases by a tested and a reference engine, each made when a case asks for it, where
    it asks (in this process or on a worker: this is what any executor's task carries)."""

    def __init__(self, tested: Engine, reference: Engine) -> None:
        self.tested_engine, self.reference_engine = tested, reference

    def tested(self, case: ImageCase, seed: int) -> RenderResult:
        """The tested engine's K batches of `case` at the case's own `seed`."""
        return self.tested_engine.render(*render_args(case, seed, render_params(case)))

    def reference(self, case: ImageCase) -> Reference:
        """The reference engine's render of `case` at the reference budget, summarised."""
        return render_reference(case, self.reference_engine)

    def closed_form(self, case: ImageCase, seed: int) -> RenderResult:
        """The closed form's batches of `case` (AnalyticEngine), beside the tested render at `seed`."""
        return AnalyticEngine().render(*closed_form_args(case, seed, render_params(case)))

    def strategy(self, case: ImageCase, strategy: str, seed: int) -> RenderResult:
        """The tested engine's K batches of `case` with its integrator set to `strategy` (one of the entry's
        `strategies`), beside the case's render at `seed` (harness/images/strategy_renders.py)."""
        _, integrator, spp, batches, _, params = render_args(case, seed, render_params(case))
        with strategy_file(self.tested_engine, case, strategy) as scene:
            return self.tested_engine.render(str(scene), integrator, spp, batches, strategy_seed(seed, strategy, case),
                                             params)

    def close(self) -> None:
        """End what the strategy started and no case asked for (nothing here)."""

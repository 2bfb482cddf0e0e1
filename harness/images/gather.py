"""A case's renders gathered as data for harness/images/evaluate.py: each render, or the RenderFailure that
took its place. The order is the cost's: a stored reference is read first; without one the tested engine
renders before the reference engine (a scene it cannot load costs no reference render); the closed form comes
last. A failed render ends the gathering: what it would have been spent on is not rendered."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from harness.comparison.summary import summarize
from harness.engines.analytic import AnalyticEngine
from harness.engines.base import RenderFailed, RenderResult
from harness.images.case_renders import CaseRenders
from harness.images.evaluate import RenderFailure
from harness.images.references import CLOSED_FORM, Reference, load_reference
from harness.images.scale_twins import SCALE_TWIN, twin_case, twin_label
from harness.images.strategy_renders import default_strategy
from harness.images.suite import USER, ImageCase
from harness.integrators import entry

@dataclass(kw_only=True)
class GatheredRenders:
    """What evaluate() takes: the tested render, each reference by name, and where the reference engine's came
    from (its `source`, for the report)."""

    tested: RenderResult | RenderFailure | None = None
    references: dict[str, Reference | RenderFailure] = field(default_factory=dict)
    source: str = "none"
    #: The tested engine's renders of the integrator's strategies by name, or the failure that ended them.
    strategies: dict[str, RenderResult | RenderFailure] = field(default_factory=dict)

    @property
    def tested_render(self) -> RenderResult | None:
        return self.tested if isinstance(self.tested, RenderResult) else None

    @property
    def rendered_references(self) -> dict[str, Reference]:
        return {name: r for name, r in self.references.items() if isinstance(r, Reference)}


def _reason(e: Exception) -> str:
    """One line saying why a render failed."""
    if isinstance(e, RenderFailed):
        return e.reason
    text = str(e).strip().splitlines()
    if text and type(e) is RuntimeError:  # how Mitsuba raises its own errors ("[parser.cpp:N] ..."): its words
        return text[0]
    return f"{type(e).__name__}: {text[0]}" if text else type(e).__name__


def failure_of(stage: str, e: Exception, output: bool = True) -> RenderFailure:
    """The failure of a render at `stage` ("mcval render", "Mitsuba reference", ...) that raised `e`, with what
    the engine printed last (`output`)."""
    return RenderFailure(reason=f"{stage}: {_reason(e)}",
                         output=e.output if output and isinstance(e, RenderFailed) else "")


def _strategies(case: ImageCase, renders: CaseRenders, seed: int,
                tested: RenderResult) -> dict[str, RenderResult | RenderFailure]:
    """The tested engine's render of each strategy of the case's integrator (the case's own render where it is
    one), up to the first that fails."""
    engine = renders.tested_engine
    own = default_strategy(case, engine.scene_file(case.path))
    out: dict[str, RenderResult | RenderFailure] = {}
    for name, _ in entry(case.integrator).strategies.settings:
        try:
            out[name] = tested if name == own else renders.strategy(case, name, seed)
        except Exception as e:
            out[name] = failure_of(f"{engine.name} render of the {name} strategy", e)
            break
    return out


def gather(case: ImageCase, renders: CaseRenders, *, seed: int, closed_form: bool, strategies: bool = False,
           on_message: Callable[[str], None] | None = None) -> GatheredRenders:
    """The renders of `case` (none for a case with a `problem`): the reference engine's stored reference or,
    without one, its render now; the tested engine's batches at `seed`; the closed form's where `closed_form`,
    else the reference engine's render of the scene's scale twin where it has one
    (harness/images/scale_twins.py); the tested engine's strategies of the integrator where `strategies`.
    `on_message` hears that a reference is rendered now."""
    out = GatheredRenders()
    if case.problem:  # a --scene file no engine can be given (what its preparation refused)
        return out
    name = renders.reference_engine.name
    shown = f"{name.capitalize()} reference"

    def tested() -> RenderResult | RenderFailure:
        try:
            return renders.tested(case, seed)
        except Exception as e:
            return failure_of(f"{renders.tested_engine.name} render", e)

    try:
        reference, out.source = load_reference(case, renders.reference_engine)
    except Exception as e:
        out.references[name] = failure_of(shown, e)
        return out
    if reference is None:
        # The engine under test renders first: a file it cannot load costs no reference render.
        out.tested = tested()
        if isinstance(out.tested, RenderFailure):
            return out
        if on_message:
            on_message(f"{case.key}: {out.source}; rendering it now" +
                       ("" if case.group == USER else " (`make references` stores it)"))
        try:
            reference = renders.reference(case)
        except Exception as e:
            out.references[name] = failure_of(shown, e)
            return out
        out.source = f"rendered now ({out.source})"
    out.references[name] = reference
    out.tested = out.tested or tested()
    if isinstance(out.tested, RenderFailure):
        return out
    if closed_form:
        try:
            exact = renders.closed_form(case, seed)
        except Exception as e:
            out.references[AnalyticEngine.name] = failure_of("closed form", e, output=False)
            return out
        out.references[AnalyticEngine.name] = Reference(summarize(exact.batches), exact.spp, exact.seconds,
                                                        CLOSED_FORM)
    elif (twin := twin_case(case)) is not None:
        label = twin_label(case, name)
        try:
            found, _ = load_reference(twin, renders.reference_engine)
            found = found or renders.reference(twin)
        except Exception as e:
            out.references[label] = failure_of(f"{name.capitalize()} reference of {twin.key}", e)
            return out
        out.references[label] = Reference(found.summary, found.spp, found.seconds, SCALE_TWIN)
    if strategies:
        out.strategies = _strategies(case, renders, seed, out.tested)
    return out

"""direct: light from every emitter at the first hit, by emitter sampling, BSDF sampling and multiple importance
sampling between them (Mitsuba 3's `direct`)."""
import xml.etree.ElementTree as ET

from harness.closed_forms import furnace, lit_plane
from harness.integrators.entry import AnalyticForm, IntegratorEntry, Strategies

#: The emitters it reads: delta lights, the environment (constant or an envmap's image) and area emitters on shapes.
EMITTERS = ("point", "spot", "directional", "constant", "envmap", "area")
#: Those that sit at a point or along a direction: no BSDF sample finds them (a projector too, which an engine
#: that models it may be given: the requirement lets every emitter through).
DELTA_EMITTERS = ("point", "spot", "directional", "projector")
#: BSDFs with a delta lobe (a mirror's, a glass's, a plastic's coat, a mask's hole): the light they pass on from an
#: emitter is found by BSDF samples only.
DELTA_BSDFS = ("conductor", "dielectric", "thindielectric", "plastic", "mask")


def has_emitter(root: ET.Element) -> str | None:
    """A requirement: an emitter (without one the image is black, which proves nothing). Any emitter counts: one
    of a kind the engine does not model (a projector) is the engine's refusal, naming it, not a scene without
    light."""
    return None if any(True for _ in root.iter("emitter")) else "no emitter"


def no_delta_lights(root: ET.Element) -> str | None:
    """Where emitter samples and BSDF samples can each find every light: a delta light's light reaches emitter
    samples only."""
    delta = sorted({e.get("type") for e in root.iter("emitter") if e.get("type") in DELTA_EMITTERS})
    return f"{' and '.join(delta)} lights, which BSDF sampling never finds" if delta else None


def no_masks(root: ET.Element) -> str | None:
    """Where the light a path's emitter samples find is the light its BSDF samples find: a mask's holes let BSDF
    samples through, while shadow rays stop at the mask (Mitsuba's path tests visibility so; ours follows it)."""
    return "a mask, whose holes BSDF samples pass and shadow rays do not" if any(
        b.get("type") == "mask" for b in root.iter("bsdf")) else None


def strategies_agree(root: ET.Element) -> str | None:
    """Where emitter sampling alone, BSDF sampling alone and MIS estimate one image: no delta light, and no delta
    lobe, through which only a BSDF sample finds an emitter."""
    if why := no_delta_lights(root):
        return why
    delta = sorted({b.get("type") for b in root.iter("bsdf") if b.get("type") in DELTA_BSDFS})
    return f"{' and '.join(delta)} bsdfs, whose delta lobes emitter sampling never follows" if delta else None


def _samples(emitter: int, bsdf: int) -> tuple:
    return (("integer", "emitter_samples", str(emitter)), ("integer", "bsdf_samples", str(bsdf)))


#: Emitter sampling alone ("ems"), BSDF sampling alone ("mats"), both with MIS ("mis"): Nori's direct_ems,
#: direct_mats and direct_mis.
STRATEGIES = Strategies(settings=(("ems", _samples(1, 0)), ("mats", _samples(0, 1)), ("mis", _samples(1, 1))),
                        applies=strategies_agree)


ENTRY = IntegratorEntry(
    name="direct",
    # Two rays a sample beside the camera ray, traced one at a time: the suite's costliest renders. At 16 spp x 8
    # batches a bias of the image mean of 1.7 % or less is found half of the time on every suite scene (0.06-0.7 %
    # on most); close_light takes SPP_FACTOR's 16 times (harness/images/suite.py).
    tested_spp=16,
    reference_spp=256,
    emitters=EMITTERS,
    # Mitsuba's defaults: shading_samples = 1 of each strategy.
    parameters=(("integer", "emitter_samples", "1"), ("integer", "bsdf_samples", "1")),
    analytic=AnalyticForm("rho/pi * E under one rectangle, disk or sphere light (Lambert's polygon formula, the "
                          "disk's off-axis form factor, pi L (r/d)^2 cos); Le (1 + a) in a furnace",
                          lit_plane.radiance, scenes=("lit_plane",), furnace=furnace.direct_radiance,
                          draws_estimator=False),
    requirements=(("an emitter", has_emitter),),
    strategies=STRATEGIES,
    # Linear in the light only: where the camera sees an area light, its pixels keep their radiance when every
    # reflectance is scaled.
    linear_in=("light",),
)

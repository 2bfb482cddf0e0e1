"""Writes sphere_floor_{milli,unit,kilo}.xml: an exact sphere (radius R = 1e-3, 1, 1e3) resting on a large
diffuse floor, the same image at every scale. Run from anywhere: python scenes/make_sphere_floor.py

Every length scales with R and the light's intensity with R^2, so the radiance is the same at every scale;
what changes is only how each renderer's ray offsets compare with R (contact shadow and occlusion).
The closed forms (harness/closed_forms/sphere.py) need the floor to reach 1e4 radii from the contact
point; it reaches 2e4.
"""
from pathlib import Path

SCALES = {"milli": 1e-3, "unit": 1.0, "kilo": 1e3}

TEMPLATE = """<?xml version="1.0" encoding="utf-8"?>
<!--
  sphere_floor_{name}.xml: ANALYTIC. An exact sphere of radius R = {r} resting on
  a grey diffuse floor z = 0 (z up), tangent at the origin, written by
  scenes/make_sphere_floor.py (every length is R times that of the unit scene,
  the light's intensity R^2 times, so the image is the same at every scale).
  Closed forms (harness/closed_forms/sphere.py), rho the surface's reflectance:
    ao, floor point at distance D from the centre:  rho * (1 - (R/D)^3)
    ao, sphere point with normal n:                  rho * (1 + n_z) / 2
    simple: rho / pi * I * max(0, cos) / r^2, floor points behind the sphere dark.
  The floor reaches 2e4 R from the contact point, so the directions it misses
  change ao on the sphere by under 1.3e-4 of rho (floor points see nothing else).
-->
<scene version="3.0.0">
    <!-- Parameters, overridable from the command line / loader ($name). -->
    <default name="integrator" value="simple"/>
    <default name="spp" value="16"/>
    <default name="res" value="128"/>

    <integrator type="$integrator"/>

    <!-- Camera looking down at the sphere from the front right: every pixel
         sees the floor or the sphere within 20 R (the top corners look down
         by about 12 degrees). The clip planes scale with R. -->
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <float name="near_clip" value="{near}"/>
        <float name="far_clip" value="{far}"/>
        <transform name="to_world">
            <lookat origin="{cam}" target="{target}" up="0, 0, 1"/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="$spp"/>
        </sampler>
        <film type="hdrfilm">
            <integer name="width" value="$res"/>
            <integer name="height" value="$res"/>
            <rfilter type="box"/>
        </film>
    </sensor>

    <!-- Floor z = 0 (normal +z), half-size 2e4 R, tiled: a central square of
         half-size 32 R holds everything the camera sees, four strips the rest.
         With one rectangle, float32 vertices 2e4 R away from the points seen
         put rounding errors of about 1e-3 R into hit points rebuilt from its
         barycentrics: the lit floor came out 3e-4 too bright at R = 1e-3. -->
{floor}
    <!-- The sphere, exact (not a mesh), resting on the floor at the origin. -->
    <shape type="sphere">
        <point name="center" value="{center}"/>
        <float name="radius" value="{r}"/>
        <bsdf type="diffuse">
            <rgb name="reflectance" value="0.2, 0.35, 0.7"/>
        </bsdf>
    </shape>

    <!-- Point light above, behind and to the left: the shadow falls towards
         the camera and touches the contact point. Used by simple. -->
    <emitter type="point">
        <point name="position" value="{light}"/>
        <rgb name="intensity" value="{intensity}"/>
    </emitter>

    <!-- Uniform environment of radiance 1. Used by ao. -->
    <emitter type="constant">
        <rgb name="radiance" value="1, 1, 1"/>
    </emitter>
</scene>
"""


def _v(*xs: float) -> str:
    return ", ".join(f"{x:g}" for x in xs)


#: The central floor tile's half-size and the floor's, in radii.
TILE, FLOOR = 32.0, 2e4

FLOOR_TILE = """    <shape type="rectangle">
        <transform name="to_world">
            <scale x="{hx}" y="{hy}"/>
            <translate x="{cx}" y="{cy}"/>
        </transform>
        <bsdf type="diffuse">
            <rgb name="reflectance" value="0.5, 0.5, 0.5"/>
        </bsdf>
    </shape>"""


def floor_tiles(r: float) -> list[tuple[float, float, float, float]]:
    """(centre x, centre y, half-width, half-height) of the five rectangles that tile the floor square."""
    t, f = TILE * r, FLOOR * r
    side, strip = (f + t) / 2, (f - t) / 2  # the strips left and right of the tile span the whole height
    return [(0.0, 0.0, t, t), (-side, 0.0, strip, f), (side, 0.0, strip, f), (0.0, -side, t, strip), (0.0, side, t, strip)]


def scene_text(name: str, r: float) -> str:
    return TEMPLATE.format(name=name, r=f"{r:g}", near=f"{1e-2 * r:g}", far=f"{1e3 * r:g}",
                           cam=_v(2.2 * r, -3.3 * r, 3.2 * r), target=_v(0, 0, 0.5 * r),
                           floor="\n".join(FLOOR_TILE.format(cx=f"{cx:.9g}", cy=f"{cy:.9g}", hx=f"{hx:.9g}", hy=f"{hy:.9g}")
                                            for cx, cy, hx, hy in floor_tiles(r)),
                           center=_v(0, 0, r), light=_v(-2.5 * r, 1.0 * r, 4.0 * r),
                           intensity=_v(*[40 * r * r] * 3))


if __name__ == "__main__":
    here = Path(__file__).resolve().parent
    for name, r in SCALES.items():
        (here / f"sphere_floor_{name}.xml").write_text(scene_text(name, r))

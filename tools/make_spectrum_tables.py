"""Writes renderer/spectrum_tables.inc: the CIE 1931 colour matching functions and the D65 illuminant (normalised)
at every nanometre from 360 to 830, as Mitsuba 3 tabulates them (mi.cie1931_xyz, mi.cie_d65, which interpolate
linearly between these points), for the renderer's conversion of per-wavelength spectra to RGB
(renderer/spectrum_rgb.cpp). Run again only if Mitsuba's tables change: python tools/make_spectrum_tables.py"""
from pathlib import Path

import mitsuba as mi

OUT = Path(__file__).resolve().parents[1] / "renderer" / "spectrum_tables.inc"


def main() -> None:
    mi.set_variant("scalar_rgb")
    lo, hi = int(mi.MI_CIE_MIN), int(mi.MI_CIE_MAX)
    rows = []
    for nm in range(lo, hi + 1):
        x, y, z = mi.cie1931_xyz(float(nm))
        rows.append(f"    {{{float(x)!r}f, {float(y)!r}f, {float(z)!r}f, {float(mi.cie_d65(float(nm)))!r}f}},")
    OUT.write_text(f"// Written by tools/make_spectrum_tables.py from Mitsuba {mi.__version__}: x, y, z, D65 at each nm from "
                   f"{lo} to {hi}.\n" + "\n".join(rows) + "\n")


if __name__ == "__main__":
    main()

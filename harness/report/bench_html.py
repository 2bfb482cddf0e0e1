"""The speed-against-error page."""
from __future__ import annotations

import base64
import html

from harness.bench.run import SAME_SAMPLER, CaseBench
from harness.report.bench_plots import convergence_png, equal_time_png
from harness.report.style import CSS
from harness.bench.throughput import REFERENCE, TESTED, WORKER


def _img(png: bytes, alt: str) -> str:
    return f'<img alt="{html.escape(alt)}" src="data:image/png;base64,{base64.b64encode(png).decode()}">'


def _f(x: float, fmt: str = ".3g") -> str:
    # NaN: the error fell below what the reference's own noise lets us measure.
    return "below ref. noise" if x != x else format(x, fmt)


def _best(b: CaseBench) -> str:
    best = b.comparison(None)
    if best["missing"]:
        return f"no {html.escape(' or '.join(best['missing']))} curve"
    return f"{_f(best['ratio'])} ({html.escape(str(best['tested']))} / {html.escape(str(best['reference']))})"


def _same(b: CaseBench) -> str:
    same = b.comparison(SAME_SAMPLER)
    return f"no {html.escape(' or '.join(same['missing']))} curve" if same["missing"] else _f(same["ratio"])


def _throughput_html(throughput: list[dict] | None) -> str:
    if not throughput:
        return "<p>No side-by-side throughput (run <code>mcval bench</code> with both engines).</p>"
    nan = {TESTED: float("nan"), REFERENCE: float("nan")}
    rows = "".join(
        f"<tr><td>{t['scene']}:{t['integrator']}</td><td>{html.escape(t['engines'][REFERENCE])}</td>"
        f"<td>{t['resolution']}², {t['spp']} spp, {t['sampler']}</td>"
        f"<td>{t['median_seconds'][TESTED]:.3f}</td><td>{t['median_seconds'][REFERENCE]:.3f}</td>"
        f"<td class='{'pass' if t['reference_over_tested'] >= 1 else 'fail'}'>{t['reference_over_tested']:.2f}</td>"
        + (f"<td>{t['median_seconds'][WORKER]:.3f}</td><td class='{'pass' if t['reference_over_tested_worker'] >= 1 else 'fail'}'>"
           f"{t['reference_over_tested_worker']:.2f}</td>" if "reference_over_tested_worker" in t else "<td>–</td><td>–</td>") +
        f"<td>{t['samples_per_second'][TESTED] / 1e6:.1f}</td><td>{t['samples_per_second'][REFERENCE] / 1e6:.1f}</td>"
        f"<td>{t.get('rays_per_second', nan)[TESTED] / 1e6:.1f}</td>"
        f"<td>{t.get('rays_per_second', nan)[REFERENCE] / 1e6:.1f}</td></tr>"
        for t in throughput)
    return ("<p>Both engines in one process, the same scene file and sampler, render time only, each timed "
            "render after a pause and an untimed one of the same engine (so neither meets the other's threads still "
            "spinning, nor its own asleep); medians of the runs, and the reference over the tested engine the median of "
            "the ratios round by round (each round renders the tested engine, the tested engine in its worker, then the "
            "reference). <em>In its worker</em> is the tested engine as "
            "<code>images</code> and <code>validate</code> run it: the <code>render --serve</code> call's wall clock "
            "(the request, the images written and read) less the scene load and BVH build. Rays/s divide the rays the tested engine traced, for "
            "both engines (Mitsuba's direct traces about as many for simple; for ao it adds a BSDF-sampled ray per hit, its MIS).</p><table><tr><th>case</th><th>reference</th><th>setting</th><th>tested s</th>"
            "<th>reference s</th><th>reference/tested per sample</th><th>tested in its worker s</th>"
            "<th>reference/worker</th><th>tested Msamples/s</th><th>reference Msamples/s</th>"
            f"<th>tested Mrays/s</th><th>reference Mrays/s</th></tr>{rows}</table>")


def _slopes_html(slopes: dict | None) -> str:
    if not slopes:
        return "<p>Not measured (our engine was not run).</p>"
    samplers = list(next(iter(slopes["slopes"].values())))
    rows = "".join(f"<tr><td>{k}</td>" + "".join(f"<td>{v[s]:.2f}</td>" for s in samplers) + "</tr>"
                   for k, v in slopes["slopes"].items())
    return (f"<p>Our samplers on {slopes['scene']} at {slopes['resolution']}², {slopes['spp'][0]} to "
            f"{slopes['spp'][-1]} spp, MSE against our own {slopes['reference_spp']}-spp image, averaged over "
            f"{slopes['seeds']} seeds: the slope of log MSE against log spp. Independent samples should give −1 "
            f"(the test allows −1 ± 0.15); sobol, stratified, steeper than {slopes['expected']['sobol'][2:]}.</p>"
            "<table><tr><th>integrator</th>" + "".join(f"<th>{s}</th>" for s in samplers) + f"</tr>{rows}</table>")


def bench_html(benches: list[CaseBench], rays: dict | None, seed: dict | None, meta: dict,
               throughput: list[dict] | None = None, slopes: dict | None = None) -> str:
    rows = "".join(
        f"<tr><td><a href='#{b.case.key}'>{b.case.scene}</a></td><td>{b.case.integrator}</td>"
        f"<td class='{'fail' if b.efficiency_ratio() < 1 else 'pass'}'>{_same(b)}</td>"
        f"<td>{_best(b)}</td>"
        + "".join(f"<td>{_f(c.fit('spp')[0], '.2f')}</td><td>{_f(c.efficiency())}</td><td>{_f(c.time_to())}</td>"
                  for c in b.curves.values()) + "</tr>" for b in benches)
    engines = list(benches[0].curves) if benches else []
    head = "".join(f"<th>{e} slope</th><th>{e} efficiency</th><th>{e} s to 1e-3</th>" for e in engines)
    sections = []
    for b in benches:
        timing = "; ".join(f"{name}: {c.timing}; first render {c.first_seconds:.2f} s" for name, c in b.curves.items())
        sections.append(f"<h3 id='{b.case.key}'>{b.case.scene} — {b.case.integrator}: efficiency ratio "
                        f"{_same(b)} with the same sampler, {_best(b)} best against best</h3>"
                        f"<p class='meta'>Errors against: {html.escape(b.truth)}. {html.escape(timing)}</p>"
                        + _img(convergence_png(b), f"convergence of {b.case.key}")
                        + "<p>Equal time (the step of each engine closest to the tested engine's at 64 spp):</p>"
                        + _img(equal_time_png(b), f"equal-time images of {b.case.key}"))
    rays_html = "<p>No ray-throughput figures (run <code>make bench</code>).</p>"
    if rays:
        rrows = "".join(f"<tr><td>{k}</td><td>{v['renderer_rays_per_second'] / 1e6:.2f}</td>"
                        f"<td>{v['raw_rays_per_second'] / 1e6:.2f}</td><td>{v['ratio']:.2f}</td></tr>"
                        for k, v in rays["integrators"].items())
        rays_html = (f"<p>{html.escape(rays['scene'])}, {rays['spp']} spp; raw = Embree tracing the same rays "
                     f"with no shading.</p><table><tr><th>integrator</th><th>renderer Mrays/s</th><th>raw Mrays/s</th>"
                     f"<th>ratio</th></tr>{rrows}</table>")
    seed_html = ""
    if seed:
        srows = "".join(f"<tr><td>{k}</td><td>{v['resolution']}², {v['spp']} spp</td><td>{v['seed_seconds']:.1f}</td>"
                        f"<td>{v['seconds']:.2f}</td><td>{_f(v.get('reference_seconds', float('nan')), '.2f')}</td></tr>"
                        for k, v in seed.items())
        seed_html = ("<h2>The seed document's settings</h2><table><tr><th>integrator</th><th>setting</th>"
                     "<th>seed document (s)</th><th>tested, median (s)</th><th>reference, median (s)</th></tr>"
                     f"{srows}</table>")
    meta_html = "".join(f"<li>{html.escape(str(k))}: {html.escape(str(v))}</li>" for k, v in meta.items())
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>mcval speed against error</title><style>{CSS}</style></head>
<body><h1>Speed against error</h1><ul class="meta">{meta_html}</ul>
<p>relMSE is measured against the stored Mitsuba reference with the reference's own variance subtracted.
Efficiency is 1 / (relMSE × seconds), the median over steps of 16 spp and more; a ratio takes it over the steps
both of its curves rendered (a sampler that rounds a sample count skips that step). Each engine runs with each of its
samplers (curves labelled engine/sampler). "Same sampler" is the tested engine (the first) over the next one run
(by default Mitsuba llvm_ad_rgb as shipped), both with independent samples: the engine comparison. "Best against
best" pairs each engine's most efficient stratified sampler on the case (mcval's: Owen-scrambled Sobol; Mitsuba's:
ldsampler or multijitter): what a user gets, named in the cell.
Slopes near −1 mean an unbiased estimator converging at the usual rate; steeper ones come from stratified
sampling; flatter ones are a finding (a bias against the reference). "Below ref. noise": the error fell below
what the reference's own variance lets us measure at 16 spp and more.</p>
<table><tr><th>scene</th><th>integrator</th><th>efficiency ratio, same sampler</th><th>best against best</th>{head}</tr>{rows}</table>
<h2>Sampler convergence</h2>{_slopes_html(slopes)}
<h2>Render throughput, side by side</h2>{_throughput_html(throughput)}
<h2>Ray throughput</h2>{rays_html}
{seed_html}
<h2>Per scene</h2>{''.join(sections)}
</body></html>
"""

"""The one-line mutations of the harness that once survived the whole suite, each applied to a copy of
harness/ and run against the tests meant to kill it: every one must now make them fail.

Deterministic and independent of the mutation tool (`make mutate` runs that). Each mutation is an exact
source line replaced; if the harness is rewritten so that a line is no longer found, the test says so
(update the line here rather than dropping the mutation).
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
REF = "tests/statistics/test_welch_reference.py"
TWINS = "tests/statistics/test_twins.py"

#: name -> (file, original line fragment, mutated fragment, test node ids that must fail).
MUTATIONS = {
    "welch one-sided p-value": (
        "statistics/welch.py", "p = 2.0 * t_sf(np.abs(t), welch_dof(a, b))", "p = t_sf(np.abs(t), welch_dof(a, b))",
        [f"{REF}::test_welch_p_values_match_scipy"]),
    "welch normal instead of t": (
        "statistics/welch.py", "p = 2.0 * t_sf(np.abs(t), welch_dof(a, b))",
        "p = 2.0 * __import__('scipy.stats').stats.norm.sf(np.abs(t))",
        [f"{REF}::test_welch_p_values_match_scipy", f"{REF}::test_welch_uses_satterthwaite_dof_and_t_tails"]),
    "welch pooled dof": (
        "statistics/welch.py", "dof = np.where(dof_den > 0, (va + vb) ** 2 / dof_den, da + db)",
        "dof = np.where(dof_den > 0, da + db, da + db)",
        [f"{REF}::test_welch_p_values_match_scipy", f"{REF}::test_welch_uses_satterthwaite_dof_and_t_tails"]),
    "no sidak split over the three scales": (
        "comparison/compare.py", "per_scale = sidak_level(alpha, len(SCALES) + judged_noise)", "per_scale = alpha",
        [f"{REF}::test_compare_splits_alpha_over_scales_then_pixels_and_channels"]),
    "sidak counts pixels, not channels": (
        "statistics/family_level.py", "share = channel_union(level, channels, rho) / channels", "share = 1.0 / channels",
        [f"{REF}::test_compare_splits_alpha_over_scales_then_pixels_and_channels",
         "tests/statistics/test_family_level.py::test_independent_tests_get_sidaks_level"]),
    "chi-square dof k instead of k - 1": (
        "statistics/chi2.py", "dof = len(exp) - 1", "dof = len(exp)",
        [f"{REF}::test_goodness_of_fit_matches_scipy", f"{REF}::test_goodness_of_fit_pools_small_cells_by_hand"]),
    "pooling threshold 5 -> 1": (
        "statistics/constants.py", "MIN_EXPECTED = 5.0", "MIN_EXPECTED = 1.0",
        [f"{REF}::test_goodness_of_fit_pools_small_cells_by_hand",
         f"{REF}::test_goodness_of_fit_folds_a_too_small_pool_into_the_smallest_bin"]),
    "normalisation tolerance 1e-3 -> 2e-2": (
        "statistics/constants.py", "NORMALISATION_TOLERANCE = 1e-3", "NORMALISATION_TOLERANCE = 2e-2",
        [f"{TWINS}::test_normalisation_half_a_percent_off_fails_and_0_05_percent_passes"]),
    "pdf-vs-Mitsuba tolerance 1e-3 -> 0.3": (
        "statistics/constants.py", "PDF_RELATIVE_TOLERANCE = 1e-3", "PDF_RELATIVE_TOLERANCE = 0.3",
        [f"{TWINS}::test_pdf_one_percent_off_the_reference_fails_and_0_05_percent_passes"]),
    "regression never flags a moved mean": (
        "images/regression.py", "if np.any(z > MEAN_SIGMAS) and np.any(m1 != m0):",
        "if np.any(z > MEAN_SIGMAS) and np.any(m1 != m1):",
        [f"{TWINS}::test_regression_flags_a_mean_moved_by_five_sigma_and_not_one"]),
    "detectable_bias x2": (
        "statistics/detectable_bias.py", "return np.where(live, root, np.inf)", "return np.where(live, 2.0 * root, np.inf)",
        [f"{TWINS}::test_detectable_bias_is_its_definition"]),
    "PSNR with 20 log10": (
        "comparison/metrics.py", "float(10 * np.log10(peak**2 / mse))", "float(20 * np.log10(peak**2 / mse))",
        [f"{REF}::test_psnr_is_its_definition"]),
    "independence: the null mean of a pair's products with the wrong sign": (
        "statistics/independence.py", "centred = gram + per_tile[:, None, None] / (k * (k - 1))",
        "centred = gram - per_tile[:, None, None] / (k * (k - 1))",
        ["tests/statistics/test_independence.py::test_the_p_value_is_near_its_level_for_independent_gaussian_batches"]),
    "a comparison's verdict without its independence check": (
        "comparison/outcome.py", "return (self.trusted and all(s.passed for s in self.scales)",
        "return (self.finite.passed and all(s.passed for s in self.scales)",
        ["tests/comparison/test_independence_check.py::test_repeating_batches_fail_where_the_scales_alone_pass"]),
    "a comparison's verdict without its variance check": (
        "comparison/outcome.py", "and (self.variance is None or self.variance.passed))", "and True)",
        ["tests/comparison/test_variance_check.py::test_a_variance_beyond_the_noise_fails_against_the_same_estimator"]),
    "efficiency ratio inverted": (
        "bench/run.py", "ratio = self.curves[a].efficiency(common) / self.curves[b].efficiency(common)",
        "ratio = self.curves[b].efficiency(common) / self.curves[a].efficiency(common)",
        [f"{REF}::test_efficiency_ratio_has_its_known_answer", f"{TWINS}::test_efficiency_ratio_of_a_twice_slower_twin",
         "tests/bench/test_run.py::test_same_sampler_and_best_against_best_pick_their_curves"]),
}


@dataclass
class Run:
    """pytest's exit code on one copy of harness/, and what it printed."""

    returncode: int
    stdout: str


def _run_all(copies: list[tuple[Path, list[str]]]) -> list[Run]:
    """pytest on each (folder holding a copy of harness/, nodes), with that copy imported instead of the
    project's harness: each in a child forked from one process that has imported the libraries once
    (tests/helpers/mutant_runner.py), two at a time."""
    runs = [{"parent": str(parent), "nodes": nodes, "out": str(parent / "pytest.log")} for parent, nodes in copies]
    res = subprocess.run([sys.executable, str(ROOT / "tests" / "helpers" / "mutant_runner.py"), str(ROOT)],
                         input=json.dumps(runs), capture_output=True, text=True, timeout=600,
                         env=dict(os.environ, PYTHONPATH=""))
    assert res.returncode == 0, res.stderr[-3000:]
    codes = json.loads(res.stdout.strip().splitlines()[-1])
    assert 13 not in codes, "a copy of harness/ is not the one imported"
    return [Run(code, Path(run["out"]).read_text()) for code, run in zip(codes, runs)]


def _copy(parent: Path) -> Path:
    # With its bytecode and the files' times (copy2): every module but the mutated one, whose time and size
    # change, loads without compiling again.
    shutil.copytree(ROOT / "harness", parent / "harness")
    return parent


def _mutate(name: str, parent: Path) -> str:
    """Applies the mutation to a copy of harness/ in `parent`; what stops it, if anything."""
    file, original, mutated, _ = MUTATIONS[name]
    path = _copy(parent) / "harness" / file
    source = path.read_text()
    if source.count(original) != 1:
        return f"{file} no longer holds {original!r}: update the mutation"
    path.write_text(source.replace(original, mutated))
    return ""


#: Every node some mutation must fail: on the unmutated harness they all pass.
TARGETED = sorted({n for *_, targets in MUTATIONS.values() for n in targets})


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """name -> (what stopped the mutation, its run); "" is the unmutated copy, run on every targeted node."""
    copies, problems = {"": (_copy(tmp_path_factory.mktemp("unmutated")), TARGETED)}, {"": ""}
    for name, (*_, nodes) in MUTATIONS.items():
        parent = tmp_path_factory.mktemp("mutant")
        problems[name] = _mutate(name, parent)
        if not problems[name]:
            copies[name] = (parent, nodes)
    done = dict(zip(copies, _run_all(list(copies.values()))))
    return {name: (problem, done.get(name)) for name, problem in problems.items()}


@pytest.mark.slow
def test_the_targeted_tests_pass_on_the_unmutated_harness(runs):
    _, res = runs[""]
    assert res.returncode == 0, res.stdout[-3000:]


@pytest.mark.slow
@pytest.mark.parametrize("name", list(MUTATIONS))
def test_listed_mutation_is_killed(name, runs):
    problem, res = runs[name]
    assert not problem, problem
    assert res.returncode == 1, f"mutation survived (exit {res.returncode}):\n{res.stdout[-3000:]}"

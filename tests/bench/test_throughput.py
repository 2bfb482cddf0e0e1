"""The side-by-side render throughput: both engines time the same case, the tested one also in its worker, and
the table shows it."""


def test_throughput_times_both_engines_on_one_case(mcval):
    from harness.bench.throughput import measure
    from harness.engines.registry import make_engine
    from tools.throughput import table
    tested, worker = make_engine("mcval", sampler="independent", in_process=True), make_engine("mcval")
    reference = make_engine("mitsuba-native", sampler="independent")
    result = measure("cornell", "simple", 16, 4, tested, reference, worker, runs=2)
    data = result.to_json()
    assert set(data["seconds"]) == {"tested", "tested worker", "reference"}
    assert data["engines"] == {"tested": "mcval/independent", "reference": "mitsuba-native/independent"}
    assert all(len(v) == 2 for v in data["seconds"].values())
    assert data["rays"] >= 16 * 16 * 4  # at least the camera rays
    assert data["reference_over_tested"] > 0 and data["samples_per_second"]["tested"] > 0
    # The worker's figure is its render and what the call adds, never less than the render inside it.
    assert data["reference_over_tested_worker"] > 0 and min(data["seconds"]["tested worker"]) > 0
    assert "cornell:simple 16² 4 spp" in table([result])


def test_mitsuba_as_shipped_is_timed_robust_too():
    from harness.commands.bench import throughput_against
    assert throughput_against("mitsuba-native") == ("mitsuba-native", "mitsuba-robust")
    assert throughput_against("mitsuba-scalar") == ("mitsuba-scalar",)
    assert throughput_against("their.toml") == ("their.toml",)


def test_each_reference_timed_has_its_line_and_row(mcval):
    """bench's lines and page name the reference of each throughput figure: as shipped and robust apart."""
    from harness.bench.throughput import measure
    from harness.engines.registry import make_engine
    from harness.report.bench_html import bench_html
    from harness.report.bench_table import bench_lines
    tested = make_engine("mcval", sampler="independent", in_process=True)
    figures = [measure("cornell", "simple", 16, 2, tested, make_engine(name, sampler="independent"), runs=1).to_json()
               for name in ("mitsuba-native", "mitsuba-robust")]
    lines = bench_lines({"throughput": figures, "sampler_slopes": None, "seed_comparison": None})
    assert [line.split("): ")[1].split(", ")[1].split()[0] for line in lines] == [
        "mitsuba-native/independent", "mitsuba-robust/independent"]
    page = bench_html([], None, None, {}, figures, None)
    assert "<td>mitsuba-native/independent</td>" in page and "<td>mitsuba-robust/independent</td>" in page

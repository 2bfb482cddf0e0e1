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

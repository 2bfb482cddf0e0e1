"""The side-by-side render throughput: both engines time the same case, ours also in its worker, and the table
shows it."""


def test_throughput_times_both_engines_on_one_case(ours):
    from harness.bench.throughput import measure
    from tools.throughput import table
    result = measure("cornell", "simple", 16, 4, runs=2)
    data = result.to_json()
    assert set(data["seconds"]) == {"mcval", "mcval worker", "mitsuba"}
    assert all(len(v) == 2 for v in data["seconds"].values())
    assert data["rays"] >= 16 * 16 * 4  # at least the camera rays
    assert data["mitsuba_over_ours"] > 0 and data["samples_per_second"]["mcval"] > 0
    # The worker's figure is its render and what the call adds, never less than the render inside it.
    assert data["mitsuba_over_ours_worker"] > 0 and min(data["seconds"]["mcval worker"]) > 0
    assert "cornell:simple 16² 4 spp" in table([result])

"""The side-by-side render throughput: both engines time the same case, and the table shows it."""


def test_throughput_times_both_engines_on_one_case(ours):
    from harness.bench.throughput import measure
    from tools.throughput import table
    result = measure("cornell", "simple", 16, 4, runs=2)
    data = result.to_json()
    assert set(data["seconds"]) == {"mcval", "mitsuba"} and all(len(v) == 2 for v in data["seconds"].values())
    assert data["rays"] >= 16 * 16 * 4  # at least the camera rays
    assert data["mitsuba_over_ours"] > 0 and data["samples_per_second"]["mcval"] > 0
    assert "cornell:simple 16² 4 spp" in table([result])

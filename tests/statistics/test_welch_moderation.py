"""harness.statistics.welch.moderate at an edge of the noise field: a pixel beside noiseless neighbours
keeps its own variance and K - 1 degrees of freedom (their mean says nothing of it), while a pixel inside
a noisy region is moderated as before. A binomial edge pixel whose batches happened to agree rejected at
p = 2e-10 with borrowed degrees of freedom."""
import numpy as np

from harness.statistics.welch import BatchStats, moderate


def _field(rng: np.random.Generator, quiet_row: bool) -> BatchStats:
    """A 24 x 24 variance field of sample variances (7 degrees of freedom) around 1e-4; with `quiet_row`,
    row 0 has no noise at all (the background above an edge)."""
    var = 1e-4 * rng.chisquare(7, (24, 24, 1)) / 7
    if quiet_row:
        var[0] = 0.0
    return BatchStats(np.zeros((24, 24, 1)), var, 8)


def test_a_pixel_beside_noiseless_neighbours_keeps_its_own_variance_and_dof():
    for seed in range(3):
        stats = _field(np.random.default_rng(seed), quiet_row=True)
        m = moderate(stats)
        dof = np.broadcast_to(m.var_dof, m.var_of_mean.shape)
        # Row 1 touches the silent row: unmoderated. Inner rows are moderated (more dof, pulled to the prior).
        assert np.all(dof[1] == 7) and np.array_equal(m.var_of_mean[1], stats.var_of_mean[1])
        assert np.all(dof[3:-1, 1:-1] > 7)
        assert not np.allclose(m.var_of_mean[3:-1, 1:-1], stats.var_of_mean[3:-1, 1:-1])


def test_without_a_silent_neighbour_the_edge_row_is_moderated_too():
    stats = _field(np.random.default_rng(7), quiet_row=False)
    dof = np.broadcast_to(moderate(stats).var_dof, (24, 24, 1))
    assert np.all(dof[1] > 7)  # the twin of the test above: the rule, not the row, keeps row 1 unmoderated

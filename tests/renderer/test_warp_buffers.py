"""The warp bindings hand out reused output buffers (a fresh one of tens of MB costs more in page faults
than the warp): an array still alive is never handed out again, and a reused buffer holds the new call's
values only, whichever warp last used it."""
import gc

import numpy as np

import mcval_renderer as m

N = 50_000


def _u(seed):
    return np.random.default_rng(seed).random((N, 2), dtype=np.float32)


def test_arrays_alive_never_share_a_buffer():
    u = _u(0)
    kept = [m.square_to_tent(u) for _ in range(6)]
    assert len({a.ctypes.data for a in kept}) == len(kept)
    for a in kept[1:]:
        np.testing.assert_array_equal(a, kept[0])


def test_a_reused_buffer_holds_only_the_new_values():
    u1, u2 = _u(1), _u(2)
    expected_tent, expected_disk = m.square_to_tent(u2), m.square_to_uniform_disk(u1)
    for _ in range(3):  # each call may take the buffer the previous one gave back
        first = m.square_to_tent(u1)
        del first
        gc.collect()
        again = m.square_to_tent(u2)
        np.testing.assert_array_equal(again, expected_tent)
        other = m.square_to_uniform_disk(u1)  # another warp, the same size
        np.testing.assert_array_equal(other, expected_disk)

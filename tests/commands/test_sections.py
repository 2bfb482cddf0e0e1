"""The warp matrix's part of a run's verdict: a matrix that checked no warp judged nothing."""
from harness.commands.sections import warp_tally


def test_a_matrix_without_warps_judged_nothing():
    assert warp_tally({"warps": [], "problems": []}).judged == 0
    tally = warp_tally({"warps": [{"pass": True}, {"pass": False}], "problems": ["lacks square_to_x_pdf"]})
    assert (tally.passed, tally.failed) == (1, 2)
    # The warp section says which warps the engine lacked.
    why = warp_tally({"warps": [], "problems": [], "nothing_judged": "lib exports none of the warps asked for (x)"})
    assert why.why_nothing() == "warps: lib exports none of the warps asked for (x)"

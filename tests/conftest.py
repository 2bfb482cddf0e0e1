import os

import pytest

# pytest-xdist tells its workers COLUMNS=80, which the harness honours (tables as wide as the terminal says);
# the tests read its output as a log would, at its own width.
os.environ.pop("COLUMNS", None)


@pytest.fixture(scope="session")
def mcval():
    from harness.engines.mcval import McvalEngine
    return McvalEngine()


@pytest.fixture(scope="session")
def mitsuba():
    from harness.engines.mitsuba import MitsubaEngine
    return MitsubaEngine()


def pytest_collection_modifyitems(items):
    """A test that takes the `mitsuba` fixture renders or samples with Mitsuba 3: it carries the mitsuba
    marker without saying so again (tests that reach Mitsuba another way are marked where they are)."""
    for item in items:
        if "mitsuba" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.mitsuba)

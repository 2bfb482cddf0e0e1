import pytest


@pytest.fixture(scope="session")
def ours():
    from harness.engines.ours import OurEngine
    return OurEngine()


@pytest.fixture(scope="session")
def mitsuba():
    from harness.engines.mitsuba import MitsubaEngine
    return MitsubaEngine()

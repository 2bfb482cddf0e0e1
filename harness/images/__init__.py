"""Image validation: renders compared with references at three scales, with verdicts."""

"""Measuring scripts that are not tests: the image calibration sweeps (null_renders, image_calibration,
pixel_variance_rules) and the mutation-testing report. Run from the repository root, e.g.
`.venv/bin/python -m tools.null_renders --help`."""

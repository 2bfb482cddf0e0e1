"""The statistics the verdicts rest on: Welch and chi-square tests, cubature, levels, calibration rates."""

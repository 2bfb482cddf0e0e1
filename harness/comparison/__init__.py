"""Comparing two renders of one image: Welch tests at pixel, tile and image scale, the finite check, error
metrics and idiff beside them. The image, invariance and bench suites all use it."""

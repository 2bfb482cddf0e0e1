"""Engines: the renderers the harness compares, each behind the small interface of `base`."""

"""Nori's scene dialect, both ways: a student's Nori file read as Mitsuba 3's (to_mitsuba), and the suite's
scenes written for a Nori build (to_nori). docs/engines.md#nori-scene-files."""

"""Metamorphic checks: physics oracles that need no reference engine.

A scene scaled, rotated or moved (camera with it), its lights doubled or its reflectances halved must give
the same image, or that image times a known factor. `rewrite` makes the variants of any scene file,
`check.run_invariances` renders them with each engine and compares with the base by the image suite's Welch
tests, `suite.select` picks the cases.
"""

"""mcval: a validation harness for Monte Carlo renderers."""

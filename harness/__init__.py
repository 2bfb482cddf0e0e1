"""mcval: a validation harness for Monte Carlo renderers."""
import os

# numpy's OpenBLAS threads spin-wait after each call and would steal the two cores from the
# renderers being timed; the harness needs no threaded linear algebra.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

"""The verbs of `mcval`, one module each: NAME, HELP, `add_arguments(parser)` and
`run(args, run_folder) -> Verdict` (harness/cli.py maps it to the exit status). The only package that prints."""
from harness.commands import bench, bsdfs, calibrate, images, integrators, invariance, references, validate, warps

#: In the order `--help` lists them.
COMMANDS = (warps, bsdfs, images, references, bench, calibrate, integrators, invariance, validate)

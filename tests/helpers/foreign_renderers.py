"""Engine files for renderers other than mcval's, written into a test's folder: each calls a small Python
script that renders through our `render` binary (one batch, as an engine file's renderer renders, or the
{batches} it is given), or misbehaves in one named way instead."""
from __future__ import annotations

import stat
import sys
from pathlib import Path

REAL_RENDER = Path(__file__).resolve().parents[2] / "build" / "render"

_HEADER = f"""#!{sys.executable}
import sys, time
scene, output, spp, seed, integrator, width, height = sys.argv[1:8]
def write(pixels, names=("R", "G", "B"), fmt="float"):
    import numpy as np, OpenImageIO as oiio
    spec = oiio.ImageSpec(pixels.shape[1], pixels.shape[0], len(names), fmt)
    spec.channelnames = tuple(names)
    out = oiio.ImageOutput.create(output)
    out.open(output, spec)
    out.write_image(np.ascontiguousarray(pixels, dtype=np.float32))
    out.close()
count = sys.argv[8] if len(sys.argv) > 8 else "1"  # {{batches}}, where the engine file gives it
def render():
    import subprocess
    subprocess.run([{str(REAL_RENDER)!r}, scene, "--integrator", integrator, "--spp", spp, "--seed", seed,
                    "--batches", count, "-q", "-o", output], check=True)
def shape(channels=3):
    import numpy as np
    return np.full((int(height), int(width), channels), 0.25, np.float32)
"""

#: What each renderer does.
BEHAVIOURS = {
    "faithful": "render()",
    # Renders every call with one seed of its own, whatever it is given: K copies of one image.
    "fixed_seed": "seed = '7'; render()",
    # Uses the seed modulo 4: of a case's 8 calls, the last 4 repeat the first 4 (see call_seed).
    "seed_mod_4": "seed = str(int(seed) % 4); render()",
    # Writes black, whatever the scene: an image without signal.
    "black": "import numpy as np; write(np.zeros((int(height), int(width), 3), np.float32))",
    "y_half": "write(shape(1), ('Y',), 'half')",
    "layer": "write(shape(), ('beauty.R', 'beauty.G', 'beauty.B'))",
    "exit": "print('\\n'.join(f'progress {i}' for i in range(80))); print('error: cannot parse', file=sys.stderr); "
            "sys.exit(3)",
    "no_image": "pass",
    "not_exr": "open(output, 'w').write('P3 1 1 255 0 0 0')",
    "wrong_size": "import numpy as np; write(np.zeros((4, 4, 3), np.float32))",
    "no_rgb": "write(shape(2), ('U', 'V'))",
    "nan": "render(); import numpy as np; im = shape(); im[2, 3] = np.nan; write(im)",
    "negative": "im = shape(); im[1, 1] = -0.5; write(im)",
    "hang": "time.sleep(600)",
    # With {batches}: says how many it was asked for (in calls.log beside it), then renders them as layers.
    "batched": "import os; open(os.path.join(os.path.dirname(__file__), 'calls.log'), 'a').write(count + '\\n'); "
               "render()",
    # With {batches}: one image written as every layer asked for, the same K times.
    "batched_repeats": "c = count; count = '1'; render(); count = c\nimport numpy as np, OpenImageIO as oiio\n"
                       "im = oiio.ImageInput.open(output); px = im.read_image('float'); im.close()\n"
                       "write(np.concatenate([px[..., :3]] * int(count), axis=-1), "
                       "[f'batch{k}.{c}' for k in range(int(count)) for c in 'RGB'])",
    # With {batches}: one layer short of those asked for.
    "batched_short": "import numpy as np\nwrite(np.concatenate([shape()] * (int(count) - 1), axis=-1), "
                     "[f'batch{k}.{c}' for k in range(int(count) - 1) for c in 'RGB'])",
    # 64 MB, far past the 1 MB a call may print, then silence: a copy orphaned by a killed test run cannot fill
    # the disk.
    "spam": "for _ in range(1 << 14): print('x' * 4096, flush=True)\nimport time\ntime.sleep(600)",
    # Renders, then writes a firefly (FACTOR times the value; a value itself past 1e3) into pixel (64, 64) of
    # BATCHES of a case's 8 calls: their seeds are distinct modulo 8 (see harness.engines.command.call_seed).
    # Renders, then writes every value FACTOR times (a 1/pi or a reflectance left out, a pdf off by pi^2).
    "scaled": "render()\nimport numpy as np, OpenImageIO as oiio\n"
              "im = oiio.ImageInput.open(output); px = im.read_image('float'); im.close()\n"
              "write(np.array(px[..., :3], np.float64) * FACTOR)",
    "firefly": "render()\nif int(seed) % 8 < BATCHES:\n    import numpy as np, OpenImageIO as oiio\n"
               "    im = oiio.ImageInput.open(output); px = im.read_image('float'); im.close()\n"
               "    px = np.array(px[..., :3], np.float64); px[64, 64] = FACTOR if FACTOR > 1e3 else px[64, 64] * FACTOR\n"
               "    write(np.minimum(px, 3.4e38))",
}

ARGUMENTS = ["{scene}", "{output}", "{spp}", "{seed}", "{integrator}", "{width}", "{height}"]
#: Behaviours whose engine file passes {batches} too (the 8th argument).
BATCHED = ("batched", "batched_repeats", "batched_short")
INTEGRATORS = ("normals", "simple", "ao")


def write_engine(folder: Path, behaviour: str, name: str | None = None, extra: str = "",
                 integrators: tuple[str, ...] = INTEGRATORS, constants: dict[str, float] | None = None) -> Path:
    """An engine file in `folder` whose renderer does `behaviour` (a key of BEHAVIOURS) with `integrators`;
    `extra`: more TOML lines before its [integrators]; `constants`: names the behaviour reads (FACTOR, BATCHES
    of "firefly", "scaled")."""
    script = folder / f"{behaviour}.py"
    preamble = "".join(f"{k} = {v!r}\n" for k, v in (constants or {}).items())
    script.write_text(_HEADER + preamble + BEHAVIOURS[behaviour] + "\n")
    script.chmod(script.stat().st_mode | stat.S_IXUSR)
    arguments = ARGUMENTS + (["{batches}"] if behaviour in BATCHED else [])
    command = ", ".join(f'"{w}"' for w in ["{here}/" + script.name, *arguments])
    path = folder / f"{behaviour}.toml"
    table = "[integrators]\n" + "".join(f'{i} = "{i}"\n' for i in integrators)
    path.write_text(f'name = "{name or behaviour.replace("_", "-")}"\ncommand = [{command}]\n{extra}{table}')
    return path

"""A damaged reference is never used and never stops a run: load_reference returns None with one line
naming the file, and the run renders a fresh reference. Every test works on a copy in tmp_path."""
import hashlib
import json
import shutil
from pathlib import Path

import numpy as np
import pytest

import harness.images.references as refs
from harness.images.suite import ImageCase

REAL = Path(refs.__file__).resolve().parents[2] / "references" / "mitsuba"
CASE = ImageCase("plane_point", "normals")


@pytest.fixture
def stored(tmp_path, monkeypatch, mitsuba):
    """(exr, json) of a sound copy of a stored reference, REFERENCES_DIR pointed at the copy."""
    folder = tmp_path / "references"
    (folder / mitsuba.name / CASE.scene).mkdir(parents=True)
    for suffix in (".exr", ".json"):
        shutil.copy(REAL / CASE.scene / f"{CASE.integrator}{suffix}", folder / mitsuba.name / CASE.scene)
    monkeypatch.setattr(refs, "REFERENCES_DIR", folder)
    exr = refs.reference_path(CASE, mitsuba)
    return exr, exr.with_suffix(".json")


def load(mitsuba, named: Path) -> str:
    """The reason load_reference gives, checked: no reference, one line, naming `named`."""
    reference, why = refs.load_reference(CASE, mitsuba)
    assert reference is None, why
    assert "\n" not in why and str(named) in why, why
    return why


def read_json(path: Path) -> dict:
    return json.loads(path.read_text())


def write_exr(path: Path, **layers: np.ndarray) -> None:
    import OpenEXR
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    with OpenEXR.File(header, {k: v.astype(np.float32) for k, v in layers.items()}) as f:
        f.write(str(path))


def exr_layers(path: Path) -> tuple[np.ndarray, np.ndarray]:
    import OpenEXR
    with OpenEXR.File(str(path)) as f:
        layers = f.channels()
        return layers["RGB"].pixels.copy(), layers["variance"].pixels.copy()


def forge_exr_hash(exr: Path, meta_path: Path) -> None:
    """Record the .exr's new size and hash, as a consistent rewrite of both files would."""
    meta = read_json(meta_path)
    data = exr.read_bytes()
    meta.update(exr_bytes=len(data), exr_sha256=hashlib.sha256(data).hexdigest())
    meta_path.write_text(json.dumps(meta))


def test_a_sound_copy_is_used(stored, mitsuba):
    reference, why = refs.load_reference(CASE, mitsuba)
    assert why == "stored reference" and reference.summary.pixel.mean.shape == (128, 128, 3)


@pytest.mark.parametrize("text,what", [
    ("[]", "not a JSON object but a list"),
    ("garbage, not JSON", "not valid JSON"),
    ("", "not valid JSON"),
    ('{"provenance": 3}', "no 'provenance' object"),
])
def test_json_that_is_not_a_reference(stored, mitsuba, text, what):
    _, meta_path = stored
    meta_path.write_text(text)
    assert what in load(mitsuba, meta_path)


def test_truncated_json(stored, mitsuba):
    _, meta_path = stored
    data = meta_path.read_bytes()
    meta_path.write_bytes(data[: len(data) // 2])
    assert "not valid JSON, truncated or damaged" in load(mitsuba, meta_path)


@pytest.mark.parametrize("field", ["tile", "image", "seconds", "content_sha256", "exr_sha256"])
def test_json_without_a_field(stored, mitsuba, field):
    _, meta_path = stored
    meta = read_json(meta_path)
    del meta[field]
    meta_path.write_text(json.dumps(meta))
    assert field in load(mitsuba, meta_path)


@pytest.mark.parametrize("edit,what", [
    (lambda m: m["tile"].update(mean="abc"), "not arrays of numbers"),
    (lambda m: m["tile"].update(mean=m["tile"]["mean"][:-1]), "shapes"),
    (lambda m: m["image"].update(mean=[1.0, 2.0]), "shapes"),
    (lambda m: m["image"].update(var_of_mean=[float("nan")] * 3), "non-finite values: 3"),
    (lambda m: m["image"].update(var_of_mean=[-1.0] * 3), "negative variances: 3"),
    (lambda m: m.update(seconds={"total": "slow"}), "'seconds'"),
])
def test_json_with_a_malformed_field(stored, mitsuba, edit, what):
    _, meta_path = stored
    meta = read_json(meta_path)
    edit(meta)
    meta_path.write_text(json.dumps(meta))
    assert what in load(mitsuba, meta_path)


def test_an_exr_without_a_variance_layer(stored, mitsuba):
    exr, meta_path = stored
    mean, _ = exr_layers(exr)
    write_exr(exr, RGB=mean)
    assert "truncated or replaced (2" in load(mitsuba, exr)  # a smaller file than the one written
    forge_exr_hash(exr, meta_path)  # even when the .json was made to agree, the layer is missing
    assert "no variance layer" in load(mitsuba, exr)


def test_a_truncated_exr(stored, mitsuba):
    exr, meta_path = stored
    data = exr.read_bytes()
    exr.write_bytes(data[: len(data) // 2])
    assert f"truncated or replaced ({len(data) // 2} of the {len(data)} bytes written)" in load(mitsuba, exr)
    forge_exr_hash(exr, meta_path)  # the decoder's own error, still one line
    assert "not a readable EXR" in load(mitsuba, exr)


def test_a_file_that_is_not_an_exr(stored, mitsuba):
    exr, meta_path = stored
    exr.write_bytes(b"not an EXR file at all")
    forge_exr_hash(exr, meta_path)
    assert "not a readable EXR" in load(mitsuba, exr)


def test_an_exr_of_the_wrong_size(stored, mitsuba):
    exr, meta_path = stored
    mean, var = exr_layers(exr)
    write_exr(exr, RGB=mean[::2, ::2], variance=var[::2, ::2])
    forge_exr_hash(exr, meta_path)
    assert "not (128, 128, 3)" in load(mitsuba, exr)


def test_an_exr_with_nonfinite_pixels(stored, mitsuba):
    exr, meta_path = stored
    mean, var = exr_layers(exr)
    mean[10, 20, 1] = np.nan
    write_exr(exr, RGB=mean, variance=var)
    forge_exr_hash(exr, meta_path)
    assert "pixels: non-finite values: 1" in load(mitsuba, exr)


def test_a_missing_exr_beside_its_json(stored, mitsuba):
    exr, _ = stored
    exr.unlink()
    assert "missing" in load(mitsuba, exr)


def test_a_summary_edited_in_the_exr(stored, mitsuba):
    """Mean x2, variance x1e6: the stored summary no longer matches what was written."""
    exr, meta_path = stored
    mean, var = exr_layers(exr)
    write_exr(exr, RGB=mean * 2, variance=var * 1e6 + 1e-6)
    assert "not the file written" in load(mitsuba, exr)
    forge_exr_hash(exr, meta_path)
    why = load(mitsuba, exr)
    assert "summary does not match its stored arrays (edited or damaged" in why and str(meta_path) in why


def test_a_summary_edited_in_the_json(stored, mitsuba):
    _, meta_path = stored
    meta = read_json(meta_path)
    for scale in ("tile", "image"):
        meta[scale]["mean"] = (np.array(meta[scale]["mean"]) * 2).tolist()
        meta[scale]["var_of_mean"] = (np.array(meta[scale]["var_of_mean"]) * 1e6).tolist()
    meta_path.write_text(json.dumps(meta))
    assert "summary does not match its stored arrays" in load(mitsuba, meta_path)


def test_the_content_hash_covers_every_stored_array(stored, mitsuba):
    reference, _ = refs.load_reference(CASE, mitsuba)
    s = reference.summary
    digest = refs.summary_sha256(s)
    assert digest == read_json(stored[1])["content_sha256"]
    for stats in (s.pixel, s.tile, s.image):
        for part in ("mean", "var_of_mean"):
            array = getattr(stats, part)
            kept = array.flat[-1]
            array.flat[-1] = kept * 2 + 1
            assert refs.summary_sha256(s) != digest, part
            array.flat[-1] = kept
    assert refs.summary_sha256(s) == digest


def test_a_stale_reference_is_reported_before_its_contents_are_read(stored, mitsuba):
    exr, meta_path = stored
    meta = read_json(meta_path)
    meta["provenance"]["summary_format"] = 1
    meta_path.write_text(json.dumps(meta))
    exr.write_bytes(b"")
    assert refs.load_reference(CASE, mitsuba) == (None, "stored reference is stale (summary_format changed)")


def test_the_image_run_renders_again_over_a_damaged_reference(stored, tmp_path, capsys):
    """The command names the damaged file on one line, renders Mitsuba's side now, and finishes."""
    from harness.cli import main

    _, meta_path = stored
    meta_path.write_text("{ damaged")
    code = main(["images", "--only", "plane_point:normals", "--out", str(tmp_path / "results")])
    assert code in (0, 1)
    captured = capsys.readouterr()
    line = next(x for x in captured.err.splitlines() if str(meta_path) in x)
    assert line.startswith("plane_point:normals: ") and "not valid JSON" in line and "rendering it now" in line
    assert "Traceback" not in captured.out + captured.err
    entry = json.loads((tmp_path / "results" / "latest" / "results.json").read_text())["images"][0]
    assert entry["reference"].startswith(f"rendered now ({meta_path}: not valid JSON")
    assert meta_path.read_text() == "{ damaged"  # a run never writes references

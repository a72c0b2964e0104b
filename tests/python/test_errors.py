"""Bad files and arguments raise Python exceptions naming them; nothing crashes the
interpreter, not even the model-file fuzz target's corpus."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import floorgrid
from conftest import ROOT

MODELS = ROOT / "tests" / "fixtures" / "models"


def test_input_error_is_a_value_error_with_file_line_field(tmp_path):
    assert issubclass(floorgrid.InputError, ValueError)
    missing = tmp_path / "missing.json"
    with pytest.raises(floorgrid.InputError) as error:
        floorgrid.Model.load(missing)
    assert error.value.file == str(missing) and str(missing) in str(error.value)
    damaged = tmp_path / "damaged.json"
    text = (MODELS / "tps.json").read_text()
    damaged.write_text(text[: len(text) // 2])
    with pytest.raises(floorgrid.InputError) as error:
        floorgrid.Model.load(damaged)
    assert error.value.file == str(damaged) and error.value.line is not None


def test_a_wrong_field_is_named(tmp_path):
    bad = tmp_path / "bad-unit.json"
    bad.write_text((MODELS / "gt.json").read_text().replace('"unit": 1', '"unit": -1', 1))
    if bad.read_text() == (MODELS / "gt.json").read_text():
        pytest.skip("the fixture has no unit field to break")
    with pytest.raises(floorgrid.InputError) as error:
        floorgrid.Model.load(bad)
    assert error.value.field is not None and "unit" in error.value.field


def test_missing_dataset_and_bad_options_are_named(tmp_path):
    with pytest.raises(floorgrid.InputError) as error:
        floorgrid.load_dataset(tmp_path / "nowhere")
    assert "nowhere" in str(error.value)
    (tmp_path / "bad.yaml").write_text("align:\n  models:\n    cv_folds: many\n")
    with pytest.raises(floorgrid.InputError) as error:
        floorgrid.align(tmp_path / "nowhere", config=tmp_path / "bad.yaml")
    assert error.value.file == str(tmp_path / "bad.yaml") and error.value.line == 3
    with pytest.raises(floorgrid.InputError) as error:
        floorgrid.align(tmp_path / "nowhere", options={"align.models.no_such_option": 1})
    assert error.value.file == "options" and "no_such_option" in str(error.value)


def corpus(tmp_path):
    """The model_json fuzz target's seed corpus (fuzz/make_corpus.py, with fuzz/regressions),
    the corpus a `make fuzz` run grew (build-fuzz), and truncations and byte flips of the seeds."""
    subprocess.run([sys.executable, str(ROOT / "fuzz" / "make_corpus.py"), str(tmp_path / "c"),
                    os.environ.get("FLOORGRID_DATA_DIR", str(ROOT.parent / "shared" / "data"))],
                   check=True, capture_output=True)
    seeds = sorted((tmp_path / "c" / "model_json").iterdir())
    fuzz_dir = Path(os.environ.get("FLOORGRID_FUZZ_DIR", str(ROOT / "build-fuzz")))
    grown = fuzz_dir / "fuzz-corpus" / "model_json"
    files = seeds + (sorted(grown.iterdir()) if grown.is_dir() else [])
    rng = np.random.default_rng(1)
    damaged = tmp_path / "damaged"
    damaged.mkdir()
    for seed in seeds:
        data = seed.read_bytes()
        for k, cut in enumerate(rng.integers(0, len(data), 4)):
            (damaged / f"{seed.name}.cut{k}").write_bytes(data[:cut])
        for k in range(4):
            flipped = bytearray(data)
            for at in rng.integers(0, len(data), 3):
                flipped[at] = int(rng.integers(0, 256))
            (damaged / f"{seed.name}.flip{k}").write_bytes(bytes(flipped))
    return files + sorted(damaged.iterdir())


def test_the_model_fuzz_corpus_never_crashes_the_interpreter(tmp_path):
    files = corpus(tmp_path)
    loaded = refused = 0
    for path in files:
        try:
            model = floorgrid.Model.load(path)
        except floorgrid.InputError as error:
            assert error.file == str(path), (path, str(error))
            refused += 1
            continue
        loaded += 1
        mapped = model.forward(np.array([[0.0, 0.0], [3.5, -2.0]]))
        model.inverse(mapped.values)
        model.forward(np.array([[0.0, 0.0, 0.5]]))
    print(f"model_json corpus: {len(files)} files, {loaded} loaded, {refused} refused")
    assert loaded > 0 and refused > 0

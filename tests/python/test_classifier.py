"""train(), test(), predict(): the classifier of `tactile classify` on real recordings."""

import subprocess

import numpy as np
import pytest

import tactile


def test_train_test_predict_agree_with_the_command_line(tmp_path, data_dir, cli):
    rec = data_dir / "biotac-materials"
    model = tactile.train(rec, rec / "labels.csv", out=tmp_path / "py.json")
    assert model.class_names == ["mat1", "mat14", "mat20", "mat7"] or len(model.class_names) == 4
    assert model.c == 10  # the stroke procedure's default, as on the command line
    subprocess.run([cli, "classify", "train", "--recordings", str(rec), "--labels",
                    str(rec / "labels.csv"), "--out", str(tmp_path / "cli.json")],
                   check=True, capture_output=True)
    result = tactile.test(tmp_path / "cli.json", rec, rec / "labels.csv")
    cli_test = subprocess.run([cli, "classify", "test", "--model", str(tmp_path / "py.json"),
                               "--recordings", str(rec), "--labels", str(rec / "labels.csv")],
                              check=True, capture_output=True, text=True).stdout
    line = f"accuracy {result['accuracy']:.3f} ({result['correct']}/{result['tested']})"
    assert line in cli_test  # each side's model scores the same on the other side's test
    assert result["tested"] == 16 and result["confusion"].sum() == 16
    assert np.trace(result["confusion"]) == result["correct"]
    files = [rec / f for f in result["files"][:3]]
    predictions = tactile.predict(model, files)
    assert [p[0] for p in predictions] == result["predicted"][:3]
    assert all(p[1] is None for p in predictions)  # no value column, no values


def test_classifier_bad_input(tmp_path, data_dir):
    rec = data_dir / "biotac-materials"
    with pytest.raises(FileNotFoundError):
        tactile.train(rec, tmp_path / "absent.csv")
    with pytest.raises(ValueError, match=r"unknown procedure 'sideways' \(known: stroke, static, dp, ru, roll\)"):
        tactile.train(rec, rec / "labels.csv", procedure="sideways")
    with pytest.raises(ValueError, match="trim"):
        tactile.train(rec, rec / "labels.csv", trim=0.7)
    with pytest.raises(ValueError, match="kernel_degree: 3 is not 1 or 2"):
        tactile.train(rec, rec / "labels.csv", kernel_degree=3)
    with pytest.raises(ValueError, match="unknown"):
        tactile.train(rec, rec / "labels.csv", inputs=["means", "colour"])
    one_class = tmp_path / "one.csv"
    one_class.write_text("file,class\nmat1_1_bio.csv,mat1\nmat1_2_bio.csv,mat1\n")
    with pytest.raises(RuntimeError, match="at least 2 classes"):
        tactile.train(rec, one_class)
    with pytest.raises(FileNotFoundError):
        tactile.test(tmp_path / "absent.json", rec, rec / "labels.csv")
    bad_model = tmp_path / "bad.json"
    bad_model.write_text("{}")
    with pytest.raises(tactile.FormatError):
        tactile.predict(bad_model, [rec / "mat1_1_bio.csv"])
    model = tactile.train(rec, rec / "labels.csv", procedure="static")
    with pytest.raises(FileNotFoundError):
        tactile.predict(model, [tmp_path / "absent.csv"])

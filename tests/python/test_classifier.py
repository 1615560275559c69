"""train(), test(), predict(): the classifier of `tactile classify` on real recordings."""

import subprocess

import numpy as np
import pytest

import tactile


def test_train_test_predict_agree_with_the_command_line(tmp_path, data_dir, cli):
    rec = data_dir / "biotac-materials"
    model = tactile.train(rec, rec / "labels.csv", out=tmp_path / "py.json")
    assert model.class_names == ["mat1", "mat14", "mat20", "mat7"] or len(model.class_names) == 4
    assert model.c == 100  # the stroke procedure's default, as on the command line
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
    with pytest.raises(ValueError, match=r"procedure: unknown value 'sideways' \(known: stroke, static, dp, ru, roll\)"):
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


def first_trials(tmp_path, data_dir, trials=("1", "2", "3")):
    """Labels of trials 1-3 of each of the four materials: 12 recordings, 3 per class."""
    rec = data_dir / "biotac-materials"
    rows = [line for line in (rec / "labels.csv").read_text().splitlines()[1:]
            if line.split(",")[0].split("_")[1] in trials]
    labels = tmp_path / "first.csv"
    labels.write_text("file,class\n" + "\n".join(rows) + "\n")
    return rec, labels


def test_train_cv_reports_the_folds_as_the_command_line(tmp_path, data_dir, cli):
    rec, labels = first_trials(tmp_path, data_dir)
    model = tactile.train(rec, labels, cv=3)
    report = model.report
    assert report["recordings"] == 12 and len(report["class_names"]) == 4
    assert report["selection"] is None and model.selection is None
    cv = report["cv"]
    assert cv["folds"] == 3 and not cv["nested"] and len(cv["fold_accuracy"]) == 3
    # Every recording is tested once, by the fold that left it out; the mean is over folds.
    assert cv["tested"] == 12 and 0 <= cv["correct"] <= 12
    assert cv["mean"] == pytest.approx(sum(cv["fold_accuracy"]) / 3)
    assert report["training_tested"] == 12
    assert (report["inputs"], report["c"]) == (["means", "bands"], model.c)  # stroke's defaults
    out = subprocess.run([cli, "classify", "train", "--recordings", str(rec), "--labels",
                          str(labels), "--out", str(tmp_path / "cli.json"), "--cv", "3"],
                         check=True, capture_output=True, text=True).stdout
    assert (f"cross-validation (3 folds, stratified): accuracy {cv['mean']:.3f} +- "
            f"{cv['spread']:.3f}") in out
    assert f"pooled {cv['correct']}/{cv['tested']}" in out
    assert (f"accuracy on the training set {report['training_correct']}/"
            f"{report['training_tested']}") in out


def test_train_select_with_cv_is_nested_and_records_the_choice(tmp_path, data_dir, cli):
    rec, labels = first_trials(tmp_path, data_dir)
    named = dict(trim=0.1, kernel_degree=1, baseline_at="none")
    model = tactile.train(rec, labels, out=tmp_path / "py.json", select=True, cv=3, **named)
    report = model.report
    selection = report["selection"]
    # Options named are not searched: 5 input sets x 2 electrode signals x 6 values of C, each
    # scored on all 12 recordings.
    assert len(selection["candidates"]) == 60
    for c in selection["candidates"]:
        assert (c["trim"], c["kernel_degree"], c["baseline_at"]) == (0.1, 1, "none")
        assert c["tested"] == 12
    chosen = selection["candidates"][selection["chosen"]]
    assert chosen["correct"] == max(c["correct"] for c in selection["candidates"])
    # The model is the chosen candidate's, and its file records the same comparison.
    assert (model.c, model.kernel_degree) == (chosen["c"], chosen["kernel_degree"])
    assert (report["inputs"], report["electrodes"]) == (chosen["inputs"], chosen["electrodes"])
    assert tactile.read_classifier_model(tmp_path / "py.json").selection == selection
    cv = report["cv"]
    assert cv["nested"] and cv["folds"] == 3 and cv["inner_folds"] == 5
    assert cv["candidates"] == 60 and len(cv["chosen"]) == 3 and cv["tested"] == 12
    out = subprocess.run([cli, "classify", "train", "--recordings", str(rec), "--labels",
                          str(labels), "--out", str(tmp_path / "cli.json"), "--select", "--cv",
                          "3", "--trim", "0.1", "--kernel-degree", "1", "--baseline-at", "none"],
                         check=True, capture_output=True, text=True).stdout
    assert (f"among 60 candidates): accuracy {cv['mean']:.3f} +- {cv['spread']:.3f}") in out
    assert f"pooled {cv['correct']}/12" in out
    for k, c in enumerate(cv["chosen"]):
        assert f"  fold {k + 1} chose {c['description']} (inner {c['accuracy']:.3f})" in out
    assert (f"classify train --select: 12 recordings, 4 classes; chose {chosen['description']} "
            f"({selection['folds']}-fold CV {chosen['accuracy']:.3f})") in out


def test_train_select_and_cv_bad_input(tmp_path, data_dir):
    rec, labels = first_trials(tmp_path, data_dir)
    with pytest.raises(ValueError, match=r"cv: 1 is out of range: must be from 2 to 1000"):
        tactile.train(rec, labels, cv=1)
    # More folds than a class has recordings (3 each): a fold would miss the class.
    with pytest.raises(ValueError, match="fold"):
        tactile.train(rec, labels, cv=4)
    with pytest.raises(ValueError, match="fold"):
        tactile.train(rec, labels, select=True, cv=4, trim=0.1, kernel_degree=1,
                      baseline_at="none")
    with pytest.raises(ValueError, match="trim"):
        tactile.train(rec, labels, select=True, trim=0.7)

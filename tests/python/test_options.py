"""Each operation's options come from one table in its library: the command line's `--help`,
the Python keywords and the README's command row must name the same options."""

import os
import pathlib
import re
import subprocess

import pytest

import tactile

README = pathlib.Path(os.environ["TACTILE_SOURCE_DIR"]) / "README.md"
DEMO = pathlib.Path(os.environ["TACTILE_E2E_DEMO_DIR"])

# Options only the command line has: where a command writes its results.
CLI_ONLY = {"capture": {"--out", "--csv", "--maps"}, "map": {"--out", "--csv"},
            "live": {"--headless", "--window", "--screenshot", "--latero", "--blade-centre-raw",
                     "--blade-raw-per-unit", "--blade-max-raw", "--blade-full-scale-um"},
            "play": set(), "synth": set(), "export": set(),
            # Required options that are Python's positional arguments.
            "classify train": {"--recordings", "--labels"},
            "classify test": {"--model", "--recordings", "--labels"},
            # The same run cut into cells for a cluster: the command line's.
            "experiment": {"--plan", "--cell", "--merge", "--status", "--slurm", "--partition",
                           "--max-parallel", "--cells-per-task", "--time", "--submit"}}
COMMANDS = [("capture", tactile.capture), ("map", tactile.map), ("live", tactile.live),
            ("play", tactile.play), ("synth", tactile.synth), ("export", tactile.export),
            ("classify train", tactile.train), ("classify test", tactile.test),
            ("experiment", tactile.experiment)]


def help_flags(cli, command):
    out = subprocess.run([cli, *command.split(), "--help"], check=True, capture_output=True,
                         text=True).stdout
    return set(re.findall(r"^\s+(--[a-z][a-z0-9-]*)", out, re.M)) - {"--help"}


def readme_flags(command):
    # A command may have several rows (one per way of using it): together they name its options.
    rows = [line.split("` |")[0] for line in README.read_text().splitlines()
            if line.startswith(f"| `tactile {command} ")]
    assert rows, f"no README row for `tactile {command}`"
    return set(re.findall(r"(--[a-z][a-z0-9-]*)", " ".join(rows)))


def python_keywords(function):
    return set(re.findall(r"^  ([a-z][a-z0-9_]*): ", function.__doc__, re.M))


@pytest.mark.parametrize("command, function", COMMANDS)
def test_help_python_and_readme_name_the_same_options(cli, command, function):
    flags = help_flags(cli, command)
    keywords = python_keywords(function)
    assert len(keywords) >= 2
    assert flags - CLI_ONLY[command] == {"--" + k.replace("_", "-") for k in keywords}
    assert readme_flags(command) == flags


def test_every_documented_keyword_is_taken(tmp_path):
    strain = tactile.read_strain_movie(DEMO / "strain.h5")
    movie = tactile.read_movie(DEMO / "movie.h5")
    for function, args in [(tactile.capture, [tmp_path]), (tactile.map, [strain]),
                           (tactile.live, [str(tmp_path)]), (tactile.play, [movie]),
                           (tactile.synth, [tmp_path / "synth"]), (tactile.export, [movie]),
                           (tactile.train, [tmp_path, tmp_path / "labels.csv"]),
                           (tactile.test, [tmp_path / "m.json", tmp_path, tmp_path / "l.csv"]),
                           (tactile.experiment, [tmp_path / "e.json"])]:
        for keyword in python_keywords(function) - {"layout"}:
            # A value no option takes: the complaint must be about the value, not the keyword.
            with pytest.raises(TypeError) as error:
                function(*args, **{keyword: object()})
            assert "unexpected keyword" not in str(error.value)
            assert str(error.value).startswith(keyword + ":")


def test_a_misspelt_keyword_names_the_closest(tmp_path):
    with pytest.raises(TypeError, match=r"'min_tracks'.*did you mean 'min_track'"):
        tactile.capture(tmp_path, px_per_mm=47, min_tracks=10)


def test_python_ranges_and_rules_are_the_command_lines(cli, tmp_path):
    cases = [({"px_per_mm": 1}, "--px-per-mm 1", "1 is out of range: must be from 2 to 5000"),
             ({"px_per_mm": 47, "smoothing": 51}, "--px-per-mm 47 --smoothing 51",
              "51 is out of range: must be from 0 to 50"),
             ({"px_per_mm": 47, "refine_window": 0.05}, "--px-per-mm 47 --refine-window 0.05",
              "0.05 is out of range: must be from 0.1 to 5"),
             ({"px_per_mm": 47, "span": 2.5}, "--px-per-mm 47 --span 2.5",
              "2.5 is not a whole number")]
    for keywords, flags, words in cases:
        with pytest.raises(ValueError) as error:
            tactile.capture(tmp_path, **keywords)
        assert words in str(error.value)
        run = subprocess.run([cli, "capture", str(tmp_path), "--out", str(tmp_path / "s.h5"),
                              *flags.split()], capture_output=True, text=True)
        assert run.returncode == 2 and words in run.stderr, run.stderr


def test_synth_rules_are_the_command_lines(cli, tmp_path):
    """The rules between synth's options (a scene's options are not a print's) and its seed's
    whole range are the same words from Python and from the command line."""
    print_ = pathlib.Path(os.environ["TACTILE_TEST_DATA_DIR"]) / "polyu-hrf-pores" / "image_12.jpg"
    cases = [({"from_print": print_, "speed": 3}, f"--from-print {print_} --speed 3",
              "speed: describes a synthetic scene, not"),
             ({"warp": "wave"}, "--warp wave", "warp: needs"),
             ({"from_print": print_, "slide_speed": 2, "slide_x": 0.1},
              f"--from-print {print_} --slide-speed 2 --slide-x 0.1", "not with"),
             ({"seed": -1}, "--seed -1", "-1 is not a whole number from 0 to 2^64 - 1"),
             ({"frames": 1}, "--frames 1", "1 is out of range: must be from 2 to 100000")]
    for keywords, flags, words in cases:
        with pytest.raises(ValueError) as error:
            tactile.synth(tmp_path / "never", **keywords)
        assert words in str(error.value)
        run = subprocess.run([cli, "synth", str(tmp_path / "never"), *flags.split()],
                             capture_output=True, text=True)
        assert run.returncode == 2 and words in run.stderr, run.stderr
    assert not (tmp_path / "never").exists()


def test_export_needs_an_output_in_both(cli, tmp_path):
    movie = tactile.read_movie(DEMO / "movie.h5")
    with pytest.raises(ValueError, match="give hjif OUT.hjif, wav OUT.wav or both"):
        tactile.export(movie)
    run = subprocess.run([cli, "export", str(DEMO / "movie.h5")], capture_output=True, text=True)
    assert run.returncode == 2 and "give --hjif OUT.hjif, --wav OUT.wav or both" in run.stderr

"""The Python package on rig logs: import_logs() and synthesize_logs() give what the command line
gives, a dataset of logs reads as any dataset, and bad input is an InputError naming the keyword."""
import os
import subprocess

import pytest

import chutelab

SOURCE = os.environ.get("CHUTELAB_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BINARY = os.environ.get("CHUTELAB_BINARY", os.path.join(SOURCE, "build", "app", "chutelab"))
LOGS = os.path.join(SOURCE, "datasets", "hidden-effect-logs")
HIDDEN = os.path.join(SOURCE, "datasets", "hidden-effect")

pytest.importorskip("pandas")


def test_a_dataset_of_logs_reads_into_means():
    d = chutelab.read_dataset(LOGS, True)
    m = d.measurements
    rn = m[(m["condition"] == "V2-26") & (m["quantity"] == "normal_force_N")]
    assert len(rn) == 1
    assert 0 < float(rn["uncertainty"].iloc[0]) < 0.02 * float(rn["value"].iloc[0])


def test_import_logs_writes_what_the_command_line_writes(tmp_path):
    ours = chutelab.import_logs(LOGS, out=tmp_path / "py")
    r = subprocess.run([BINARY, "import-logs", "--dataset", LOGS, "--out", str(tmp_path / "cli")],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    for f in ("measurements.csv", "log_provenance.csv", "log_checks.csv"):
        assert (tmp_path / "py" / f).read_bytes() == (tmp_path / "cli" / f).read_bytes(), f
    assert "source_file" in (tmp_path / "py" / "measurements.csv").read_text()
    assert len(ours.measurements) > 0


def test_synthesize_logs_and_its_errors(tmp_path):
    truth = tmp_path / "truth.csv"
    truth.write_text("condition,quantity,value\n" + "".join(
        f"{c},normal_force_N,30\n{c},shear_force_N,2.5\n{c},impact_point_y_mm,-60\n"
        for c in ("V2-26", "V2-41", "V3-28", "V3-41", "V4-28", "V4-41", "V5-28", "V5-44")))
    d = chutelab.synthesize_logs(HIDDEN, truth, seed=5, out=tmp_path / "logs")
    assert (tmp_path / "logs" / "logs" / "layout.toml").exists()
    m = d.measurements
    rn = m[(m["condition"] == "V3-41") & (m["quantity"] == "normal_force_N")]
    assert abs(float(rn["value"].iloc[0]) - 30.0) < 4 * float(rn["uncertainty"].iloc[0])
    with pytest.raises(chutelab.InputError) as e:
        chutelab.synthesize_logs(HIDDEN, truth, seed=-1, out=tmp_path / "x")
    assert e.value.field == "seed"
    with pytest.raises(chutelab.InputError) as e:
        chutelab.import_logs(HIDDEN, out=tmp_path / "y")
    assert "layout.toml" in str(e.value)

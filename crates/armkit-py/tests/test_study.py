"""Every seed study runs from Python with all its checks passing, and its
series come back as arrays."""

import re

import numpy as np
import pytest

import armkit
from armkit import study


@pytest.mark.parametrize("name", study.names())
def test_seed_study_checks_all_pass(name):
    report = study.run(name)
    assert report.checks, "a study without checks proves nothing"
    failed = [c["text"] for c in report.checks if not c["passed"]]
    assert report.all_passed and not failed, failed
    assert report.passed == len(report.checks)
    for check in report.checks:
        passed = check["value"] <= check["threshold"] if check["comparison"] == "<=" else check["value"] >= check["threshold"]
        assert passed == check["passed"]
    for series in report.series.values():
        assert isinstance(series["x"], np.ndarray)
        for values in series["columns"].values():
            assert values.shape == series["x"].shape


def test_study_options_and_bad_names():
    heavy = study.run("beam-table", mass=800.0)
    light = study.run("beam-table")
    assert heavy.checks != light.checks
    with pytest.raises(ValueError, match=re.escape("unknown study `nope`; the studies are: beam-table")):
        study.run("nope")
    with pytest.raises(ValueError, match=re.escape("invalid argument `options`: study `beam-table`: unknown field `weight`")):
        study.run("beam-table", weight=3.0)


def test_continuous_path_study_takes_the_library_options():
    report = study.run("continuous-path", segment_sweep=[4, 16], cubic_quintic_segments=[])
    assert list(report.series["error_vs_segments"]["x"]) == [4.0, 16.0]
    midpoint = [f for f in report.findings if "midpoint" in f["claim"]]
    assert midpoint and midpoint[0]["status"] == "not reproduced"


def test_avoidance_study_as_printed_line_and_open_loop_options():
    # Seed 004's method as printed on a near-miss line and the open-loop
    # runs: rows of their own; `None` / False leave them out; the plan and
    # the feedback of the main runs by the CLI's names.
    base = dict(miss_sweep=[], joint_step_sweep=[], ks=[1, 5])
    report = study.run("avoidance", as_printed_miss=0.003, as_printed_eps_dq=5.0, **base)
    claims = [f["claim"] for f in report.findings]
    assert any("the method as printed on a near-miss line" in c for c in claims)
    assert any("open-loop tracker" in c for c in claims)
    # A row restating counted evidence names it; counted rows carry None.
    restating = {f["claim"]: f["same_evidence_as"] for f in report.findings}
    assert restating["seed 004, Figs 5-6, the method as printed on a near-miss line: the joints "
                     "that jump at the singularity are 4 and 6"]
    assert restating["seed 004, Figs 5-6: the joints that jump at the singularity are 4 and 6"] is None
    bare = study.run("avoidance", as_printed_miss=None, open_loop=False, region_plan="exact",
                     feedback="next-pose", **base)
    assert not any("as printed on a near-miss" in f["claim"] or "open-loop" in f["claim"]
                   for f in bare.findings)
    with pytest.raises(ValueError, match="region_plan|unknown variant"):
        study.run("avoidance", region_plan="printed", **base)

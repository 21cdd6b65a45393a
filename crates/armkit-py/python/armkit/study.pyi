"""The seed studies: run one by name, get its checks, series and notes."""

from typing import Any, Dict, List, Optional, final

__all__ = ["run", "names", "StudyReport"]

@final
class StudyReport:
    """What a study produced; a failed check is in ``checks``, never an exception."""

    name: str
    checks: List[Dict[str, Any]]
    """Each: name, value, threshold, comparison ("<=" / ">="), unit, detail, passed, text."""
    series: Dict[str, Dict[str, Any]]
    """By name: title, x_label, y_label, x (array), columns (label -> array)."""
    notes: List[str]
    findings: List[Dict[str, Optional[str]]]
    """The paper's claims, each: claim, measured, status ("reproduced",
    "reproduced with deviation", "not reproduced", "not attempted") and
    same_evidence_as (the row it restates, not counted; None when counted)."""
    passed: int
    all_passed: bool

def names() -> List[str]:
    """The studies ``run`` knows: beam-table, mpc-ex1 .. mpc-ex3-undamped,
    distribution, continuous-path, avoidance, space-robot."""

def run(name: str, **options: Any) -> StudyReport:
    """Runs a seed study; ``options`` are the library's option names (e.g.
    ``payload=50.0`` for distribution, ``ks=[1, 5]`` for avoidance,
    ``solver="clarabel"`` for the MPC examples). A value of the wrong type
    is a ValueError naming its keyword."""

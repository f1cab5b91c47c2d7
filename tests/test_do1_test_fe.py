"""DO1 as a test of the fe level over realisations (rules do1_test_fe_shot and do1_test_fe): the committed study
against the records it must agree with, and the task's refusals of a bad member, step or target."""
from pathlib import Path
from types import SimpleNamespace as NS

import pandas as pd
import pytest

from penetration.tasks.laboratory import do1_test_fe_shot

ROOT = Path(__file__).resolve().parents[1]


def test_the_first_semi_infinite_realisation_is_do1_tests_own_fe_shot():
    """Member 0 in the semi-infinite target is the same run spec as do1_test's fe row (the solver is deterministic):
    a change to one path that the other does not share shows here."""
    members = pd.read_csv(ROOT / "figures/fe/do1_test_members.csv")
    first = members[(members.target == "semi_infinite") & (members.member == 0)].iloc[0]
    fe = pd.read_csv(ROOT / "figures/do1_test.csv").set_index("level").loc["fe"]
    assert first.depth_m == pytest.approx(fe.dop_pred_m, rel=1e-12)
    assert first.failure_strain == pytest.approx(fe.failure_strain, rel=1e-12)


def test_every_realisation_takes_the_laboratory_failure_strain_and_the_table_is_its_members():
    members = pd.read_csv(ROOT / "figures/fe/do1_test_members.csv")
    cal = pd.read_csv(ROOT / "figures/fe/full/calibration_fe_laboratory.csv").set_index("fold").loc["all"]
    assert members.failure_strain.to_numpy() == pytest.approx(cal.value, rel=1e-12)
    table = pd.read_csv(ROOT / "figures/fe/do1_test.csv").set_index("target")
    for target, g in members.groupby("target"):
        assert table.loc[target, "realisations"] == len(g) == g.member.nunique()
        assert table.loc[target, "mean_m"] == pytest.approx(g.depth_m.mean(), rel=1e-11)
        # the realisations differ in the striking velocity by parts in 1e9 only
        assert g.striking_velocity_ms.max() / g.striking_velocity_ms.min() - 1 < 1e-7


@pytest.mark.parametrize("member, step, target, text", [
    (-1, 1e-9, "block", r"do1_test_fe member -1; allowed: >= 0$"),
    (1, 0.0, "block", r"do1_test_fe.velocity_step = 0.0; allowed: 0 < velocity_step <= 1e-6"),
    (1, 1e-3, "block", r"do1_test_fe.velocity_step = 0.001; allowed: 0 < velocity_step <= 1e-6"),
    (1, 1e-9, "slab", r"do1_test_fe.targets: 'slab'; allowed: one of \('semi_infinite', 'block'\)")])
def test_a_bad_member_step_or_target_is_refused_before_the_run(member, step, target, text):
    with pytest.raises(ValueError, match=text):
        do1_test_fe_shot(NS(), NS(), NS(member=member, velocity_step=step, target=target))

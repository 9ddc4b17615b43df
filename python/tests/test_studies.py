"""The studies from Python: restitution tables, the two-grain solver, the validation table."""
import numpy as np
import pytest

import yuxi


def test_collide_gives_the_restitution_table_as_arrays():
    t = yuxi.collide(models=["linear", "hertz_mindlin"], v0_min=1e-3, v0_max=1e-2, per_decade=2)
    assert set(t["model"]) == {"linear", "hertz_mindlin"}
    n = len(t["model"])
    assert n == 6 and t["e_n"].shape == (n,)
    linear = t["model"] == "linear"
    # A linear spring-dashpot's restitution hardly depends on the impact speed (0.1 % over this
    # decade); the Hertzian model's dashpot makes it fall.
    assert np.ptp(t["e_n"][linear]) < 2e-3
    assert ((t["e_n"] > 0) & (t["e_n"] <= 1)).all()


def test_the_thermodynamic_model_comes_with_its_exact_rows():
    t = yuxi.collide(models="thermodynamic", v0_min=1e-4, v0_max=1e-2, per_decade=1)
    exact = t["source"] == "exact"
    engine = t["source"] == "engine"
    assert exact.sum() == engine.sum() == 3
    # Jiang & Liu (2018): the restitution falls with the impact speed, and the engine follows
    # the exact solution.
    assert (np.diff(t["e_n"][exact]) < 0).all()
    assert np.allclose(t["e_n"][engine], t["e_n"][exact], atol=0.02)


def test_two_grain_returns_the_time_series():
    s = yuxi.two_grain(v0=1e-3)
    assert 0 < s["restitution"] < 1
    assert len(s["t"]) == len(s["fn"]) > 100
    # The total energy is conserved by the exact solver.
    assert s["max_energy_error"] < 1e-6
    with pytest.raises(ValueError, match="exact two-grain"):
        yuxi.two_grain(model="linear")


def test_validate_returns_the_table():
    rows = yuxi.validate(["L1"])
    assert rows and all(r["case"] == "L1" for r in rows)
    assert all(r["passed"] for r in rows)
    assert {c["case"] for c in yuxi.validation_cases()} >= {"L1", "B1", "B2", "B3"}
    with pytest.raises(ValueError, match="unknown validation case"):
        yuxi.validate(["no-such-case"])

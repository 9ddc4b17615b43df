"""Scenes from files, TOML strings and dicts: one reader, one set of checks, one set of
messages."""
import os

import numpy as np
import pytest

import yuxi
from conftest import BOX_TOML, REPO


def test_a_scene_from_a_dict_is_the_scene_from_its_toml(box_scene):
    from_dict = yuxi.Scene(box_scene)
    from_toml = yuxi.Scene(BOX_TOML)
    assert from_dict.toml() == from_toml.toml()
    assert from_dict.resolved() == from_toml.resolved()
    assert from_dict.name == "box" and from_dict.dt == 2.0e-4


def test_a_scene_from_a_file_reads_its_relative_paths(tmp_path):
    scene = yuxi.Scene(os.path.join(REPO, "scenes", "basin-small.toml"))
    assert scene.name == "basin-small"
    # The filled-in scene states every default and reads back to itself.
    again = yuxi.Scene.from_dict(scene.resolved())
    assert again.toml() == scene.toml()


def test_numpy_values_are_taken_as_their_python_equivalents(box_scene):
    box_scene["domain"]["hi"] = np.array([8.0, 8.0, 12.0])
    box_scene["run"]["dt"] = np.float64(2.0e-4)
    assert yuxi.Scene(box_scene).toml() == yuxi.Scene(BOX_TOML).toml()


def test_a_bad_value_raises_the_cli_message_with_its_key(box_scene, tmp_path):
    box_scene["contact"]["pair"][0]["k_n"] = -1.0
    with pytest.raises(yuxi.SceneError) as caught:
        yuxi.Simulation(box_scene, output=tmp_path / "out")
    assert "k_n" in str(caught.value)
    assert caught.value.key is not None and caught.value.key.endswith("k_n")
    # Nothing was written.
    assert not (tmp_path / "out").exists()


def test_a_missing_table_and_a_wrong_type_are_named(box_scene):
    del box_scene["materials"]
    with pytest.raises(yuxi.SceneError, match="materials"):
        yuxi.Scene(box_scene)
    with pytest.raises(yuxi.SceneError, match="dt"):
        yuxi.Scene(BOX_TOML.replace("dt = 2.0e-4", 'dt = "fast"'))


def test_a_value_with_no_toml_form_is_refused(box_scene):
    box_scene["run"]["name"] = object()
    with pytest.raises(yuxi.SceneError, match="run.name"):
        yuxi.Scene(box_scene)


def test_a_time_step_too_large_for_the_stiffness_is_refused(box_scene, tmp_path):
    box_scene["run"]["dt"] = 0.01
    with pytest.raises(yuxi.SceneError, match="dt") as refused:
        yuxi.Simulation(box_scene, output=tmp_path / "out")
    assert not (tmp_path / "out").exists()
    assert "force_dt=True" in str(refused.value) and "--force" not in str(refused.value)


def test_a_folder_that_holds_a_run_is_not_overwritten(box_scene, tmp_path):
    out = tmp_path / "out"
    yuxi.Simulation(box_scene, output=out, progress=False).close()
    with pytest.raises(FileExistsError, match="already holds a run") as refused:
        yuxi.Simulation(box_scene, output=out)
    assert "overwrite=True" in str(refused.value) and "--overwrite" not in str(refused.value)
    yuxi.Simulation(box_scene, output=out, overwrite=True, progress=False).close()


def test_changed_merges_tables(box_scene):
    scene = yuxi.Scene(box_scene).changed({"run": {"t_end": 0.5}})
    assert scene.t_end == 0.5 and scene.dt == 2.0e-4


def test_a_dict_scene_s_errors_name_the_key_and_its_misspelling(box_scene):
    box_scene["fill"][0]["radious"] = box_scene["fill"][0].pop("radius")
    with pytest.raises(yuxi.SceneError) as error:
        yuxi.Scene(box_scene)
    message = str(error.value)
    assert message.startswith("<dict>: fill[1].radius:")  # no lines of a text never seen
    assert "(the table has 'radious': misspelt?)" in message
    assert error.value.key == "fill[1].radius"
    box_scene["fill"][0]["radius"] = box_scene["fill"][0].pop("radious")
    box_scene["contact"]["pair"][1]["gama_r"] = 3.0
    with pytest.raises(yuxi.SceneError, match="did you mean 'gamma_r'") as error:
        yuxi.Scene(box_scene)
    assert error.value.key == "contact.pair[2].gama_r"

"""The package's surface: how rovers and scenarios are given, the extras
it names when missing, its stubs and docstrings."""

import ast
import importlib
import inspect
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

import rover
from conftest import REPO

PACKAGE = Path(rover.__file__).parent


def test_a_rover_given_as_a_dict_is_the_rover_of_its_file(data):
    path = REPO / "models" / "mer.toml"
    with open(path, "rb") as f:
        description = tomllib.load(f)
    from_dict, from_file = rover.load(description), rover.load(path)
    assert (from_dict.name, from_dict.dof, from_dict.wheel_names, from_dict.max_torque) == (
        from_file.name,
        from_file.dof,
        from_file.wheel_names,
        from_file.max_torque,
    )
    scenario = {"duration": 0.5, "settle": 0.2, "output_rate": 10.0}
    a = rover.simulate(description, scenario)
    b = rover.simulate(from_file, scenario)
    assert a.status == "completed"
    assert np.array_equal(a.table, b.table)
    sim = rover.Simulation(description, scenario)
    assert sim.dof == from_file.dof
    assert rover.load(from_file) is from_file


def test_a_rover_dict_that_is_not_a_description_is_an_error_naming_the_field():
    with pytest.raises(rover.RoverError, match=r"^error: name: missing field `gravity`\n --> <dict>:1:1"):
        rover.load({"name": "x"})
    with pytest.raises(TypeError, match="^rover: a built-in name, a path, TOML text or a dict is a rover, not int"):
        rover.load(3)


def test_a_scenario_that_names_its_rover_runs_alone(data):
    scenario = data / "slip_rough.toml"
    whole = rover.simulate(None, scenario)
    for r in (rover.simulate(scenario), rover.simulate(scenario=scenario), rover.simulate(str(scenario))):
        assert np.array_equal(r.table, whole.table)
    sim = rover.Simulation(scenario)
    assert sim.columns == whole.columns
    with open(scenario, "rb") as f:
        assert rover.simulate(tomllib.load(f)).status == whole.status


def test_a_call_without_scenario_or_rover_says_what_to_give():
    with pytest.raises(TypeError, match=r"^simulate\(\) needs a scenario: simulate\(scenario\) when the scenario names its rover"):
        rover.simulate()
    for r in ("swing4", rover.load("swing4")):
        with pytest.raises(TypeError, match=r"^simulate\(\): a rover but no scenario; give one: simulate\(rover, scenario\)$"):
            rover.simulate(r)
    with pytest.raises(TypeError, match=r"^Simulation\(\): a rover but no scenario"):
        rover.Simulation("swing4")
    nameless = {"duration": 1.0}
    for call in (rover.simulate, rover.Simulation):
        with pytest.raises(rover.RoverError) as e:
            call(nameless)
        message = str(e.value)
        assert message.startswith("error: no rover: give one as the `rover` argument or as `rover = \"...\"` in <dict>")
        assert "command line" not in message
        assert "swing4" in message


@pytest.fixture
def without(monkeypatch):
    """Make modules unimportable, as when they are not installed."""

    def hide(*modules):
        for m in modules:
            monkeypatch.setitem(sys.modules, m, None)

    return hide


def test_a_sweep_without_ray_names_the_extra_and_writes_nothing(without, tmp_path):
    without("ray")
    out = tmp_path / "sweep"
    with pytest.raises(ImportError) as e:
        rover.sweep({"rover": "swing4", "duration": 0.5}, grid={"control.speed.kp": [1.0]}, out=out)
    assert str(e.value).startswith("rover.sweep() needs ray, which is not installed: install the package with its `sweep` extra")
    assert "pip install './python[sweep]'" in str(e.value)
    assert not out.exists()
    (tmp_path / "plan.toml").write_text('scenario = "x.toml"\n')
    with pytest.raises(ImportError, match=r"^rover.sweep_plan\(\) needs ray.*`sweep` extra"):
        rover.sweep_plan(tmp_path / "plan.toml")
    assert not (tmp_path / "tasks").exists()


def test_a_parquet_table_without_pyarrow_names_the_extra(without, tmp_path):
    without("pyarrow")
    with pytest.raises(ImportError, match=r"needs pyarrow, which is not installed: .*`sweep` extra"):
        rover.sweep({"rover": "swing4", "duration": 0.5}, grid={"control.speed.kp": [1.0]}, out=tmp_path / "s")
    assert not (tmp_path / "s").exists()


def test_the_gym_environment_without_gymnasium_names_the_extra(without, monkeypatch):
    without("gymnasium")
    monkeypatch.delitem(sys.modules, "rover.gym", raising=False)
    with pytest.raises(ImportError, match=r"^rover.gym needs gymnasium, which is not installed: .*`gym` extra .*pip install './python\[gym\]'"):
        importlib.import_module("rover.gym")


def test_to_pandas_without_pandas_names_the_extra(without, data):
    r = rover.simulate(data / "slip_rough.toml")
    without("pandas")
    with pytest.raises(ImportError, match=r"^Result.to_pandas\(\) needs pandas.*`pandas` extra"):
        r.to_pandas()


def test_the_extras_named_are_the_packages():
    with open(REPO / "python" / "pyproject.toml", "rb") as f:
        extras = tomllib.load(f)["project"]["optional-dependencies"]
    for module, extra in rover._EXTRAS.items():
        assert module in extras[extra], (module, extra)


def test_a_plan_file_with_a_misspelled_field_is_refused_before_any_task_runs(tmp_path):
    (tmp_path / "base.toml").write_text('rover = "swing4"\nduration = 0.5\n\n[control.speed]\nspeed = 0.1\n')
    plan = tmp_path / "plan.toml"
    plan.write_text('scenario = "base.toml"\nout = "."\n\n[grid]\n"control.speed.sped" = [0.1, 0.2]\n')
    with pytest.raises(rover.RoverError) as e:
        rover.sweep_plan(plan)
    assert "unknown field `sped`" in str(e.value)
    assert str(e.value).startswith(f"error: {plan}: grid.")
    assert not (tmp_path / "tasks").exists()


def native_names(tree: ast.Module):
    """Top-level names of the stub, and each class's members."""
    top, members = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            top.add(node.name)
        if isinstance(node, ast.ClassDef):
            members[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
    return top, members


def test_the_stub_declares_every_native_function_class_and_member():
    assert (PACKAGE / "py.typed").exists()
    top, members = native_names(ast.parse((PACKAGE / "_native.pyi").read_text()))
    public = {n for n in dir(rover._native) if not n.startswith("_")}
    assert public == top
    for name, declared in members.items():
        cls = getattr(rover._native, name)
        if issubclass(cls, BaseException):
            continue
        actual = {n for n in vars(cls) if not n.startswith("_")}
        assert actual == {n for n in declared if not n.startswith("_")}, name


def test_help_shows_a_docstring_and_signature_for_every_native_name():
    for name in dir(rover._native):
        if name.startswith("_"):
            continue
        obj = getattr(rover._native, name)
        assert obj.__doc__, name
        if isinstance(obj, type):
            for member, attr in vars(obj).items():
                if not member.startswith("_"):
                    assert attr.__doc__, f"{name}.{member}"
        else:
            inspect.signature(obj)
    assert str(inspect.signature(rover._native.Simulation)) == "(rover, text, origin, base, generic=False)"
    for method in ("get_state", "set_state", "snapshot", "restore", "set_torques", "step"):
        assert getattr(rover.Simulation, method).__doc__, method

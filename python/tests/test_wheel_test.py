"""The single-wheel testbed from Python against the command line's."""

import tomllib

import numpy as np
import pytest

import rover

COLUMNS = [
    "slip",
    "sinkage",
    "drawbar_pull",
    "torque",
    "lateral_force",
    "entry_angle",
    "drawbar_pull_over_load",
    "torque_over_load_radius",
]
SOILS = ["lete_sand", "dry_sand", "lunar_nominal", "lunar_simulant", "mars_simulant"]
WHEEL = dict(radius=0.25, width=0.16, load=150.0)
# The required keys of a [soil] table, lunar_nominal's values.
LUNAR = dict(
    n=1.0, k_c=1400.0, k_phi=820000.0, cohesion=170.0, friction_angle_deg=35.0, shear_modulus=0.018
)


def cli_args(soil, radius, width, load, slips, slip_angle_deg=0.0):
    """`rover wheel-test`'s arguments for the same test (each number in
    Python's shortest exact form, which Rust parses back to the same
    float; `--flag=value`, so that negative values pass)."""
    return [
        "wheel-test",
        f"--soil={soil}",
        f"--radius={float(radius)!r}",
        f"--width={float(width)!r}",
        f"--load={float(load)!r}",
        "--slip=" + ",".join(repr(float(s)) for s in slips),
        f"--slip-angle-deg={float(slip_angle_deg)!r}",
    ]


def read_csv(text):
    lines = text.splitlines()
    cols = lines[0].split(",")
    table = np.array([[float(c) for c in line.split(",")] for line in lines[1:]])
    return cols, table


@pytest.mark.parametrize(
    "soil, slips, slip_angle_deg",
    [
        ("lunar_nominal", [-0.5, -0.1, 0.0, 0.1, 0.2, 0.4, 0.6], 0.0),
        ("lunar_simulant", [0.05, 0.3, 0.7], 5.0),
        ("soil.toml", [-0.2, 0.0, 0.25, 0.5], -3.0),
    ],
)
def test_the_columns_equal_the_command_lines_csv_bit_for_bit(
    cli, data, soil, slips, slip_angle_deg
):
    if soil.endswith(".toml"):
        soil = str(data / soil)
    done = cli(*cli_args(soil, **WHEEL, slips=slips, slip_angle_deg=slip_angle_deg))
    cols, table = read_csv(done.stdout)

    out = rover.wheel_test(soil, **WHEEL, slips=slips, slip_angle_deg=slip_angle_deg)
    assert cols == COLUMNS
    assert list(out) == cols
    for i, name in enumerate(cols):
        got = out[name]
        assert got.dtype == np.float64 and got.shape == (len(slips),), name
        # Bit for bit: the same 64-bit patterns, not merely close values.
        assert np.array_equal(got.view(np.uint64), table[:, i].view(np.uint64)), name
    if slip_angle_deg:
        assert np.all(out["lateral_force"] != 0.0)
    else:
        assert np.all(out["lateral_force"] == 0.0)


def test_a_soil_as_a_dict_runs_as_its_file(data):
    path = data / "soil.toml"
    table = tomllib.loads(path.read_text())["soil"]
    slips = [-0.3, 0.0, 0.2, 0.6]
    from_file = rover.wheel_test(path, **WHEEL, slips=slips)
    from_dict = rover.wheel_test(table, **WHEEL, slips=slips)
    assert from_file.keys() == from_dict.keys()
    for name in from_file:
        assert np.array_equal(from_dict[name], from_file[name]), name
    # The optional keys are taken: their defaults give other numbers.
    defaults = rover.wheel_test({k: table[k] for k in LUNAR}, **WHEEL, slips=slips)
    assert not np.array_equal(defaults["drawbar_pull"], from_file["drawbar_pull"])


@pytest.mark.parametrize("soil", SOILS)
def test_the_drawbar_pull_rises_with_slip_from_braking_to_driving(soil):
    # Up to 60 % slip: past it the slip-sinkage of the Mars simulant's
    # weak soil takes back some of its pull.
    slips = np.linspace(-0.6, 0.6, 13)
    out = rover.wheel_test(soil, **WHEEL, slips=slips)
    assert np.array_equal(out["slip"], slips)
    assert np.all(np.diff(out["drawbar_pull"]) > 0.0), out["drawbar_pull"]
    # Braking pulls back, well-driven wheels pull forward.
    assert out["drawbar_pull"][0] < 0.0 < out["drawbar_pull"][-1]


@pytest.mark.parametrize("soil", SOILS)
def test_the_wheel_sinks_deeper_under_more_load(soil):
    loads = [25.0, 50.0, 100.0, 200.0, 400.0]
    sinkage = [rover.wheel_test(soil, 0.25, 0.16, load, [0.2])["sinkage"][0] for load in loads]
    assert np.all(np.diff(sinkage) > 0.0), sinkage
    assert 0.0 < sinkage[0] and sinkage[-1] < 0.25


def test_the_ratios_and_the_sinkage_follow_from_the_other_columns():
    radius, load = 0.3, 220.0
    slips = [-0.4, 0.0, 0.15, 0.5]
    out = rover.wheel_test("dry_sand", radius, 0.2, load, slips, slip_angle_deg=8.0)
    # The same division as the command line's: equal, not merely close.
    assert np.array_equal(out["drawbar_pull_over_load"], out["drawbar_pull"] / load)
    assert np.array_equal(out["torque_over_load_radius"], out["torque"] / (load * radius))
    sinkage = radius * (1.0 - np.cos(out["entry_angle"]))
    np.testing.assert_allclose(out["sinkage"], sinkage, rtol=1e-12)
    assert np.all((out["entry_angle"] > 0.0) & (out["entry_angle"] < np.pi / 2))


def test_one_slip_or_none_gives_arrays_of_that_length():
    one = rover.wheel_test("lete_sand", 0.25, 0.16, 150.0, 0.2)
    assert all(v.shape == (1,) for v in one.values())
    none = rover.wheel_test("lete_sand", 0.25, 0.16, 150.0, [])
    assert list(none) == COLUMNS and all(v.shape == (0,) for v in none.values())
    with pytest.raises(ValueError, match="slips"):
        rover.wheel_test("lete_sand", 0.25, 0.16, 150.0, [[0.1, 0.2]])


@pytest.mark.parametrize(
    "change, names",
    [
        (dict(soil="mud"), "--soil mud"),
        (dict(slips=[0.1, 1.2]), "--slip 1.2"),
        (dict(slips=[-1.0]), "--slip -1"),
        (dict(width=0.0), "--width 0"),
        (dict(radius=-0.25), "--radius -0.25"),
        (dict(load=0.0), "--load 0"),
        (dict(slip_angle_deg=95.0), "--slip-angle-deg 95"),
        (dict(load=1e6), "at slip 0.2"),
    ],
)
def test_bad_input_is_a_value_error_with_the_command_lines_message(cli, change, names):
    args = dict(soil="lunar_nominal", **WHEEL, slips=[0.2])
    args.update(change)
    done = cli(*cli_args(**args), check=False)
    assert done.returncode == 2, done.stderr
    with pytest.raises(ValueError) as e:
        rover.wheel_test(**args)
    assert str(e.value) == done.stderr.rstrip("\n")
    assert str(e.value).startswith(f"error: {names}")


def test_a_load_past_the_axle_says_what_the_soil_carries():
    carries = r"at slip 0\.2: the soil carries at most [0-9.]+ N under this wheel"
    with pytest.raises(ValueError, match=carries):
        rover.wheel_test("lunar_nominal", 0.25, 0.16, 1e6, [0.2])


def test_a_bad_key_in_a_soil_file_is_named_as_on_the_command_line(cli, tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(
        "[soil]\nn = 1.0\nk_c = 1400.0\nk_phi = 820000.0\ncohesion = 170.0\n"
        "friction_angle = 35.0\nshear_modulus = 0.018\n"
    )
    args = dict(soil=str(path), **WHEEL, slips=[0.2])
    done = cli(*cli_args(**args), check=False)
    assert done.returncode == 2
    with pytest.raises(ValueError) as e:
        rover.wheel_test(**args)
    assert str(e.value) == done.stderr.rstrip("\n")
    assert "unknown field `friction_angle`" in str(e.value)


@pytest.mark.parametrize(
    "change, names",
    [
        (dict(n=-1.0), "soil.n = -1"),
        (dict(friction_angle_deg=90), "soil.friction_angle_deg = 90"),
        (dict(rear_ratio=1.5), "soil.rear_ratio = 1.5"),
        (dict(cohesion=float("nan")), "soil.cohesion = NaN"),
        (dict(k_c=0.0, k_phi=0.0), "soil.k_phi = 0"),
        (dict(friction_angle=35.0), "unknown field `friction_angle`"),
        (dict(k_c=None), "missing field `k_c`"),
        (dict(n="soft"), 'n = "soft"'),
    ],
)
def test_a_bad_soil_dict_is_a_value_error_naming_the_key(change, names):
    soil = {**LUNAR, **change}
    soil = {k: v for k, v in soil.items() if v is not None}
    with pytest.raises(ValueError) as e:
        rover.wheel_test(soil, **WHEEL, slips=[0.2])
    assert str(e.value).startswith("error: --soil <dict>: ")
    assert names in str(e.value)


def test_a_soil_neither_a_name_a_path_nor_a_dict_is_a_type_error():
    with pytest.raises(TypeError, match="a soil is a name, a path or a dict"):
        rover.wheel_test(0.5, **WHEEL, slips=[0.2])

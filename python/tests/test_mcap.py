"""A run's MCAP log (docs/VIEW.md) read back with the MCAP project's own
Python reader: every channel with its schema, every message decoded, the
body's transform at every instant equal to run.csv's pose, and each
wheel's frame, composed down the tree, at run.csv's wheel centre."""

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory

import rover

SCENARIO = {
    "rover": "swing4",
    "duration": 1.5,
    "settle": 0.3,
    "output_rate": 40.0,
    "terrain": {"kind": "random", "z_r": 0.1},
    "control": {
        "speed": {"speed": 0.15},
        "steering": {"kind": "slip", "delta_tau": 0.2},
    },
}

SCHEMAS = {
    "/tf": ("foxglove.FrameTransforms", "protobuf", "protobuf"),
    "/row": ("rover.Row", "jsonschema", "json"),
    "/rover": ("foxglove.SceneUpdate", "protobuf", "protobuf"),
    "/terrain": ("foxglove.SceneUpdate", "protobuf", "protobuf"),
}


def read_csv(path):
    lines = path.read_text().splitlines()
    cols = lines[0].split(",")
    return cols, np.array([[float(c) for c in line.split(",")] for line in lines[1:]])


def read_mcap(path):
    """Every message of the file, decoded, by topic: (log_time, message)."""
    protobuf = DecoderFactory()
    out = {}
    with open(path, "rb") as f:
        reader = make_reader(f)
        summary = reader.get_summary()
        channels = {c.topic: c for c in summary.channels.values()}
        assert set(channels) == set(SCHEMAS)
        for topic, (name, schema_encoding, encoding) in SCHEMAS.items():
            channel = channels[topic]
            schema = summary.schemas[channel.schema_id]
            assert (schema.name, schema.encoding, channel.message_encoding) == (
                name,
                schema_encoding,
                encoding,
            )
            assert len(schema.data) > 0
        for schema, channel, message in reader.iter_messages(log_time_order=True):
            if channel.message_encoding == "json":
                decoded = json.loads(message.data)
            else:
                decoded = protobuf.decoder_for(channel.message_encoding, schema)(message.data)
            assert decoded is not None
            out.setdefault(channel.topic, []).append((message.log_time, decoded))
    return out


def quat_mul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
    )


def axis(angle, k):
    v = [0.0, 0.0, 0.0]
    v[k] = math.sin(angle / 2)
    return (math.cos(angle / 2), *v)


def attitude(phi, theta, psi):
    """R = Rz(ψ)·Rx(φ)·Ry(θ) (MODEL.md §1) as (w, x, y, z)."""
    return quat_mul(quat_mul(axis(psi, 2), axis(phi, 0)), axis(theta, 1))


def rotate(q, v):
    w, x, y, z = q
    p = quat_mul(quat_mul(q, (0.0, *v)), (w, -x, -y, -z))
    return np.array(p[1:])


def pose_of(tf):
    t, r = tf.translation, tf.rotation
    return np.array([t.x, t.y, t.z]), (r.w, r.x, r.y, r.z)


def check_log(path, cols, table):
    messages = read_mcap(path)
    rows = len(table)
    assert rows > 10
    assert [len(messages[t]) for t in ("/tf", "/row", "/rover", "/terrain")] == [rows, rows, 1, 1]
    col = {c: i for i, c in enumerate(cols)}
    wheels = sum(1 for c in cols if c.startswith("Fn"))
    rover_scene = messages["/rover"][0][1]
    terrain = messages["/terrain"][0][1]
    assert {e.frame_id for e in rover_scene.entities} >= {"body"}
    mesh = terrain.entities[0].triangles[0]
    assert len(mesh.indices) % 3 == 0 and len(mesh.points) > 100
    for k, ((t_tf, tfs), (t_row, row)) in enumerate(zip(messages["/tf"], messages["/row"])):
        values = table[k]
        t = values[col["t"]]
        assert t_tf == t_row == round(t * 1e9)
        # The row channel: every column, the CSV's numbers.
        assert list(row) == cols
        assert np.array_equal(np.array([row[c] for c in cols]), values)
        frames = {tf.child_frame_id: tf for tf in tfs.transforms}
        body = frames["body"]
        assert body.parent_frame_id == "world"
        at, q = pose_of(body)
        # The translation is the CSV's pose exactly; the rotation its
        # angles' quaternion to rounding.
        assert np.array_equal(at, values[[col["X"], col["Y"], col["Z"]]])
        expected = attitude(values[col["phi"]], values[col["theta"]], values[col["psi"]])
        sign = 1.0 if np.dot(q, expected) >= 0 else -1.0
        assert np.allclose(sign * np.array(q), expected, atol=1e-12, rtol=0)
        # Each wheel's frame, composed from the world down, at W{j}.
        assert sum(1 for c in frames if c.startswith("wheel/")) == wheels
        # Wheel frames in the transforms' order are the description's.
        wheel_tfs = [tf for tf in tfs.transforms if tf.child_frame_id.startswith("wheel/")]
        for j, tf in enumerate(wheel_tfs, start=1):
            chain = [tf]
            while chain[-1].parent_frame_id != "world":
                chain.append(frames[chain[-1].parent_frame_id])
            p = np.zeros(3)
            for link in chain:
                offset, r = pose_of(link)
                p = rotate(r, p) + offset
            centre = values[[col[f"W{j}X"], col[f"W{j}Y"], col[f"W{j}Z"]]]
            assert np.allclose(p, centre, atol=1e-9, rtol=0), (tf.child_frame_id, p, centre)


def test_the_mcap_log_of_a_python_run_decodes_and_holds_the_runs_pose(tmp_path):
    path = tmp_path / "python.mcap"
    r = rover.simulate(None, SCENARIO, mcap=path)
    assert r.status == "completed"
    check_log(path, r.columns, r.table)


def test_rover_simulate_mcap_writes_run_mcap_beside_run_csv(cli, tmp_path):
    scenario = tmp_path / "s.toml"
    scenario.write_text(
        'rover = "swing4"\nduration = 1.0\noutput_rate = 50.0\n'
        '[terrain]\nkind = "random"\nz_r = 0.1\n[control.speed]\nspeed = 0.1\n'
        "[output]\nmcap = true\n"
    )
    out = tmp_path / "out"
    cli("simulate", "--scenario", scenario, "--out", out, "--quiet", "--no-plots")
    cols, table = read_csv(out / "run.csv")
    check_log(out / "run.mcap", cols, table)
    # Without the key nor --mcap, the earlier run's log is removed.
    scenario.write_text(scenario.read_text().replace("mcap = true", "mcap = false"))
    cli("simulate", "--scenario", scenario, "--out", out, "--quiet", "--no-plots")
    assert not (out / "run.mcap").exists()


def test_an_mcap_path_that_cannot_be_written_is_an_error_before_the_run(tmp_path):
    path = tmp_path / "missing" / "run.mcap"
    with pytest.raises(rover.RoverError, match=r"mcap=.*missing.*cannot create the MCAP log"):
        rover.simulate(None, SCENARIO, mcap=path)


def test_rover_simulate_refuses_an_mcap_it_cannot_create(cli, tmp_path):
    scenario = tmp_path / "s.toml"
    scenario.write_text('rover = "swing4"\nduration = 0.2\n')
    out = tmp_path / "out"
    (out / "run.mcap").mkdir(parents=True)
    done = cli(
        "simulate", "--scenario", scenario, "--out", out, "--quiet", "--no-plots", "--mcap",
        check=False,
    )
    assert done.returncode != 0
    assert "run.mcap: cannot create the MCAP log" in done.stderr
    assert '"failed"' in (out / "summary.json").read_text()


def test_the_shipped_layout_reads_only_the_logs_topics_and_columns():
    layout = json.loads((Path(__file__).resolve().parents[2] / "docs/view/rover-layout.json").read_text())
    panels = layout["configById"]
    column = re.compile(r"^(t|X|Y|Z|phi|theta|psi|vx|V_set|(Fn|Fd|Fc|slip|sinkage|tau|delta)[1-6])$")
    paths = [p["value"] for c in panels.values() for p in c.get("paths", [])]
    assert len(paths) > 10
    for path in paths:
        topic, field = path.split(".", 1)
        assert topic == "/row" and column.match(field), path
    scene = panels["3D!rover"]
    assert set(scene["topics"]) <= set(SCHEMAS) and scene["followTf"] == "body"

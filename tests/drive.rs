//! `rover drive` from a plain WebSocket client, as a rig would use it: the
//! rover follows the speed command, bad commands are answered with an
//! error and change nothing, and the page's files are served.

use std::io::{Read, Write};
use std::net::TcpStream;
use std::time::{Duration, Instant};

use rover::drive::{DriveArgs, start};
use serde_json::Value;
use tungstenite::{Message, WebSocket, stream::MaybeTlsStream};

use crate::support::scratch_file;

type Client = WebSocket<MaybeTlsStream<TcpStream>>;

fn args(rover: &str, scenario: &str) -> DriveArgs {
    DriveArgs {
        rover: Some(rover.into()),
        scenario: Some(scenario.into()),
        port: 0,
        rate: 1000.0,
        method: None,
        generic: false,
        report: None,
        report_speed: 0.1,
        pacing: rover::drive::live::Pacing::Spin,
    }
}

/// The next JSON text message (states and replies alike).
fn next(ws: &mut Client) -> Value {
    loop {
        match ws.read().expect("the server keeps the connection") {
            Message::Text(t) => return serde_json::from_str(t.as_str()).unwrap(),
            _ => continue,
        }
    }
}

/// The next message of `kind` ("state", "error", "hello").
fn next_of(ws: &mut Client, kind: &str) -> Value {
    loop {
        let v = next(ws);
        if v["type"] == kind {
            return v;
        }
    }
}

fn get(port: u16, path: &str) -> String {
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    write!(s, "GET {path} HTTP/1.1\r\nHost: localhost\r\n\r\n").unwrap();
    let mut out = String::new();
    s.read_to_string(&mut out).unwrap();
    out
}

/// A client asks for 0.1 m/s on flat ground: within a few simulated
/// seconds the forward speed in the states it receives is within 5 % of
/// it and stays there, the set-point is echoed as `V_set`, and the rover
/// has moved forward. The states carry every CSV column by its name.
#[test]
fn a_websocket_client_drives_the_rover_to_its_speed_set_point() {
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let running = start(&args("swing4", &scenario)).unwrap();
    let (mut ws, _) = tungstenite::connect(format!("ws://127.0.0.1:{}/ws", running.port)).unwrap();
    let hello = next_of(&mut ws, "hello");
    let columns = hello["meta"]["columns"].as_array().unwrap().clone();
    assert_eq!(hello["meta"]["steering"], "slip", "{hello}");
    // Each column's unit, from the same row as run.csv's.
    let units = hello["meta"]["units"].as_array().unwrap();
    assert_eq!(units.len(), columns.len());
    let unit = |c: &str| &units[columns.iter().position(|n| n == c).unwrap()];
    assert_eq!([unit("X"), unit("y1"), unit("Fn1")], ["m", "rad", "N"]);
    ws.send(Message::text(r#"{"rate": 100, "speed": 0.1}"#))
        .unwrap();
    let first = next_of(&mut ws, "state");
    for c in &columns {
        let c = c.as_str().unwrap();
        assert!(first.get(c).is_some(), "state without `{c}`: {first}");
    }
    let x0 = first["X"].as_f64().unwrap();
    // Wall-clock bound only against a hung loop; the checks are on
    // simulated time.
    let give_up = Instant::now() + Duration::from_secs(120);
    let mut within_since: Option<f64> = None;
    let last = loop {
        assert!(
            Instant::now() < give_up,
            "no steady 0.1 m/s within 2 minutes"
        );
        let s = next_of(&mut ws, "state");
        assert!(s["error"].is_null(), "{}", s["error"]);
        let (t, vx) = (s["t"].as_f64().unwrap(), s["vx"].as_f64().unwrap());
        assert_eq!(s["V_set"].as_f64(), Some(0.1));
        if (vx - 0.1).abs() < 0.005 {
            let since = *within_since.get_or_insert(t);
            if t - since >= 1.0 {
                break s;
            }
        } else {
            within_since = None;
        }
        assert!(t < 20.0, "vx = {vx} at t = {t} s");
    };
    assert!(
        last["X"].as_f64().unwrap() - x0 > 0.1,
        "moved {} m",
        last["X"].as_f64().unwrap() - x0
    );
    let timing = running.stop();
    assert!(timing.compute.count() > 1000);
}

/// Bad messages each get an error naming the problem, and leave the
/// command as it was: the loop and the connection go on.
#[test]
fn bad_commands_are_answered_with_errors_and_change_nothing() {
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let running = start(&args("swing4", &scenario)).unwrap();
    let (mut ws, _) = tungstenite::connect(format!("ws://127.0.0.1:{}/ws", running.port)).unwrap();
    next_of(&mut ws, "hello");
    ws.send(Message::text(r#"{"speed": 0.05}"#)).unwrap();
    for (bad, says) in [
        ("speed 1", "not JSON"),
        ("[1, 2]", "JSON object"),
        (r#"{"speed": "fast"}"#, "`speed` must be a number"),
        (r#"{"sped": 1}"#, "unknown key `sped`"),
        (r#"{"torques": [1, 2]}"#, "4 wheels"),
        (r#"{"steer": 0.1}"#, "steers by slip"),
        (r#"{"steering": [0.1, 0, 0, 0]}"#, "does not steer"),
        (
            r#"{"speed": 1, "torques": [0, 0, 0, 0]}"#,
            "cannot be mixed",
        ),
        (r#"{"rate": 0}"#, "`rate`"),
        (r#"{"rate": 1e9}"#, "`rate`"),
        (r#"{"speed": 1e999}"#, "not JSON"),
    ] {
        ws.send(Message::text(bad)).unwrap();
        let e = next_of(&mut ws, "error");
        let message = e["message"].as_str().unwrap();
        assert!(message.contains(says), "{bad}: {message}");
    }
    let s = next_of(&mut ws, "state");
    assert_eq!(s["V_set"].as_f64(), Some(0.05), "{s}");
    assert!(s["error"].is_null());
    running.stop();
}

/// The page, its script and three.js, the rover's description and the
/// terrain are served; anything else is a 404, never a crash; a plain GET
/// of /ws is told to use a WebSocket.
#[test]
fn the_page_and_its_data_are_served() {
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let running = start(&args("exomars", &scenario)).unwrap();
    let port = running.port;
    assert!(get(port, "/").contains("<canvas"), "{}", get(port, "/"));
    assert!(get(port, "/app.js").starts_with("HTTP/1.1 200"));
    assert!(get(port, "/three.min.js").contains("WebGLRenderer"));
    let meta = get(port, "/meta.json");
    assert!(meta.contains("\"rover\":\"exomars\""), "{meta}");
    let terrain = get(port, "/terrain.json");
    let body = terrain.split("\r\n\r\n").nth(1).unwrap();
    let t: Value = serde_json::from_str(body).unwrap();
    assert_eq!(t["z"].as_array().unwrap().len(), 256 * 256);
    assert!(get(port, "/nothing").starts_with("HTTP/1.1 404"));
    assert!(get(port, "/ws").starts_with("HTTP/1.1 400"));
    running.stop();
}

/// A port already taken is an error naming it, not a panic.
#[test]
fn a_port_in_use_is_a_clear_error() {
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port();
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let mut a = args("swing4", &scenario);
    a.port = port;
    let e = start(&a).err().expect("the port is taken").to_string();
    assert!(
        e.contains(&format!("127.0.0.1:{port}")) && e.contains("--port"),
        "{e}"
    );
}

/// `rover view` serves a finished run: its CSV, the rover named in its
/// summary (with its wheels' sizes) and no WebSocket; a folder without a
/// run is a clear error.
#[test]
fn view_serves_a_finished_run() {
    let scenario = scratch_file(
        "drive-view",
        "run.toml",
        "rover = \"swing4\"\nduration = 0.5\n[control.speed]\nspeed = 0.05\n[integrator.rk4]\nstep = 1e-3\n",
    );
    let out = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("drive-view/out");
    rover::cli::simulate(&rover::cli::SimulateArgs {
        rover: None,
        scenario: scenario.clone().into(),
        out: out.clone(),
        quiet: true,
        no_plots: true,
        generic: false,
    })
    .unwrap();
    let viewing = rover::drive::start_view(&rover::drive::ViewArgs {
        out: out.clone(),
        rover: None,
        scenario: Some(scenario.into()),
        port: 0,
    })
    .unwrap();
    let port = viewing.port;
    let csv = get(port, "/run.csv");
    assert!(
        csv.starts_with("HTTP/1.1 200") && csv.contains("\r\n\r\nt,X,Y,Z"),
        "{csv}"
    );
    let meta = get(port, "/meta.json");
    assert!(
        meta.contains("\"mode\":\"view\"") && meta.contains("\"radius\":[0.09"),
        "{meta}"
    );
    assert!(get(port, "/ws").starts_with("HTTP/1.1 404"));
    viewing.stop();
    let empty = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("drive-view/empty");
    std::fs::create_dir_all(&empty).unwrap();
    let e = rover::drive::start_view(&rover::drive::ViewArgs {
        out: empty,
        rover: None,
        scenario: None,
        port: 0,
    })
    .expect_err("no run there")
    .to_string();
    assert!(e.contains("run.csv") && e.contains("cannot read"), "{e}");
}

/// With a watchdog, a client that stops sending commands has the speed
/// zeroed once it expires; a message that is not a command (a rate) does
/// not bring the old set-point back, and the next command does.
#[test]
fn the_watchdog_zeroes_the_command_of_a_silent_client() {
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let running = start(&args("swing4", &scenario)).unwrap();
    let (mut ws, _) = tungstenite::connect(format!("ws://127.0.0.1:{}/ws", running.port)).unwrap();
    next_of(&mut ws, "hello");
    ws.send(Message::text(r#"{"watchdog": 0.3, "speed": 0.05}"#))
        .unwrap();
    let give_up = Instant::now() + Duration::from_secs(60);
    loop {
        let s = next_of(&mut ws, "state");
        if s["watchdog_tripped"] == true {
            assert_eq!(s["V_set"].as_f64(), Some(0.0), "{s}");
            break;
        }
        assert!(Instant::now() < give_up, "the watchdog never tripped");
    }
    ws.send(Message::text(r#"{"rate": 60}"#)).unwrap();
    for _ in 0..5 {
        let s = next_of(&mut ws, "state");
        assert_eq!(s["V_set"].as_f64(), Some(0.0), "{s}");
    }
    ws.send(Message::text(r#"{"speed": 0.02}"#)).unwrap();
    loop {
        let s = next_of(&mut ws, "state");
        if s["V_set"].as_f64() == Some(0.02) {
            break;
        }
        assert!(Instant::now() < give_up, "the new command never took");
    }
    running.stop();
}

/// `--report` drives without a server and prints the latencies; bad
/// rates and durations are errors naming the flag.
#[test]
fn the_report_gives_latencies_and_bad_settings_are_errors() {
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let mut a = args("lrv", &scenario);
    a.rate = 200.0;
    let text = rover::drive::report(&a, 0.5).unwrap();
    assert!(text.starts_with("lrv with ros2, pacing spin:"), "{text}");
    for part in ["median", "99.9th percentile", "overruns:"] {
        assert!(text.contains(part), "{text}");
    }
    assert!(!text.contains("stopped"), "{text}");
    assert!(
        rover::drive::report(&a, -1.0)
            .unwrap_err()
            .to_string()
            .contains("--report -1")
    );
    for bad in [0.0, f64::NAN, 1e9] {
        a.rate = bad;
        let e = rover::drive::report(&a, 0.5).unwrap_err().to_string();
        assert!(e.contains("--rate"), "{e}");
    }
}

/// Body axes from world axes: Rᵀ·v, R = Rz(ψ)·Rx(φ)·Ry(θ) (MODEL.md).
fn to_body(s: &Value, v: [f64; 3]) -> [f64; 3] {
    let (phi, theta, psi) = (
        s["phi"].as_f64().unwrap(),
        s["theta"].as_f64().unwrap(),
        s["psi"].as_f64().unwrap(),
    );
    let rz = |a: f64, v: [f64; 3]| {
        [
            a.cos() * v[0] + a.sin() * v[1],
            -a.sin() * v[0] + a.cos() * v[1],
            v[2],
        ]
    };
    let rx = |a: f64, v: [f64; 3]| {
        [
            v[0],
            a.cos() * v[1] + a.sin() * v[2],
            -a.sin() * v[1] + a.cos() * v[2],
        ]
    };
    let ry = |a: f64, v: [f64; 3]| {
        [
            a.cos() * v[0] - a.sin() * v[2],
            v[1],
            a.sin() * v[0] + a.cos() * v[2],
        ]
    };
    ry(theta, rx(phi, rz(psi, v)))
}

/// A joint of the hello's sketch at a state's coordinates, body axes, as
/// docs/DRIVE.md says a client evaluates it.
fn joint_at(joint: &Value, s: &Value) -> [f64; 3] {
    let c = joint["c"].as_array().unwrap();
    let mut u = [0.0; 3];
    for k in 0..3 {
        u[k] = c[k].as_f64().unwrap();
    }
    for t in joint["terms"].as_array().unwrap() {
        let i = t["coord"].as_u64().unwrap() + 1;
        let xi = s[format!("y{i}")].as_f64().unwrap() - t["center"].as_f64().unwrap();
        let mut p = 1.0;
        for c in t["coeffs"].as_array().unwrap() {
            for k in 0..3 {
                u[k] += c[k].as_f64().unwrap() * p;
            }
            p *= xi;
        }
    }
    u
}

/// The hello's sketch, evaluated at the coordinates of the states a client
/// receives while the MER's rocker-bogie rides the rough terrain, puts
/// each wheel's joint where the state has that wheel (its `W` columns
/// taken to body axes), and keeps every member its length: the page draws
/// the real members where they are.
#[test]
fn the_sketch_in_the_hello_draws_the_members_at_the_live_coordinates() {
    let mut a = args("mer", "");
    a.scenario = None;
    let running = start(&a).unwrap();
    let (mut ws, _) = tungstenite::connect(format!("ws://127.0.0.1:{}/ws", running.port)).unwrap();
    let hello = next_of(&mut ws, "hello");
    let sketch = &hello["meta"]["sketch"];
    let joints = sketch["joints"].as_array().unwrap();
    let links = sketch["links"].as_array().unwrap();
    let members: std::collections::BTreeSet<&str> = links
        .iter()
        .map(|l| l["member"].as_str().unwrap())
        .collect();
    assert_eq!(
        members.into_iter().collect::<Vec<_>>(),
        ["bogie_left", "bogie_right", "rocker_left", "rocker_right"],
        "{sketch}"
    );
    let first = next_of(&mut ws, "state");
    ws.send(Message::text(r#"{"rate": 50, "speed": 0.2}"#))
        .unwrap();
    let dist = |a: [f64; 3], b: [f64; 3]| {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    };
    let lengths = |s: &Value| -> Vec<f64> {
        links
            .iter()
            .map(|l| {
                let [a, b] = [0, 1].map(|k| l["joints"][k].as_u64().unwrap() as usize);
                dist(joint_at(&joints[a], s), joint_at(&joints[b], s))
            })
            .collect()
    };
    let rest = lengths(&first);
    let give_up = Instant::now() + Duration::from_secs(120);
    let mut rocked = 0.0f64;
    while rocked < 0.02 {
        assert!(
            Instant::now() < give_up,
            "the rocker never moved: {rocked} rad"
        );
        let s = next_of(&mut ws, "state");
        assert!(s["error"].is_null(), "{}", s["error"]);
        rocked = rocked.max((s["y1"].as_f64().unwrap() - first["y1"].as_f64().unwrap()).abs());
        for (j, joint) in joints.iter().enumerate() {
            if let Some(w) = joint["wheel"].as_u64() {
                let k = w + 1;
                let world = [
                    s[format!("W{k}X")].as_f64().unwrap() - s["X"].as_f64().unwrap(),
                    s[format!("W{k}Y")].as_f64().unwrap() - s["Y"].as_f64().unwrap(),
                    s[format!("W{k}Z")].as_f64().unwrap() - s["Z"].as_f64().unwrap(),
                ];
                let d = dist(to_body(&s, world), joint_at(joint, &s));
                assert!(d < 1e-6, "joint {j} (wheel {k}) is {d} m off its wheel");
            }
        }
        for (k, (r, d)) in rest.iter().zip(lengths(&s)).enumerate() {
            assert!((r - d).abs() < 3e-3, "link {k}: {r} m at rest, {d} m now");
        }
    }
    running.stop();
}

/// `stop` returns with every server thread ended and the port free, even
/// with a WebSocket client connected and a client that opened a
/// connection and sent nothing; the WebSocket client is told the
/// connection closed.
#[test]
fn stopping_ends_the_server_threads_and_frees_the_port() {
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let running = start(&args("swing4", &scenario)).unwrap();
    let port = running.port;
    let threads = running.server_threads();
    let (mut ws, _) = tungstenite::connect(format!("ws://127.0.0.1:{port}/ws")).unwrap();
    next_of(&mut ws, "hello");
    next_of(&mut ws, "state");
    let mut idle = TcpStream::connect(("127.0.0.1", port)).unwrap();
    let give_up = Instant::now() + Duration::from_secs(10);
    // The accept loop, the WebSocket session, the idle connection.
    while threads.load(std::sync::atomic::Ordering::SeqCst) < 3 {
        assert!(
            Instant::now() < give_up,
            "the server never took the connections"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    let began = Instant::now();
    running.stop();
    assert!(
        began.elapsed() < Duration::from_secs(5),
        "{:?}",
        began.elapsed()
    );
    assert_eq!(threads.load(std::sync::atomic::Ordering::SeqCst), 0);
    std::net::TcpListener::bind(("127.0.0.1", port)).expect("the port is free after stop");
    let closed = loop {
        match ws.read() {
            Ok(Message::Close(_)) | Err(_) => break true,
            Ok(_) => continue,
        }
    };
    assert!(closed);
    let mut buf = [0u8; 16];
    assert_eq!(
        idle.read(&mut buf).unwrap_or(0),
        0,
        "the idle connection is closed"
    );
}

/// `rover view`'s server stops the same way.
#[test]
fn stopping_the_view_frees_its_port() {
    let scenario = scratch_file(
        "drive-view-stop",
        "run.toml",
        "rover = \"swing4\"\nduration = 0.1\n[integrator.rk4]\nstep = 1e-3\n",
    );
    let out = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("drive-view-stop/out");
    rover::cli::simulate(&rover::cli::SimulateArgs {
        rover: None,
        scenario: scenario.into(),
        out: out.clone(),
        quiet: true,
        no_plots: true,
        generic: false,
    })
    .unwrap();
    let viewing = rover::drive::start_view(&rover::drive::ViewArgs {
        out,
        rover: None,
        scenario: None,
        port: 0,
    })
    .unwrap();
    let port = viewing.port;
    let threads = viewing.server_threads();
    assert!(get(port, "/meta.json").contains("\"sketch\""));
    let _idle = TcpStream::connect(("127.0.0.1", port)).unwrap();
    viewing.stop();
    assert_eq!(threads.load(std::sync::atomic::Ordering::SeqCst), 0);
    std::net::TcpListener::bind(("127.0.0.1", port)).expect("the port is free after stop");
}

/// The next binary message (skipping text).
fn next_binary(ws: &mut Client) -> Vec<f64> {
    loop {
        if let Message::Binary(b) = ws.read().expect("the server keeps the connection") {
            assert_eq!(b.len() % 8, 0, "{} bytes", b.len());
            return b
                .chunks_exact(8)
                .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
                .collect();
        }
    }
}

/// A rig subscribes to binary frames: each is the hello's `binary_layout`
/// of little-endian f64, the publication count rising, the time advancing,
/// the command echoed and the rover's weight on its wheels; errors still
/// come as JSON text, and subscribing to JSON brings the text states back.
#[test]
fn a_rig_subscribes_to_binary_state_frames() {
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let running = start(&args("swing4", &scenario)).unwrap();
    let (mut ws, _) = tungstenite::connect(format!("ws://127.0.0.1:{}/ws", running.port)).unwrap();
    let hello = next_of(&mut ws, "hello");
    let layout: Vec<String> = hello["meta"]["binary_layout"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap().to_string())
        .collect();
    let columns = hello["meta"]["columns"].as_array().unwrap();
    assert_eq!(layout.len(), 8 + columns.len());
    let at = |name: &str| layout.iter().position(|c| c == name).unwrap();
    ws.send(Message::text(
        r#"{"subscribe": "binary", "rate": 200, "speed": 0.05}"#,
    ))
    .unwrap();
    let mut frames = Vec::new();
    while frames.len() < 200 {
        let f = next_binary(&mut ws);
        assert_eq!(f.len(), layout.len());
        frames.push(f);
    }
    for w in frames.windows(2) {
        assert!(w[1][at("seq")] > w[0][at("seq")]);
        assert!(w[1][at("t")] > w[0][at("t")]);
        assert!(w[1][at("steps")] > w[0][at("steps")]);
    }
    let last = frames.last().unwrap();
    assert_eq!(last[at("V_set")], 0.05);
    assert_eq!(last[at("flags")], 0.0);
    assert!(last[at("wall")] > 0.0 && last[at("rtf")] > 0.0, "{last:?}");
    // Swing4: 32.4 kg on the Moon, its weight on the four wheels once
    // settled (a second of 200 frames at 200 Hz).
    let load: f64 = (1..=4).map(|k| last[at(&format!("Fn{k}"))]).sum();
    assert!(
        (load - 32.4 * 1.62).abs() < 0.1 * 32.4 * 1.62,
        "Σ Fn = {load}"
    );
    ws.send(Message::text(r#"{"subscribe": "morse"}"#)).unwrap();
    let e = next_of(&mut ws, "error");
    assert!(
        e["message"].as_str().unwrap().contains("`subscribe`"),
        "{e}"
    );
    ws.send(Message::text(r#"{"subscribe": "json"}"#)).unwrap();
    let s = next_of(&mut ws, "state");
    assert_eq!(s["V_set"].as_f64(), Some(0.05));
    running.stop();
}

/// With a scenario's active suspension, the loop moves the springs'
/// neutrals as the rover pitches and rolls on rough ground, and a reset
/// puts them back; without one they stay where the description has them.
#[test]
fn a_scenarios_active_suspension_runs_in_the_loop() {
    use rover::drive::live;
    let spec = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4").unwrap();
    let rough = rover::drive::DEFAULT_SCENARIO;
    let active = format!(
        "{rough}[control.active_suspension]\nsample_time = 0.1\nkp_pitch = 0.6\nkp_roll = 0.6\n"
    );
    let dir = std::path::Path::new(".");
    let run = |text: &str| {
        let scenario =
            rover_scenario::scenario::Scenario::parse(text, std::path::Path::new("s.toml"))
                .unwrap();
        let config = live::LoopConfig::new(1000.0, None, &scenario);
        let mut sim = live::Sim::new(
            rover_models::Swing4::new(),
            &spec.model,
            &scenario,
            dir,
            &config,
        )
        .unwrap();
        let mut command = live::Command::zero(4);
        command.speed = 0.1;
        sim.set_command(&command);
        for _ in 0..3000 {
            sim.step().unwrap();
        }
        let moved = sim.neutrals().to_vec();
        sim.reset();
        (moved, sim.neutrals().to_vec())
    };
    let at_rest: Vec<f64> = spec.model.coordinates.iter().map(|c| c.neutral).collect();
    let (moved, after_reset) = run(&active);
    let shift = moved
        .iter()
        .zip(&at_rest)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(shift > 1e-3, "neutrals {moved:?}, at rest {at_rest:?}");
    assert_eq!(after_reset, at_rest);
    let (passive, _) = run(rough);
    assert_eq!(passive, at_rest);
}

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
        allow_origin: Vec::new(),
        token: None,
        rate: 1000.0,
        method: None,
        generic: false,
        report: None,
        report_speed: 0.1,
        pacing: rover::drive::live::Pacing::Spin,
        estimate: false,
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
    request(
        port,
        &format!("GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n"),
    )
}

/// Send `head` as it is and read the answer until the server closes (what
/// came before a reset counts: a refused client may be reset once answered).
fn request(port: u16, head: &str) -> String {
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    let _ = s.write_all(head.as_bytes());
    let mut out = Vec::new();
    let mut chunk = [0u8; 4096];
    while let Ok(n) = s.read(&mut chunk) {
        if n == 0 {
            break;
        }
        out.extend_from_slice(&chunk[..n]);
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// A WebSocket client as a rig connects: no Origin, the server's token.
fn connect(running: &rover::drive::Running) -> Client {
    let url = format!("ws://127.0.0.1:{}/ws?token={}", running.port, running.token);
    tungstenite::connect(url).unwrap().0
}

/// A client asks for 0.1 m/s on flat ground: within a few simulated
/// seconds the forward speed in the states it receives is within 5 % of
/// it and stays there, the set-point is echoed as `V_set`, and the rover
/// has moved forward. The states carry every CSV column by its name.
#[test]
fn a_websocket_client_drives_the_rover_to_its_speed_set_point() {
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let running = start(&args("swing4", &scenario)).unwrap();
    let mut ws = connect(&running);
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
    let mut ws = connect(&running);
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
        (r#"{"rate": 1e-300}"#, "`rate` = "),
        (r#"{"rate": 5e-324}"#, "`rate` = "),
        (r#"{"speed": 1e308}"#, "`speed` = 1"),
        (r#"{"speed": -5}"#, "beyond ±4.5 m/s"),
        (r#"{"delta_tau": -1e308}"#, "`delta_tau` = "),
        (r#"{"watchdog": 1e308}"#, "`watchdog` = "),
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
    let plain = get(port, &format!("/ws?token={}", running.token));
    assert!(plain.starts_with("HTTP/1.1 400"), "{plain}");
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
        mcap: false,
    })
    .unwrap();
    let viewing = rover::drive::start_view(&rover::drive::ViewArgs {
        out: out.clone(),
        rover: None,
        scenario: Some(scenario.into()),
        port: 0,
        allow_origin: Vec::new(),
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
    // The Host and Origin policy holds for the view too.
    let rebound = request(
        port,
        &format!("GET /run.csv HTTP/1.1\r\nHost: rebound.example:{port}\r\n\r\n"),
    );
    assert!(
        rebound.starts_with("HTTP/1.1 421") && !rebound.contains("t,X,Y,Z"),
        "{rebound}"
    );
    let foreign = request(
        port,
        &format!(
            "GET /run.csv HTTP/1.1\r\nHost: localhost:{port}\r\nOrigin: http://evil.example\r\n\r\n"
        ),
    );
    assert!(
        foreign.starts_with("HTTP/1.1 403") && !foreign.contains("t,X,Y,Z"),
        "{foreign}"
    );
    viewing.stop();
    let empty = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("drive-view/empty");
    std::fs::create_dir_all(&empty).unwrap();
    let e = rover::drive::start_view(&rover::drive::ViewArgs {
        out: empty,
        rover: None,
        scenario: None,
        port: 0,
        allow_origin: Vec::new(),
    })
    .expect_err("no run there")
    .to_string();
    assert!(e.contains("run.csv") && e.contains("cannot read"), "{e}");
}

/// A run's output folder carries its ground: `rover simulate` writes
/// `terrain.json` (the terrain under the path), and `rover view` without
/// `--scenario` serves it, so a run on rough ground is not drawn flat; a
/// `terrain.json` that is not a grid of heights is not served.
#[test]
fn view_draws_the_terrain_the_run_had_without_its_scenario() {
    let scenario = scratch_file(
        "drive-view-terrain",
        "rough.toml",
        "rover = \"swing4\"\nduration = 0.3\n[terrain]\nkind = \"random\"\nz_r = 0.2\nnode_amplitude = 0.25\npatch_radius = 0.6\npatch_blend = 0.5\n[control.speed]\nspeed = 0.05\n[integrator.rk4]\nstep = 1e-3\n",
    );
    let out = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("drive-view-terrain/out");
    let run = |scenario: &std::path::Path| {
        rover::cli::simulate(&rover::cli::SimulateArgs {
            rover: None,
            scenario: scenario.into(),
            out: out.clone(),
            quiet: true,
            no_plots: true,
            generic: false,
            mcap: false,
        })
        .unwrap()
    };
    run(scenario.as_ref());
    let view = || {
        rover::drive::start_view(&rover::drive::ViewArgs {
            out: out.clone(),
            rover: None,
            scenario: None,
            port: 0,
            allow_origin: Vec::new(),
        })
        .unwrap()
    };
    let body = |port: u16| -> Value {
        let r = get(port, "/terrain.json");
        assert!(r.starts_with("HTTP/1.1 200"), "{r}");
        serde_json::from_str(r.split("\r\n\r\n").nth(1).unwrap()).unwrap()
    };
    // The terrain grid `rover view` serves, and its heights.
    let heights = || {
        let viewing = view();
        let grid = body(viewing.port);
        viewing.stop();
        let z: Vec<f64> = grid["z"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(Value::as_f64)
            .collect();
        (grid, z)
    };
    let (grid, z) = heights();
    // The same ground as the scenario's terrain built anew and sampled
    // under the path of run.csv (`rover view --scenario`): the run's own
    // terrain, sampled at its end, is that terrain.
    let rebuilt = rover::drive::start_view(&rover::drive::ViewArgs {
        out: out.clone(),
        rover: None,
        scenario: Some(scenario.clone().into()),
        port: 0,
        allow_origin: Vec::new(),
    })
    .unwrap();
    assert_eq!(
        body(rebuilt.port),
        grid,
        "the ground of the run's end against the rebuilt terrain"
    );
    rebuilt.stop();
    let relief = z.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
        - z.iter().cloned().fold(f64::INFINITY, f64::min);
    assert!(relief > 0.05, "relief {relief} m: drawn flat");
    let (nx, ny) = (grid["nx"].as_u64().unwrap(), grid["ny"].as_u64().unwrap());
    assert!(
        nx <= 256 && ny <= 256 && z.len() as u64 == nx * ny,
        "{nx} × {ny}"
    );
    // The grid covers the path with its margin: the start is inside.
    let x0 = grid["x0"].as_f64().unwrap();
    assert!(x0 <= -rover::drive::PATH_MARGIN + 0.01, "x0 = {x0}");
    // A run on flat ground over the same folder replaces it.
    let flat = scratch_file(
        "drive-view-terrain",
        "flat.toml",
        "rover = \"swing4\"\nduration = 0.2\n[integrator.rk4]\nstep = 1e-3\n",
    );
    run(flat.as_ref());
    let (_, z) = heights();
    assert!(z.iter().all(|h| (h - z[0]).abs() < 1e-9), "not flat");
    // Not a grid: flat ground (`null`), not the file.
    rover_files::write_whole(&out.join("terrain.json"), b"{\"z\": [1, 2]}").unwrap();
    let viewing = view();
    assert_eq!(body(viewing.port), Value::Null);
    viewing.stop();
}

/// With a watchdog, a client that stops sending commands has the speed
/// zeroed once it expires; a message that is not a command (a rate) does
/// not bring the old set-point back, and the next command does.
#[test]
fn the_watchdog_zeroes_the_command_of_a_silent_client() {
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let running = start(&args("swing4", &scenario)).unwrap();
    let mut ws = connect(&running);
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
    assert!(!text.contains("estimator"), "{text}");
    // With the estimator: what its sensor instants cost, 50 in 0.5 s at
    // 100 Hz (fewer when the loop dropped ticks).
    a.estimate = true;
    let text = rover::drive::report(&a, 0.5).unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with("estimator: "))
        .unwrap_or_else(|| panic!("{text}"));
    let instants: u64 = line["estimator: ".len()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        (25..=51).contains(&instants) && line.contains("at 100 Hz"),
        "{text}"
    );
    assert!(!text.contains("stopped"), "{text}");
    a.estimate = false;
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
    let mut ws = connect(&running);
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
    let mut ws = connect(&running);
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
        mcap: false,
    })
    .unwrap();
    let viewing = rover::drive::start_view(&rover::drive::ViewArgs {
        out,
        rover: None,
        scenario: None,
        port: 0,
        allow_origin: Vec::new(),
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
    let mut ws = connect(&running);
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

/// The status line of a WebSocket handshake to `url` with `headers`: 101
/// when accepted, the refusal's status otherwise, and the refusal's text.
fn handshake(url: &str, headers: &[(&str, &str)]) -> (u16, String) {
    use tungstenite::client::IntoClientRequest;
    let mut req = url.into_client_request().unwrap();
    for (name, value) in headers {
        req.headers_mut().insert(
            tungstenite::http::HeaderName::from_bytes(name.as_bytes()).unwrap(),
            value.parse().unwrap(),
        );
    }
    match tungstenite::connect(req) {
        Ok((mut ws, response)) => {
            let hello = next_of(&mut ws, "hello");
            assert_eq!(hello["meta"]["mode"], "drive");
            (response.status().as_u16(), String::new())
        }
        Err(tungstenite::Error::Http(response)) => (
            response.status().as_u16(),
            String::from_utf8_lossy(response.body().as_deref().unwrap_or_default()).into_owned(),
        ),
        Err(e) => panic!("{url}: {e}"),
    }
}

/// Only this server's own names are served: a request whose Host is any
/// other name (a page on a rebound domain) is refused, on the files and
/// the WebSocket alike, and so is a request without a Host.
#[test]
fn a_foreign_host_is_refused() {
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let running = start(&args("swing4", &scenario)).unwrap();
    let port = running.port;
    for host in [
        format!("127.0.0.1:{port}"),
        format!("localhost:{port}"),
        format!("[::1]:{port}"),
    ] {
        let ok = request(
            port,
            &format!("GET /meta.json HTTP/1.1\r\nHost: {host}\r\n\r\n"),
        );
        assert!(ok.starts_with("HTTP/1.1 200"), "{host}: {ok}");
    }
    for path in ["/", "/meta.json", "/terrain.json", "/app.js"] {
        let rebound = request(
            port,
            &format!("GET {path} HTTP/1.1\r\nHost: rebound.example:{port}\r\n\r\n"),
        );
        assert!(
            rebound.starts_with("HTTP/1.1 421") && rebound.contains("rebound.example"),
            "{rebound}"
        );
        assert!(!rebound.contains("\"rover\""), "{rebound}");
    }
    let other_port = request(
        port,
        &format!("GET / HTTP/1.1\r\nHost: 127.0.0.1:{}\r\n\r\n", port ^ 1),
    );
    assert!(other_port.starts_with("HTTP/1.1 421"), "{other_port}");
    let none = request(port, "GET / HTTP/1.1\r\n\r\n");
    assert!(
        none.starts_with("HTTP/1.1 400") && none.contains("Host"),
        "{none}"
    );
    let twice = request(
        port,
        &format!("GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nHost: rebound.example\r\n\r\n"),
    );
    assert!(twice.starts_with("HTTP/1.1 400"), "{twice}");
    let url = format!("ws://127.0.0.1:{port}/ws?token={}", running.token);
    let (status, text) = handshake(&url, &[("Host", "rebound.example")]);
    assert_eq!(status, 421, "{text}");
    running.stop();
}

/// The WebSocket: a page of a foreign origin is refused even with the
/// token; the server's own page and an allowed origin connect without
/// one; a client without an Origin (a program) needs the token, in the
/// query or as a bearer header, and a wrong one is refused.
#[test]
fn who_may_open_the_websocket() {
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let mut a = args("swing4", &scenario);
    a.allow_origin = vec!["http://localhost:3000/".into()];
    let running = start(&a).unwrap();
    let port = running.port;
    let token = running.token.clone();
    assert_eq!(token.len(), 32, "{token}");
    let bare = format!("ws://127.0.0.1:{port}/ws");
    let with_token = format!("{bare}?token={token}");
    for (url, headers, want) in [
        (
            &bare,
            vec![("Origin", format!("http://127.0.0.1:{port}"))],
            101,
        ),
        (
            &bare,
            vec![("Origin", format!("http://localhost:{port}"))],
            101,
        ),
        (
            &bare,
            vec![("Origin", "http://localhost:3000".to_string())],
            101,
        ),
        (&with_token, vec![], 101),
        (
            &bare,
            vec![("Authorization", format!("Bearer {token}"))],
            101,
        ),
        (
            &bare,
            vec![("Origin", "http://evil.example".to_string())],
            403,
        ),
        (
            &with_token,
            vec![("Origin", "http://evil.example".to_string())],
            403,
        ),
        (&with_token, vec![("Origin", "null".to_string())], 403),
        (
            &bare,
            vec![("Origin", "http://localhost:3001".to_string())],
            403,
        ),
        (&bare, vec![], 401),
        (
            &format!("{bare}?token=0123456789abcdef0123456789abcdef"),
            vec![],
            401,
        ),
        (
            &bare,
            vec![("Authorization", format!("Basic {token}"))],
            401,
        ),
    ] {
        let h: Vec<(&str, &str)> = headers.iter().map(|(n, v)| (*n, v.as_str())).collect();
        let (status, text) = handshake(url, &h);
        assert_eq!(status, want, "{url} {headers:?}: {text}");
        if want == 401 {
            assert!(text.contains("token"), "{text}");
        }
        if want == 403 {
            assert!(text.contains("--allow-origin"), "{text}");
        }
    }
    // The page's plain files do not need the token; a foreign page's
    // request for them is refused.
    let page = request(
        port,
        &format!("GET /meta.json HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n"),
    );
    assert!(page.starts_with("HTTP/1.1 200"), "{page}");
    let foreign = request(
        port,
        &format!(
            "GET /meta.json HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nOrigin: http://evil.example\r\n\r\n"
        ),
    );
    assert!(foreign.starts_with("HTTP/1.1 403"), "{foreign}");
    running.stop();
}

/// `--token`, `--allow-origin`, `--rate` and `--report-speed` are checked
/// before anything starts, each error naming its flag.
#[test]
fn bad_access_flags_and_extreme_settings_are_errors() {
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let mut a = args("swing4", &scenario);
    a.token = Some("rig-token-0123456789".into());
    let running = start(&a).unwrap();
    assert_eq!(running.token, "rig-token-0123456789");
    running.stop();
    for bad in [
        "short",
        "has space in it, long enough",
        "ünïcödé-0123456789",
    ] {
        a.token = Some(bad.into());
        let e = start(&a).err().expect("a bad token").to_string();
        assert!(e.contains("--token") && e.contains("16 to 256"), "{e}");
    }
    a.token = None;
    for bad in [
        "localhost:3000",
        "http://x/app",
        "ftp://x",
        "http://x:70000",
    ] {
        a.allow_origin = vec![bad.into()];
        let e = start(&a).err().expect("a bad origin").to_string();
        assert!(e.contains("--allow-origin") && e.contains(bad), "{e}");
    }
    a.allow_origin = Vec::new();
    for rate in [1e-19, 1e300, -1.0, f64::INFINITY] {
        a.rate = rate;
        let e = start(&a).err().expect("a bad rate").to_string();
        assert!(
            e.contains("--rate") && e.contains("between 1 and 20000"),
            "{e}"
        );
    }
    a.rate = 1000.0;
    for speed in [1e308, -1e308, f64::NAN, 5.0] {
        a.report_speed = speed;
        let e = rover::drive::report(&a, 0.1).unwrap_err().to_string();
        assert!(
            e.contains("--report-speed") && e.contains("±4.5 m/s"),
            "{e}"
        );
    }
    // The library's loop refuses a rate it cannot pace, without a panic.
    let model = rover_scenario::prepare::load_rover("swing4", None)
        .unwrap()
        .model;
    let scenario = rover_scenario::scenario::Scenario::parse(
        "duration = 1.0\n",
        std::path::Path::new("s.toml"),
    )
    .unwrap();
    let plant = rover_runtime::generic_plant::GenericPlant::new(model.clone()).unwrap();
    let config = rover::drive::live::LoopConfig::new(1e-19, None, &scenario);
    let e =
        rover::drive::live::Sim::new(plant, &model, &scenario, std::path::Path::new("."), &config)
            .err()
            .expect("no loop at 1e-19 Hz")
            .to_string();
    assert!(e.contains("--rate"), "{e}");
}

/// Connections beyond the cap are answered 503 without being served;
/// once some close, new ones are served again.
#[test]
fn too_many_connections_are_refused() {
    use rover::drive::server::MAX_CONNECTIONS;
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let running = start(&args("swing4", &scenario)).unwrap();
    let port = running.port;
    // Idle: each holds a connection until its head times out.
    let idle: Vec<TcpStream> = (0..MAX_CONNECTIONS)
        .map(|_| TcpStream::connect(("127.0.0.1", port)).unwrap())
        .collect();
    let busy = get(port, "/meta.json");
    assert!(
        busy.starts_with("HTTP/1.1 503") && busy.contains("too many connections"),
        "{busy}"
    );
    drop(idle);
    let give_up = Instant::now() + Duration::from_secs(10);
    loop {
        let again = get(port, "/meta.json");
        if again.starts_with("HTTP/1.1 200") {
            break;
        }
        assert!(Instant::now() < give_up, "never served again: {again}");
        std::thread::sleep(Duration::from_millis(20));
    }
    running.stop();
}

/// A WebSocket message over the cap closes that connection (code 1009,
/// message too big) without being answered as a command; a request head
/// over its cap, or with a body, is refused; the server goes on serving.
#[test]
fn oversized_messages_and_requests_are_refused() {
    use rover::drive::server::{MAX_HEAD, MAX_MESSAGE};
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let running = start(&args("swing4", &scenario)).unwrap();
    let port = running.port;
    let mut ws = connect(&running);
    next_of(&mut ws, "hello");
    // Under the cap, an unknown key is answered.
    let small = format!(r#"{{"speed": 0.1, "pad": "{}"}}"#, "x".repeat(1000));
    ws.send(Message::text(small)).unwrap();
    assert!(
        next_of(&mut ws, "error")["message"]
            .as_str()
            .unwrap()
            .contains("`pad`")
    );
    let big = format!(
        r#"{{"speed": 0.1, "pad": "{}"}}"#,
        "x".repeat(MAX_MESSAGE + 1)
    );
    let _ = ws.send(Message::text(big));
    let code = loop {
        match ws.read() {
            Ok(Message::Close(frame)) => break frame.map(|f| u16::from(f.code)),
            Ok(Message::Text(t)) => {
                let v: Value = serde_json::from_str(t.as_str()).unwrap();
                assert_ne!(v["type"], "error", "the oversized message was read: {v}");
            }
            Ok(_) => {}
            Err(_) => break None,
        }
    };
    if let Some(code) = code {
        assert_eq!(code, 1009);
    }
    // The same with a binary message.
    let mut ws = connect(&running);
    next_of(&mut ws, "hello");
    let _ = ws.send(Message::binary(vec![0u8; 4 * MAX_MESSAGE]));
    loop {
        match ws.read() {
            Ok(Message::Close(_)) | Err(_) => break,
            Ok(Message::Text(t)) => assert!(!t.contains("\"error\""), "answered: {t}"),
            Ok(_) => {}
        }
    }
    let long = format!(
        "GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nX-Pad: {}\r\n\r\n",
        "x".repeat(MAX_HEAD)
    );
    let r = request(port, &long);
    assert!(r.starts_with("HTTP/1.1 431"), "{}", &r[..r.len().min(200)]);
    let body = request(
        port,
        &format!("GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Length: 5\r\n\r\nhello"),
    );
    assert!(body.starts_with("HTTP/1.1 413"), "{body}");
    let mut ws = connect(&running);
    next_of(&mut ws, "hello");
    next_of(&mut ws, "state");
    running.stop();
}

/// A client sending a stream of random and mutated messages, text and
/// binary, gets an error or nothing for each, never a dropped connection;
/// the loop keeps stepping and the last good command holds.
#[test]
fn a_live_server_survives_random_messages() {
    use proptest::strategy::{Strategy, ValueTree};
    use proptest::test_runner::{Config, RngSeed, TestRunner};
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    let running = start(&args("swing4", &scenario)).unwrap();
    let mut ws = connect(&running);
    next_of(&mut ws, "hello");
    ws.send(Message::text(r#"{"speed": 0.03}"#)).unwrap();
    let mut runner = TestRunner::new(Config {
        rng_seed: RngSeed::Fixed(2012),
        failure_persistence: None,
        ..Config::default()
    });
    let strategy = fuzz::message();
    for _ in 0..300 {
        let m = strategy.new_tree(&mut runner).unwrap().current();
        let is_command = matches!(&m, fuzz::Msg::Text(t) if protocol_ok(t));
        if is_command {
            continue;
        }
        match m {
            fuzz::Msg::Text(t) => ws.send(Message::text(t)).unwrap(),
            fuzz::Msg::Binary(b) => ws.send(Message::binary(b)).unwrap(),
        }
        let e = next_of(&mut ws, "error");
        assert!(!e["message"].as_str().unwrap().is_empty(), "{e}");
    }
    let s = next_of(&mut ws, "state");
    assert_eq!(s["V_set"].as_f64(), Some(0.03), "{s}");
    assert!(s["error"].is_null(), "{s}");
    running.stop();
}

/// Whether the protocol takes `text` for swing4 at 1 kHz.
fn protocol_ok(text: &str) -> bool {
    rover::drive::protocol::parse(text, &fuzz::info("swing4"), 1000.0).is_ok()
}

/// Random and mutated protocol messages, fed to `protocol::parse` and
/// `protocol::apply`: nothing panics, every refusal is a non-empty text,
/// and what is taken is within the rover's ranges.
mod fuzz {
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngSeed};
    use rover::drive::live::{self, RoverInfo};
    use rover::drive::protocol::{self, KEYS, MAX_RAW_STEERING, MAX_STEER};

    /// A message as sent over the WebSocket.
    #[derive(Clone, Debug)]
    pub enum Msg {
        Text(String),
        Binary(Vec<u8>),
    }

    /// swing4 (slip-steered) or exomars (Ackermann), loaded once.
    pub fn info(rover: &str) -> RoverInfo {
        static LOADED: std::sync::OnceLock<[RoverInfo; 2]> = std::sync::OnceLock::new();
        let [swing4, exomars] = LOADED.get_or_init(|| {
            ["swing4", "exomars"].map(|r| {
                RoverInfo::new(&rover_scenario::prepare::load_rover(r, None).unwrap().model)
            })
        });
        match rover {
            "swing4" => swing4.clone(),
            _ => exomars.clone(),
        }
    }

    const HOSTILE: &[&str] = &[
        "1e308",
        "-1e308",
        "1e-320",
        "5e-324",
        "-0.0",
        "0",
        "1e999",
        "NaN",
        "Infinity",
        "null",
        "true",
        "\"1\"",
        "[]",
        "{}",
        "[1e308, 1e308, 1e308, 1e308]",
        "[0, 0, 0, 0, 0, 0]",
        "99999999999999999999999",
        "-1",
        "1.2000000001",
        "3.2",
    ];

    /// Valid messages to mutate.
    const SEEDS: &[&str] = &[
        r#"{"speed": 0.1}"#,
        r#"{"speed": 0.1, "delta_tau": 0.2}"#,
        r#"{"speed": 0.1, "steer": 0.2}"#,
        r#"{"torques": [1, 1, 1, 1], "steering": [0, 0, 0, 0]}"#,
        r#"{"rate": 60, "watchdog": 0.5, "subscribe": "binary"}"#,
        r#"{"pause": true, "reset": true}"#,
    ];

    fn json_value() -> impl Strategy<Value = String> {
        let leaf = prop_oneof![
            Just("null".to_string()),
            any::<bool>().prop_map(|b| b.to_string()),
            any::<f64>().prop_map(|v| format!("{v:e}")),
            any::<i64>().prop_map(|v| v.to_string()),
            (0..HOSTILE.len()).prop_map(|k| HOSTILE[k].to_string()),
            "[a-z\"\\\\]{0,8}".prop_map(|s| format!("{:?}", s)),
        ];
        leaf.prop_recursive(3, 24, 6, |inner| {
            prop_oneof![
                prop::collection::vec(inner.clone(), 0..6)
                    .prop_map(|v| format!("[{}]", v.join(","))),
                prop::collection::vec((key(), inner), 0..5).prop_map(|kv| {
                    let body: Vec<String> = kv.iter().map(|(k, v)| format!("{k:?}:{v}")).collect();
                    format!("{{{}}}", body.join(","))
                }),
            ]
        })
    }

    fn key() -> impl Strategy<Value = String> {
        prop_oneof![
            4 => (0..KEYS.len()).prop_map(|k| KEYS[k].to_string()),
            1 => "[a-z_]{0,10}",
        ]
    }

    /// An object of protocol keys with random values.
    fn object() -> impl Strategy<Value = String> {
        prop::collection::vec((key(), json_value()), 0..6).prop_map(|kv| {
            let body: Vec<String> = kv.iter().map(|(k, v)| format!("{k:?}:{v}")).collect();
            format!("{{{}}}", body.join(","))
        })
    }

    /// A valid message with one number or token replaced, or bytes cut
    /// out or inserted.
    fn mutated() -> impl Strategy<Value = String> {
        (
            0..SEEDS.len(),
            0usize..64,
            0usize..HOSTILE.len(),
            0usize..3,
            any::<u8>(),
        )
            .prop_map(|(seed, at, hostile, how, byte)| {
                let text = SEEDS[seed];
                let at = at % text.len();
                let at = (0..=at)
                    .rev()
                    .find(|&k| text.is_char_boundary(k))
                    .unwrap_or(0);
                match how {
                    0 => {
                        // Replace the number (or word) at `at`.
                        let end = text[at..]
                            .find([',', '}', ']', ' '])
                            .map_or(text.len(), |k| at + k);
                        format!("{}{}{}", &text[..at], HOSTILE[hostile], &text[end..])
                    }
                    1 => format!("{}{}", &text[..at], &text[(at + 1).min(text.len())..]),
                    _ => format!("{}{}{}", &text[..at], byte as char, &text[at..]),
                }
            })
    }

    pub fn message() -> impl Strategy<Value = Msg> {
        prop_oneof![
            3 => object().prop_map(Msg::Text),
            3 => mutated().prop_map(Msg::Text),
            1 => json_value().prop_map(Msg::Text),
            1 => prop::collection::vec(any::<u8>(), 0..64)
                .prop_map(|b| Msg::Text(String::from_utf8_lossy(&b).into_owned())),
            1 => prop::collection::vec(any::<u8>(), 0..64).prop_map(Msg::Binary),
        ]
    }

    fn config() -> Config {
        Config {
            cases: 2000,
            rng_seed: RngSeed::Fixed(2012),
            failure_persistence: None,
            ..Config::default()
        }
    }

    /// Parse, and apply what is taken to a fresh inbox: the command in
    /// force stays finite and within the rover's ranges.
    fn survives(text: &str, info: &RoverInfo) {
        let wheels = info.steerable.len();
        match protocol::parse(text, info, 1000.0) {
            Ok(req) => {
                let shared = live::shared(10, wheels, 1000.0);
                let mut inbox = shared.inbox.lock().unwrap();
                protocol::apply(&req, &mut inbox);
                let c = &inbox.command;
                assert!(c.speed.abs() <= info.max_speed(), "{text}: {c:?}");
                assert!(c.steer.abs() <= MAX_STEER, "{text}: {c:?}");
                assert!(c.delta_tau.abs() <= info.max_delta_tau(), "{text}: {c:?}");
                assert!(c.torques.iter().all(|v| v.is_finite()), "{text}: {c:?}");
                assert!(
                    c.steering.iter().all(|v| v.abs() <= MAX_RAW_STEERING),
                    "{text}: {c:?}"
                );
                assert!((0.0..=3600.0).contains(&inbox.watchdog_s), "{text}");
                if let Some(rate) = req.rate {
                    assert!(
                        std::time::Duration::try_from_secs_f64(1.0 / rate).is_ok(),
                        "{text}"
                    );
                }
            }
            Err(e) => {
                let m = e.to_string();
                assert!(!m.trim().is_empty(), "{text}: an empty refusal");
                let reply: serde_json::Value =
                    serde_json::from_str(&protocol::error_json(&m)).unwrap();
                assert_eq!(reply["type"], "error");
            }
        }
    }

    proptest! {
        #![proptest_config(config())]

        #[test]
        fn random_messages_never_panic_the_protocol(m in message(), rover in 0usize..2) {
            let info = info(["swing4", "exomars"][rover]);
            match m {
                Msg::Text(t) => survives(&t, &info),
                Msg::Binary(b) => survives(&String::from_utf8_lossy(&b), &info),
            }
        }
    }
}

/// The access policy on its own: the hosts, origins and tokens it takes.
mod access_policy {
    use rover::drive::access::*;

    fn access() -> Access {
        Access::new(
            "127.0.0.1:8080".parse().unwrap(),
            &["https://rig.example.org".to_string()],
            Some("0123456789abcdef".to_string()),
        )
    }

    fn creds<'a>(host: &'a str, origin: Option<&'a str>) -> Credentials<'a> {
        Credentials {
            host: Some(host),
            origin,
            ..Credentials::default()
        }
    }

    #[test]
    fn hosts_of_this_server_only() {
        let a = access();
        for ok in ["127.0.0.1:8080", "LOCALHOST:8080", "[::1]:8080"] {
            assert_eq!(a.check_request(&creds(ok, None)), Ok(()), "{ok}");
        }
        for bad in ["evil.example:8080", "127.0.0.1:8081", "localhost", ""] {
            let e = a.check_request(&creds(bad, None)).unwrap_err();
            assert!(e.status.starts_with("421"), "{bad}: {e:?}");
        }
        let e = a.check_request(&Credentials::default()).unwrap_err();
        assert!(e.status.starts_with("400") && e.reason.contains("Host"));
    }

    #[test]
    fn origins_own_or_allowed_only() {
        let a = access();
        let host = "127.0.0.1:8080";
        for ok in [
            "http://127.0.0.1:8080",
            "http://localhost:8080",
            "https://rig.example.org",
        ] {
            assert_eq!(a.check_websocket(&creds(host, Some(ok))), Ok(()), "{ok}");
        }
        for bad in [
            "http://evil.example",
            "null",
            "https://127.0.0.1:8080",
            "http://127.0.0.1:8081",
        ] {
            let mut c = creds(host, Some(bad));
            c.query_token = Some("0123456789abcdef");
            let e = a.check_websocket(&c).unwrap_err();
            assert!(e.status.starts_with("403"), "{bad}: {e:?}");
        }
    }

    #[test]
    fn a_client_without_origin_needs_the_token() {
        let a = access();
        let mut c = creds("127.0.0.1:8080", None);
        assert!(a.check_websocket(&c).unwrap_err().status.starts_with("401"));
        c.query_token = Some("0123456789abcdeX");
        assert!(a.check_websocket(&c).unwrap_err().reason.contains("wrong"));
        c.query_token = Some("0123456789abcdef");
        assert_eq!(a.check_websocket(&c), Ok(()));
        c.query_token = None;
        c.authorization = Some("Bearer 0123456789abcdef");
        assert_eq!(a.check_websocket(&c), Ok(()));
        c.authorization = Some("Basic 0123456789abcdef");
        assert!(a.check_websocket(&c).is_err());
        // The plain routes do not ask for it.
        assert_eq!(a.check_request(&creds("127.0.0.1:8080", None)), Ok(()));
    }

    #[test]
    fn allowed_origins_are_checked_and_normalised() {
        for (given, want) in [
            ("http://localhost:3000", "http://localhost:3000"),
            ("HTTPS://Rig.Example.org:443/", "https://rig.example.org"),
            ("http://[::1]:9000", "http://[::1]:9000"),
        ] {
            assert_eq!(parse_origin(given).as_deref(), Ok(want));
        }
        for bad in [
            "localhost:3000",
            "ftp://x",
            "http://x/path",
            "http://x:0",
            "http://x:99999",
            "http://",
            "http://u@x",
            "http://a b",
            "http://[zz]",
        ] {
            let e = parse_origin(bad).unwrap_err();
            assert!(e.starts_with("--allow-origin"), "{bad}: {e}");
        }
    }

    #[test]
    fn tokens() {
        let t = random_token();
        assert_eq!(t.len(), 32);
        assert_ne!(t, random_token());
        assert!(check_token("--token", &t).is_ok());
        assert!(check_token("--token", "short").is_err());
        assert!(check_token("--token", "sixteen chars ok?").is_err());
    }
}

/// On a soft soil the wheels leave ruts, and a client is sent them: a
/// `ruts` message whose tiles hold the depths (counts of `scale` metres)
/// of the map's nodes, one of them nonzero once the rover has driven off
/// its first presses.
#[test]
fn a_drive_on_soil_sends_the_ruts() {
    let scenario = scratch_file(
        "drive",
        "soil.toml",
        "duration = 1.0\n[terrain]\nkind = \"flat\"\nsoil = \"dry_sand\"\n",
    );
    let running = start(&args("mer", &scenario)).unwrap();
    let mut ws = connect(&running);
    next_of(&mut ws, "hello");
    ws.send(Message::text(r#"{"rate": 20, "speed": 0.3}"#))
        .unwrap();
    // Wall-clock bound only against a hung loop.
    let give_up = Instant::now() + Duration::from_secs(120);
    let (deepest, nodes) = loop {
        assert!(Instant::now() < give_up, "no rut within 2 minutes");
        let m = next(&mut ws);
        if m["type"] == "state" {
            assert!(m["error"].is_null(), "{}", m["error"]);
            continue;
        }
        if m["type"] != "ruts" {
            continue;
        }
        assert_eq!(m["cell"].as_f64(), Some(0.02), "{m}");
        let scale = m["scale"].as_f64().unwrap();
        let tiles = m["tiles"].as_array().unwrap();
        assert!(!tiles.is_empty());
        let mut deepest = 0.0f64;
        for t in tiles {
            let [nx, ny] = [0, 1].map(|k| t["nodes"][k].as_u64().unwrap() as usize);
            let depth = t["depth"].as_array().unwrap();
            assert_eq!(depth.len(), nx * ny, "{t}");
            for k in depth {
                deepest = deepest.max(k.as_f64().unwrap() * scale);
            }
        }
        if deepest > 0.0 {
            break (deepest, tiles.len());
        }
    };
    // A rut, shallower than the wheel's radius.
    assert!(
        deepest > 1e-4 && deepest < 0.13,
        "{deepest} m over {nodes} tiles"
    );
    running.stop();
}

/// `--estimate`: the filter fed the sensors' readings of the live loop's
/// true state (the default MEMS set, no fix) follows the rover. Swing4
/// driven at 0.2 m/s from the flat start onto the rough default ground,
/// straight for 4 s, then slip-steered into a left turn for 4 s: at every
/// sensor instant (100 Hz, every tenth step at 1 kHz) the estimated
/// position is within 2 cm of the truth, roll and pitch within 0.5°, each
/// wheel centre drawn at the estimate within 3 cm of the true one; the
/// published values are the estimate's, and its 1σ is positive.
#[test]
fn the_estimate_follows_the_rover_on_rough_ground() {
    use rover::drive::{ghost, live};
    let spec = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4").unwrap();
    let scenario = rover_scenario::scenario::Scenario::parse(
        rover::drive::DEFAULT_SCENARIO,
        std::path::Path::new("s.toml"),
    )
    .unwrap();
    let dir = std::path::Path::new(".");
    let model = &spec.model;
    let config = live::LoopConfig::new(1000.0, None, &scenario);
    let mut sim = live::Sim::new(rover_models::Swing4::new(), model, &scenario, dir, &config)
        .unwrap()
        .with_estimate(model, &scenario, dir, &ghost::default_sensors())
        .unwrap();
    let (m, k) = (model.m(), model.wheels.len());
    let names = ghost::columns(m, k);
    let at = |c: &str| names.iter().position(|n| n == c).unwrap();
    let mut est = vec![0.0; sim.estimate_len()];
    assert_eq!(est.len(), names.len());
    let row_names = sim.columns().names().to_vec();
    let col = |c: &str| row_names.iter().position(|n| n == c).unwrap();
    let mut row = vec![0.0; row_names.len()];
    let mut command = live::Command::zero(k);
    command.speed = 0.2;
    sim.set_command(&command);
    let (mut position, mut attitude, mut wheel, mut roll, mut instants) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0);
    for step in 1..=8000 {
        if step == 4000 {
            // A quarter of the smallest motor limit, left.
            command.delta_tau = 0.25
                * sim
                    .info()
                    .max_torque
                    .iter()
                    .cloned()
                    .fold(f64::INFINITY, f64::min);
            sim.set_command(&command);
        }
        sim.step().unwrap();
        let g = sim.ghost().unwrap();
        assert!(g.error().is_none(), "{:?}", g.error());
        if (g.time() - sim.t()).abs() > 1e-9 {
            continue;
        }
        instants += 1;
        let (e, y) = (g.state().to_vec(), sim.y().to_vec());
        position = position.max((e[0] - y[0]).hypot(e[1] - y[1]));
        attitude = attitude.max((e[3] - y[3]).abs()).max((e[4] - y[4]).abs());
        roll = roll.max(y[3].abs());
        sim.estimate_row(&mut est);
        sim.row(&mut row);
        for (i, c) in ["est_X", "est_Y", "est_Z", "est_phi", "est_theta", "est_psi"]
            .iter()
            .enumerate()
        {
            assert_eq!(est[at(c)], e[i], "{c}");
        }
        assert_eq!(est[at("est_t")], sim.t());
        for j in 1..=k {
            let d: f64 = ["X", "Y", "Z"]
                .iter()
                .map(|a| est[at(&format!("est_W{j}{a}"))] - row[col(&format!("W{j}{a}"))])
                .map(|v| v * v)
                .sum();
            wheel = wheel.max(d.sqrt());
        }
        for c in ["est_sigma_X", "est_sigma_Y", "est_sigma_psi"] {
            assert!(
                est[at(c)] > 0.0 && est[at(c)] < 0.05,
                "{c} = {}",
                est[at(c)]
            );
        }
    }
    assert_eq!(instants, 800);
    let travelled = sim.y()[0].hypot(sim.y()[1]);
    // On the rough ground past the flat start, rolling there.
    assert!(
        travelled > 1.2 && roll > 2f64.to_radians(),
        "{travelled} m, roll {roll} rad"
    );
    assert!(position < 0.02, "position off by {position} m");
    assert!(
        attitude < 0.5f64.to_radians(),
        "attitude off by {} °",
        attitude.to_degrees()
    );
    assert!(wheel < 0.03, "a wheel centre off by {wheel} m");
}

/// With `--estimate` each state carries the estimate under the `est_`
/// names and `est_error` (null while it runs), the hello says which
/// sensors at what rate, and a binary frame carries the same values after
/// the columns; without it, no `est_` key, none in the layout, no
/// `estimate` in the hello.
#[test]
fn the_state_carries_the_estimate_only_with_the_flag() {
    let scenario = scratch_file("drive", "flat.toml", "duration = 1.0\n");
    for estimate in [false, true] {
        let mut a = args("swing4", &scenario);
        a.estimate = estimate;
        let running = start(&a).unwrap();
        let mut ws = connect(&running);
        let hello = next_of(&mut ws, "hello");
        let layout: Vec<String> = hello["meta"]["binary_layout"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_str().unwrap().to_string())
            .collect();
        ws.send(Message::text(r#"{"rate": 100, "speed": 0.1}"#))
            .unwrap();
        let s = loop {
            let s = next_of(&mut ws, "state");
            if s["t"].as_f64().unwrap() > 1.0 {
                break s;
            }
        };
        let est: Vec<&String> = s
            .as_object()
            .unwrap()
            .keys()
            .filter(|k| k.starts_with("est_"))
            .collect();
        if !estimate {
            assert!(est.is_empty(), "{est:?}");
            assert!(hello["meta"].get("estimate").is_none(), "{hello}");
            assert!(!layout.iter().any(|c| c.starts_with("est_")));
            running.stop();
            continue;
        }
        let meta = &hello["meta"]["estimate"];
        assert_eq!(meta["sensors"], "default", "{meta}");
        assert_eq!(meta["rate_hz"].as_f64(), Some(100.0));
        let names = rover::drive::ghost::columns(4, 4);
        let mut want: Vec<String> = names.clone();
        want.push("est_error".into());
        want.sort();
        let mut got: Vec<String> = est.iter().map(|k| k.to_string()).collect();
        got.sort();
        assert_eq!(got, want);
        assert!(s["est_error"].is_null(), "{s}");
        let (t, est_t) = (s["t"].as_f64().unwrap(), s["est_t"].as_f64().unwrap());
        assert!(
            est_t <= t && t - est_t < 0.01 + 1e-9,
            "t {t}, est_t {est_t}"
        );
        for c in ["X", "Y", "Z"] {
            let d = s[format!("est_{c}")].as_f64().unwrap() - s[c].as_f64().unwrap();
            assert!(d.abs() < 0.02, "est_{c} off by {d} m: {s}");
        }
        // Binary: the columns, then the estimate's values.
        let columns = hello["meta"]["columns"].as_array().unwrap();
        assert_eq!(layout.len(), 8 + columns.len() + names.len());
        assert_eq!(layout[8 + columns.len()..], names[..]);
        ws.send(Message::text(r#"{"subscribe": "binary"}"#))
            .unwrap();
        let f = next_binary(&mut ws);
        assert_eq!(f.len(), layout.len());
        let slot = |c: &str| f[layout.iter().position(|n| n == c).unwrap()];
        assert!((slot("est_X") - slot("X")).abs() < 0.02);
        assert_eq!(slot("flags"), 0.0);
        running.stop();
    }
}

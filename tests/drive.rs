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
    let (port, _) = rover::drive::start_view(&rover::drive::ViewArgs {
        out: out.clone(),
        rover: None,
        scenario: Some(scenario.into()),
        port: 0,
    })
    .unwrap();
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
    assert!(text.starts_with("lrv with ros2:"), "{text}");
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

//! The WebSocket protocol (docs/DRIVE.md): JSON text messages, commands in
//! and state out. A message is checked whole before any of it applies, and
//! a bad one is answered with `{"type": "error", "message": …}` naming the
//! field: the connection and the loop go on. The ruts' messages
//! (`"type": "ruts"`) are [`super::rut_feed`]'s.

use std::fmt::Write as _;
use std::time::Instant;

use serde_json::{Map, Value};

use super::live::{Inbox, Mode, RoverInfo, Snapshot};

/// Every key a command message may have.
pub const KEYS: &[&str] = &[
    "speed",
    "steer",
    "delta_tau",
    "torques",
    "steering",
    "pause",
    "reset",
    "rate",
    "watchdog",
    "subscribe",
];

/// How a client receives the state.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Format {
    /// JSON text messages, every value by name ([`state_json`]).
    #[default]
    Json,
    /// Binary messages: little-endian f64 in the fixed order of
    /// [`binary_layout`] ([`state_binary`]).
    Binary,
}

/// The loop's own figures at the head of a binary state frame, before the
/// CSV's columns.
pub const BINARY_HEAD: &[&str] = &[
    "seq",
    "wall",
    "rtf",
    "steps",
    "overruns",
    "dropped_ticks",
    "step_us",
    "flags",
];

/// Bits of the binary frame's `flags`.
pub const FLAG_PAUSED: u32 = 1;
/// See [`FLAG_PAUSED`].
pub const FLAG_WATCHDOG: u32 = 2;
/// See [`FLAG_PAUSED`]: the simulation has stopped on an error (its text
/// comes in the JSON state; subscribe to JSON to read it).
pub const FLAG_ERROR: u32 = 4;
/// See [`FLAG_PAUSED`]: the estimation has stopped on an error (`rover
/// drive --estimate`; its text is the JSON state's `est_error`).
pub const FLAG_ESTIMATE_ERROR: u32 = 8;

/// The name of each f64 of a binary state frame, in order: [`BINARY_HEAD`],
/// the CSV's columns, then the estimate's values (`rover drive
/// --estimate`; none otherwise).
pub fn binary_layout(columns: &[String], estimate: &[String]) -> Vec<String> {
    BINARY_HEAD
        .iter()
        .map(|s| s.to_string())
        .chain(columns.iter().cloned())
        .chain(estimate.iter().cloned())
        .collect()
}

/// Largest |steer| accepted \[rad\]: beyond, the Ackermann angles of the
/// inner wheels pass 90°.
pub const MAX_STEER: f64 = 1.2;

/// Largest |angle| of a raw `steering` value \[rad\]: half a turn either
/// way reaches every direction a wheel can point.
pub const MAX_RAW_STEERING: f64 = std::f64::consts::PI;

/// Lowest `rate` a client may ask for [messages per second]: one state
/// every 100 s. Its period must be a time the server can wait, and a
/// client that wants fewer states can simply skip them.
pub const MIN_RATE: f64 = 0.01;

/// Longest `watchdog` \[s\]: an hour; a longer silence is no link
/// failure to guard against (0 turns it off).
pub const MAX_WATCHDOG: f64 = 3600.0;

/// A command message, checked.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Request {
    /// Speed set-point [m/s].
    pub speed: Option<f64>,
    /// Ackermann steering angle \[rad\].
    pub steer: Option<f64>,
    /// Slip steering torque difference [N·m].
    pub delta_tau: Option<f64>,
    /// Raw torques [N·m].
    pub torques: Option<Vec<f64>>,
    /// Raw steering angles \[rad\].
    pub steering: Option<Vec<f64>>,
    /// Pause or resume.
    pub pause: Option<bool>,
    /// Back to the initial state.
    pub reset: bool,
    /// State messages per second for this client.
    pub rate: Option<f64>,
    /// Watchdog timeout \[s\] (0: off).
    pub watchdog: Option<f64>,
    /// This client's state format from now on.
    pub subscribe: Option<Format>,
}

impl Request {
    /// Whether it changes what drives the rover (and so feeds the watchdog).
    pub fn is_command(&self) -> bool {
        self.speed.is_some()
            || self.steer.is_some()
            || self.delta_tau.is_some()
            || self.torques.is_some()
            || self.steering.is_some()
    }
}

/// Why a client's message was refused: its text goes back to the client,
/// and the loop's command is left as it was.
#[derive(Debug, thiserror::Error)]
pub enum MessageError {
    /// Not JSON at all.
    #[error("not JSON: {0}")]
    NotJson(serde_json::Error),
    /// JSON, but not an object.
    #[error("a message is a JSON object such as {{\"speed\": 0.1}}, got {0}")]
    NotObject(Value),
    /// A key the protocol does not have.
    #[error("unknown key `{key}`; the keys are {}", KEYS.join(", "))]
    UnknownKey {
        /// The key.
        key: String,
    },
    /// A key's value is of the wrong kind or out of its range.
    #[error("{message}")]
    Value {
        /// The key.
        key: &'static str,
        /// What is wrong and what the key takes.
        message: String,
    },
    /// Keys that do not fit this rover, or do not go together.
    #[error("{0}")]
    Combination(&'static str),
}

/// A bad value of `key`.
fn bad(key: &'static str, message: String) -> MessageError {
    MessageError::Value { key, message }
}

fn number(obj: &Map<String, Value>, key: &'static str) -> Result<Option<f64>, MessageError> {
    match obj.get(key) {
        None => Ok(None),
        Some(Value::Number(n)) => match n.as_f64() {
            Some(v) if v.is_finite() => Ok(Some(v)),
            _ => Err(bad(
                key,
                format!("`{key}` must be a finite number, got {n}"),
            )),
        },
        Some(other) => Err(bad(key, format!("`{key}` must be a number, got {other}"))),
    }
}

fn per_wheel(
    obj: &Map<String, Value>,
    key: &'static str,
    wheels: usize,
) -> Result<Option<Vec<f64>>, MessageError> {
    let Some(v) = obj.get(key) else {
        return Ok(None);
    };
    let Value::Array(items) = v else {
        return Err(bad(
            key,
            format!("`{key}` must be an array of {wheels} numbers (one per wheel), got {v}"),
        ));
    };
    if items.len() != wheels {
        return Err(bad(
            key,
            format!(
                "`{key}` has {} values; the rover has {wheels} wheels",
                items.len()
            ),
        ));
    }
    items
        .iter()
        .enumerate()
        .map(|(k, x)| match x.as_f64() {
            Some(v) if v.is_finite() => Ok(v),
            _ => Err(bad(
                key,
                format!(
                    "`{key}`[{k}] (wheel {}) must be a finite number, got {x}",
                    k + 1
                ),
            )),
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

/// Parse and check one message for a rover; `max_rate` is the loop's rate.
pub fn parse(text: &str, info: &RoverInfo, max_rate: f64) -> Result<Request, MessageError> {
    let value: Value = serde_json::from_str(text).map_err(MessageError::NotJson)?;
    let Value::Object(obj) = value else {
        return Err(MessageError::NotObject(value));
    };
    if let Some(k) = obj.keys().find(|k| !KEYS.contains(&k.as_str())) {
        return Err(MessageError::UnknownKey { key: k.clone() });
    }
    let wheels = info.steerable.len();
    let mut r = Request {
        speed: number(&obj, "speed")?,
        steer: number(&obj, "steer")?,
        delta_tau: number(&obj, "delta_tau")?,
        torques: per_wheel(&obj, "torques", wheels)?,
        steering: per_wheel(&obj, "steering", wheels)?,
        rate: number(&obj, "rate")?,
        watchdog: number(&obj, "watchdog")?,
        ..Request::default()
    };
    match obj.get("pause") {
        None => {}
        Some(Value::Bool(b)) => r.pause = Some(*b),
        Some(v) => {
            return Err(bad(
                "pause",
                format!("`pause` must be true or false, got {v}"),
            ));
        }
    }
    match obj.get("subscribe") {
        None => {}
        Some(Value::String(f)) if f == "json" => r.subscribe = Some(Format::Json),
        Some(Value::String(f)) if f == "binary" => r.subscribe = Some(Format::Binary),
        Some(v) => {
            return Err(bad(
                "subscribe",
                format!("`subscribe` must be \"json\" or \"binary\" (the state's format), got {v}"),
            ));
        }
    }
    match obj.get("reset") {
        None | Some(Value::Bool(false)) => {}
        Some(Value::Bool(true)) => r.reset = true,
        Some(v) => return Err(bad("reset", format!("`reset` must be true, got {v}"))),
    }
    if let Some(v) = r.speed {
        let max = info.max_speed();
        if v.abs() > max {
            return Err(bad(
                "speed",
                format!(
                    "`speed` = {v:?} m/s is beyond ±{max} m/s, what this rover's wheels plausibly reach ({} wheel radii a second)",
                    super::live::MAX_SPEED_RADII
                ),
            ));
        }
    }
    if let Some(s) = r.steer {
        if !info.ackermann() {
            return Err(MessageError::Combination(
                "this rover has no steerable wheel: it steers by slip, send `delta_tau` [N·m]",
            ));
        }
        if s.abs() > MAX_STEER {
            return Err(bad(
                "steer",
                format!("`steer` = {s:?} rad is beyond ±{MAX_STEER} rad"),
            ));
        }
    }
    if let Some(dt) = r.delta_tau {
        if info.ackermann() {
            return Err(MessageError::Combination(
                "this rover steers its wheels (Ackermann): send `steer` [rad], or raw `steering`",
            ));
        }
        let max = info.max_delta_tau();
        if dt.abs() > max {
            return Err(bad(
                "delta_tau",
                format!(
                    "`delta_tau` = {dt:?} N·m is beyond ±{max} N·m (twice the rover's largest motor torque: beyond it each side's wheels are held at their motor limits whatever it is)"
                ),
            ));
        }
    }
    let loop_mode = r.speed.is_some() || r.steer.is_some() || r.delta_tau.is_some();
    let raw = r.torques.is_some() || r.steering.is_some();
    if loop_mode && raw {
        return Err(MessageError::Combination(
            "`speed`/`steer`/`delta_tau` (the loop's speed controller) and raw `torques`/`steering` cannot be mixed in one message",
        ));
    }
    if let Some(angles) = &r.steering
        && let Some(k) = (0..wheels).find(|&k| !info.steerable[k] && angles[k] != 0.0)
    {
        return Err(bad(
            "steering",
            format!("`steering`[{k}]: wheel {} does not steer; give it 0", k + 1),
        ));
    }
    if let Some(angles) = &r.steering
        && let Some(k) = (0..wheels).find(|&k| angles[k].abs() > MAX_RAW_STEERING)
    {
        return Err(bad(
            "steering",
            format!(
                "`steering`[{k}] (wheel {}) = {:?} rad is beyond ±π rad",
                k + 1,
                angles[k]
            ),
        ));
    }
    if let Some(rate) = r.rate
        && !(MIN_RATE..=max_rate).contains(&rate)
    {
        return Err(bad(
            "rate",
            format!(
                "`rate` = {rate:?}: state messages per second, from {MIN_RATE} to {max_rate} (the loop's rate)"
            ),
        ));
    }
    if let Some(w) = r.watchdog
        && !(0.0..=MAX_WATCHDOG).contains(&w)
    {
        return Err(bad(
            "watchdog",
            format!("`watchdog` = {w:?}: seconds, from 0 (off) to {MAX_WATCHDOG}"),
        ));
    }
    Ok(r)
}

/// Apply a checked request to the inbox (the loop takes it at its next step).
pub fn apply(r: &Request, inbox: &mut Inbox) {
    let c = &mut inbox.command;
    if r.speed.is_some() || r.steer.is_some() || r.delta_tau.is_some() {
        if c.mode == Mode::Raw {
            // Leaving raw mode: no raw value carries over.
            c.torques.iter_mut().for_each(|v| *v = 0.0);
            c.steering.iter_mut().for_each(|v| *v = 0.0);
        }
        c.mode = Mode::Speed;
    }
    if let Some(v) = r.speed {
        c.speed = v;
    }
    if let Some(v) = r.steer {
        c.steer = v;
    }
    if let Some(v) = r.delta_tau {
        c.delta_tau = v;
    }
    if r.torques.is_some() || r.steering.is_some() {
        if c.mode == Mode::Speed {
            c.speed = 0.0;
            c.steer = 0.0;
            c.delta_tau = 0.0;
        }
        c.mode = Mode::Raw;
    }
    if let Some(t) = &r.torques {
        c.torques.copy_from_slice(t);
    }
    if let Some(s) = &r.steering {
        c.steering.copy_from_slice(s);
    }
    if let Some(p) = r.pause {
        inbox.paused = p;
    }
    if r.reset {
        inbox.resets += 1;
        c.speed = 0.0;
        c.steer = 0.0;
        c.delta_tau = 0.0;
        c.torques.iter_mut().for_each(|v| *v = 0.0);
        c.steering.iter_mut().for_each(|v| *v = 0.0);
    }
    if let Some(w) = r.watchdog {
        inbox.watchdog_s = w;
    }
    if r.is_command() {
        inbox.last_command = Instant::now();
    }
    inbox.seq += 1;
}

/// A number as JSON (non-finite values are `null`).
fn num(out: &mut String, v: f64) {
    if v.is_finite() {
        rover_files::push_f64(out, v);
    } else {
        out.push_str("null");
    }
}

/// A JSON string literal.
fn string(out: &mut String, s: &str) {
    out.push_str(&Value::String(s.to_string()).to_string());
}

/// The state message: `"type": "state"`, every CSV column under its CSV
/// name, with `--estimate` the estimate's values under theirs (`estimate`,
/// [`super::ghost::columns`]) and `est_error`, then the loop's own figures.
pub fn state_json(columns: &[String], estimate: &[String], s: &Snapshot) -> String {
    let mut out = String::with_capacity(32 * (columns.len() + estimate.len()) + 256);
    out.push_str("{\"type\":\"state\"");
    for (name, v) in columns.iter().zip(&s.values) {
        let _ = write!(out, ",\"{name}\":");
        num(&mut out, *v);
    }
    if !estimate.is_empty() {
        for (name, v) in estimate.iter().zip(&s.estimate) {
            let _ = write!(out, ",\"{name}\":");
            num(&mut out, *v);
        }
        out.push_str(",\"est_error\":");
        match &s.estimate_error {
            Some(e) => string(&mut out, e),
            None => out.push_str("null"),
        }
    }
    out.push_str(",\"wall\":");
    num(&mut out, s.wall_s);
    out.push_str(",\"rtf\":");
    num(&mut out, s.real_time_factor);
    let _ = write!(
        out,
        ",\"steps\":{},\"overruns\":{},\"dropped_ticks\":{},\"step_us\":",
        s.steps, s.overruns, s.dropped_ticks
    );
    num(&mut out, s.step_s * 1e6);
    let _ = write!(
        out,
        ",\"paused\":{},\"watchdog_tripped\":{},\"error\":",
        s.paused, s.watchdog_tripped
    );
    match &s.error {
        Some(e) => string(&mut out, e),
        None => out.push_str("null"),
    }
    out.push('}');
    out
}

/// The binary state frame: the f64 of [`binary_layout`], little-endian,
/// 8 · (8 + columns + estimate) bytes. Counts are exact as f64 up to
/// 2^53; a non-finite value is NaN.
pub fn state_binary(s: &Snapshot) -> Vec<u8> {
    let mut flags = 0;
    if s.paused {
        flags |= FLAG_PAUSED;
    }
    if s.watchdog_tripped {
        flags |= FLAG_WATCHDOG;
    }
    if s.error.is_some() {
        flags |= FLAG_ERROR;
    }
    if s.estimate_error.is_some() {
        flags |= FLAG_ESTIMATE_ERROR;
    }
    let head = [
        s.seq as f64,
        s.wall_s,
        s.real_time_factor,
        s.steps as f64,
        s.overruns as f64,
        s.dropped_ticks as f64,
        s.step_s * 1e6,
        f64::from(flags),
    ];
    let mut out = Vec::with_capacity(8 * (head.len() + s.values.len() + s.estimate.len()));
    for v in head.iter().chain(&s.values).chain(&s.estimate) {
        let v = if v.is_finite() { *v } else { f64::NAN };
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}

/// An error reply.
pub fn error_json(message: &str) -> String {
    serde_json::json!({"type": "error", "message": message}).to_string()
}

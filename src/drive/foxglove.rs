//! `rover drive` in Foxglove's live protocol (`foxglove.websocket.v1`,
//! docs/VIEW.md): a WebSocket that asks for that subprotocol, at `/` or
//! `/ws` of the same server, gets the channels of a run's MCAP log
//! ([`rover_scenario::output::foxglove`]) live: every step's frames and
//! row, the rover's geometry and the terrain. A client may publish JSON
//! commands (the page's protocol, docs/DRIVE.md) on a channel it
//! advertises.
//!
//! Why not the Foxglove SDK's own server: it speaks the SDK's
//! subprotocols (`foxglove.sdk.v1`) and not `foxglove.websocket.v1`,
//! which Lichtblick and the `@foxglove/ws-protocol` clients ask for; its
//! handshake has no hook for this server's Origin, Host and token checks
//! ([`super::access`]); and it runs a tokio runtime of its own beside a
//! real-time loop that has none. So the messages are the SDK's (its
//! schemas and protobuf encoders, the same bytes as in run.mcap) and the
//! protocol's few framing rules are written here, on the server's own
//! WebSocket; tests/browser/foxglove.mjs checks them with the
//! `@foxglove/ws-protocol` client.
//!
//! Protocol errors (JSON that is not a known operation, a subscription to
//! a channel that does not exist, a message on a channel the client did
//! not advertise, a command the rover cannot take) are answered with a
//! `status` message of level error; the session and the simulation go on.

use std::collections::HashMap;
use std::net::TcpStream;
use std::sync::atomic::Ordering;
use std::time::Duration;

use rover_runtime::row::Columns;
use rover_runtime::terrain::Terrain;
use rover_scenario::output::HeightGrid;
use rover_scenario::output::foxglove::{Channels, Topic, nanoseconds};
use rover_spec::Spec;
use serde::Deserialize;
use serde_json::json;
use tungstenite::{Message, WebSocket};

use super::live::{RoverInfo, Shared};
use super::protocol;
use super::server::{close_oversized, read_timed_out};

/// The WebSocket subprotocol.
pub const SUBPROTOCOL: &str = "foxglove.websocket.v1";

/// Most terrain nodes along the live mesh's longer side (a message of
/// about half a megabyte).
pub const LIVE_TERRAIN_NODES: usize = 96;

/// The half-width of the live terrain around the start on an unbounded
/// terrain \[m\], as the page's.
pub const LIVE_TERRAIN_HALF_WIDTH: f64 = 20.0;

/// Binary opcodes, server to client.
const MESSAGE_DATA: u8 = 0x01;
const TIME: u8 = 0x02;
/// Binary opcode, client to server.
const CLIENT_MESSAGE_DATA: u8 = 0x01;

/// Status levels.
const ERROR: u8 = 2;
const WARNING: u8 = 1;

/// How long a session waits for a client message before it sends the
/// rows that came meanwhile.
const POLL: Duration = Duration::from_millis(2);

/// What every Foxglove session of one `rover drive` shares.
#[derive(Debug)]
pub struct FoxgloveFeed {
    channels: Channels,
    server_info: String,
    advertise: String,
    terrain: Vec<u8>,
}

/// A channel's id in the advertisement: its place in [`Topic::ALL`], from 1.
fn channel_id(topic: Topic) -> u32 {
    Topic::ALL.iter().position(|t| *t == topic).unwrap_or(0) as u32 + 1
}

fn topic_of(id: u32) -> Option<Topic> {
    Topic::ALL.get((id as usize).checked_sub(1)?).copied()
}

impl FoxgloveFeed {
    /// The channels of `spec`'s rover for rows of `columns`, the terrain
    /// around `start` (or the whole map, when smaller).
    pub fn new(
        spec: &Spec,
        columns: &Columns,
        terrain: &Terrain,
        start: [f64; 2],
    ) -> Result<Self, String> {
        let units = columns.units(&spec.coordinate_linear);
        let channels = Channels::new(spec, columns.names(), &units).map_err(|e| e.to_string())?;
        let h = LIVE_TERRAIN_HALF_WIDTH;
        let grid = HeightGrid::sample(
            terrain,
            [start[0] - h, start[1] - h],
            [start[0] + h, start[1] + h],
            LIVE_TERRAIN_NODES,
        );
        let terrain = Channels::terrain(&grid).map_err(|e| e.to_string())?;
        let advertised: Vec<serde_json::Value> = channels
            .infos()
            .iter()
            .map(|c| {
                // Binary schemas travel base64-encoded, text ones as text.
                let schema = if c.schema_encoding == "protobuf" {
                    data_encoding::BASE64.encode(&c.schema)
                } else {
                    String::from_utf8_lossy(&c.schema).into_owned()
                };
                json!({
                    "id": channel_id(c.topic),
                    "topic": c.topic.name(),
                    "encoding": c.message_encoding,
                    "schemaName": c.schema_name,
                    "schema": schema,
                    "schemaEncoding": c.schema_encoding,
                })
            })
            .collect();
        let server_info = json!({
            "op": "serverInfo",
            "name": format!("rover drive ({})", spec.name),
            "capabilities": ["clientPublish", "time"],
            "supportedEncodings": ["json"],
            "metadata": {"rover": spec.name},
            "sessionId": format!("{:x}", std::process::id()),
        });
        Ok(FoxgloveFeed {
            channels,
            server_info: server_info.to_string(),
            advertise: json!({"op": "advertise", "channels": advertised}).to_string(),
            terrain,
        })
    }
}

/// A client's operation (text messages).
#[derive(Debug, Deserialize)]
#[serde(tag = "op", rename_all = "camelCase", deny_unknown_fields)]
enum ClientOp {
    Subscribe {
        subscriptions: Vec<Subscription>,
    },
    Unsubscribe {
        #[serde(rename = "subscriptionIds")]
        subscription_ids: Vec<u32>,
    },
    Advertise {
        channels: Vec<ClientChannel>,
    },
    Unadvertise {
        #[serde(rename = "channelIds")]
        channel_ids: Vec<u32>,
    },
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "camelCase")]
struct Subscription {
    id: u32,
    channel_id: u32,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "camelCase")]
struct ClientChannel {
    id: u32,
    topic: String,
    encoding: String,
    #[serde(default)]
    #[allow(dead_code)]
    schema_name: Option<String>,
}

fn status(level: u8, message: &str) -> Message {
    Message::text(json!({"op": "status", "level": level, "message": message}).to_string())
}

/// A `messageData` frame: opcode, subscription id, timestamp, payload.
fn message_data(subscription: u32, ns: u64, payload: &[u8]) -> Message {
    let mut b = Vec::with_capacity(13 + payload.len());
    b.push(MESSAGE_DATA);
    b.extend_from_slice(&subscription.to_le_bytes());
    b.extend_from_slice(&ns.to_le_bytes());
    b.extend_from_slice(payload);
    Message::binary(b)
}

fn time(ns: u64) -> Message {
    let mut b = Vec::with_capacity(9);
    b.push(TIME);
    b.extend_from_slice(&ns.to_le_bytes());
    Message::binary(b)
}

/// One session's state: its subscriptions and its advertised channels.
struct Session<'a> {
    feed: &'a FoxgloveFeed,
    shared: &'a Shared,
    info: &'a RoverInfo,
    rate_hz: f64,
    /// Subscription id → topic.
    subscriptions: HashMap<u32, Topic>,
    /// The client's channels (id → topic) that carry JSON commands.
    published: HashMap<u32, String>,
    /// The simulated time of the last row sent \[ns\].
    last_ns: u64,
}

impl Session<'_> {
    /// Answer one text message; the messages to send back.
    fn text(&mut self, text: &str, out: &mut Vec<Message>) {
        let op = match serde_json::from_str::<ClientOp>(text) {
            Ok(op) => op,
            Err(e) => {
                out.push(status(
                    ERROR,
                    &format!(
                        "not a foxglove.websocket.v1 operation this server takes ({e}): it takes subscribe, unsubscribe, advertise and unadvertise"
                    ),
                ));
                return;
            }
        };
        match op {
            ClientOp::Subscribe { subscriptions } => {
                for s in subscriptions {
                    let Some(topic) = topic_of(s.channel_id) else {
                        out.push(status(
                            ERROR,
                            &format!(
                                "subscription {}: no channel {} (the channels are 1 to {}, as advertised)",
                                s.id,
                                s.channel_id,
                                Topic::ALL.len()
                            ),
                        ));
                        continue;
                    };
                    if self.subscriptions.contains_key(&s.id) {
                        out.push(status(
                            ERROR,
                            &format!(
                                "subscription {} is already in use: unsubscribe it first",
                                s.id
                            ),
                        ));
                        continue;
                    }
                    self.subscriptions.insert(s.id, topic);
                    // The one-off messages, at once.
                    match topic {
                        Topic::Rover => {
                            out.push(message_data(s.id, self.last_ns, self.feed.channels.rover()))
                        }
                        Topic::Terrain => {
                            out.push(message_data(s.id, self.last_ns, &self.feed.terrain))
                        }
                        Topic::Tf | Topic::Row => {}
                    }
                }
            }
            ClientOp::Unsubscribe { subscription_ids } => {
                for id in subscription_ids {
                    if self.subscriptions.remove(&id).is_none() {
                        out.push(status(WARNING, &format!("no subscription {id} to end")));
                    }
                }
            }
            ClientOp::Advertise { channels } => {
                for c in channels {
                    if c.encoding != "json" {
                        out.push(status(
                            ERROR,
                            &format!(
                                "client channel {} ({}): encoding `{}`; this server takes JSON commands (encoding `json`, docs/DRIVE.md)",
                                c.id, c.topic, c.encoding
                            ),
                        ));
                        continue;
                    }
                    self.published.insert(c.id, c.topic);
                }
            }
            ClientOp::Unadvertise { channel_ids } => {
                for id in channel_ids {
                    if self.published.remove(&id).is_none() {
                        out.push(status(WARNING, &format!("no client channel {id} to end")));
                    }
                }
            }
        }
    }

    /// A binary message: a command on a channel the client advertised.
    fn binary(&mut self, data: &[u8], out: &mut Vec<Message>) {
        let (Some(&op), Some(id)) = (
            data.first(),
            data.get(1..5)
                .and_then(|b| <[u8; 4]>::try_from(b).ok())
                .map(u32::from_le_bytes),
        ) else {
            out.push(status(
                ERROR,
                "a binary message shorter than its header (opcode and channel id)",
            ));
            return;
        };
        if op != CLIENT_MESSAGE_DATA {
            out.push(status(
                ERROR,
                &format!("binary opcode {op:#04x}: this server takes 0x01 (message data) only"),
            ));
            return;
        }
        let Some(topic) = self.published.get(&id) else {
            out.push(status(
                ERROR,
                &format!("message on client channel {id}, which the client did not advertise"),
            ));
            return;
        };
        let text = match std::str::from_utf8(&data[5..]) {
            Ok(t) => t,
            Err(_) => {
                out.push(status(ERROR, &format!("{topic}: a command is JSON text")));
                return;
            }
        };
        match protocol::parse(text, self.info, self.rate_hz) {
            Ok(req) => {
                if let Ok(mut inbox) = self.shared.inbox.lock() {
                    protocol::apply(&req, &mut inbox);
                }
            }
            Err(e) => out.push(status(ERROR, &format!("{topic}: {e}"))),
        }
    }
}

/// Serve one Foxglove client until it leaves or the server stops.
pub fn session(
    mut ws: WebSocket<TcpStream>,
    feed: &FoxgloveFeed,
    shared: &Shared,
    info: &RoverInfo,
    rate_hz: f64,
    stopping: impl Fn() -> bool,
) {
    let mut channels = feed.channels.clone();
    let mut s = Session {
        feed,
        shared,
        info,
        rate_hz,
        subscriptions: HashMap::new(),
        published: HashMap::new(),
        last_ns: 0,
    };
    for m in [&feed.server_info, &feed.advertise] {
        if ws.send(Message::text(m.clone())).is_err() {
            return;
        }
    }
    shared.row_readers.fetch_add(1, Ordering::Relaxed);
    let mut seen = shared.rows.lock().map(|f| f.pushed()).unwrap_or(0);
    let mut rows = Vec::new();
    let mut out = Vec::new();
    let width = shared.rows.lock().map(|f| f.columns()).unwrap_or(1).max(1);
    'serve: loop {
        if shared.stop.load(Ordering::Relaxed) || stopping() {
            let _ = ws.close(None);
            let _ = ws.flush();
            break;
        }
        let _ = ws.get_mut().set_read_timeout(Some(POLL));
        match ws.read() {
            Ok(Message::Text(text)) => s.text(text.as_str(), &mut out),
            Ok(Message::Binary(data)) => s.binary(&data, &mut out),
            Ok(Message::Close(_)) => break,
            Ok(_) => {}
            Err(tungstenite::Error::Capacity(_)) => {
                close_oversized(&mut ws);
                break;
            }
            Err(e) if read_timed_out(&e) => {}
            Err(_) => break,
        }
        for m in out.drain(..) {
            if ws.send(m).is_err() {
                break 'serve;
            }
        }
        rows.clear();
        if let Ok(f) = shared.rows.lock() {
            f.read(&mut seen, &mut rows);
        }
        let streaming: Vec<(u32, Topic)> = s
            .subscriptions
            .iter()
            .filter(|(_, t)| matches!(t, Topic::Tf | Topic::Row))
            .map(|(id, t)| (*id, *t))
            .collect();
        for row in rows.chunks_exact(width) {
            let ns = nanoseconds(row[0]);
            s.last_ns = ns;
            if streaming.is_empty() {
                continue;
            }
            let Ok((tf, json)) = channels.encode_row(row[0], row) else {
                continue;
            };
            for (id, topic) in &streaming {
                let payload = if *topic == Topic::Tf { tf } else { json };
                if ws.send(message_data(*id, ns, payload)).is_err() {
                    break 'serve;
                }
            }
        }
        if !rows.is_empty() && ws.send(time(s.last_ns)).is_err() {
            break;
        }
    }
    shared.row_readers.fetch_sub(1, Ordering::Relaxed);
}

//! The web side: a small HTTP/1.1 server on std's sockets (one thread per
//! connection; the page, its script, three.js, the rover's description,
//! the terrain, a run's CSV) and the WebSocket at `/ws` (tungstenite over
//! the same socket). No async runtime: a handful of clients at tens of
//! messages per second is what it serves, and the real-time loop runs on
//! its own thread whatever the server does.
//!
//! Every request goes through [`Access`] (the Host, the Origin, the
//! WebSocket's token), and what a client can make the server hold is
//! bounded (docs/DRIVE.md, "Who may connect"): at most
//! [`MAX_CONNECTIONS`] connections at once, a request head of at most
//! [`MAX_HEAD`] bytes read within [`HEAD_TIMEOUT`], no request body, and
//! WebSocket messages of at most [`MAX_MESSAGE`] bytes.

use std::collections::HashMap;
use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use tungstenite::protocol::frame::CloseFrame;
use tungstenite::protocol::frame::coding::CloseCode;
use tungstenite::protocol::{Role, WebSocketConfig};
use tungstenite::{Message, WebSocket};

use super::access::{Access, Credentials, Refusal};
use super::live::{RoverInfo, Shared};
use super::protocol;
use super::rut_feed::RUT_PERIOD;

/// Connections served at once (page loads, WebSocket clients, requests
/// being read); one more is answered 503 and closed. A page takes one
/// WebSocket and a few short requests: 32 is several operators and rigs.
pub const MAX_CONNECTIONS: usize = 32;
/// Largest request head (request line and headers) \[bytes\]: a browser's
/// GET is well under 2 kB.
pub const MAX_HEAD: usize = 8 * 1024;
/// Time a client has to send its whole request head: a client that
/// trickles it in holds a connection no longer than this.
pub const HEAD_TIMEOUT: Duration = Duration::from_secs(5);
/// Time a write may block on a client that does not read (a response, a
/// state message): past it the connection is dropped, so that a stalled
/// client holds no thread.
pub const WRITE_TIMEOUT: Duration = Duration::from_secs(5);
/// Largest WebSocket message (and frame) a client may send \[bytes\]: a
/// command is tens of bytes. A larger one closes the connection with
/// code 1009 (message too big) before its payload is read.
pub const MAX_MESSAGE: usize = 64 * 1024;
/// The most a WebSocket connection buffers for a client that reads slowly
/// \[bytes\]: several state messages; a send beyond it fails and the
/// connection ends.
pub const MAX_WRITE_BUFFER: usize = 1024 * 1024;

/// Ends a connection whose client sent a message over [`MAX_MESSAGE`],
/// saying why.
pub(super) fn close_oversized(ws: &mut WebSocket<TcpStream>) {
    let _ = ws.close(Some(CloseFrame {
        code: CloseCode::Size,
        reason: format!("messages are at most {MAX_MESSAGE} bytes").into(),
    }));
    let _ = ws.flush();
}

/// A read that found nothing within its timeout: the connection goes on.
pub(super) fn read_timed_out(e: &tungstenite::Error) -> bool {
    matches!(e, tungstenite::Error::Io(e)
        if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut))
}

/// The WebSocket's limits: small buffers, [`MAX_MESSAGE`] in.
fn websocket_config() -> WebSocketConfig {
    WebSocketConfig::default()
        .read_buffer_size(4 * 1024)
        .write_buffer_size(0)
        .max_write_buffer_size(MAX_WRITE_BUFFER)
        .max_message_size(Some(MAX_MESSAGE))
        .max_frame_size(Some(MAX_MESSAGE))
}

/// The page and its scripts, in the binary: nothing is fetched at run time.
const INDEX: &str = include_str!("web/index.html");
const APP: &str = include_str!("web/app.js");
const THREE: &str = include_str!("web/three.min.js");

/// What the server serves besides the page.
pub enum Content {
    /// A live loop: `/ws` reaches it.
    Drive {
        /// Shared with the loop.
        shared: Arc<Shared>,
        /// The CSV's column names.
        columns: Arc<Vec<String>>,
        /// With `--estimate`, the names of the estimate's values (empty
        /// otherwise).
        estimate: Arc<Vec<String>>,
        /// The rover, to check commands.
        info: RoverInfo,
        /// The loop's rate \[Hz\].
        rate_hz: f64,
        /// The Foxglove channels (`foxglove.websocket.v1` clients).
        #[cfg(feature = "mcap")]
        foxglove: Arc<super::foxglove::FoxgloveFeed>,
    },
    /// A finished run: `/run.csv` is its CSV.
    View {
        /// The CSV's bytes, read once from the run's folder.
        csv: Arc<Vec<u8>>,
        /// `/ruts.json`: the run's ruts as one `ruts` message
        /// ([`super::rut_feed`]), or `null`.
        ruts: String,
    },
}

/// The server's state, shared by the connection threads.
pub struct App {
    /// `/meta.json`: the mode, the rover's geometry, the loop's settings.
    pub meta: String,
    /// `/terrain.json`: a grid of heights.
    pub terrain: String,
    /// Mode-specific content.
    pub content: Content,
    /// Who may connect.
    pub access: Access,
    /// Each WebSocket client's state rate, to set the loop's publication rate.
    rates: Mutex<HashMap<u64, f64>>,
    next_client: AtomicU64,
    /// Ends the accept loop and every connection.
    stop: AtomicBool,
    /// The connection threads, each with a handle on its socket (to shut
    /// it down when a client holds it past the stop).
    connections: Mutex<Vec<(Option<TcpStream>, JoinHandle<()>)>>,
    /// Live server threads: the accept loop and the connections.
    threads: Arc<AtomicUsize>,
    /// Open connections, against [`MAX_CONNECTIONS`].
    open: Arc<AtomicUsize>,
}

/// Counts a live thread until it ends (however it ends).
struct Alive(Arc<AtomicUsize>);

impl Alive {
    fn new(count: &Arc<AtomicUsize>) -> Self {
        count.fetch_add(1, Ordering::SeqCst);
        Alive(count.clone())
    }
}

impl Drop for Alive {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

/// A running server: its port, and [`Server::stop`], which returns once
/// every one of its threads has ended and the port is free.
pub struct Server {
    /// The port it listens on (127.0.0.1).
    pub port: u16,
    app: Arc<App>,
    accept: JoinHandle<()>,
}

/// How long [`Server::stop`] lets the WebSocket sessions close their
/// connections themselves (they look every 20 ms) before shutting the
/// remaining sockets down.
const CLOSE_GRACE: Duration = Duration::from_millis(250);

impl Server {
    /// Serve `app` on `listener`: an accept thread, one thread per connection.
    pub fn start(listener: TcpListener, app: Arc<App>) -> std::io::Result<Server> {
        let port = listener.local_addr()?.port();
        let alive = Alive::new(&app.threads);
        let accept_app = app.clone();
        let accept = std::thread::Builder::new()
            .name("rover-server".into())
            .spawn(move || {
                let _alive = alive;
                serve(listener, &accept_app);
            })?;
        Ok(Server { port, app, accept })
    }

    /// The number of the server's threads still running (the accept loop
    /// and the connections); 0 once [`Server::stop`] has returned.
    pub fn threads(&self) -> Arc<AtomicUsize> {
        self.app.threads.clone()
    }

    /// Stop: the accept loop ends and closes the listening socket, each
    /// WebSocket client is sent a close frame, any connection still open
    /// after a short grace is shut down, and every thread is joined.
    pub fn stop(self) {
        self.app.stop.store(true, Ordering::SeqCst);
        // Wake the blocking accept; it sees the flag and returns.
        let _ = TcpStream::connect_timeout(
            &std::net::SocketAddr::from(([127, 0, 0, 1], self.port)),
            Duration::from_secs(1),
        );
        let _ = self.accept.join();
        let connections = match self.app.connections.lock() {
            Ok(mut c) => std::mem::take(&mut *c),
            Err(_) => Vec::new(),
        };
        let until = Instant::now() + CLOSE_GRACE;
        while Instant::now() < until && connections.iter().any(|(_, h)| !h.is_finished()) {
            std::thread::sleep(Duration::from_millis(5));
        }
        for (stream, handle) in connections {
            if !handle.is_finished()
                && let Some(s) = &stream
            {
                let _ = s.shutdown(std::net::Shutdown::Both);
            }
            let _ = handle.join();
        }
    }
}

impl App {
    /// A server's state.
    pub fn new(meta: String, terrain: String, content: Content, access: Access) -> Arc<Self> {
        Arc::new(App {
            meta,
            terrain,
            content,
            access,
            rates: Mutex::new(HashMap::new()),
            next_client: AtomicU64::new(0),
            stop: AtomicBool::new(false),
            connections: Mutex::new(Vec::new()),
            threads: Arc::new(AtomicUsize::new(0)),
            open: Arc::new(AtomicUsize::new(0)),
        })
    }

    fn stopping(&self) -> bool {
        self.stop.load(Ordering::SeqCst)
    }
}

/// Accept connections until stopped; one thread each, kept to be joined.
fn serve(listener: TcpListener, app: &Arc<App>) {
    for stream in listener.incoming() {
        if app.stopping() {
            break;
        }
        let Ok(mut stream) = stream else { continue };
        if app.open.load(Ordering::SeqCst) >= MAX_CONNECTIONS {
            busy(&mut stream);
            continue;
        }
        let slot = Alive::new(&app.open);
        // The list's copy of the socket keeps it open: each connection
        // shuts its socket down when done, so that its client sees the end.
        let handle = stream.try_clone().ok();
        let closer = stream.try_clone().ok();
        let conn_app = app.clone();
        let alive = Alive::new(&app.threads);
        let spawned = std::thread::Builder::new()
            .name("rover-http".into())
            .spawn(move || {
                let _alive = alive;
                let _slot = slot;
                // A client that goes away mid-request is nothing to report.
                let _ = connection(stream, &conn_app);
                if let Some(s) = closer {
                    let _ = s.shutdown(std::net::Shutdown::Both);
                }
            });
        if let (Ok(thread), Ok(mut c)) = (spawned, app.connections.lock()) {
            // Ended connections are joined here, so that the list stays short.
            let mut k = 0;
            while k < c.len() {
                if c[k].1.is_finished() {
                    let _ = c.swap_remove(k).1.join();
                } else {
                    k += 1;
                }
            }
            c.push((handle, thread));
        }
    }
}

/// A request's method, target and the headers that matter here.
#[derive(Default)]
struct Request {
    method: String,
    target: String,
    host: Option<String>,
    origin: Option<String>,
    authorization: Option<String>,
    websocket_key: Option<String>,
    /// The `Sec-WebSocket-Protocol` subprotocols offered, every such
    /// header's list joined.
    protocols: Vec<String>,
    /// Whether it announces a body (none is read).
    body: bool,
    /// A header that must come once came twice.
    repeated: Option<&'static str>,
    /// Bytes read past the head (a WebSocket client's first frames).
    rest: Vec<u8>,
}

impl Request {
    /// The target's path, without the query.
    fn path(&self) -> &str {
        self.target.split('?').next().unwrap_or("")
    }

    /// The target's `token` query parameter.
    fn query_token(&self) -> Option<&str> {
        let (_, query) = self.target.split_once('?')?;
        query.split('&').find_map(|p| p.strip_prefix("token="))
    }

    /// Whether the client offers the WebSocket subprotocol `name`.
    fn offers(&self, name: &str) -> bool {
        self.protocols.iter().any(|p| p == name)
    }

    fn credentials(&self) -> Credentials<'_> {
        Credentials {
            host: self.host.as_deref(),
            origin: self.origin.as_deref(),
            query_token: self.query_token(),
            authorization: self.authorization.as_deref(),
        }
    }
}

/// Why no request could be read.
enum HeadError {
    /// The client closed the connection (or it failed) first: nothing to answer.
    Gone,
    /// The head passed [`MAX_HEAD`].
    TooLarge,
    /// The head did not come whole within [`HEAD_TIMEOUT`].
    Timeout,
}

fn read_request(stream: &mut TcpStream) -> Result<Request, HeadError> {
    let until = Instant::now() + HEAD_TIMEOUT;
    let mut buf = Vec::with_capacity(1024);
    let mut chunk = [0u8; 1024];
    let end = loop {
        let left = until.saturating_duration_since(Instant::now());
        if left.is_zero() {
            return Err(HeadError::Timeout);
        }
        stream
            .set_read_timeout(Some(left))
            .map_err(|_| HeadError::Gone)?;
        let n = match stream.read(&mut chunk) {
            Ok(0) => return Err(HeadError::Gone),
            Ok(n) => n,
            Err(e)
                if matches!(
                    e.kind(),
                    std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
                ) =>
            {
                return Err(HeadError::Timeout);
            }
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(_) => return Err(HeadError::Gone),
        };
        // The end may straddle the previous chunk.
        let from = buf.len().saturating_sub(3);
        buf.extend_from_slice(&chunk[..n]);
        if let Some(k) = buf[from..].windows(4).position(|w| w == b"\r\n\r\n") {
            break from + k + 4;
        }
        if buf.len() > MAX_HEAD {
            return Err(HeadError::TooLarge);
        }
    };
    if end > MAX_HEAD {
        return Err(HeadError::TooLarge);
    }
    let text = String::from_utf8_lossy(&buf[..end]);
    let mut lines = text.split("\r\n");
    let mut first = lines.next().unwrap_or("").split_whitespace();
    let mut req = Request {
        method: first.next().unwrap_or("").to_string(),
        target: first.next().unwrap_or("").to_string(),
        rest: buf[end..].to_vec(),
        ..Request::default()
    };
    for line in lines {
        let Some((name, value)) = line.split_once(':') else {
            continue;
        };
        let value = Some(value.trim().to_string());
        let name = name.trim().to_ascii_lowercase();
        let once = |slot: &mut Option<String>, repeated: &mut Option<&'static str>, key| {
            if slot.is_some() {
                *repeated = Some(key);
            }
            *slot = value.clone();
        };
        match name.as_str() {
            "host" => once(&mut req.host, &mut req.repeated, "Host"),
            "origin" => once(&mut req.origin, &mut req.repeated, "Origin"),
            "authorization" => once(&mut req.authorization, &mut req.repeated, "Authorization"),
            "sec-websocket-key" => once(
                &mut req.websocket_key,
                &mut req.repeated,
                "Sec-WebSocket-Key",
            ),
            "sec-websocket-protocol" => req.protocols.extend(
                value
                    .iter()
                    .flat_map(|v| v.split(','))
                    .map(|p| p.trim().to_string())
                    .filter(|p| !p.is_empty()),
            ),
            "transfer-encoding" => req.body = true,
            "content-length" => req.body |= value.as_deref() != Some("0"),
            _ => {}
        }
    }
    Ok(req)
}

/// The answer to a connection beyond [`MAX_CONNECTIONS`], from the accept
/// thread: what the client sent so far is read without waiting (so that
/// closing does not reset the connection under the answer), then 503.
fn busy(stream: &mut TcpStream) {
    let mut sink = [0u8; 4096];
    if stream.set_nonblocking(true).is_ok() {
        let _ = stream.read(&mut sink);
        let _ = stream.set_nonblocking(false);
    }
    let _ = stream.set_write_timeout(Some(Duration::from_millis(200)));
    let _ = respond(
        stream,
        "503 Service Unavailable",
        "text/plain",
        format!("too many connections (at most {MAX_CONNECTIONS} at once): close one and retry\n")
            .as_bytes(),
    );
    let _ = stream.shutdown(std::net::Shutdown::Write);
}

fn refused(stream: &mut TcpStream, r: &Refusal) -> std::io::Result<()> {
    respond(
        stream,
        r.status,
        "text/plain; charset=utf-8",
        format!("{}\n", r.reason).as_bytes(),
    )
}

fn respond(stream: &mut TcpStream, status: &str, kind: &str, body: &[u8]) -> std::io::Result<()> {
    let head = format!(
        "HTTP/1.1 {status}\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n",
        body.len()
    );
    if body.len() <= 4096 {
        // One write: a short answer (a refusal) reaches the client whole,
        // even when the connection is closed right after.
        let mut all = head.into_bytes();
        all.extend_from_slice(body);
        stream.write_all(&all)?;
    } else {
        stream.write_all(head.as_bytes())?;
        stream.write_all(body)?;
    }
    stream.flush()
}

fn connection(mut stream: TcpStream, app: &App) -> std::io::Result<()> {
    stream.set_write_timeout(Some(WRITE_TIMEOUT))?;
    let req = match read_request(&mut stream) {
        Ok(req) => req,
        Err(HeadError::Gone) => return Ok(()),
        Err(HeadError::TooLarge) => {
            return respond(
                &mut stream,
                "431 Request Header Fields Too Large",
                "text/plain",
                format!("the request head is over {MAX_HEAD} bytes\n").as_bytes(),
            );
        }
        Err(HeadError::Timeout) => {
            return respond(
                &mut stream,
                "408 Request Timeout",
                "text/plain",
                format!(
                    "the request head did not come within {} s\n",
                    HEAD_TIMEOUT.as_secs()
                )
                .as_bytes(),
            );
        }
    };
    if let Some(header) = req.repeated {
        return respond(
            &mut stream,
            "400 Bad Request",
            "text/plain",
            format!("the {header} header came twice: send it once\n").as_bytes(),
        );
    }
    let path = req.path();
    // A Foxglove client (docs/VIEW.md) connects at `/` or `/ws` with its
    // subprotocol: a WebSocket, checked as one.
    let foxglove = req.websocket_key.is_some()
        && req.offers(FOXGLOVE_SUBPROTOCOL)
        && (path == "/" || path == "/ws")
        && matches!(app.content, Content::Drive { .. });
    let check = if foxglove || (path == "/ws" && matches!(app.content, Content::Drive { .. })) {
        app.access.check_websocket(&req.credentials())
    } else {
        app.access.check_request(&req.credentials())
    };
    if let Err(r) = check {
        return refused(&mut stream, &r);
    }
    if req.method != "GET" {
        return respond(
            &mut stream,
            "405 Method Not Allowed",
            "text/plain",
            b"only GET\n",
        );
    }
    if req.body {
        return respond(
            &mut stream,
            "413 Content Too Large",
            "text/plain",
            b"a GET has no body here\n",
        );
    }
    if foxglove {
        return foxglove_session(stream, req, app);
    }
    match path {
        "/" | "/index.html" => respond(
            &mut stream,
            "200 OK",
            "text/html; charset=utf-8",
            INDEX.as_bytes(),
        ),
        "/app.js" => respond(
            &mut stream,
            "200 OK",
            "text/javascript; charset=utf-8",
            APP.as_bytes(),
        ),
        "/three.min.js" => respond(
            &mut stream,
            "200 OK",
            "text/javascript; charset=utf-8",
            THREE.as_bytes(),
        ),
        "/favicon.ico" => respond(&mut stream, "204 No Content", "image/x-icon", b""),
        "/meta.json" => respond(
            &mut stream,
            "200 OK",
            "application/json",
            app.meta.as_bytes(),
        ),
        "/terrain.json" => respond(
            &mut stream,
            "200 OK",
            "application/json",
            app.terrain.as_bytes(),
        ),
        "/ruts.json" => match &app.content {
            Content::View { ruts, .. } => {
                respond(&mut stream, "200 OK", "application/json", ruts.as_bytes())
            }
            // Live, the ruts come over the WebSocket.
            Content::Drive { .. } => respond(&mut stream, "200 OK", "application/json", b"null"),
        },
        "/run.csv" => match &app.content {
            Content::View { csv, .. } => respond(&mut stream, "200 OK", "text/csv", csv),
            Content::Drive { .. } => respond(
                &mut stream,
                "404 Not Found",
                "text/plain",
                b"no run file while driving live\n",
            ),
        },
        "/ws" => match (&app.content, &req.websocket_key) {
            (Content::Drive { .. }, Some(key)) => {
                stream.write_all(switching(key, None).as_bytes())?;
                let ws = WebSocket::from_partially_read(
                    stream,
                    req.rest,
                    Role::Server,
                    Some(websocket_config()),
                );
                session(ws, app);
                Ok(())
            }
            (Content::Drive { .. }, None) => respond(
                &mut stream,
                "400 Bad Request",
                "text/plain",
                b"/ws is a WebSocket: connect with a WebSocket client\n",
            ),
            (Content::View { .. }, _) => respond(
                &mut stream,
                "404 Not Found",
                "text/plain",
                b"no live loop when viewing a run\n",
            ),
        },
        _ => respond(&mut stream, "404 Not Found", "text/plain", b"not found\n"),
    }
}

/// The subprotocol of Foxglove's live protocol.
const FOXGLOVE_SUBPROTOCOL: &str = "foxglove.websocket.v1";

/// The WebSocket handshake's answer, accepting `key` (with `subprotocol`).
fn switching(key: &str, subprotocol: Option<&str>) -> String {
    let accept = tungstenite::handshake::derive_accept_key(key.as_bytes());
    let protocol = subprotocol
        .map(|p| format!("Sec-WebSocket-Protocol: {p}\r\n"))
        .unwrap_or_default();
    format!(
        "HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Accept: {accept}\r\n{protocol}\r\n"
    )
}

/// A Foxglove client, admitted: the handshake, then its session.
#[cfg(feature = "mcap")]
fn foxglove_session(mut stream: TcpStream, req: Request, app: &App) -> std::io::Result<()> {
    let (
        Content::Drive {
            shared,
            info,
            rate_hz,
            foxglove,
            ..
        },
        Some(key),
    ) = (&app.content, &req.websocket_key)
    else {
        return Ok(());
    };
    stream.write_all(switching(key, Some(FOXGLOVE_SUBPROTOCOL)).as_bytes())?;
    let ws =
        WebSocket::from_partially_read(stream, req.rest, Role::Server, Some(websocket_config()));
    super::foxglove::session(ws, foxglove, shared, info, *rate_hz, || app.stopping());
    Ok(())
}

/// Without the `mcap` feature, no Foxglove channels: a clear refusal.
#[cfg(not(feature = "mcap"))]
fn foxglove_session(mut stream: TcpStream, _req: Request, _app: &App) -> std::io::Result<()> {
    respond(
        &mut stream,
        "501 Not Implemented",
        "text/plain",
        b"this rover was built without the `mcap` feature: no Foxglove channels\n",
    )
}

/// The loop publishes at the highest rate any client asked for.
fn update_publication(app: &App, shared: &Shared, rate_hz: f64) {
    let Ok(rates) = app.rates.lock() else { return };
    let highest = rates.values().cloned().fold(30.0, f64::max);
    let every = ((rate_hz / highest).floor() as u64).max(1);
    shared.publish_every.store(every, Ordering::Relaxed);
}

/// One WebSocket client: its commands in, the state out at its rate.
fn session(mut ws: WebSocket<TcpStream>, app: &App) {
    let Content::Drive {
        shared,
        columns,
        estimate,
        info,
        rate_hz,
        ..
    } = &app.content
    else {
        return;
    };
    let id = app.next_client.fetch_add(1, Ordering::Relaxed);
    let mut period = Duration::from_micros(33_333);
    if let Ok(mut r) = app.rates.lock() {
        r.insert(id, 30.0);
    }
    let hello = format!("{{\"type\":\"hello\",\"meta\":{}}}", app.meta);
    if ws.send(Message::text(hello)).is_err() {
        return;
    }
    let mut next_send = Instant::now();
    let mut sent_seq = 0u64;
    let mut format = protocol::Format::Json;
    // The ruts' revision this client has every tile of, and when it is
    // next sent what changed since.
    let mut ruts_sent = 0u64;
    let mut next_ruts = Instant::now();
    // Whether this client was told the estimation stopped (once per
    // failure; a reset that restarts it clears it).
    let mut told_estimate_error = false;
    loop {
        if shared.stop.load(Ordering::Relaxed) || app.stopping() {
            let _ = ws.close(None);
            let _ = ws.flush();
            break;
        }
        let wait = next_send
            .saturating_duration_since(Instant::now())
            .clamp(Duration::from_micros(500), Duration::from_millis(20));
        let _ = ws.get_mut().set_read_timeout(Some(wait));
        match ws.read() {
            Ok(Message::Text(text)) => match protocol::parse(text.as_str(), info, *rate_hz) {
                Ok(req) => {
                    if let Ok(mut inbox) = shared.inbox.lock() {
                        protocol::apply(&req, &mut inbox);
                    }
                    if let Some(f) = req.subscribe {
                        format = f;
                    }
                    // The rate was range-checked: its period is a Duration.
                    if let Some((rate, p)) = req
                        .rate
                        .and_then(|r| Some((r, Duration::try_from_secs_f64(1.0 / r).ok()?)))
                    {
                        period = p;
                        if let Ok(mut r) = app.rates.lock() {
                            r.insert(id, rate);
                        }
                        update_publication(app, shared, *rate_hz);
                    }
                }
                Err(message) => {
                    if ws
                        .send(Message::text(protocol::error_json(&message.to_string())))
                        .is_err()
                    {
                        break;
                    }
                }
            },
            Ok(Message::Binary(_)) => {
                let m = protocol::error_json("send commands as JSON text messages");
                if ws.send(Message::text(m)).is_err() {
                    break;
                }
            }
            Ok(Message::Close(_)) => break,
            Ok(_) => {}
            Err(tungstenite::Error::Capacity(_)) => {
                close_oversized(&mut ws);
                break;
            }
            Err(e) if read_timed_out(&e) => {}
            Err(_) => break,
        }
        let now = Instant::now();
        if now >= next_send {
            let (message, stopped) = match shared.state.lock() {
                Ok(s) if s.seq != sent_seq => {
                    sent_seq = s.seq;
                    let message = match format {
                        protocol::Format::Json => {
                            Message::text(protocol::state_json(columns, estimate, &s))
                        }
                        protocol::Format::Binary => Message::binary(protocol::state_binary(&s)),
                    };
                    // The text only when it is to be sent.
                    let stopped = s
                        .estimate_error
                        .as_ref()
                        .map(|e| (!told_estimate_error).then(|| e.clone()));
                    (Some(message), stopped)
                }
                _ => (None, None),
            };
            if let Some(message) = message {
                if ws.send(message).is_err() {
                    break;
                }
                match stopped {
                    Some(Some(why)) => {
                        told_estimate_error = true;
                        let m = protocol::error_json(&format!("{why}; a reset restarts it"));
                        if ws.send(Message::text(m)).is_err() {
                            break;
                        }
                    }
                    Some(None) => {}
                    None => told_estimate_error = false,
                }
            }
            next_send += period;
            if next_send < now {
                // Behind (a slow client): skip, never burst.
                next_send = now + period;
            }
        }
        if now >= next_ruts {
            next_ruts = now + RUT_PERIOD;
            let message = match shared.ruts.lock() {
                Ok(feed) => feed.message(ruts_sent),
                Err(_) => None,
            };
            if let Some((text, revision)) = message {
                if ws.send(Message::text(text)).is_err() {
                    break;
                }
                ruts_sent = revision;
            }
        }
    }
    if let Ok(mut r) = app.rates.lock() {
        r.remove(&id);
    }
    update_publication(app, shared, *rate_hz);
}

//! Who may connect (docs/DRIVE.md, "Who may connect"): one policy that
//! every request to the server goes through, the page's files and the
//! WebSocket alike.
//!
//! The server listens on the loopback interface, but that alone does not
//! keep other programs' requests out: any web page open in the operator's
//! browser can open a WebSocket to 127.0.0.1 (browsers do not apply the
//! same-origin rule to WebSockets; they send an `Origin` header and leave
//! the check to the server), and a page on a name that re-resolves to
//! 127.0.0.1 (DNS rebinding) can read the server's answers as if they were
//! its own, with its own name in the `Host` header. So:
//!
//! - the `Host` header must name this server (127.0.0.1, localhost or
//!   \[::1\] with its port): a rebound name is refused;
//! - an `Origin` header, when a request has one, must be the page's own
//!   origin or one the operator allowed (`--allow-origin`): a foreign page
//!   is refused, with or without the token (a browser always sends its
//!   page's origin, so a token in a foreign page would be a leaked token);
//! - a WebSocket without an `Origin` comes from a program, not a browser
//!   page: it must present the token the server prints at start (or the
//!   one given with `--token` or `ROVER_DRIVE_TOKEN`), as `?token=…` or
//!   `Authorization: Bearer …`. Any local program could otherwise drive
//!   the rover.

use std::io::Read;
use std::net::SocketAddr;

/// Why a request was refused: the HTTP status line and a short text for
/// the client.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Refusal {
    /// Status code and reason phrase, as in the status line.
    pub status: &'static str,
    /// What is wrong and how to connect instead.
    pub reason: String,
}

fn refuse(status: &'static str, reason: String) -> Refusal {
    Refusal { status, reason }
}

/// The headers a request's admission depends on.
#[derive(Clone, Debug, Default)]
pub struct Credentials<'a> {
    /// The `Host` header.
    pub host: Option<&'a str>,
    /// The `Origin` header.
    pub origin: Option<&'a str>,
    /// The `token` query parameter of the request's target.
    pub query_token: Option<&'a str>,
    /// The `Authorization` header.
    pub authorization: Option<&'a str>,
}

/// The policy of one server: its own hosts and origins, the allowed
/// foreign origins, and the token of the WebSocket (none when there is no
/// WebSocket: `rover view`).
#[derive(Clone, Debug)]
pub struct Access {
    hosts: Vec<String>,
    origins: Vec<String>,
    token: Option<String>,
}

/// Shortest token accepted from `--token` or `ROVER_DRIVE_TOKEN`: 16
/// characters of the URL-safe alphabet, about 96 bits, too many to guess
/// from a local program within a drive.
pub const MIN_TOKEN_LEN: usize = 16;
/// Longest token accepted: it travels in a URL and a header.
pub const MAX_TOKEN_LEN: usize = 256;

impl Access {
    /// The policy of a server bound to `addr`, allowing the (already
    /// checked, [`parse_origin`]) origins of `allow`, with the WebSocket's
    /// `token`.
    pub fn new(addr: SocketAddr, allow: &[String], token: Option<String>) -> Self {
        let port = addr.port();
        let mut names = vec![
            "127.0.0.1".to_string(),
            "localhost".to_string(),
            "[::1]".to_string(),
        ];
        let bound = match addr {
            SocketAddr::V4(a) => a.ip().to_string(),
            SocketAddr::V6(a) => format!("[{}]", a.ip()),
        };
        if !names.contains(&bound) {
            names.push(bound);
        }
        let mut hosts: Vec<String> = names.iter().map(|n| format!("{n}:{port}")).collect();
        if port == 80 {
            // A browser leaves the scheme's default port out.
            hosts.extend(names.iter().cloned());
        }
        let mut origins: Vec<String> = hosts.iter().map(|h| format!("http://{h}")).collect();
        origins.extend(allow.iter().cloned());
        Access {
            hosts,
            origins,
            token,
        }
    }

    /// The page's own origin as the server prints it.
    fn own(&self) -> &str {
        &self.origins[0]
    }

    /// Every request: the `Host` names this server, and an `Origin`, if
    /// any, is this server's or an allowed one.
    pub fn check_request(&self, c: &Credentials) -> Result<(), Refusal> {
        let Some(host) = c.host else {
            return Err(refuse(
                "400 Bad Request",
                format!(
                    "no Host header: send `Host: {}`",
                    &self.own()["http://".len()..]
                ),
            ));
        };
        let host = host.trim();
        if !self.hosts.iter().any(|h| h.eq_ignore_ascii_case(host)) {
            return Err(refuse(
                "421 Misdirected Request",
                format!(
                    "Host `{}` is not this server: open {}/ (the server answers to 127.0.0.1, localhost and [::1] on its port only)",
                    printable(host),
                    self.own()
                ),
            ));
        }
        if let Some(origin) = c.origin
            && !self.allows(origin)
        {
            return Err(refuse(
                "403 Forbidden",
                format!(
                    "Origin `{}` may not use this server: only its own page ({}) and origins given with --allow-origin may",
                    printable(origin.trim()),
                    self.own()
                ),
            ));
        }
        Ok(())
    }

    /// The WebSocket upgrade: [`Access::check_request`], then a client
    /// without an `Origin` (a program, not a page) must present the token.
    pub fn check_websocket(&self, c: &Credentials) -> Result<(), Refusal> {
        self.check_request(c)?;
        if c.origin.is_some() {
            return Ok(());
        }
        let Some(token) = &self.token else {
            return Err(refuse(
                "403 Forbidden",
                "this server has no token: it takes no client without an Origin header".to_string(),
            ));
        };
        let bearer = c.authorization.and_then(|a| {
            let (scheme, value) = a.trim().split_once(' ')?;
            scheme.eq_ignore_ascii_case("bearer").then(|| value.trim())
        });
        let given = match (c.query_token, bearer) {
            (Some(t), _) | (None, Some(t)) => t,
            (None, None) => {
                return Err(refuse(
                    "401 Unauthorized",
                    "a WebSocket client without an Origin header must present the token `rover drive` printed: connect to /ws?token=<token> or send `Authorization: Bearer <token>`".to_string(),
                ));
            }
        };
        if !same(given.as_bytes(), token.as_bytes()) {
            return Err(refuse(
                "401 Unauthorized",
                "wrong token: use the one `rover drive` printed at start (or the one given with --token or ROVER_DRIVE_TOKEN)".to_string(),
            ));
        }
        Ok(())
    }

    fn allows(&self, origin: &str) -> bool {
        let origin = origin.trim();
        self.origins.iter().any(|o| o.eq_ignore_ascii_case(origin))
    }
}

/// Compare without stopping at the first difference: how long a wrong
/// token takes to refuse says nothing of how much of it was right.
fn same(a: &[u8], b: &[u8]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

/// A client's header value, quoted in a refusal: printable ASCII, cut at
/// 100 characters.
fn printable(s: &str) -> String {
    let mut out: String = s
        .chars()
        .take(100)
        .map(|c| {
            if c.is_ascii_graphic() || c == ' ' {
                c
            } else {
                '?'
            }
        })
        .collect();
    if s.chars().count() > 100 {
        out.push('…');
    }
    out
}

/// An `--allow-origin` value, checked and in the form a browser sends it:
/// `scheme://host[:port]`, scheme `http` or `https`, lower case, the
/// scheme's default port left out, no path, query or user.
pub fn parse_origin(url: &str) -> Result<String, String> {
    let fail = |what: &str| {
        Err(format!(
            "--allow-origin `{}`: {what}; give an origin such as http://localhost:3000 or https://rig.example.org (scheme://host[:port], no path)",
            printable(url)
        ))
    };
    let Some((scheme, rest)) = url.split_once("://") else {
        return fail("no scheme");
    };
    let scheme = scheme.to_ascii_lowercase();
    let default_port = match scheme.as_str() {
        "http" => 80,
        "https" => 443,
        _ => return fail("the scheme is not http or https"),
    };
    // A lone trailing slash is how a browser's address bar shows an origin.
    let rest = rest.strip_suffix('/').unwrap_or(rest);
    if rest.contains(['/', '?', '#']) {
        return fail("an origin has no path, query or fragment");
    }
    if rest.contains('@') {
        return fail("an origin has no user name");
    }
    let (host, port) = if let Some(v6) = rest.strip_prefix('[') {
        let Some((addr, after)) = v6.split_once(']') else {
            return fail("an IPv6 address without its closing `]`");
        };
        if addr.parse::<std::net::Ipv6Addr>().is_err() {
            return fail("not an IPv6 address between `[` and `]`");
        }
        match after {
            "" => (format!("[{addr}]"), None),
            p if p.starts_with(':') => (format!("[{addr}]"), Some(&p[1..])),
            _ => return fail("unexpected text after the IPv6 address"),
        }
    } else {
        match rest.rsplit_once(':') {
            Some((h, p)) => (h.to_string(), Some(p)),
            None => (rest.to_string(), None),
        }
    };
    let host_ok = !host.is_empty()
        && (host.starts_with('[')
            || host
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '.'));
    if !host_ok {
        return fail("the host is empty or has characters a host name cannot have");
    }
    let port = match port {
        None => None,
        Some(p) => match p.parse::<u16>() {
            Ok(0) | Err(_) => return fail("the port is not a number from 1 to 65535"),
            Ok(p) if p == default_port => None,
            Ok(p) => Some(p),
        },
    };
    let host = host.to_ascii_lowercase();
    Ok(match port {
        Some(p) => format!("{scheme}://{host}:{p}"),
        None => format!("{scheme}://{host}"),
    })
}

/// A token given by the user (`flag` names where it came from), checked:
/// long enough not to be guessed, and of characters that pass unchanged
/// in a URL's query and a header.
pub fn check_token(flag: &str, token: &str) -> Result<String, String> {
    let ok = |c: char| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.' | '~');
    if !(MIN_TOKEN_LEN..=MAX_TOKEN_LEN).contains(&token.len()) || !token.chars().all(ok) {
        return Err(format!(
            "{flag}: a token is {MIN_TOKEN_LEN} to {MAX_TOKEN_LEN} characters of A–Z, a–z, 0–9, `-`, `_`, `.`, `~` (got {} characters); leave it out and `rover drive` makes and prints a random one",
            token.chars().count()
        ));
    }
    Ok(token.to_string())
}

/// A fresh random token: 128 bits as 32 hex digits, from the system's
/// random source (16 bytes of /dev/urandom); where there is none, from
/// std's randomly keyed hasher over the time, the process and a counter.
pub fn random_token() -> String {
    let mut bytes = [0u8; 16];
    let from_system = std::fs::File::open("/dev/urandom")
        .and_then(|f| f.take(16).read_exact(&mut bytes))
        .is_ok();
    if !from_system {
        use std::hash::{BuildHasher, Hasher};
        for (k, half) in bytes.chunks_mut(8).enumerate() {
            // Each RandomState is keyed afresh by the standard library.
            let mut h = std::collections::hash_map::RandomState::new().build_hasher();
            h.write_u128(
                std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map(|d| d.as_nanos())
                    .unwrap_or(0),
            );
            h.write_u32(std::process::id());
            h.write_usize(k);
            half.copy_from_slice(&h.finish().to_le_bytes());
        }
    }
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

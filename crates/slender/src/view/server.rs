//! The local HTTP server of `slender view` (tiny_http): serves the page and its vendored
//! three.js from the binary, and passes each request, a `POST /api` body or a message of the
//! page's WebSocket ([`socket`](super::socket)), to
//! [`protocol::handle`](super::protocol::handle) with the one [`Session`], on one thread, in
//! the order they arrive.
//!
//! Bound to 127.0.0.1 unless `--host` says otherwise. On a loopback address a request whose
//! `Host` header names another host is refused (a web page elsewhere cannot reach the server
//! through DNS rebinding), and `POST /api` requires `Content-Type: application/json` (which a
//! cross-site form cannot send without a CORS preflight, which this server never grants).

use std::io::Read;
use std::net::{SocketAddr, TcpListener, ToSocketAddrs};
use std::sync::mpsc::{channel, Sender};

use anyhow::{anyhow, Context as _, Result};
use slender_core::scene::Session;
use socket2::{Domain, Protocol, Socket, Type};
use tiny_http::{Header, Method, Request, Response, Server};

use super::history::History;
use super::protocol::MAX_REQUEST_BYTES;
use super::socket::{self, SocketRequest};

/// What the session's thread handles next: an HTTP request or a WebSocket message.
enum Incoming {
    Http(Request),
    Socket(SocketRequest),
}

impl From<SocketRequest> for Incoming {
    fn from(r: SocketRequest) -> Self {
        Self::Socket(r)
    }
}

/// One file of the page.
struct Asset {
    path: &'static str,
    content_type: &'static str,
    bytes: &'static [u8],
}

const JS: &str = "text/javascript; charset=utf-8";

/// The page and its third-party code (three.js r180, MIT: page/vendor/three/LICENSE).
const ASSETS: &[Asset] = &[
    Asset {
        path: "/app.js",
        content_type: JS,
        bytes: include_bytes!("page/app.js"),
    },
    Asset {
        path: "/style.css",
        content_type: "text/css; charset=utf-8",
        bytes: include_bytes!("page/style.css"),
    },
    Asset {
        path: "/vendor/three/three.module.min.js",
        content_type: JS,
        bytes: include_bytes!("page/vendor/three/three.module.min.js"),
    },
    Asset {
        path: "/vendor/three/three.core.min.js",
        content_type: JS,
        bytes: include_bytes!("page/vendor/three/three.core.min.js"),
    },
    Asset {
        path: "/vendor/three/OrbitControls.js",
        content_type: JS,
        bytes: include_bytes!("page/vendor/three/OrbitControls.js"),
    },
    Asset {
        path: "/vendor/three/TransformControls.js",
        content_type: JS,
        bytes: include_bytes!("page/vendor/three/TransformControls.js"),
    },
    Asset {
        path: "/vendor/three/LICENSE",
        content_type: "text/plain; charset=utf-8",
        bytes: include_bytes!("page/vendor/three/LICENSE"),
    },
];

const INDEX: &str = include_str!("page/index.html");

fn header(name: &str, value: &str) -> Header {
    Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("a valid header")
}

/// A listening socket on `host:port` with TCP_NODELAY, which the accepted connections inherit
/// (Linux, macOS, Windows): tiny_http writes a reply in several pieces, and with Nagle's
/// algorithm each piece after the first would wait for the client's delayed ACK (~40 ms on
/// loopback), capping a drag at ~20 updates per second.
fn listener(host: &str, port: u16) -> Result<TcpListener> {
    let address = (host, port)
        .to_socket_addrs()
        .with_context(|| format!("--host {host}: not an address of this machine"))?
        .next()
        .ok_or_else(|| anyhow!("--host {host}: no address"))?;
    let socket = Socket::new(
        Domain::for_address(address),
        Type::STREAM,
        Some(Protocol::TCP),
    )
    .context("creating the server socket")?;
    // A restarted server may bind the port while old connections linger in TIME_WAIT (on
    // Windows the option would let another process steal the port: Unix only).
    #[cfg(unix)]
    socket.set_reuse_address(true)?;
    socket.set_tcp_nodelay(true)?;
    socket
        .bind(&address.into())
        .with_context(|| format!("cannot listen on {address}"))?;
    socket.listen(64)?;
    Ok(socket.into())
}

fn escape_html(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The server of one session.
pub struct ViewServer {
    server: Server,
    address: SocketAddr,
    loopback: bool,
    index: String,
}

impl ViewServer {
    /// Binds `host:port` (port 0: any free port); `scene_name` titles the page.
    pub fn bind(host: &str, port: u16, scene_name: &str) -> Result<Self> {
        let server = Server::from_listener(listener(host, port)?, None)
            .map_err(|e| anyhow!("cannot listen on {host}:{port}: {e}"))?;
        let address = server
            .server_addr()
            .to_ip()
            .ok_or_else(|| anyhow!("the server has no IP address"))?;
        Ok(Self {
            server,
            loopback: address.ip().is_loopback(),
            address,
            index: INDEX.replace("{{SCENE}}", &escape_html(scene_name)),
        })
    }

    /// The page's URL.
    pub fn url(&self) -> String {
        format!("http://{}/", self.address)
    }

    /// Serves until the process is stopped.
    pub fn serve(&self, session: &mut Session) -> Result<()> {
        let mut history = History::default();
        let (events, incoming) = channel::<Incoming>();
        std::thread::scope(|scope| {
            // tiny_http's requests and the sockets' messages meet in one queue, read by this
            // thread, which alone touches the session.
            let http = events.clone();
            let server = &self.server;
            scope.spawn(move || {
                for request in server.incoming_requests() {
                    if http.send(Incoming::Http(request)).is_err() {
                        return;
                    }
                }
            });
            for event in incoming {
                match event {
                    Incoming::Http(request) => {
                        self.respond(session, &mut history, request, &events)
                    }
                    Incoming::Socket(SocketRequest { text, reply }) => {
                        // A socket that closed meanwhile no longer wants its reply.
                        let _ = reply.send(history.handle(session, &text));
                    }
                }
            }
        });
        Ok(())
    }

    /// True if the request's Host header names this server (always, off loopback).
    fn host_allowed(&self, request: &Request) -> bool {
        if !self.loopback {
            return true;
        }
        let port = self.address.port();
        let Some(host) = request
            .headers()
            .iter()
            .find(|h| h.field.equiv("Host"))
            .map(|h| h.value.as_str().to_ascii_lowercase())
        else {
            return false;
        };
        [
            format!("127.0.0.1:{port}"),
            format!("localhost:{port}"),
            format!("[::1]:{port}"),
            self.address.to_string(),
        ]
        .contains(&host)
    }

    fn respond(
        &self,
        session: &mut Session,
        history: &mut History,
        mut request: Request,
        events: &Sender<Incoming>,
    ) {
        let plain = |code: u16, text: &str| {
            Response::from_string(text)
                .with_status_code(code)
                .with_header(header("Content-Type", "text/plain; charset=utf-8"))
        };
        if !self.host_allowed(&request) {
            let _ = request.respond(plain(403, "forbidden: unexpected Host header"));
            return;
        }
        let url = request.url().split('?').next().unwrap_or("").to_string();
        let response = match (request.method(), url.as_str()) {
            (Method::Get, "/ws") => match socket::check_upgrade(&request) {
                Ok(key) => {
                    socket::accept(request, &key, events.clone());
                    return;
                }
                Err((code, message)) => plain(code, &message),
            },
            (Method::Get, "/" | "/index.html") => Response::from_data(self.index.as_bytes())
                .with_header(header("Content-Type", "text/html; charset=utf-8")),
            (Method::Get, path) => match ASSETS.iter().find(|a| a.path == path) {
                Some(a) => {
                    Response::from_data(a.bytes).with_header(header("Content-Type", a.content_type))
                }
                None => plain(404, "not found"),
            },
            (Method::Post, "/api") => {
                let json = request.headers().iter().any(|h| {
                    h.field.equiv("Content-Type")
                        && h.value
                            .as_str()
                            .to_ascii_lowercase()
                            .starts_with("application/json")
                });
                if !json {
                    plain(415, "POST /api takes Content-Type: application/json")
                } else {
                    let mut body = Vec::new();
                    let read = request
                        .as_reader()
                        .take(MAX_REQUEST_BYTES as u64 + 1)
                        .read_to_end(&mut body);
                    let reply = match read {
                        Err(e) => format!(
                            "{{\"ok\":false,\"error\":{{\"field\":\"request\",\"message\":{}}}}}",
                            serde_json::Value::from(format!("reading the request: {e}"))
                        ),
                        Ok(_) => match String::from_utf8(body) {
                            Ok(text) => history.handle(session, &text),
                            Err(_) => "{\"ok\":false,\"error\":{\"field\":\"request\",\"message\":\"not UTF-8 text\"}}".to_string(),
                        },
                    };
                    Response::from_data(reply.into_bytes())
                        .with_header(header("Content-Type", "application/json"))
                        .with_header(header("Cache-Control", "no-store"))
                }
            }
            _ => plain(405, "method not allowed"),
        };
        // A client that went away is not an error of the server.
        let _ = request.respond(response);
    }
}

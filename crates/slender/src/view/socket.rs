//! The page's requests over one WebSocket (`GET /ws`): the same JSON messages as `POST /api`,
//! one text message per request and one per reply, answered in order.
//!
//! Why a socket as well as `POST /api`: in the browser tests a `fetch` round trip costs the page
//! 3 ms on an idle machine and 9–10 ms while it renders on two shared cores, where a WebSocket
//! message costs under 1 ms; the solve of a drag takes about 0.5 ms. The page uses the socket
//! when it opens and falls back to `POST /api` otherwise.
//!
//! Threads: tiny_http hands over the upgraded connection, and a thread per connection reads its
//! frames (tungstenite: framing, masking, ping and close are its job, not hand-written here). It
//! passes each request to the server's one thread, which owns the session and the undo history,
//! and writes back the reply it gets. Requests from every socket and every `POST /api` are
//! therefore handled one at a time, in the order they arrive.
//!
//! Security: a browser lets any web page open a WebSocket to 127.0.0.1 (no CORS for sockets), so
//! the upgrade is refused unless its `Origin`, when it has one, is the page's own
//! (`http://` + the `Host` the server accepted).

use std::sync::mpsc::{channel, Sender};

use tiny_http::{Header, Request, Response};
use tungstenite::protocol::{Role, WebSocketConfig};
use tungstenite::{Message, WebSocket};

use super::protocol::MAX_REQUEST_BYTES;

/// A request read from a socket, with where its reply goes.
pub struct SocketRequest {
    /// The JSON text of the request.
    pub text: String,
    /// Receives the reply's JSON text.
    pub reply: Sender<String>,
}

/// Why an upgrade is refused: the HTTP status and a message.
pub type Refusal = (u16, String);

fn header<'a>(request: &'a Request, name: &'static str) -> Option<&'a str> {
    request
        .headers()
        .iter()
        .find(|h| h.field.equiv(name))
        .map(|h| h.value.as_str())
}

/// Checks an upgrade request to `/ws` (its `Host` already accepted) and returns the
/// `Sec-WebSocket-Accept` value of the reply.
pub fn check_upgrade(request: &Request) -> Result<String, Refusal> {
    let has_token = |name: &'static str, token: &str| {
        header(request, name)
            .is_some_and(|v| v.split(',').any(|t| t.trim().eq_ignore_ascii_case(token)))
    };
    if !(has_token("Upgrade", "websocket") && has_token("Connection", "upgrade")) {
        return Err((
            400,
            "GET /ws is a WebSocket: it needs `Upgrade: websocket` and `Connection: upgrade`"
                .into(),
        ));
    }
    if header(request, "Sec-WebSocket-Version").map(str::trim) != Some("13") {
        return Err((
            400,
            "Sec-WebSocket-Version: only version 13 is spoken".into(),
        ));
    }
    let Some(key) = header(request, "Sec-WebSocket-Key").map(str::trim) else {
        return Err((400, "Sec-WebSocket-Key: missing".into()));
    };
    if let Some(origin) = header(request, "Origin") {
        let host = header(request, "Host").unwrap_or("");
        if !origin.eq_ignore_ascii_case(&format!("http://{host}")) {
            return Err((
                403,
                format!("forbidden: a WebSocket from {origin}, not from this page (http://{host})"),
            ));
        }
    }
    Ok(tungstenite::handshake::derive_accept_key(key.as_bytes()))
}

/// Completes the upgrade (the 101 reply) and serves the connection on a thread of its own,
/// sending each request to `requests`.
pub fn accept<E: From<SocketRequest> + Send + 'static>(
    request: Request,
    accept_key: &str,
    requests: Sender<E>,
) {
    let reply = Response::empty(101).with_header(
        Header::from_bytes(&b"Sec-WebSocket-Accept"[..], accept_key.as_bytes())
            .expect("a base64 header value"),
    );
    let stream = request.upgrade("websocket", reply);
    let spawned = std::thread::Builder::new()
        .name("slender-view-socket".into())
        .spawn(move || serve_connection(stream, requests));
    if let Err(e) = spawned {
        eprintln!("slender view: cannot serve a WebSocket: {e}");
    }
}

/// Reads requests until the connection closes. A message over [`MAX_REQUEST_BYTES`] or a broken
/// frame closes the connection (the page then falls back to `POST /api`); a binary message
/// gets an error reply like any malformed request.
fn serve_connection<E: From<SocketRequest>>(
    stream: Box<dyn tiny_http::ReadWrite + Send>,
    requests: Sender<E>,
) {
    let config = WebSocketConfig::default()
        .max_message_size(Some(MAX_REQUEST_BYTES))
        .max_frame_size(Some(MAX_REQUEST_BYTES));
    let mut socket = WebSocket::from_raw_socket(stream, Role::Server, Some(config));
    loop {
        let reply = match socket.read() {
            Ok(Message::Text(text)) => {
                let (reply, answer) = channel();
                let request = SocketRequest {
                    text: text.as_str().to_owned(),
                    reply,
                };
                // The server's thread is gone: nothing left to serve.
                if requests.send(request.into()).is_err() {
                    return;
                }
                match answer.recv() {
                    Ok(r) => r,
                    Err(_) => return,
                }
            }
            Ok(Message::Binary(_)) => {
                "{\"ok\":false,\"error\":{\"field\":\"request\",\"message\":\"a binary WebSocket message: requests are JSON text\"}}".to_string()
            }
            // Pings are answered, and a close handshake completed, by tungstenite on the next
            // read.
            Ok(_) => continue,
            Err(_) => return,
        };
        if socket.send(Message::text(reply)).is_err() {
            return;
        }
    }
}

#[cfg(test)]
mod tests {
    //! The socket end to end, against a real server on a free port: the same replies as the
    //! message handler, hostile frames answered or the connection dropped (never a panic), and
    //! a page of another origin refused.

    use std::net::TcpStream;

    use serde_json::Value;
    use slender_core::scene::{Scene, Session};
    use tungstenite::client::IntoClientRequest;
    use tungstenite::{Message, WebSocket};

    use super::super::server::ViewServer;

    const SCENE: &str = r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
elements = 10
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 0.5 }
section = { shape = "circle", diameter = 0.004 }
material = { young = 1.0e9, poisson = 0.4, density = 1400.0 }
supports = [{ kind = "clamp", vertex = "start" }]
"#;

    /// Starts a server for the scene on a free port and returns its `host:port`.
    fn start() -> String {
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let scene: Scene = toml::from_str(SCENE).expect("scene");
            let mut session = Session::new(scene).expect("compiles");
            let server = ViewServer::bind("127.0.0.1", 0, "test.toml").expect("binds");
            let url = server.url();
            tx.send(url).expect("the test waits");
            server.serve(&mut session).expect("serves");
        });
        let url = rx.recv().expect("the server starts");
        url.trim_start_matches("http://")
            .trim_end_matches('/')
            .to_string()
    }

    fn connect(host: &str, origin: Option<&str>) -> tungstenite::Result<WebSocket<TcpStream>> {
        let mut request = format!("ws://{host}/ws").into_client_request()?;
        if let Some(o) = origin {
            request
                .headers_mut()
                .insert("Origin", o.parse().expect("a header value"));
        }
        let stream = TcpStream::connect(host).expect("connects");
        tungstenite::client(request, stream)
            .map(|(socket, _)| socket)
            .map_err(|e| match e {
                tungstenite::HandshakeError::Failure(e) => e,
                tungstenite::HandshakeError::Interrupted(_) => unreachable!("blocking stream"),
            })
    }

    fn ask(socket: &mut WebSocket<TcpStream>, message: Message) -> Value {
        socket.send(message).expect("sends");
        loop {
            match socket.read().expect("a reply") {
                Message::Text(t) => return serde_json::from_str(t.as_str()).expect("JSON"),
                Message::Ping(_) | Message::Pong(_) => continue,
                other => panic!("unexpected {other:?}"),
            }
        }
    }

    fn tip(state: &Value) -> Vec<f64> {
        let p = &state["view"]["rods"][0]["positions"];
        let last = p.as_array().expect("positions").last().expect("a vertex");
        last.as_array()
            .expect("a point")
            .iter()
            .map(|x| x.as_f64().expect("a number"))
            .collect()
    }

    #[test]
    fn the_page_socket_answers_like_the_handler_and_survives_hostile_frames() {
        let host = start();
        let mut ws = connect(&host, Some(&format!("http://{host}"))).expect("same origin");
        let state = ask(&mut ws, Message::text(r#"{"op":"state"}"#));
        assert_eq!(state["ok"], true, "{state}");
        let before = tip(&state);

        // Malformed requests get the handler's error replies, naming the problem.
        let bad = ask(&mut ws, Message::text("{not json"));
        assert_eq!(bad["ok"], false);
        assert!(
            bad["error"]["message"]
                .as_str()
                .is_some_and(|m| !m.is_empty()),
            "{bad}"
        );
        let nan = ask(
            &mut ws,
            Message::text(r#"{"op":"move","rod":0,"support":0,"position":[0,0,"nan"]}"#),
        );
        assert_eq!(nan["ok"], false, "{nan}");
        let binary = ask(&mut ws, Message::binary(vec![0u8, 159, 146, 150]));
        assert_eq!(binary["ok"], false);
        assert!(binary["error"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("binary")));
        let unchanged = ask(&mut ws, Message::text(r#"{"op":"state"}"#));
        assert_eq!(tip(&unchanged), before, "refused requests change nothing");

        // A message over the limit drops the connection; the server serves on.
        let huge = "x".repeat(super::MAX_REQUEST_BYTES + 10);
        let _ = ws.send(Message::text(huge));
        let dropped = loop {
            match ws.read() {
                Ok(Message::Text(_)) => break false,
                Ok(_) => continue,
                Err(_) => break true,
            }
        };
        assert!(dropped, "an oversized message closes the connection");

        // A new connection (no Origin: not a browser) edits the same session.
        let mut again = connect(&host, None).expect("connects");
        let moved = ask(
            &mut again,
            Message::text(r#"{"op":"gravity","gravity":[0.0,0.0,-19.62]}"#),
        );
        assert_eq!(moved["ok"], true, "{moved}");
        let after = tip(&ask(&mut again, Message::text(r#"{"op":"state"}"#)));
        assert!(
            after[2] < before[2],
            "twice the gravity bends the cable further"
        );
    }

    #[test]
    fn a_socket_from_another_origin_is_refused() {
        let host = start();
        match connect(&host, Some("http://evil.example")) {
            Err(tungstenite::Error::Http(response)) => assert_eq!(response.status(), 403),
            Err(e) => panic!("refused, but not by a 403: {e}"),
            Ok(_) => panic!("a page of another origin opened the socket"),
        }
        // The page's own origin still gets in.
        assert!(connect(&host, Some(&format!("http://{host}"))).is_ok());
    }
}

//! `planlab serve`: the static file server the playground runs on.
//!
//! HTTP/1.1 by hyper, files by tower-http's `ServeFile` (streamed in 64 KiB
//! chunks, `Range` answered 206 or 416, `Last-Modified`/`If-Modified-Since`).
//! This module adds what those leave to the caller:
//!
//! - loopback only: a `--host` that resolves to anything else is refused;
//! - GET and HEAD only (405 otherwise), `.wasm` as `application/wasm`;
//! - a file's precompressed twin `NAME.br` or `NAME.gz` (written by the
//!   site build) is sent instead when the request accepts that encoding,
//!   with `Content-Encoding` and `Vary: accept-encoding`: compression costs
//!   nothing per request and needs no compressor in the server;
//! - nothing outside the site folder: paths are percent-decoded, `..`, roots
//!   and NUL/backslash are refused, and the resolved file must stay under the
//!   canonical root, so symlinks cannot escape either (404 in every case);
//! - a folder without its trailing slash is redirected (307) to it, a folder
//!   with it serves its `index.html`; no listings;
//! - a request target over [`MAX_TARGET`] bytes is 414 (hyper itself answers
//!   414 above 64 KiB and 431 when the whole head outgrows its ~400 KiB
//!   buffer);
//! - time and connection limits, see [`Limits`].

use std::collections::HashMap;
use std::convert::Infallible;
use std::future::Future;
use std::io;
use std::net::{SocketAddr, ToSocketAddrs};
use std::path::{Component, Path, PathBuf};
use std::pin::Pin;
use std::sync::{Arc, Mutex, PoisonError};
use std::task::{Context, Poll};
use std::time::Duration;

use bytes::Bytes;
use http_body_util::{combinators::UnsyncBoxBody, BodyExt, Full};
use hyper::body::{Body as HttpBody, Frame, Incoming, SizeHint};
use hyper::header::{self, HeaderValue};
use hyper::server::conn::http1;
use hyper::service::service_fn;
use hyper::{Method, Request, Response, StatusCode};
use hyper_util::rt::{TokioIo, TokioTimer};
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::net::TcpStream;
use tokio::sync::{Notify, OwnedSemaphorePermit, Semaphore, TryAcquireError};
use tokio::time::Sleep;
use tower_http::services::ServeFile;

/// Longest request target (path and query) served; longer is 414. Far above
/// any URL the playground makes, and the usual limit of other servers.
pub const MAX_TARGET: usize = 8 * 1024;

/// Time and connection limits of the server.
///
/// The defaults are meant for a browser on the same machine. Tests shorten
/// them through environment variables, deliberately left out of `--help`:
/// `PLANLAB_SERVE_HEADER_TIMEOUT_MS`, `PLANLAB_SERVE_WRITE_TIMEOUT_MS`,
/// `PLANLAB_SERVE_MAX_CONNECTIONS`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Time for a whole request head to arrive, counted from when the server
    /// starts waiting for it: this closes slowloris clients and idle
    /// keep-alive connections alike. Default 10 s.
    pub header_timeout: Duration,
    /// Longest a response write may make no progress (a client that stopped
    /// reading) before the connection is dropped. Default 15 s.
    pub write_timeout: Duration,
    /// Connections served at once. When every slot is taken, one more
    /// connection is accepted and the one idle longest (no request head yet,
    /// or between requests) is closed to make room for it, or the next to
    /// fall idle when none is; further ones wait in the listen backlog.
    /// So idle sockets cannot hold a request back until their header
    /// timeout. Default 64 (a browser opens about 6 per host).
    pub max_connections: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            header_timeout: Duration::from_secs(10),
            write_timeout: Duration::from_secs(15),
            max_connections: 64,
        }
    }
}

impl Limits {
    /// The defaults, with any of the `PLANLAB_SERVE_*` variables applied.
    pub fn from_env() -> Result<Self, String> {
        // Bounded so that no value can overflow a deadline or the semaphore.
        let var = |name: &str, max: u64| -> Result<Option<u64>, String> {
            match std::env::var(name) {
                Err(_) => Ok(None),
                Ok(v) => match v.trim().parse::<u64>() {
                    Ok(n) if (1..=max).contains(&n) => Ok(Some(n)),
                    _ => Err(format!(
                        "{name} must be a whole number from 1 to {max}, not {v:?}"
                    )),
                },
            }
        };
        const DAY_MS: u64 = 86_400_000;
        let mut limits = Limits::default();
        if let Some(ms) = var("PLANLAB_SERVE_HEADER_TIMEOUT_MS", DAY_MS)? {
            limits.header_timeout = Duration::from_millis(ms);
        }
        if let Some(ms) = var("PLANLAB_SERVE_WRITE_TIMEOUT_MS", DAY_MS)? {
            limits.write_timeout = Duration::from_millis(ms);
        }
        if let Some(n) = var("PLANLAB_SERVE_MAX_CONNECTIONS", 100_000)? {
            // At most 100 000, so it fits any usize.
            limits.max_connections = n as usize;
        }
        Ok(limits)
    }
}

/// Content type for a file name, by extension.
pub fn content_type(path: &Path) -> &'static str {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .as_deref()
    {
        Some("html") | Some("htm") => "text/html; charset=utf-8",
        Some("js") | Some("mjs") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("json") => "application/json",
        Some("wasm") => "application/wasm",
        Some("svg") => "image/svg+xml",
        Some("png") => "image/png",
        Some("ico") => "image/x-icon",
        Some("txt") | Some("map") | Some("scen") | Some("yaml") | Some("yml") | Some("md") => {
            "text/plain; charset=utf-8"
        }
        Some("pgm") => "image/x-portable-graymap",
        _ => "application/octet-stream",
    }
}

fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = s.get(i + 1..i + 3)?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// Percent-encodes all but RFC 3986 unreserved bytes, for a `Location`.
fn percent_encode(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for b in s.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~".contains(&b) {
            out.push(char::from(b));
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// What a request target maps to under the site root.
#[derive(Debug, PartialEq, Eq)]
pub enum Target {
    /// A file under the root (canonical path).
    File(PathBuf),
    /// A folder named without its trailing slash: redirect to this
    /// root-relative location (always one leading `/`, so never off-site).
    Redirect(String),
    /// Missing, outside the root, or not a valid path.
    NotFound,
}

/// Maps a request target (path, optional query) to a file under `root`
/// (already canonical).
pub fn resolve(root: &Path, target: &str) -> Target {
    let target = target.split('#').next().unwrap_or("");
    let (path, query) = match target.split_once('?') {
        Some((p, q)) => (p, Some(q)),
        None => (target, None),
    };
    let Some(decoded) = percent_decode(path) else {
        return Target::NotFound;
    };
    if decoded.contains('\0') || decoded.contains('\\') {
        return Target::NotFound;
    }
    let mut names = Vec::new();
    for comp in Path::new(decoded.trim_start_matches('/')).components() {
        match comp {
            Component::Normal(c) => match c.to_str() {
                Some(c) => names.push(c),
                None => return Target::NotFound,
            },
            Component::CurDir => {}
            // `..`, a root or a drive prefix inside the path: refuse outright.
            _ => return Target::NotFound,
        }
    }
    let inside = |p: PathBuf| match p.canonicalize() {
        Ok(canon) if canon.starts_with(root) => Some(canon),
        _ => None,
    };
    let Some(canon) = inside(names.iter().fold(root.to_path_buf(), |p, n| p.join(n))) else {
        return Target::NotFound;
    };
    let slash = names.is_empty() || decoded.ends_with('/');
    if canon.is_dir() {
        if !slash {
            // Rebuilt from the checked names: `//host` can never come out.
            let mut loc: String = names
                .iter()
                .map(|n| format!("/{}", percent_encode(n)))
                .collect();
            loc.push('/');
            if let Some(q) = query {
                loc.push('?');
                loc.push_str(q);
            }
            return Target::Redirect(loc);
        }
        return match inside(canon.join("index.html")) {
            Some(index) if index.is_file() => Target::File(index),
            _ => Target::NotFound,
        };
    }
    // `file.js/` names a folder that is not there.
    if canon.is_file() && !slash {
        Target::File(canon)
    } else {
        Target::NotFound
    }
}

type Body = UnsyncBoxBody<Bytes, io::Error>;

fn text(status: StatusCode, msg: &'static str) -> Response<Body> {
    let mut res = Response::new(
        Full::new(Bytes::from_static(msg.as_bytes()))
            .map_err(|e| match e {})
            .boxed_unsync(),
    );
    *res.status_mut() = status;
    res.headers_mut().insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static("text/plain; charset=utf-8"),
    );
    res
}

async fn respond(req: Request<Incoming>, root: Arc<PathBuf>) -> Response<Body> {
    if req.method() != Method::GET && req.method() != Method::HEAD {
        let mut res = text(StatusCode::METHOD_NOT_ALLOWED, "only GET and HEAD\n");
        res.headers_mut()
            .insert(header::ALLOW, HeaderValue::from_static("GET, HEAD"));
        return res;
    }
    let target = req.uri().path_and_query().map_or("/", |pq| pq.as_str());
    if target.len() > MAX_TARGET {
        return text(StatusCode::URI_TOO_LONG, "request target too long\n");
    }
    // `resolve` stats and canonicalizes: blocking calls, kept off the
    // runtime's few worker threads.
    let lookup = {
        let target = target.to_owned();
        tokio::task::spawn_blocking(move || resolve(&root, &target)).await
    };
    let Ok(found) = lookup else {
        return text(StatusCode::INTERNAL_SERVER_ERROR, "lookup failed\n");
    };
    match found {
        Target::NotFound => text(StatusCode::NOT_FOUND, "not found\n"),
        Target::Redirect(loc) => {
            let mut res = text(StatusCode::TEMPORARY_REDIRECT, "moved\n");
            // `loc` is built from unreserved bytes, `/`, `%` and a query hyper
            // already accepted, so it is a valid header value.
            if let Ok(v) = HeaderValue::from_str(&loc) {
                res.headers_mut().insert(header::LOCATION, v);
            }
            res
        }
        Target::File(path) => {
            // A valid multi-range is answered with the whole file (allowed by
            // RFC 9110) instead of tower-http's 416.
            // `NAME.br`/`NAME.gz` beside a file (the site build writes
            // them) go to clients that accept them, with `Vary`.
            let served = ServeFile::new(&path)
                .precompressed_br()
                .precompressed_gzip()
                .ignore_multi_range_requests(true)
                .try_call(req)
                .await;
            match served {
                Ok(res) => {
                    let mut res = res.map(|b| b.boxed_unsync());
                    if res.status().is_success() {
                        // Our table, not mime_guess: charsets, and the same
                        // types on every platform.
                        res.headers_mut().insert(
                            header::CONTENT_TYPE,
                            HeaderValue::from_static(content_type(&path)),
                        );
                    }
                    res
                }
                // Gone between resolving and opening, or unreadable.
                Err(e) if e.kind() == io::ErrorKind::NotFound => {
                    text(StatusCode::NOT_FOUND, "not found\n")
                }
                Err(_) => text(StatusCode::INTERNAL_SERVER_ERROR, "cannot read file\n"),
            }
        }
    }
}

async fn handle(req: Request<Incoming>, root: Arc<PathBuf>) -> Result<Response<Body>, Infallible> {
    let mut res = respond(req, root).await;
    let h = res.headers_mut();
    // The playground is rebuilt in place; make browsers revalidate.
    h.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-cache"));
    h.insert(
        header::X_CONTENT_TYPE_OPTIONS,
        HeaderValue::from_static("nosniff"),
    );
    Ok(res)
}

/// A TCP stream whose writes fail once they make no progress for `limit`:
/// hyper has no write timeout, and without one a client that stops reading
/// holds its connection (and open file) for as long as it likes. Reads are
/// left alone: hyper polls them mid-response to notice hang-ups, and its
/// header timeout already covers the reads that matter.
struct StallGuard {
    inner: TcpStream,
    limit: Duration,
    stalled: Option<Pin<Box<Sleep>>>,
}

impl StallGuard {
    fn guard<T>(&mut self, cx: &mut Context<'_>, r: Poll<io::Result<T>>) -> Poll<io::Result<T>> {
        if r.is_ready() {
            self.stalled = None;
            return r;
        }
        let limit = self.limit;
        let timer = self
            .stalled
            .get_or_insert_with(|| Box::pin(tokio::time::sleep(limit)));
        match timer.as_mut().poll(cx) {
            Poll::Ready(()) => Poll::Ready(Err(io::Error::new(
                io::ErrorKind::TimedOut,
                "client stopped reading",
            ))),
            Poll::Pending => Poll::Pending,
        }
    }
}

impl AsyncRead for StallGuard {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        Pin::new(&mut self.inner).poll_read(cx, buf)
    }
}

impl AsyncWrite for StallGuard {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        let r = Pin::new(&mut self.inner).poll_write(cx, buf);
        self.guard(cx, r)
    }

    fn poll_write_vectored(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bufs: &[io::IoSlice<'_>],
    ) -> Poll<io::Result<usize>> {
        let r = Pin::new(&mut self.inner).poll_write_vectored(cx, bufs);
        self.guard(cx, r)
    }

    fn is_write_vectored(&self) -> bool {
        self.inner.is_write_vectored()
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        let r = Pin::new(&mut self.inner).poll_flush(cx);
        self.guard(cx, r)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        let r = Pin::new(&mut self.inner).poll_shutdown(cx);
        self.guard(cx, r)
    }
}

/// The connections being served and which of them are idle, so that a
/// newcomer finding every slot taken can have an idle one closed
/// ([`Conns::make_room`]).
#[derive(Default)]
struct Conns(Mutex<ConnTable>);

#[derive(Default)]
struct ConnTable {
    next_id: u64,
    /// Counts connections falling idle: an exact order, unlike a clock.
    tick: u64,
    live: HashMap<u64, Live>,
    /// A newcomer waits and nothing was idle: close the next to fall idle.
    waiting: bool,
}

struct Live {
    /// The `tick` it last fell idle at (accepted counts); `None` while it
    /// answers a request.
    idle_since: Option<u64>,
    /// Whether it has ever started answering a request.
    answered: bool,
    /// Whether it has been asked to close already.
    closing: bool,
    close: Arc<Notify>,
}

impl ConnTable {
    fn close(&mut self, id: u64) {
        if let Some(c) = self.live.get_mut(&id) {
            c.closing = true;
            c.close.notify_one();
        }
    }
}

impl Conns {
    fn table(&self) -> std::sync::MutexGuard<'_, ConnTable> {
        // Nothing panics while holding it; a poisoned table is still sound.
        self.0.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Registers a connection just accepted (idle: no request yet).
    fn open(self: &Arc<Self>) -> ConnMark {
        let mut t = self.table();
        let id = t.next_id;
        t.next_id += 1;
        t.tick += 1;
        let close = Arc::new(Notify::new());
        let live = Live {
            idle_since: Some(t.tick),
            answered: false,
            closing: false,
            close: Arc::clone(&close),
        };
        t.live.insert(id, live);
        ConnMark {
            conns: Arc::clone(self),
            id,
            close,
        }
    }

    fn answering(&self, id: u64) {
        if let Some(c) = self.table().live.get_mut(&id) {
            c.idle_since = None;
            c.answered = true;
        }
    }

    fn idle(&self, id: u64) {
        let mut t = self.table();
        t.tick += 1;
        let tick = t.tick;
        let Some(c) = t.live.get_mut(&id) else {
            return;
        };
        c.idle_since = Some(tick);
        let closing = c.closing;
        if t.waiting && !closing {
            t.waiting = false;
            t.close(id);
        }
    }

    /// Every slot is taken and a newcomer waits: asks the connection idle
    /// longest to close, or, when none is idle, the next to fall idle.
    fn make_room(&self) {
        let mut t = self.table();
        let oldest = t
            .live
            .iter()
            .filter(|(_, c)| !c.closing)
            .filter_map(|(&id, c)| c.idle_since.map(|since| (since, id)))
            .min();
        match oldest {
            Some((_, id)) => t.close(id),
            None => t.waiting = true,
        }
    }

    /// The newcomer has its slot.
    fn room_made(&self) {
        self.table().waiting = false;
    }
}

/// A connection's entry in [`Conns`], removed on drop.
struct ConnMark {
    conns: Arc<Conns>,
    id: u64,
    /// Notified when the connection is to close for a newcomer.
    close: Arc<Notify>,
}

impl ConnMark {
    /// Marks the connection as answering a request until the returned mark
    /// drops.
    fn answering(&self) -> Answering {
        self.conns.answering(self.id);
        Answering {
            conns: Arc::clone(&self.conns),
            id: self.id,
        }
    }

    fn ever_answered(&self) -> bool {
        self.conns
            .table()
            .live
            .get(&self.id)
            .is_some_and(|c| c.answered)
    }
}

impl Drop for ConnMark {
    fn drop(&mut self) {
        self.conns.table().live.remove(&self.id);
    }
}

/// Its connection answers a request while this lives; it rides in the
/// response body, which hyper drops once the body is written (or the
/// connection ends).
struct Answering {
    conns: Arc<Conns>,
    id: u64,
}

impl Drop for Answering {
    fn drop(&mut self) {
        self.conns.idle(self.id);
    }
}

/// A response body carrying its connection's [`Answering`] mark.
struct Marked {
    body: Body,
    _answering: Answering,
}

impl HttpBody for Marked {
    type Data = Bytes;
    type Error = io::Error;

    fn poll_frame(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
    ) -> Poll<Option<Result<Frame<Bytes>, io::Error>>> {
        Pin::new(&mut self.body).poll_frame(cx)
    }

    fn is_end_stream(&self) -> bool {
        self.body.is_end_stream()
    }

    fn size_hint(&self) -> SizeHint {
        self.body.size_hint()
    }
}

/// A slot for a connection accepted while every slot was taken: an idle
/// connection is asked to make room ([`Conns::make_room`]). `None` when the
/// server is shutting down.
async fn slot_for_newcomer(slots: &Arc<Semaphore>, conns: &Conns) -> Option<OwnedSemaphorePermit> {
    let slot = match Arc::clone(slots).try_acquire_owned() {
        Ok(slot) => slot,
        Err(TryAcquireError::Closed) => return None,
        Err(TryAcquireError::NoPermits) => {
            conns.make_room();
            Arc::clone(slots).acquire_owned().await.ok()?
        }
    };
    conns.room_made();
    Some(slot)
}

/// The addresses `host:port` names, all of them loopback, or an error.
fn loopback_addrs(host: &str, port: u16) -> Result<Vec<SocketAddr>, String> {
    let addrs: Vec<SocketAddr> = (host, port)
        .to_socket_addrs()
        .map_err(|e| format!("cannot resolve --host {host}: {e}"))?
        .collect();
    if addrs.is_empty() || addrs.iter().any(|a| !a.ip().is_loopback()) {
        return Err(format!(
            "--host {host} is not a loopback address: planlab serve binds loopback only (127.0.0.1, ::1, localhost)"
        ));
    }
    Ok(addrs)
}

async fn run(root: PathBuf, addrs: Vec<SocketAddr>, limits: Limits) -> Result<(), String> {
    let bound = std::net::TcpListener::bind(&addrs[..])
        .and_then(|l| l.set_nonblocking(true).map(|()| l))
        .and_then(tokio::net::TcpListener::from_std);
    let listener = bound.map_err(|e| format!("cannot bind {}: {e}", addrs[0]))?;
    let addr = listener
        .local_addr()
        .map_err(|e| format!("cannot read bound address: {e}"))?;
    outln!("serving {} on http://{addr}/", root.display());
    let root = Arc::new(root);
    let slots = Arc::new(Semaphore::new(limits.max_connections));
    let conns = Arc::new(Conns::default());
    loop {
        // Take a free slot before accepting. With none free, accept one
        // client anyway, to close an idle connection for it; the rest wait
        // in the backlog.
        let free = match Arc::clone(&slots).try_acquire_owned() {
            Ok(slot) => Some(slot),
            Err(TryAcquireError::NoPermits) => None,
            Err(TryAcquireError::Closed) => return Ok(()),
        };
        let stream = match listener.accept().await {
            Ok((s, _)) => s,
            Err(e) => {
                eprintln!("planlab serve: connection failed: {e}");
                // Out of descriptors and the like: do not spin on it.
                tokio::time::sleep(Duration::from_millis(100)).await;
                continue;
            }
        };
        let slot = match free {
            Some(slot) => slot,
            None => match slot_for_newcomer(&slots, &conns).await {
                Some(slot) => slot,
                None => return Ok(()),
            },
        };
        let _ = stream.set_nodelay(true);
        let io = TokioIo::new(StallGuard {
            inner: stream,
            limit: limits.write_timeout,
            stalled: None,
        });
        let mark = Arc::new(conns.open());
        let service = {
            let (root, mark) = (Arc::clone(&root), Arc::clone(&mark));
            service_fn(move |req| {
                let answering = mark.answering();
                let root = Arc::clone(&root);
                async move {
                    let res = handle(req, root).await?;
                    Ok::<_, Infallible>(res.map(|body| Marked {
                        body,
                        _answering: answering,
                    }))
                }
            })
        };
        let conn = http1::Builder::new()
            .timer(TokioTimer::new())
            .header_read_timeout(limits.header_timeout)
            .serve_connection(io, service);
        tokio::spawn(async move {
            {
                let mut conn = std::pin::pin!(conn);
                let mut to_close = std::pin::pin!(mark.close.notified());
                // Served to its end (timeouts and hang-ups included: nothing
                // to report), or asked to close for a newcomer.
                let asked = std::future::poll_fn(|cx| {
                    if conn.as_mut().poll(cx).is_ready() {
                        return Poll::Ready(false);
                    }
                    to_close.as_mut().poll(cx).map(|()| true)
                })
                .await;
                // Never answered: no response to finish, and a half-sent head
                // would keep hyper waiting, so it is dropped. Otherwise hyper
                // closes it: at once between requests, else after the
                // response.
                if asked && mark.ever_answered() {
                    conn.as_mut().graceful_shutdown();
                    let _ = conn.await;
                }
            }
            // The socket is closed; its entry goes before its slot.
            drop(mark);
            drop(slot);
        });
    }
}

/// Serves `dir` on `host:port` (loopback only) until the process is killed.
/// Port 0 picks a free port; the bound address is printed on stdout first.
pub fn serve(dir: &Path, host: &str, port: u16) -> Result<(), String> {
    let limits = Limits::from_env()?;
    let root = dir
        .canonicalize()
        .map_err(|e| format!("cannot serve {}: {e}", dir.display()))?;
    if !root.join("index.html").is_file() {
        return Err(format!(
            "{} has no index.html: build the page first (see README)",
            root.display()
        ));
    }
    let addrs = loopback_addrs(host, port)?;
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(|e| format!("cannot start the server runtime: {e}"))?;
    runtime.block_on(run(root, addrs, limits))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn site() -> (PathBuf, PathBuf) {
        let base = std::env::temp_dir().join(format!("planlab-serve-test-{}", std::process::id()));
        let root = base.join("site");
        std::fs::create_dir_all(root.join("pkg")).unwrap();
        std::fs::create_dir_all(root.join("empty")).unwrap();
        std::fs::write(root.join("index.html"), "<html></html>").unwrap();
        std::fs::write(root.join("pkg/a.wasm"), b"\0asm").unwrap();
        std::fs::write(root.join("pkg/index.html"), "pkg").unwrap();
        std::fs::write(base.join("secret.txt"), "secret").unwrap();
        (base, root.canonicalize().unwrap())
    }

    #[test]
    fn resolves_inside_and_refuses_outside() {
        let (_base, root) = site();
        let file = |p: &str| Target::File(root.join(p));
        assert_eq!(resolve(&root, "/"), file("index.html"));
        assert_eq!(resolve(&root, "/pkg/a.wasm?x=1"), file("pkg/a.wasm"));
        assert_eq!(resolve(&root, "/pkg/%61.wasm"), file("pkg/a.wasm"));
        assert_eq!(resolve(&root, "/pkg/"), file("pkg/index.html"));
        for evil in [
            "/../secret.txt",
            "/%2e%2e/secret.txt",
            "/pkg/../../secret.txt",
            "//etc/passwd",
            "/..%2fsecret.txt",
            "/%00",
            "/%zz",
            "/missing.js",
            "/index.html/",
            "/empty/",
        ] {
            assert_eq!(resolve(&root, evil), Target::NotFound, "{evil}");
        }
    }

    #[test]
    fn folder_without_slash_redirects_on_site() {
        let (_base, root) = site();
        let to = |l: &str| Target::Redirect(l.to_string());
        assert_eq!(resolve(&root, "/pkg"), to("/pkg/"));
        assert_eq!(resolve(&root, "/pkg?a=1#f"), to("/pkg/?a=1"));
        assert_eq!(resolve(&root, "/./pkg"), to("/pkg/"));
        // Not `//pkg/`, which a browser reads as the host `pkg`.
        assert_eq!(resolve(&root, "//pkg"), to("/pkg/"));
        assert_eq!(resolve(&root, "/empty"), to("/empty/"));
    }

    #[test]
    fn wasm_content_type() {
        assert_eq!(
            content_type(Path::new("x/planlab_bg.wasm")),
            "application/wasm"
        );
        assert_eq!(
            content_type(Path::new("index.html")),
            "text/html; charset=utf-8"
        );
    }

    #[test]
    fn only_loopback_hosts() {
        assert!(loopback_addrs("127.0.0.1", 0).is_ok());
        assert!(loopback_addrs("::1", 0).is_ok());
        let e = loopback_addrs("0.0.0.0", 0).unwrap_err();
        assert!(e.contains("loopback only"), "{e}");
    }
}

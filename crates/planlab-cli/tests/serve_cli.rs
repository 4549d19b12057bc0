//! `planlab serve` over real TCP on 127.0.0.1 (ephemeral ports): Range,
//! redirects, limits and timeouts, traversal refusals, MIME types, start
//! errors. Timeouts are shortened through the `PLANLAB_SERVE_*` variables so
//! every test ends within a few seconds; every read has a deadline.

use std::io::{BufRead, BufReader, ErrorKind, Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdout, Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};
use std::thread;
use std::time::{Duration, Instant};

const SECRET: &str = "TOP-SECRET-OUTSIDE-THE-SITE";
const BIG: usize = 32 << 20;

/// The 1000 bytes of `nums.bin`, each different from its neighbours.
fn nums() -> Vec<u8> {
    (0..1000u32).map(|i| (i % 251) as u8).collect()
}

/// A fresh site folder for one test, with a secret file next to it.
fn site(name: &str) -> PathBuf {
    let base =
        std::env::temp_dir().join(format!("planlab-serve-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&base);
    let root = base.join("site");
    for d in ["pkg", "sub", "nosub"] {
        std::fs::create_dir_all(root.join(d)).unwrap();
    }
    let files: [(&str, &[u8]); 8] = [
        ("index.html", b"<html>home</html>"),
        ("sub/index.html", b"<html>sub</html>"),
        ("pkg/a.wasm", b"\0asm\x01\0\0\0"),
        ("app.js", b"export {};"),
        ("style.css", b"body{}"),
        ("data.json", b"{}"),
        ("icon.svg", b"<svg/>"),
        ("img.png", b"\x89PNG\r\n\x1a\n"),
    ];
    for (p, body) in files {
        std::fs::write(root.join(p), body).unwrap();
    }
    std::fs::write(root.join("nums.bin"), nums()).unwrap();
    std::fs::write(base.join("secret.txt"), SECRET).unwrap();
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("../secret.txt", root.join("leak.txt")).unwrap();
        std::os::unix::fs::symlink("..", root.join("up")).unwrap();
    }
    root
}

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_planlab"))
}

/// A running `planlab serve`, killed on drop.
struct Server {
    child: Child,
    addr: SocketAddr,
    _stdout: BufReader<ChildStdout>,
}

impl Server {
    fn start(root: &Path, env: &[(&str, &str)]) -> Server {
        let mut child = bin()
            .args(["serve", "--dir"])
            .arg(root)
            .args(["--port", "0"])
            .envs(env.iter().copied())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("spawn planlab serve");
        let mut stdout = BufReader::new(child.stdout.take().unwrap());
        let (tx, rx) = mpsc::channel();
        let reader = thread::spawn(move || {
            let mut line = String::new();
            let _ = stdout.read_line(&mut line);
            let _ = tx.send(line);
            stdout
        });
        let line = match rx.recv_timeout(Duration::from_secs(20)) {
            Ok(l) => l,
            Err(_) => {
                let _ = child.kill();
                panic!("planlab serve printed no address within 20 s");
            }
        };
        let stdout = reader.join().unwrap();
        // "serving DIR on http://127.0.0.1:PORT/"
        let addr = line
            .trim()
            .rsplit("http://")
            .next()
            .and_then(|a| a.trim_end_matches('/').parse().ok())
            .unwrap_or_else(|| panic!("no address in {line:?}"));
        Server {
            child,
            addr,
            _stdout: stdout,
        }
    }

    fn connect(&self) -> TcpStream {
        let s = TcpStream::connect_timeout(&self.addr, Duration::from_secs(5)).unwrap();
        s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
        s.set_write_timeout(Some(Duration::from_secs(5))).unwrap();
        s
    }

    /// Sends `raw`, reads until the server closes.
    fn send(&self, raw: &[u8]) -> Reply {
        let mut s = self.connect();
        s.write_all(raw).unwrap();
        let mut out = Vec::new();
        s.read_to_end(&mut out).unwrap();
        Reply::parse(&out)
    }

    fn get(&self, target: &str, extra: &str) -> Reply {
        self.request("GET", target, extra)
    }

    fn request(&self, method: &str, target: &str, extra: &str) -> Reply {
        let raw = format!(
            "{method} {target} HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n{extra}\r\n"
        );
        self.send(raw.as_bytes())
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

#[derive(Debug)]
struct Reply {
    status: u16,
    headers: Vec<(String, String)>,
    body: Vec<u8>,
}

impl Reply {
    fn parse(raw: &[u8]) -> Reply {
        let end = raw
            .windows(4)
            .position(|w| w == b"\r\n\r\n")
            .unwrap_or_else(|| panic!("no header end in {:?}", String::from_utf8_lossy(raw)));
        let head = String::from_utf8_lossy(&raw[..end]);
        let mut lines = head.split("\r\n");
        let status = lines
            .next()
            .and_then(|l| l.split(' ').nth(1))
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| panic!("no status in {head}"));
        let headers = lines
            .filter_map(|l| l.split_once(':'))
            .map(|(k, v)| (k.trim().to_ascii_lowercase(), v.trim().to_string()))
            .collect();
        Reply {
            status,
            headers,
            body: raw[end + 4..].to_vec(),
        }
    }

    fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }
}

/// True when `r` is the server closing the connection (EOF or reset), false
/// for a read that timed out with the connection still open.
fn closed(r: &std::io::Result<usize>) -> bool {
    match r {
        Ok(0) => true,
        Ok(_) => false,
        Err(e) => matches!(
            e.kind(),
            ErrorKind::ConnectionReset | ErrorKind::ConnectionAborted
        ),
    }
}

#[test]
fn files_are_served_with_their_types() {
    let srv = Server::start(&site("mime"), &[]);
    for (path, ctype) in [
        ("/pkg/a.wasm", "application/wasm"),
        ("/app.js", "text/javascript; charset=utf-8"),
        ("/style.css", "text/css; charset=utf-8"),
        ("/index.html", "text/html; charset=utf-8"),
        ("/", "text/html; charset=utf-8"),
        ("/data.json", "application/json"),
        ("/icon.svg", "image/svg+xml"),
        ("/img.png", "image/png"),
    ] {
        let r = srv.get(path, "");
        assert_eq!(r.status, 200, "{path}");
        assert_eq!(r.header("content-type"), Some(ctype), "{path}");
        assert_eq!(r.header("x-content-type-options"), Some("nosniff"));
    }
    assert_eq!(srv.get("/pkg/a.wasm", "").body, b"\0asm\x01\0\0\0");
    let head = srv.request("HEAD", "/pkg/a.wasm", "");
    assert_eq!(head.status, 200);
    assert_eq!(head.header("content-length"), Some("8"));
    assert!(head.body.is_empty());
    let post = srv.request("POST", "/index.html", "Content-Length: 0\r\n");
    assert_eq!(post.status, 405);
    assert_eq!(post.header("allow"), Some("GET, HEAD"));
}

#[test]
fn precompressed_twins_go_to_clients_that_accept_them() {
    let root = site("precompressed");
    // The server sends a twin as it is: marker bodies show which file went.
    std::fs::write(root.join("big.js"), b"export const plain = 1;").unwrap();
    std::fs::write(root.join("big.js.br"), b"BROTLI-TWIN").unwrap();
    std::fs::write(root.join("big.js.gz"), b"GZIP-TWIN").unwrap();
    std::fs::write(root.join("pkg/a.wasm.gz"), b"GZIP-WASM").unwrap();
    let srv = Server::start(&root, &[]);
    for (accept, body, encoding) in [
        (
            "Accept-Encoding: gzip, deflate, br\r\n",
            &b"BROTLI-TWIN"[..],
            Some("br"),
        ),
        ("Accept-Encoding: gzip\r\n", b"GZIP-TWIN", Some("gzip")),
        (
            "Accept-Encoding: br;q=0, gzip;q=1\r\n",
            b"GZIP-TWIN",
            Some("gzip"),
        ),
        ("", b"export const plain = 1;", None),
        (
            "Accept-Encoding: identity\r\n",
            b"export const plain = 1;",
            None,
        ),
    ] {
        let r = srv.get("/big.js", accept);
        assert_eq!(r.status, 200, "{accept:?}");
        assert_eq!(r.body, body, "{accept:?}");
        assert_eq!(r.header("content-encoding"), encoding, "{accept:?}");
        // The type is the file's own, never the twin's.
        assert_eq!(
            r.header("content-type"),
            Some("text/javascript; charset=utf-8")
        );
        assert_eq!(r.header("vary"), Some("accept-encoding"), "{accept:?}");
    }
    // Only a gzip twin: a client accepting br too gets gzip.
    let wasm = srv.get("/pkg/a.wasm", "Accept-Encoding: br, gzip\r\n");
    assert_eq!(wasm.body, b"GZIP-WASM");
    assert_eq!(wasm.header("content-encoding"), Some("gzip"));
    assert_eq!(wasm.header("content-type"), Some("application/wasm"));
    // No twin at all: the file itself, unencoded.
    let css = srv.get("/style.css", "Accept-Encoding: br, gzip\r\n");
    assert_eq!(css.body, b"body{}");
    assert_eq!(css.header("content-encoding"), None);
}

#[test]
fn range_returns_exactly_the_bytes() {
    let srv = Server::start(&site("range"), &[]);
    let nums = nums();
    for (range, from, to) in [
        ("bytes=10-19", 10, 19),
        ("bytes=0-0", 0, 0),
        ("bytes=-5", 995, 999),
        ("bytes=990-", 990, 999),
        ("bytes=990-5000", 990, 999),
    ] {
        let r = srv.get("/nums.bin", &format!("Range: {range}\r\n"));
        assert_eq!(r.status, 206, "{range}");
        assert_eq!(
            r.header("content-range"),
            Some(format!("bytes {from}-{to}/1000").as_str()),
            "{range}"
        );
        assert_eq!(r.body, &nums[from..=to], "{range}");
    }
    let whole = srv.get("/nums.bin", "");
    assert_eq!(whole.status, 200);
    assert_eq!(whole.header("accept-ranges"), Some("bytes"));
    assert_eq!(whole.body, nums);
    // Several ranges: answered whole rather than refused.
    let multi = srv.get("/nums.bin", "Range: bytes=0-1,5-6\r\n");
    assert_eq!(multi.status, 200);
    assert_eq!(multi.body, nums);
}

#[test]
fn unsatisfiable_range_is_416() {
    let srv = Server::start(&site("range416"), &[]);
    for range in ["bytes=1000-1005", "bytes=5000-"] {
        let r = srv.get("/nums.bin", &format!("Range: {range}\r\n"));
        assert_eq!(r.status, 416, "{range}");
        assert_eq!(r.header("content-range"), Some("bytes */1000"), "{range}");
    }
}

#[test]
fn folder_without_slash_is_redirected() {
    let srv = Server::start(&site("redirect"), &[]);
    for (target, location) in [
        ("/sub", "/sub/"),
        ("/sub?x=1", "/sub/?x=1"),
        ("/nosub", "/nosub/"),
        // Never `//sub/`, which a browser would read as the host `sub`.
        ("//sub", "/sub/"),
    ] {
        let r = srv.get(target, "");
        assert_eq!(r.status, 307, "{target}");
        assert_eq!(r.header("location"), Some(location), "{target}");
    }
    let sub = srv.get("/sub/", "");
    assert_eq!(sub.status, 200);
    assert_eq!(sub.body, b"<html>sub</html>");
    assert_eq!(sub.header("content-type"), Some("text/html; charset=utf-8"));
    // No index.html, no listing.
    assert_eq!(srv.get("/nosub/", "").status, 404);
}

#[test]
fn overlong_request_line_is_414() {
    let srv = Server::start(&site("uri"), &[]);
    let long = |n: usize| format!("/{}", "a".repeat(n - 1));
    assert_eq!(srv.get(&long(100 * 1024), "").status, 414);
    // Our own limit, below hyper's 64 KiB one.
    assert_eq!(srv.get(&long(9000), "").status, 414);
    assert_eq!(srv.get(&long(8000), "").status, 404);
}

#[test]
fn slowloris_client_is_disconnected_within_the_header_timeout() {
    let srv = Server::start(
        &site("slowloris"),
        &[("PLANLAB_SERVE_HEADER_TIMEOUT_MS", "1000")],
    );
    let mut s = srv.connect();
    s.set_read_timeout(Some(Duration::from_secs(8))).unwrap();
    let start = Instant::now();
    s.write_all(b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n")
        .unwrap();
    let stop = Arc::new(AtomicBool::new(false));
    let (mut w, stop2) = (s.try_clone().unwrap(), Arc::clone(&stop));
    // One more header line every 100 ms, never the blank line that ends them.
    let dribble = thread::spawn(move || {
        while !stop2.load(Ordering::Relaxed) && start.elapsed() < Duration::from_secs(8) {
            if w.write_all(b"X-Slow: 1\r\n").is_err() {
                break;
            }
            thread::sleep(Duration::from_millis(100));
        }
    });
    let mut buf = [0u8; 512];
    let r = s.read(&mut buf);
    let took = start.elapsed();
    stop.store(true, Ordering::Relaxed);
    dribble.join().unwrap();
    assert!(closed(&r), "still open after {took:?}: {r:?}");
    assert!(
        took >= Duration::from_millis(800) && took < Duration::from_secs(3),
        "closed after {took:?}"
    );
}

#[test]
fn idle_connections_are_closed_within_the_header_timeout() {
    let srv = Server::start(
        &site("idle"),
        &[("PLANLAB_SERVE_HEADER_TIMEOUT_MS", "1000")],
    );
    // Connected, never a byte.
    let mut s = srv.connect();
    let start = Instant::now();
    let r = s.read(&mut [0u8; 64]);
    assert!(closed(&r), "{r:?}");
    assert!(
        start.elapsed() < Duration::from_secs(3),
        "{:?}",
        start.elapsed()
    );
    // Kept alive after one answered request, then silent.
    let mut s = srv.connect();
    s.write_all(b"GET /data.json HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        .unwrap();
    let mut got = Vec::new();
    let mut buf = [0u8; 1024];
    while !got.ends_with(b"\r\n\r\n{}") {
        let n = s.read(&mut buf).unwrap();
        assert!(n > 0, "closed before the reply: {got:?}");
        got.extend_from_slice(&buf[..n]);
    }
    let start = Instant::now();
    let r = s.read(&mut buf);
    assert!(closed(&r), "{r:?}");
    assert!(
        start.elapsed() < Duration::from_secs(3),
        "{:?}",
        start.elapsed()
    );
}

#[test]
fn client_that_never_reads_blocks_no_one_and_is_dropped() {
    let root = site("noread");
    std::fs::write(root.join("big.bin"), vec![7u8; BIG]).unwrap();
    let srv = Server::start(&root, &[("PLANLAB_SERVE_WRITE_TIMEOUT_MS", "1000")]);
    let mut a = srv.connect();
    a.write_all(b"GET /big.bin HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        .unwrap();
    // Let the server fill the socket buffers and stall on `a`.
    thread::sleep(Duration::from_millis(300));
    let start = Instant::now();
    let other = srv.get("/index.html", "");
    assert_eq!(other.status, 200);
    assert!(
        start.elapsed() < Duration::from_secs(2),
        "{:?}",
        start.elapsed()
    );
    // Past the write timeout the server has let go of `a`: reading now gets
    // what the kernels had buffered, then the end, never the whole file.
    thread::sleep(Duration::from_millis(2500));
    let mut got = 0usize;
    let mut buf = vec![0u8; 1 << 20];
    let end = loop {
        let r = a.read(&mut buf);
        match r {
            Ok(n) if n > 0 => got += n,
            _ => break r,
        }
    };
    assert!(
        closed(&end),
        "connection still open after {got} bytes: {end:?}"
    );
    assert!(got < BIG, "the whole file arrived ({got} bytes)");
    drop(srv);
    // 32 MiB is too much to leave in the temp folder after every run.
    let _ = std::fs::remove_file(root.join("big.bin"));
}

#[test]
fn connections_over_the_cap_wait_for_a_slot() {
    // Both slots answer a download their clients do not read: busy, so
    // neither is closed for a newcomer, which waits for one to end.
    let root = site("cap");
    std::fs::write(root.join("big.bin"), vec![7u8; BIG]).unwrap();
    let srv = Server::start(&root, &[("PLANLAB_SERVE_MAX_CONNECTIONS", "2")]);
    let mut busy = [srv.connect(), srv.connect()];
    for b in &mut busy {
        b.write_all(b"GET /big.bin HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
            .unwrap();
        // The answer has begun: the server holds the request, not a head.
        let mut first = [0u8; 12];
        b.read_exact(&mut first).unwrap();
        assert_eq!(&first, b"HTTP/1.1 200");
    }
    let mut c = srv.connect();
    c.write_all(b"GET /data.json HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n")
        .unwrap();
    c.set_read_timeout(Some(Duration::from_millis(700)))
        .unwrap();
    let r = c.read(&mut [0u8; 64]);
    assert!(
        matches!(&r, Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut)),
        "answered while both slots were taken: {r:?}"
    );
    let [stopped, _still] = busy;
    drop(stopped);
    c.set_read_timeout(Some(Duration::from_secs(3))).unwrap();
    let mut out = Vec::new();
    c.read_to_end(&mut out).unwrap();
    assert_eq!(Reply::parse(&out).status, 200);
    drop(srv);
    let _ = std::fs::remove_file(root.join("big.bin"));
}

/// Reads one reply on a kept-alive connection: the head, then as many body
/// bytes as its Content-Length says.
fn read_reply(s: &mut TcpStream) -> std::io::Result<Reply> {
    let mut got = Vec::new();
    let mut buf = [0u8; 1024];
    loop {
        if let Some(end) = got.windows(4).position(|w| w == b"\r\n\r\n") {
            let head = Reply::parse(&got[..end + 4]);
            let len: usize = head.header("content-length").unwrap().parse().unwrap();
            if got.len() >= end + 4 + len {
                return Ok(Reply::parse(&got));
            }
        }
        let n = s.read(&mut buf)?;
        if n == 0 {
            return Err(ErrorKind::UnexpectedEof.into());
        }
        got.extend_from_slice(&buf[..n]);
    }
}

#[test]
fn idle_connections_holding_every_slot_are_closed_for_a_request() {
    // Before: a request behind idle connections holding every slot waited
    // for one's header timeout, here a minute, far past the 5 s reads.
    let srv = Server::start(
        &site("shed"),
        &[
            ("PLANLAB_SERVE_MAX_CONNECTIONS", "4"),
            ("PLANLAB_SERVE_HEADER_TIMEOUT_MS", "60000"),
        ],
    );
    let get = b"GET /data.json HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n";
    // Idle longest first: silent since connected, half a request head, kept
    // alive after an answered request, silent.
    let mut silent = srv.connect();
    let mut half = srv.connect();
    half.write_all(b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n")
        .unwrap();
    let mut kept = srv.connect();
    kept.write_all(get).unwrap();
    assert_eq!(read_reply(&mut kept).unwrap().status, 200);
    let mut newest = srv.connect();
    // Each request finds every slot taken (the one before it stays open),
    // and the connection idle longest is closed for it.
    let mut served = Vec::new();
    for (name, idle) in [
        ("silent", &mut silent),
        ("half head", &mut half),
        ("kept alive", &mut kept),
    ] {
        let mut c = srv.connect();
        c.write_all(get).unwrap();
        let reply = read_reply(&mut c).unwrap_or_else(|e| {
            panic!("no answer while idle connections held every slot ({name} is oldest): {e}")
        });
        assert_eq!(reply.status, 200);
        assert_eq!(reply.body, b"{}");
        let r = idle.read(&mut [0u8; 64]);
        assert!(closed(&r), "{name}: not closed for the request: {r:?}");
        served.push(c);
    }
    // Only as many as were needed: the newest idle one is still open.
    newest
        .set_read_timeout(Some(Duration::from_millis(300)))
        .unwrap();
    let r = newest.read(&mut [0u8; 64]);
    assert!(
        matches!(&r, Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut)),
        "the newest idle connection was closed too: {r:?}"
    );
}

#[test]
fn nothing_outside_the_site_is_served() {
    let srv = Server::start(&site("traversal"), &[]);
    let mut targets = vec![
        "/../secret.txt",
        "/%2e%2e/secret.txt",
        "/%2E%2E/secret.txt",
        "/..%2fsecret.txt",
        "/%2e%2e%2fsecret.txt",
        "/pkg/../../secret.txt",
        "/pkg/%2e%2e/%2e%2e/secret.txt",
        "/..\\secret.txt",
        "/%5c..%5csecret.txt",
        "/secret.txt%00.html",
        "http://127.0.0.1/../secret.txt",
        "../secret.txt",
    ];
    let abs = std::env::temp_dir().join(format!(
        "planlab-serve-cli-{}-traversal/secret.txt",
        std::process::id()
    ));
    let abs = abs.to_string_lossy().into_owned();
    let double = format!("/{abs}");
    targets.push(&abs);
    targets.push(&double);
    if cfg!(unix) {
        targets.extend(["/leak.txt", "/up/secret.txt", "/up/", "/up"]);
    }
    for t in targets {
        let r = srv.send(
            format!("GET {t} HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n").as_bytes(),
        );
        assert!(matches!(r.status, 400 | 404), "{t}: {}", r.status);
        assert!(
            !String::from_utf8_lossy(&r.body).contains(SECRET),
            "{t} leaked the secret"
        );
    }
    // The same file is there to be served when it is inside.
    assert_eq!(srv.get("/index.html", "").status, 200);
}

/// Runs `planlab serve ARGS` expecting it to fail at start, within 20 s.
fn start_error(args: &[&str], env: &[(&str, &str)]) -> String {
    let mut child = bin()
        .arg("serve")
        .args(args)
        .envs(env.iter().copied())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(20);
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            panic!("planlab serve {args:?} is serving instead of failing");
        }
        thread::sleep(Duration::from_millis(20));
    };
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    assert!(!status.success(), "{args:?}");
    assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    assert!(err.starts_with("planlab: error: "), "{err}");
    err
}

#[test]
fn start_errors_are_one_line() {
    let root = site("errors");
    let dir = root.to_str().unwrap();
    let missing = root.join("missing");
    let e = start_error(&["--dir", missing.to_str().unwrap(), "--port", "0"], &[]);
    assert!(e.contains("cannot serve"), "{e}");
    let e = start_error(
        &["--dir", root.join("nosub").to_str().unwrap(), "--port", "0"],
        &[],
    );
    assert!(e.contains("no index.html"), "{e}");
    let taken = TcpListener::bind(("127.0.0.1", 0)).unwrap();
    let port = taken.local_addr().unwrap().port().to_string();
    let e = start_error(&["--dir", dir, "--port", &port], &[]);
    assert!(e.contains("cannot bind"), "{e}");
    for host in ["0.0.0.0", "::"] {
        let e = start_error(&["--dir", dir, "--port", "0", "--host", host], &[]);
        assert!(e.contains("loopback only"), "{e}");
    }
    let e = start_error(
        &["--dir", dir, "--port", "0"],
        &[("PLANLAB_SERVE_WRITE_TIMEOUT_MS", "soon")],
    );
    assert!(e.contains("PLANLAB_SERVE_WRITE_TIMEOUT_MS"), "{e}");
    for (var, value) in [
        ("PLANLAB_SERVE_MAX_CONNECTIONS", "0"),
        ("PLANLAB_SERVE_MAX_CONNECTIONS", "18446744073709551615"),
        ("PLANLAB_SERVE_HEADER_TIMEOUT_MS", "18446744073709551615"),
    ] {
        let e = start_error(&["--dir", dir, "--port", "0"], &[(var, value)]);
        assert!(e.contains(var), "{e}");
    }
}

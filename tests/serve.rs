//! `layertrace serve` over plain HTTP (no browser; tests/browser/test_page.py drives the
//! page in Chromium): the page and its assets, a conversion, the errors, the busy answer.
#![cfg(feature = "serve")]

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Stdio};
use std::time::Duration;

mod common;

/// A running `layertrace serve --port 0 ARGS`, killed when dropped.
struct Server {
    child: Child,
    addr: String,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn serve(args: &[&str]) -> Server {
    let mut child = common::bin()
        .args(["serve", "--port", "0", "--quiet"])
        .args(args)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stderr.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let addr = line
        .split("serving http://")
        .nth(1)
        .and_then(|rest| rest.split('/').next())
        .unwrap_or_else(|| panic!("no address in {line:?}"))
        .to_string();
    assert!(addr.starts_with("127.0.0.1:"), "{addr}");
    Server { child, addr }
}

/// Sends `head` (request line and headers, without the blank line) and `body`; returns the
/// status and the body of the answer.
fn request(addr: &str, head: &str, body: &[u8]) -> (u16, String) {
    let mut s = TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
    write!(
        s,
        "{head}\r\nHost: {addr}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
        body.len()
    )
    .unwrap();
    s.write_all(body).unwrap();
    let mut answer = Vec::new();
    s.read_to_end(&mut answer).unwrap();
    let answer = String::from_utf8_lossy(&answer).into_owned();
    let status = answer[9..12].parse().unwrap();
    let (head, body) = answer.split_once("\r\n\r\n").unwrap_or((&answer, ""));
    let chunked = head
        .lines()
        .any(|l| l.eq_ignore_ascii_case("transfer-encoding: chunked"));
    let body = if chunked {
        unchunk(body)
    } else {
        body.to_string()
    };
    (status, body)
}

/// The body of a chunked answer (tiny_http chunks answers over 32 KiB): each chunk is its
/// size in hexadecimal, CRLF, the bytes, CRLF; a chunk of size 0 ends it.
fn unchunk(mut rest: &str) -> String {
    let mut body = String::new();
    loop {
        let (size, after) = rest.split_once("\r\n").expect("a chunk size line");
        let size = usize::from_str_radix(size.trim(), 16).expect("a hexadecimal chunk size");
        if size == 0 {
            return body;
        }
        body.push_str(&after[..size]);
        rest = &after[size + 2..];
    }
}

fn sample() -> Vec<u8> {
    std::fs::read("samples/glyph_g_liberationserif_cap120.png").unwrap()
}

#[test]
fn page_assets_and_a_conversion() {
    let server = serve(&[]);
    let (status, page) = request(&server.addr, "GET / HTTP/1.1", b"");
    assert_eq!(status, 200);
    assert!(page.contains("<script src=\"/app.js\""), "{page}");
    assert!(
        !page.contains("http://") && !page.contains("https://"),
        "no external resource"
    );
    for asset in ["/app.js", "/style.css"] {
        let (status, body) = request(&server.addr, &format!("GET {asset} HTTP/1.1"), b"");
        assert_eq!(status, 200, "{asset}");
        assert!(
            !body.contains("http://") && !body.contains("https://"),
            "{asset}"
        );
    }
    let (status, body) = request(
        &server.addr,
        "POST /api/vectorize?model=conic&threshold=&name=g.png HTTP/1.1",
        &sample(),
    );
    assert_eq!(status, 200, "{body}");
    let v: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert_eq!(v["differing"], 0);
    // Chromium draws pages under 512 px both ways as one tile: no tile count.
    assert!(v["chromium_tiles"].is_null());
    assert_eq!(v["pieces"], 27);
    assert_eq!(
        (v["width"].as_u64(), v["height"].as_u64()),
        (Some(110), Some(163))
    );
    assert!(v["svg"].as_str().unwrap().starts_with("<svg"));
    let json: serde_json::Value = serde_json::from_str(v["json"].as_str().unwrap()).unwrap();
    assert_eq!(json["format"], "layertrace-decomposition/2");
    assert!(v["diff_png"].as_str().unwrap().starts_with("iVBORw0KGgo")); // PNG signature
    assert!(v["decomposition_png"]
        .as_str()
        .unwrap()
        .starts_with("iVBORw0KGgo"));
    // The model reaches the library; its parser's message comes back.
    let (status, body) = request(
        &server.addr,
        "POST /api/vectorize?model=line HTTP/1.1",
        &sample(),
    );
    assert_eq!(status, 200);
    assert!(body.contains(r#"\"model\": \"line\""#), "{body}");
}

#[test]
fn colours_and_smooth_reach_the_library() {
    let server = serve(&[]);
    let logo = std::fs::read("samples/colour/colour_logo_aa.png").unwrap();
    // The page sends every field; a colour run ignores threshold, invert and turdsize.
    let (status, body) = request(
        &server.addr,
        "POST /api/vectorize?colors=4&threshold=90&invert=1&turdsize=3&alpha=0&smooth= HTTP/1.1",
        &logo,
    );
    assert_eq!(status, 200, "{body}");
    let v: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert_eq!(v["differing"], 0);
    assert_eq!(v["seams"], 0);
    let colours = v["colours"].as_array().unwrap();
    assert!((2..=4).contains(&colours.len()), "{colours:?}");
    assert!(colours.iter().all(|c| c["differing"] == 0));
    let svg = v["svg"].as_str().unwrap();
    assert_eq!(svg.matches("<path").count(), colours.len());
    for c in colours {
        assert!(svg.contains(&format!("fill=\"{}\"", c["colour"].as_str().unwrap())));
    }
    assert!(v["diff_png"].as_str().unwrap().starts_with("iVBORw0KGgo"));
    assert_eq!(v["beyond"], serde_json::Value::Null);
    // The partition layout.
    let (status, body) = request(
        &server.addr,
        "POST /api/vectorize?colors=4&layout=partition HTTP/1.1",
        &logo,
    );
    assert_eq!(status, 200, "{body}");
    let v: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert_eq!(v["differing"], 0);
    assert!(v["json"]
        .as_str()
        .unwrap()
        .contains(r#""layout": "partition""#));
    // Smooth, one colour: pixels change only within ν.
    let (status, body) = request(
        &server.addr,
        "POST /api/vectorize?smooth=1&colors= HTTP/1.1",
        &sample(),
    );
    assert_eq!(status, 200, "{body}");
    let v: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert_eq!(v["beyond"], 0);
    assert_eq!(v["smooth"], 1.0);
    assert!(v["differing"].as_u64().unwrap() > 0);
    assert_eq!(v["colours"], serde_json::Value::Null);
}

#[test]
fn errors_are_one_line_json() {
    let server = serve(&["--max-upload", "1K", "--max-pixels", "1000"]);
    let cases: [(&str, &[u8], u16, &str); 9] = [
        (
            "POST /api/vectorize?name=a.png HTTP/1.1",
            b"not an image",
            422,
            "cannot decode a.png",
        ),
        (
            "POST /api/vectorize?name=g.png HTTP/1.1",
            &sample(),
            422,
            "more than the limit of 1000",
        ),
        (
            "POST /api/vectorize HTTP/1.1",
            &[0; 2000],
            413,
            "--max-upload",
        ),
        (
            "POST /api/vectorize?model=quadric3 HTTP/1.1",
            b"",
            400,
            "3-D point sets",
        ),
        (
            "POST /api/vectorize?colour=red HTTP/1.1",
            b"",
            400,
            "unknown parameter 'colour'",
        ),
        (
            "POST /api/vectorize?colors=1 HTTP/1.1",
            b"",
            400,
            "not a number from 2 to 256",
        ),
        (
            "POST /api/vectorize?smooth=0 HTTP/1.1",
            b"",
            400,
            "not a distance in (0, 16]",
        ),
        (
            "POST /api/vectorize?colors=4&alpha=1 HTTP/1.1",
            b"",
            400,
            "do not go together",
        ),
        (
            "GET /api/vectorize HTTP/1.1",
            b"",
            405,
            "method not allowed",
        ),
    ];
    for (head, body, status, message) in cases {
        let (got, answer) = request(&server.addr, head, body);
        assert_eq!(got, status, "{head}: {answer}");
        let v: serde_json::Value = serde_json::from_str(&answer).unwrap();
        let error = v["error"].as_str().unwrap();
        assert!(error.contains(message), "{head}: {error}");
    }
    let (status, _) = request(&server.addr, "GET /etc/passwd HTTP/1.1", b"");
    assert_eq!(status, 404);
}

#[test]
fn a_foreign_host_name_is_refused() {
    let server = serve(&[]);
    let mut s = TcpStream::connect(&server.addr).unwrap();
    write!(
        s,
        "GET / HTTP/1.1\r\nHost: attacker.example:8080\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut answer = String::new();
    s.read_to_string(&mut answer).unwrap();
    assert!(answer.starts_with("HTTP/1.1 421"), "{answer}");
}

#[test]
fn requests_beyond_the_workers_are_busy() {
    let server = serve(&["--workers", "1"]);
    // The first conversion holds the only slot while it waits for its body (over 1 KiB:
    // tiny_http reads smaller bodies whole before it hands the request over).
    let mut first = TcpStream::connect(&server.addr).unwrap();
    let png = std::fs::read("samples/lineart_cat_symbola_h300.png").unwrap();
    assert!(png.len() > 2048);
    write!(
        first,
        "POST /api/vectorize HTTP/1.1\r\nHost: {}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
        server.addr,
        png.len()
    )
    .unwrap();
    first.write_all(&png[..100]).unwrap();
    first.flush().unwrap();
    std::thread::sleep(Duration::from_millis(300));
    let (status, body) = request(&server.addr, "POST /api/vectorize HTTP/1.1", &png);
    assert_eq!(status, 503, "{body}");
    assert!(body.contains("busy"), "{body}");
    // The page itself is still served, and once the first is done the slot is free again.
    assert_eq!(request(&server.addr, "GET / HTTP/1.1", b"").0, 200);
    first.write_all(&png[100..]).unwrap();
    let mut answer = String::new();
    first
        .set_read_timeout(Some(Duration::from_secs(60)))
        .unwrap();
    first.read_to_string(&mut answer).unwrap();
    assert!(answer.starts_with("HTTP/1.1 200"), "{answer}");
    assert_eq!(
        request(&server.addr, "POST /api/vectorize HTTP/1.1", &png).0,
        200
    );
}

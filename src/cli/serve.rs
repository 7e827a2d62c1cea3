//! `layertrace serve`: a web page to drop an image on and look at its vectorization.
//!
//! One page (`web/`, embedded in the binary: no CDN, nothing fetched from elsewhere) and one
//! endpoint, `POST /api/vectorize?model=…&threshold=…`, whose body is the image file and
//! whose answer is JSON: the SVG, the decomposition's JSON, the difference and
//! decomposition pictures (PNG, base64) and the figures. Served by tiny_http, synchronous:
//! the accepting thread answers the page itself and hands each conversion to a thread of
//! its own, at most `--workers` at a time (more get 503 at once). Loopback by default;
//! uploads and pixels are bounded, and on loopback a request whose `Host` is not a loopback
//! name is refused (no DNS rebinding from a web site).

use clap::Parser;
use layertrace::{
    colour_diff_image, diff_image, png_bytes, vectorize, Cover, Error, Layout, Options,
    ParseLayoutError, Vectorized, MAX_BAND,
};
use std::io::Read;
use std::net::{IpAddr, SocketAddr};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::Instant;
use tiny_http::{Header, Method, Request, Response, Server};

use super::args::{parse_model, parse_threshold};

const INDEX_HTML: &str = include_str!("../../web/index.html");
const APP_JS: &str = include_str!("../../web/app.js");
const STYLE_CSS: &str = include_str!("../../web/style.css");

const AFTER_HELP: &str = "\
Example:
  layertrace serve --port 8080
  then open http://127.0.0.1:8080/ and drop an image on the page.

The page shows the input, the SVG, the differences (the --diff picture: missing pixels red,
extra blue) and the decomposition picture side by side, with zoom, the piece count and the
differing pixels, and offers the SVG and the JSON for download. Nothing leaves the machine:
the page's script and style are served by layertrace itself.

Limits: uploads larger than --max-upload get 413, images with more pixels than
--max-pixels an error on the page; at most --workers conversions run at once and a request
beyond them gets 503 (busy) at once. Ctrl-C stops the server.";

/// Serve the web page: drop an image, see its vectorization, download the SVG and JSON.
#[derive(Parser, Debug)]
#[command(name = "layertrace serve", bin_name = "layertrace serve", version,
          after_help = AFTER_HELP)]
pub struct ServeArgs {
    /// The TCP port (0: any free port; the address is printed on standard error).
    #[arg(long, short, default_value_t = 8080)]
    pub port: u16,

    /// The address to listen on; the default is loopback only. Any other address lets
    /// other machines convert images on this one.
    #[arg(long, default_value = "127.0.0.1")]
    pub host: IpAddr,

    /// Conversions run at once, 1 to 64; a request beyond them gets 503 (busy).
    #[arg(long, value_name = "N", default_value_t = 2,
          value_parser = clap::value_parser!(u16).range(1..=64))]
    pub workers: u16,

    /// Largest upload accepted, e.g. 32M, 512K (bytes without a suffix).
    #[arg(long, value_name = "SIZE", default_value = "32M",
          value_parser = layertrace::parse_memory_size)]
    pub max_upload: u64,

    /// Refuse images with more pixels than this (checked before decoding).
    #[arg(long, value_name = "N", default_value_t = 16_000_000,
          value_parser = clap::value_parser!(u64).range(1..))]
    pub max_pixels: u64,

    /// No line per conversion on standard error.
    #[arg(long, short)]
    pub quiet: bool,
}

/// What every request handler shares.
struct State {
    args: ServeArgs,
    /// The address actually bound.
    addr: SocketAddr,
    /// Conversions running now.
    busy: AtomicUsize,
}

/// Releases a conversion slot when dropped (also on a panic in the conversion thread).
struct Slot(Arc<State>);

impl Drop for Slot {
    fn drop(&mut self) {
        self.0.busy.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Listens and serves until the process is stopped; only a failure to listen returns.
pub fn run(args: ServeArgs) -> Result<(), Error> {
    let server = Server::http((args.host, args.port)).map_err(|e| {
        Error::Arguments(format!(
            "cannot listen on {}: {e}",
            SocketAddr::new(args.host, args.port)
        ))
    })?;
    let addr = server
        .server_addr()
        .to_ip()
        .unwrap_or_else(|| SocketAddr::new(args.host, args.port));
    if !args.host.is_loopback() {
        eprintln!(
            "layertrace: warning: listening on {addr}, not loopback: other machines can use it"
        );
    }
    eprintln!("layertrace: serving http://{addr}/ (Ctrl-C stops)");
    let state = Arc::new(State {
        args,
        addr,
        busy: AtomicUsize::new(0),
    });
    for request in server.incoming_requests() {
        handle(request, &state);
    }
    Ok(())
}

fn header(name: &str, value: &str) -> Header {
    Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("a valid ASCII header")
}

/// Answers `request`, ignoring a client that went away.
fn send<R: Read>(request: Request, response: Response<R>) {
    let response = response
        .with_header(header("X-Content-Type-Options", "nosniff"))
        .with_header(header("Cache-Control", "no-store"));
    let _ = request.respond(response);
}

fn text(status: u16, content_type: &str, body: &str) -> Response<std::io::Cursor<Vec<u8>>> {
    Response::from_string(body)
        .with_status_code(status)
        .with_header(header("Content-Type", content_type))
}

/// A JSON error answer `{"error": message}`.
fn error(status: u16, message: &str) -> Response<std::io::Cursor<Vec<u8>>> {
    let body = serde_json::json!({ "error": message }).to_string();
    text(status, "application/json", &body)
}

fn handle(mut request: Request, state: &Arc<State>) {
    if !host_allowed(&request, state) {
        let response = error(421, "this server answers only to a loopback Host name");
        return send(request, response);
    }
    let url = request.url().to_string();
    let (path, query) = url.split_once('?').unwrap_or((&url, ""));
    match (request.method(), path) {
        (Method::Get | Method::Head, "/" | "/index.html") => {
            let csp = "default-src 'self'; img-src 'self' blob: data:; \
                       connect-src 'self' blob:; object-src 'none'; \
                       base-uri 'none'; form-action 'none'; frame-ancestors 'none'";
            let response = text(200, "text/html; charset=utf-8", INDEX_HTML)
                .with_header(header("Content-Security-Policy", csp));
            send(request, response)
        }
        (Method::Get | Method::Head, "/app.js") => {
            send(request, text(200, "text/javascript; charset=utf-8", APP_JS))
        }
        (Method::Get | Method::Head, "/style.css") => {
            send(request, text(200, "text/css; charset=utf-8", STYLE_CSS))
        }
        (Method::Post, "/api/vectorize") => {
            if request
                .body_length()
                .is_some_and(|n| n as u64 > state.args.max_upload)
            {
                let message = too_large(state.args.max_upload);
                return send(request, error(413, &message));
            }
            let running = state.busy.fetch_add(1, Ordering::SeqCst);
            let slot = Slot(Arc::clone(state));
            if running >= usize::from(state.args.workers) {
                drop(slot);
                let message = format!(
                    "busy: {} conversions are already running; try again in a moment",
                    state.args.workers
                );
                return send(
                    request,
                    error(503, &message).with_header(header("Retry-After", "1")),
                );
            }
            let query = query.to_string();
            let spawned = std::thread::Builder::new()
                .name("convert".into())
                .spawn(move || {
                    let response = convert(&mut request, &query, &slot.0);
                    // Free before answering: a client that sends its next request as
                    // soon as it has this answer finds the slot free.
                    drop(slot);
                    send(request, response);
                });
            if let Err(e) = spawned {
                eprintln!("layertrace: cannot start a conversion thread: {e}");
            }
        }
        (_, "/" | "/index.html" | "/app.js" | "/style.css" | "/api/vectorize") => {
            send(request, error(405, "method not allowed"))
        }
        _ => send(request, error(404, "not found")),
    }
}

fn too_large(max: u64) -> String {
    format!("the upload is larger than the server's limit of {max} bytes (--max-upload)")
}

/// On loopback, the `Host` header must name loopback (`localhost`, `127.0.0.1`, `[::1]`),
/// so that a web site whose name resolves to 127.0.0.1 cannot use the server.
fn host_allowed(request: &Request, state: &State) -> bool {
    if !state.addr.ip().is_loopback() {
        return true;
    }
    let Some(host) = request
        .headers()
        .iter()
        .find(|h| h.field.equiv("Host"))
        .map(|h| h.value.as_str().to_ascii_lowercase())
    else {
        return true; // HTTP/1.0 without Host: not from a browser
    };
    let name = match host.rsplit_once(':') {
        Some((name, port)) if !name.ends_with(':') && port.bytes().all(|b| b.is_ascii_digit()) => {
            name
        }
        _ => host.as_str(),
    };
    matches!(name, "localhost" | "[::1]") || name.parse::<IpAddr>().is_ok_and(|ip| ip.is_loopback())
}

/// The conversion options of a query string, or what is wrong with it.
fn options(query: &str, state: &State) -> Result<(Options, String), String> {
    let mut options = Options::default()
        .fidelity(true)
        .json(true)
        .picture(None)
        .max_pixels(state.args.max_pixels);
    let mut name = String::from("upload");
    for pair in query.split('&').filter(|p| !p.is_empty()) {
        let (key, value) = pair.split_once('=').unwrap_or((pair, ""));
        let value = percent_decode(value).ok_or_else(|| format!("bad encoding of '{key}'"))?;
        match key {
            "model" => options = options.model(parse_model(&value)?),
            "threshold" if value.trim().is_empty() => {}
            "threshold" => options = options.threshold(parse_threshold(value.trim())?),
            "invert" => options = options.invert(matches!(value.as_str(), "1" | "true" | "on")),
            "turdsize" => {
                let n = value
                    .trim()
                    .parse::<u64>()
                    .ok()
                    .filter(|&n| n <= 1_000_000)
                    .ok_or_else(|| {
                        format!("turdsize '{value}' is not a whole number from 0 to 1000000")
                    })?;
                options = options.turdsize(n)
            }
            "cover" => options = options.cover(value.parse::<Cover>().map_err(|e| e.to_string())?),
            "colors" if value.trim().is_empty() => {}
            "colors" => {
                let n = value
                    .trim()
                    .parse::<u16>()
                    .ok()
                    .filter(|n| (2..=256).contains(n))
                    .ok_or_else(|| format!("colours '{value}' is not a number from 2 to 256"))?;
                options = options.colors(n)
            }
            "smooth" if value.trim().is_empty() => {}
            "smooth" => {
                let nu = value
                    .trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|nu| *nu > 0.0 && *nu <= MAX_BAND)
                    .ok_or_else(|| {
                        format!("smooth '{value}' is not a distance in (0, {MAX_BAND}] pixels")
                    })?;
                options = options.smooth(nu)
            }
            "alpha" => options = options.alpha(matches!(value.as_str(), "1" | "true" | "on")),
            "layout" => {
                options = options.layout(match value.as_str() {
                    "" => Layout::Stack,
                    other => other.parse().map_err(|e: ParseLayoutError| e.to_string())?,
                })
            }
            "name" => {
                name = value
                    .chars()
                    .filter(|c| !c.is_control())
                    .take(200)
                    .collect()
            }
            _ => return Err(format!("unknown parameter '{key}'")),
        }
    }
    // A colour run reads no threshold, inversion or turdsize (the page greys them out).
    if options.colors.is_some() && options.alpha {
        return Err(
            "colours and 'alpha is the shape' do not go together: colours already \
                    keep transparent pixels out"
                .into(),
        );
    }
    Ok((options, name))
}

/// Decodes `%XX` escapes and `+` (a space) of a query value; `None` when not UTF-8 or a
/// `%` is not followed by two hexadecimal digits.
fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'%' => {
                let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
                out.push(u8::from_str_radix(hex, 16).ok()?);
                i += 3;
            }
            b'+' => {
                out.push(b' ');
                i += 1;
            }
            b => {
                out.push(b);
                i += 1;
            }
        }
    }
    String::from_utf8(out).ok()
}

/// Reads the upload, vectorizes it and makes the JSON answer (or the error's).
fn convert(
    request: &mut Request,
    query: &str,
    state: &State,
) -> Response<std::io::Cursor<Vec<u8>>> {
    let start = Instant::now();
    let (options, name) = match options(query, state) {
        Ok(o) => o,
        Err(message) => return error(400, &message),
    };
    let max = state.args.max_upload;
    let mut body = Vec::new();
    if let Err(e) = request.as_reader().take(max + 1).read_to_end(&mut body) {
        return error(400, &format!("cannot read the upload: {e}"));
    }
    if body.len() as u64 > max {
        return error(413, &too_large(max));
    }
    let result = vectorize(body.as_slice(), &options);
    let seconds = start.elapsed().as_secs_f64();
    let answer = match result {
        Ok(out) => answer(&out, &name, seconds),
        Err(e) => Err(e),
    };
    match answer {
        Ok(body) => {
            if !state.args.quiet {
                eprintln!("layertrace: {name}: converted in {seconds:.3} s");
            }
            text(200, "application/json", &body)
        }
        Err(e) => {
            let message = e.to_string().replace("<memory>", &name);
            if !state.args.quiet {
                eprintln!("layertrace: {message}");
            }
            error(422, &message)
        }
    }
}

/// The JSON answer of a conversion.
fn answer(out: &Vectorized, name: &str, seconds: f64) -> Result<String, Error> {
    let picture_error = |source| Error::Arguments(format!("cannot encode a picture: {source}"));
    let fidelity = out.fidelity.as_ref();
    let colour = out.colour.as_ref();
    let colour_fidelity = colour.and_then(|c| c.fidelity.as_ref());
    let diff = match (fidelity, colour, colour_fidelity) {
        (Some(f), _, _) => {
            base64(&png_bytes(&diff_image(&out.mask, &f.rendered)).map_err(picture_error)?)
        }
        (None, Some(c), Some(f)) => base64(
            &png_bytes(&colour_diff_image(&c.regions.image, &f.rendered)).map_err(picture_error)?,
        ),
        _ => String::new(),
    };
    let svg = out.svg.as_ref();
    let report = fidelity.map(|f| f.report);
    let band = fidelity
        .and_then(|f| f.band)
        .or_else(|| colour_fidelity.and_then(|f| f.band));
    let colours: Option<Vec<serde_json::Value>> = colour_fidelity.map(|f| {
        f.colours
            .iter()
            .map(|d| {
                serde_json::json!({
                    "colour": d.colour.to_string(),
                    "pixels": d.pixels,
                    "differing": d.differing,
                })
            })
            .collect()
    });
    Ok(serde_json::json!({
        "name": name,
        "width": out.mask.width(),
        "height": out.mask.height(),
        "threshold": out.threshold,
        "contours": out.decomposition.contours.len(),
        "pieces": out.decomposition.piece_count(),
        "commands": svg.map_or(0, |s| s.commands.total()),
        "svg_bytes": out.svg_text().len(),
        "differing": report.map(|r| r.differing).or(colour_fidelity.map(|f| f.differing)),
        "colours": colours,
        "seams": colour_fidelity.map(|f| f.seams),
        "smooth": band.map(|b| b.nu),
        "beyond": band.map(|b| b.beyond),
        "max_distance": band.map(|b| b.max_distance),
        "missing": report.map(|r| r.missing),
        "extra": report.map(|r| r.extra),
        "iou": report.map(|r| r.iou),
        "chromium_tiles": fidelity.and_then(|f| f.tiled).map(|t| t.differing),
        "seconds": seconds,
        "svg": out.svg_text(),
        "json": out.json.as_deref().unwrap_or(""),
        "diff_png": diff,
        "decomposition_png": out.picture.as_deref().map(base64).unwrap_or_default(),
    })
    .to_string())
}

/// Standard base64 with padding (RFC 4648), for the PNG pictures in the JSON answer.
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(ALPHABET[((n >> (18 - 6 * i)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, encoded) in cases {
            assert_eq!(base64(plain.as_bytes()), encoded, "{plain:?}");
        }
    }

    #[test]
    fn percent_decoding() {
        assert_eq!(
            percent_decode("adaptive%3A16%3A20").as_deref(),
            Some("adaptive:16:20")
        );
        assert_eq!(percent_decode("poly%3a3+x").as_deref(), Some("poly:3 x"));
        assert_eq!(percent_decode("%4"), None);
        assert_eq!(percent_decode("%zz"), None);
        assert_eq!(percent_decode("%ff"), None); // not UTF-8
    }
}

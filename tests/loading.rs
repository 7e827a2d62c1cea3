//! Loading through the CLI: standard input, pipes and FIFOs, truncated and forged JPEGs,
//! `--max-memory`, and a memory-limited run that must end with a message, never an abort.

mod common;

use common::{bin, bin_path};
use std::io::{Cursor, Write};
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::Duration;

const SAMPLE: &str = "samples/glyph_g_liberationserif_cap120.png";

/// A fresh folder of its own (random name, removed when dropped, even when the test fails).
fn scratch(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(&format!("layertrace-load-{name}-"))
        .tempdir()
        .unwrap()
}

/// Runs the CLI with `stdin` as standard input (written from another thread, so that a child
/// that stops reading early cannot block the test).
fn run(args: &[&str], stdin: Option<Vec<u8>>) -> Output {
    let mut child = bin()
        .args(args)
        .stdin(if stdin.is_some() {
            Stdio::piped()
        } else {
            Stdio::null()
        })
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let writer = stdin.map(|data| {
        let mut pipe = child.stdin.take().unwrap();
        std::thread::spawn(move || {
            // The child may refuse the input and exit before reading it all.
            let _ = pipe.write_all(&data);
        })
    });
    let out = child.wait_with_output().unwrap();
    if let Some(w) = writer {
        w.join().unwrap();
    }
    out
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Exit code 1 and a one-line message containing `needle`.
fn assert_fails_with(out: &Output, needle: &str) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains(needle), "{needle:?} not in {err:?}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err:?}");
}

fn jpeg(width: u32, height: u32) -> Vec<u8> {
    let img = image::RgbImage::from_fn(width, height, |x, y| {
        let ink = ((x as i64 - 100).pow(2) + (y as i64 - 70).pow(2)) < 50 * 50;
        let v = if ink { 10 } else { 240 };
        image::Rgb([v, v, v.saturating_add(5)])
    });
    let mut out = Vec::new();
    let enc = image::codecs::jpeg::JpegEncoder::new_with_quality(&mut out, 90);
    img.write_with_encoder(enc).unwrap();
    out
}

#[test]
fn stdin_and_pipes_read_like_files() {
    let tmp = scratch("stdin");
    let dir = tmp.path();
    let svg = |n: &str| dir.join(n).to_string_lossy().into_owned();
    let bytes = std::fs::read(SAMPLE).unwrap();
    let from_file = run(&[SAMPLE, "-o", &svg("file.svg"), "-q"], None);
    assert!(from_file.status.success(), "{}", stderr(&from_file));
    let from_dash = run(&["-", "-o", &svg("dash.svg"), "-q"], Some(bytes.clone()));
    assert!(from_dash.status.success(), "{}", stderr(&from_dash));
    let from_dev = run(
        &["/dev/stdin", "-o", &svg("dev.svg"), "-q"],
        Some(bytes.clone()),
    );
    assert!(from_dev.status.success(), "{}", stderr(&from_dev));
    let expected = std::fs::read(svg("file.svg")).unwrap();
    assert!(!expected.is_empty());
    assert_eq!(std::fs::read(svg("dash.svg")).unwrap(), expected);
    assert_eq!(std::fs::read(svg("dev.svg")).unwrap(), expected);
    // A JPEG through a pipe too (it is decoded from memory).
    let j = jpeg(200, 140);
    std::fs::write(dir.join("in.jpg"), &j).unwrap();
    let a = run(&[&svg("in.jpg"), "-o", &svg("j1.svg"), "-q"], None);
    let b = run(&["-", "-o", &svg("j2.svg"), "-q"], Some(j));
    assert!(a.status.success() && b.status.success(), "{}", stderr(&b));
    assert_eq!(
        std::fs::read(svg("j1.svg")).unwrap(),
        std::fs::read(svg("j2.svg")).unwrap()
    );
    // Messages name standard input.
    let out = run(&["-"], Some(b"not an image at all".to_vec()));
    assert_fails_with(&out, "<stdin>");
    assert_fails_with(&run(&["-"], Some(Vec::new())), "no data");
}

#[test]
fn stdin_beyond_the_bound_is_refused() {
    // --max-memory 1M: at most 512 KiB are read from a pipe.
    let junk = vec![0x89u8; 2 << 20];
    let out = run(&["-", "--max-memory", "1M"], Some(junk));
    assert_fails_with(&out, "input is longer than 512 KiB");
    assert!(stderr(&out).contains("<stdin>"), "{}", stderr(&out));
}

#[test]
fn fifo_without_writer_fails_at_once() {
    let tmp = scratch("fifo");
    let dir = tmp.path();
    let fifo = dir.join("in.png");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let mut child = bin()
        .arg(&fifo)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // A bound, not a timing: the old code waits forever for a writer.
    let mut status = None;
    for _ in 0..200 {
        if let Some(s) = child.try_wait().unwrap() {
            status = Some(s);
            break;
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    if status.is_none() {
        child.kill().unwrap();
        child.wait().unwrap();
        panic!("still waiting for a writer after 20 s");
    }
    let out = child.wait_with_output().unwrap();
    assert_fails_with(&out, "no data");
}

#[test]
fn truncated_jpeg_is_an_error() {
    let tmp = scratch("jpeg");
    let dir = tmp.path();
    let good = jpeg(200, 140);
    let p = |n: &str| dir.join(n).to_string_lossy().into_owned();
    std::fs::write(p("good.jpg"), &good).unwrap();
    let ok = run(&[&p("good.jpg"), "-q"], None);
    assert!(ok.status.success(), "{}", stderr(&ok));
    for percent in [30, 80, 99] {
        let name = format!("cut{percent}.jpg");
        std::fs::write(p(&name), &good[..good.len() * percent / 100]).unwrap();
        assert_fails_with(&run(&[&p(&name)], None), "truncated");
    }
}

/// Position of the first SOF0 segment's height field.
fn sof_dimensions_at(jpeg: &[u8]) -> usize {
    let mut i = 2;
    loop {
        assert_eq!(jpeg[i], 0xFF);
        let m = jpeg[i + 1];
        let len = usize::from(u16::from_be_bytes([jpeg[i + 2], jpeg[i + 3]]));
        if m == 0xC0 {
            return i + 5;
        }
        i += 2 + len;
    }
}

#[test]
fn forged_jpeg_header_is_refused_before_allocating() {
    let tmp = scratch("forged");
    let dir = tmp.path();
    let mut j = jpeg(64, 48);
    assert!(j.len() < 8000, "{} bytes", j.len());
    let at = sof_dimensions_at(&j);
    assert_eq!(&j[at..at + 4], &[0, 48, 0, 64]);
    // 65500 x 6000: 393 million pixels, within --max-pixels, 1.1 GiB decoded.
    j[at..at + 2].copy_from_slice(&6000u16.to_be_bytes());
    j[at + 2..at + 4].copy_from_slice(&65500u16.to_be_bytes());
    let path = dir.join("forged.jpg");
    std::fs::write(&path, &j).unwrap();
    // With 256 MiB allowed, refusing for memory would also be clean; but the file is
    // recognised as impossible before that.
    let out = run(
        &[path.to_str().unwrap(), "--max-memory", "256M", "-q"],
        None,
    );
    assert_fails_with(&out, "truncated");
    assert!(stderr(&out).contains("65500x6000"), "{}", stderr(&out));
    // And the size is checked against --max-pixels first.
    let out = run(&[path.to_str().unwrap(), "--max-pixels", "1000000"], None);
    assert_fails_with(&out, "--max-pixels");
}

#[test]
fn max_memory_flag() {
    let big = "samples/syn_big3000_many_shapes.png";
    let out = run(&[big, "--max-memory", "2M"], None);
    assert_fails_with(
        &out,
        "more than the limit of 2 MiB (raise it with --max-memory)",
    );
    let ok = run(&[big, "--max-memory", "1.5GiB", "-q"], None);
    assert!(ok.status.success(), "{}", stderr(&ok));
    for bad in ["0", "lots", "-5", "1.2.3G", "12Q"] {
        let out = run(&[SAMPLE, "--max-memory", bad], None);
        assert_eq!(out.status.code(), Some(2), "{bad}: {}", stderr(&out));
    }
}

/// A 4000 x 4000 RGBA PNG of 16 bits per sample (128 MB decoded), mostly white.
fn large_rgba16_png(path: &Path) {
    let n = 4000u32;
    let img = image::ImageBuffer::<image::Rgba<u16>, Vec<u16>>::from_fn(n, n, |x, y| {
        let (dx, dy) = (i64::from(x) - 2000, i64::from(y) - 1800);
        if dx * dx + dy * dy < 900 * 900 {
            image::Rgba([0, 0, 0, 65535])
        } else {
            image::Rgba([65535, 65535, 65535, 65535])
        }
    });
    let mut out = Cursor::new(Vec::new());
    let enc = image::codecs::png::PngEncoder::new_with_quality(
        &mut out,
        image::codecs::png::CompressionType::Fast,
        image::codecs::png::FilterType::Sub,
    );
    image::DynamicImage::ImageRgba16(img)
        .write_with_encoder(enc)
        .unwrap();
    std::fs::write(path, out.into_inner()).unwrap();
}

#[test]
fn large_image_under_address_space_limit() {
    let tmp = scratch("ulimit");
    let dir = tmp.path();
    let png = dir.join("rgba16.png");
    large_rgba16_png(&png);
    // 300 MB of address space: streamed, the image needs its 2 MB mask; decoded whole, it
    // took 128 MB plus copies, and running out aborted (SIGABRT, exit 134).
    let script = "ulimit -v 300000 && exec \"$0\" \"$@\"";
    let out = Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(bin_path())
        .arg(&png)
        .args(["--threads", "1", "-q", "-o"])
        .arg(dir.join("out.svg"))
        .output()
        .unwrap();
    let err = stderr(&out);
    assert!(out.status.code().is_some(), "killed by a signal: {err}");
    assert_eq!(out.status.code(), Some(0), "{err}");
    let svg = std::fs::read_to_string(dir.join("out.svg")).unwrap();
    assert!(svg.contains("<path"), "{svg}");
    // With less room, a clean refusal.
    let out = Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(bin_path())
        .arg(&png)
        .args(["--threads", "1", "--max-memory", "1M"])
        .output()
        .unwrap();
    assert_fails_with(&out, "--max-memory");
}

/// Tiny contours by the hundred thousand (a one-pixel checkerboard): the work after tracing
/// is estimated from the contours and refused before it is allocated when over the limit,
/// which decoding (90 KB of grey) is far below; no output is written.
#[test]
fn work_after_tracing_is_checked_against_max_memory() {
    let tmp = scratch("checker");
    let dir = tmp.path();
    let img = image::GrayImage::from_fn(300, 300, |x, y| {
        image::Luma([if (x + y) % 2 == 0 { 0 } else { 255 }])
    });
    let path = dir.join("checker.png");
    img.save(&path).unwrap();
    let svg = dir.join("c.svg");
    let (p, s) = (path.to_str().unwrap(), svg.to_str().unwrap());
    let out = run(&[p, "-o", s, "--report", "--max-memory", "8M"], None);
    assert_fails_with(
        &out,
        "more than the limit of 8 MiB (raise it with --max-memory)",
    );
    assert!(!svg.exists());
    let out = run(&[p, "-o", s, "-q"], None);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(svg.exists());
    tmp.close().unwrap();
}

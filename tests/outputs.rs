//! Output files through the command line: never the input, never two outputs to one place,
//! all of them or none, nothing left behind on signals, and every option checked when parsed.

mod common;

use common::{bin, bin_path, cli_in, names, repo};

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const SAMPLE: &str = "samples/glyph_g_liberationserif_cap120.png";
const BIG: &str = "samples/syn_big3000_many_shapes.png";

fn scratch() -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix("layertrace-outputs-")
        .tempdir()
        .unwrap()
}

/// One line on standard error, starting with the tool's name.
fn one_line(err: &str) {
    assert_eq!(err.trim_end().lines().count(), 1, "not one line: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[cfg(unix)]
#[test]
fn the_input_is_never_overwritten() {
    let dir = scratch();
    let d = dir.path();
    // The input under the names each option accepts (the format is read from the content).
    for ext in ["png", "svg"] {
        std::fs::copy(repo(SAMPLE), d.join(format!("x.{ext}"))).unwrap();
        std::os::unix::fs::symlink(format!("x.{ext}"), d.join(format!("link.{ext}"))).unwrap();
    }
    let original = std::fs::read(d.join("x.png")).unwrap();
    for (flag, ext) in [
        ("-o", "svg"),
        ("--json", "png"),
        ("--decomposition", "png"),
        ("--diff", "png"),
    ] {
        let input = format!("x.{ext}");
        for out in [
            format!("x.{ext}"),
            format!("./x.{ext}"),
            format!("link.{ext}"),
        ] {
            let (code, err) = cli_in(d, &[&input, flag, &out]);
            assert_eq!(code, 1, "{flag} {out}: {err}");
            one_line(&err);
            assert!(err.contains("is the input file"), "{err}");
            assert_eq!(std::fs::read(d.join(&input)).unwrap(), original);
        }
        // Reading through the link, writing the file itself.
        let (code, _) = cli_in(d, &[&format!("link.{ext}"), flag, &input]);
        assert_eq!(code, 1);
    }
    // A name of the wrong format is refused first, as a usage error.
    let (code, err) = cli_in(d, &["x.png", "-o", "x.png"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("unknown output format 'png'"), "{err}");
    assert_eq!(std::fs::read(d.join("x.png")).unwrap(), original);
    assert_eq!(names(d), ["link.png", "link.svg", "x.png", "x.svg"]);
}

#[test]
fn two_outputs_to_one_place_are_usage_errors() {
    let dir = scratch();
    let d = dir.path();
    let sample = repo(SAMPLE);
    let s = sample.to_str().unwrap();
    for args in [
        vec![s, "-o", "-", "--json", "-"],
        vec![s, "-o", "a.svg", "--json", "a.svg"],
        vec![s, "--decomposition", "a.png", "--diff", "./a.png"],
        vec![s, "--json", "/dev/stdout", "-o", "-"],
    ] {
        let out = bin().current_dir(d).args(&args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        one_line(&err);
        assert!(err.contains("same destination"), "{err}");
        assert!(out.stdout.is_empty(), "{args:?}: wrote to standard output");
    }
    assert!(names(d).is_empty());
}

/// A run that fails after some outputs are ready changes none of them.
#[test]
fn outputs_are_all_or_nothing() {
    let dir = scratch();
    let d = dir.path();
    std::fs::write(d.join("old.svg"), "old svg").unwrap();
    std::fs::write(d.join("old.json"), "old json").unwrap();
    let big = repo(BIG);
    // The JSON is ready long before the picture turns out too large.
    let (code, err) = cli_in(
        d,
        &[
            big.to_str().unwrap(),
            "--json",
            "old.json",
            "-o",
            "old.svg",
            "--decomposition",
            "d.png",
            "--scale",
            "64",
        ],
    );
    assert_eq!(code, 1, "{err}");
    one_line(&err);
    assert!(err.contains("--scale"), "{err}");
    // An unwritable output is found before any work.
    let sample = repo(SAMPLE);
    let (code, err) = cli_in(
        d,
        &[
            sample.to_str().unwrap(),
            "-o",
            "old.svg",
            "--json",
            "old.json",
            "--diff",
            "no/such/dir/d.png",
        ],
    );
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("no/such/dir/d.png"), "{err}");
    assert_eq!(names(d), ["old.json", "old.svg"]);
    assert_eq!(
        std::fs::read_to_string(d.join("old.svg")).unwrap(),
        "old svg"
    );
    assert_eq!(
        std::fs::read_to_string(d.join("old.json")).unwrap(),
        "old json"
    );
    // And when everything succeeds, every output is in place.
    let (code, err) = cli_in(
        d,
        &[
            sample.to_str().unwrap(),
            "-o",
            "old.svg",
            "--json",
            "old.json",
            "--diff",
            "d.png",
            "-q",
        ],
    );
    assert_eq!(code, 0, "{err}");
    assert_eq!(names(d), ["d.png", "old.json", "old.svg"]);
    assert!(std::fs::read_to_string(d.join("old.svg"))
        .unwrap()
        .starts_with("<svg"));
}

/// SIGTERM or SIGINT at any moment: exit 128 + the signal, or success if the run was over;
/// never a temporary file left, never a partial output.
#[cfg(unix)]
#[test]
fn signals_leave_no_temporary_files() {
    let big = repo(BIG);
    let mut interrupted = 0;
    for (i, delay_ms) in [50u64, 150, 300, 600, 1000, 1500].into_iter().enumerate() {
        let dir = scratch();
        let d = dir.path();
        let mut child = bin()
            .current_dir(d)
            .args([
                big.to_str().unwrap(),
                "-o",
                "o.svg",
                "--json",
                "o.json",
                "--decomposition",
                "d.png",
                "-q",
            ])
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(delay_ms));
        let (sig, name) = if i % 2 == 0 { (15, "TERM") } else { (2, "INT") };
        let _ = Command::new("kill")
            .args([format!("-{name}"), child.id().to_string()])
            .status();
        let status = child.wait().unwrap();
        let left = names(d);
        match status.code() {
            Some(0) => assert_eq!(left, ["d.png", "o.json", "o.svg"]),
            Some(c) => {
                assert_eq!(c, 128 + sig, "{delay_ms} ms");
                assert!(left.is_empty(), "{delay_ms} ms: left {left:?}");
                interrupted += 1;
            }
            None => panic!("{delay_ms} ms: killed by the signal itself, no cleanup"),
        }
    }
    assert!(
        interrupted > 0,
        "no run was interrupted: the test proves nothing"
    );
}

/// `>&-`: the output would be lost (Rust reopens a closed descriptor on /dev/null).
#[cfg(target_os = "linux")]
#[test]
fn closed_standard_output_is_an_error() {
    let sample = repo(SAMPLE);
    for flag in ["-o", "--json"] {
        let out = Command::new("sh")
            .arg("-c")
            .arg(r#"exec "$0" "$@" >&-"#)
            .arg(bin_path())
            .args([sample.to_str().unwrap(), flag, "-"])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{flag}: {err}");
        assert!(err.contains("standard output is closed"), "{err}");
    }
    // Redirected to /dev/null on purpose is fine.
    let out = Command::new("sh")
        .arg("-c")
        .arg(r#"exec "$0" "$@" >/dev/null"#)
        .arg(bin_path())
        .args([sample.to_str().unwrap(), "-o", "-", "-q"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
}

/// A FIFO that nobody reads: an error at once, not a wait forever.
#[cfg(unix)]
#[test]
fn fifo_output_without_reader_fails_promptly() {
    let dir = scratch();
    let fifo = dir.path().join("fifo.svg");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let mut child = bin()
        .args([repo(SAMPLE).to_str().unwrap(), "-o", fifo.to_str().unwrap()])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > Duration::from_secs(30) {
            child.kill().unwrap();
            panic!("blocked on a FIFO without reader");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    assert_eq!(status.code(), Some(1));
}

/// Legal names of up to 255 bytes work (the temporary's name does not grow with them).
#[test]
fn long_output_names() {
    let dir = scratch();
    let name = format!("{}.svg", "n".repeat(251));
    let (code, err) = cli_in(dir.path(), &[repo(SAMPLE).to_str().unwrap(), "-o", &name]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(names(dir.path()), [name]);
}

/// Every numeric option is checked when parsed: exit 2 and one message, never a panic.
#[test]
fn options_out_of_range_are_refused() {
    let dir = scratch();
    let sample = repo(SAMPLE);
    let s = sample.to_str().unwrap();
    for bad in [
        vec!["--tolerance", "0.0005"],
        vec!["--tolerance", "0"],
        vec!["--tolerance", "NaN"],
        vec!["--tolerance", "inf"],
        vec!["--min-clearance=-1"],
        vec!["--min-clearance", "1e9"],
        vec!["--threads", "0"],
        vec!["--threads", "20000"],
        vec!["--max-pixels", "0"],
        vec!["--scale", "0"],
        vec!["--grid", "7"],
        vec!["--fill", "\"/><script>alert(1)</script>"],
        vec!["--fill", "not-a-colour"],
    ] {
        let mut args = vec![s, "-o", "o.svg"];
        args.extend(&bad);
        let (code, err) = cli_in(dir.path(), &args);
        assert_eq!(code, 2, "{bad:?}: {err}");
        assert!(err.starts_with("error: invalid value"), "{bad:?}: {err}");
        assert!(!err.contains("panicked"), "{bad:?}: {err}");
    }
    assert!(names(dir.path()).is_empty());
    // The edges of the ranges work.
    for good in [
        vec!["--tolerance", "0.001"],
        vec!["--threads", "1"],
        vec!["--fill", "#1a237e"],
        vec!["--fill", "rgb(10, 20, 30)"],
    ] {
        let mut args = vec![s, "-o", "o.svg", "-q"];
        args.extend(&good);
        let (code, err) = cli_in(dir.path(), &args);
        assert_eq!(code, 0, "{good:?}: {err}");
    }
}

//! Command lines made from fuzz bytes, run through the tool's own code (`src/cli`): whatever
//! the options, no panic, exit code 0, 1 or 2, the input untouched, and no temporary file or
//! partial output left behind.
//!
//! The bytes are split on NUL into arguments. Arguments holding `/` are dropped and `-` is
//! dropped too, so every path stays inside a scratch directory (the working directory) and
//! standard input is never read; the input `in.png` is a bundled glyph.
#![no_main]

#[path = "../../src/cli/mod.rs"]
mod cli;

use libfuzzer_sys::fuzz_target;
use std::ffi::OsString;
use std::path::PathBuf;
use std::sync::OnceLock;

const IMAGE: &[u8] = include_bytes!("../../samples/glyph_at_dejavusans_cap40.png");

/// The scratch directory, made the working directory once.
fn scratch() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("layertrace-fuzz-cli-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::env::set_current_dir(&dir).unwrap();
        dir
    })
}

fn entries() -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(".")
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fuzz_target!(|data: &[u8]| {
    let dir = scratch();
    // A clean directory holding only the input.
    for name in entries() {
        let p = dir.join(&name);
        if p.is_dir() {
            let _ = std::fs::remove_dir_all(&p);
        } else {
            let _ = std::fs::remove_file(&p);
        }
    }
    std::fs::write("in.png", IMAGE).unwrap();

    let mut argv: Vec<OsString> = vec!["layertrace".into()];
    for token in data.split(|&b| b == 0).take(16) {
        let s = String::from_utf8_lossy(token);
        if s.contains('/') || s == "-" || s.is_empty() {
            continue;
        }
        argv.push(s.into_owned().into());
    }
    if !argv.iter().any(|a| a == "in.png") {
        argv.push("in.png".into());
    }
    let code = cli::main(argv.clone());
    let left = entries();
    assert!(
        !left.iter().any(|n| n.starts_with(".layertrace-")),
        "{argv:?}: temporary left: {left:?}"
    );
    assert_eq!(std::fs::read("in.png").unwrap(), IMAGE, "{argv:?}: input changed");
    // Exit codes are opaque; failures must leave nothing but the input.
    if code != std::process::ExitCode::SUCCESS {
        let only_input = left.iter().all(|n| n == "in.png");
        assert!(only_input, "{argv:?}: failed but left {left:?}");
    }
});

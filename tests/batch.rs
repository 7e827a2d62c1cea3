//! Many inputs in one run (`--out-dir`): every input written as a single run would write it,
//! failures named and counted with the others still written, and the arguments that cannot
//! work refused before any work.

mod common;

use common::{bin, cli_in, names, repo};

use std::path::Path;
use std::process::Stdio;
use std::time::Duration;

const SAMPLES: [&str; 3] = [
    "samples/glyph_g_liberationserif_cap120.png",
    "samples/glyph_at_dejavusans_cap40.png",
    "samples/digits_liberationsans_cap40.png",
];

/// A scratch folder `in/` holding copies of the samples.
fn inputs() -> tempfile::TempDir {
    let dir = tempfile::Builder::new()
        .prefix("layertrace-batch-")
        .tempdir()
        .unwrap();
    std::fs::create_dir(dir.path().join("in")).unwrap();
    for s in SAMPLES {
        let name = Path::new(s).file_name().unwrap();
        std::fs::copy(repo(s), dir.path().join("in").join(name)).unwrap();
    }
    dir
}

#[test]
fn a_folder_and_files_give_what_single_runs_give() {
    let dir = inputs();
    let d = dir.path();
    // A file that is not an image, a missing file and a non-image extension in the folder.
    std::fs::write(d.join("in/broken.png"), b"\x89PNG\r\n\x1a\nnot an image").unwrap();
    std::fs::write(d.join("in/notes.txt"), b"ignored").unwrap();
    std::fs::write(d.join("extra.pbm"), b"P1\n3 3\n0 0 0\n0 1 0\n0 0 0\n").unwrap();
    let (code, err) = cli_in(
        d,
        &[
            "in",
            "extra.pbm",
            "missing.png",
            "--out-dir",
            "out",
            "--model",
            "circle",
        ],
    );
    assert_eq!(code, 1, "{err}");
    // Every good input written, the failures named, one line each, and a count.
    let mut want: Vec<String> = SAMPLES
        .iter()
        .map(|s| {
            let stem = Path::new(s).file_stem().unwrap().to_string_lossy();
            format!("{stem}.svg")
        })
        .collect();
    want.push("extra.svg".into());
    want.sort();
    assert_eq!(names(&d.join("out")), want, "{err}");
    assert!(
        err.contains("broken.png") && err.contains("missing.png"),
        "{err}"
    );
    assert!(err.contains("2 of 6 inputs failed"), "{err}");
    assert_eq!(err.lines().count(), 4 + 2 + 1, "{err}");
    for s in SAMPLES {
        assert!(err.contains(Path::new(s).file_name().unwrap().to_str().unwrap()));
    }

    // Each SVG is the one a run on that file alone writes.
    for s in SAMPLES {
        let stem = Path::new(s)
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        let single = d.join(format!("{stem}-single.svg"));
        let (code, err) = cli_in(
            d,
            &[
                repo(s).to_str().unwrap(),
                "-o",
                single.to_str().unwrap(),
                "--model",
                "circle",
                "-q",
            ],
        );
        assert_eq!(code, 0, "{err}");
        let batch = std::fs::read(d.join("out").join(format!("{stem}.svg"))).unwrap();
        assert_eq!(batch, std::fs::read(&single).unwrap(), "{s}");
    }

    // All good: exit 0, existing outputs replaced, one summary line per input.
    std::fs::remove_file(d.join("in/broken.png")).unwrap();
    std::fs::write(d.join("out/extra.svg"), b"old").unwrap();
    let (code, err) = cli_in(d, &["in", "extra.pbm", "--out-dir", "out", "--report"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        err.lines()
            .filter(|l| l.starts_with("fidelity: 0 differing"))
            .count(),
        4,
        "{err}"
    );
    assert!(std::fs::read_to_string(d.join("out/extra.svg"))
        .unwrap()
        .starts_with("<svg"));
    let (code, err) = cli_in(d, &["in", "--out-dir", "out", "-q"]);
    assert_eq!((code, err.as_str()), (0, ""));
    // Another format by name.
    let (code, err) = cli_in(d, &["in", "--out-dir", "pdf", "--out-format", "pdf", "-q"]);
    assert_eq!(code, 0, "{err}");
    let pdfs = names(&d.join("pdf"));
    assert_eq!(pdfs.len(), SAMPLES.len());
    for name in pdfs {
        assert!(name.ends_with(".pdf"), "{name}");
        assert!(std::fs::read(d.join("pdf").join(name))
            .unwrap()
            .starts_with(b"%PDF-"));
    }
    assert!(
        !names(&d.join("out")).iter().any(|n| n.starts_with('.')),
        "temporaries left"
    );
}

#[test]
fn a_batch_whose_every_input_fails_says_nothing_was_written() {
    let dir = tempfile::Builder::new()
        .prefix("layertrace-batch-")
        .tempdir()
        .unwrap();
    let d = dir.path();
    std::fs::write(d.join("broken.png"), b"\x89PNG\r\n\x1a\nnot an image").unwrap();
    let (code, err) = cli_in(d, &["broken.png", "missing.png", "--out-dir", "out"]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("all 2 inputs failed; nothing was written"),
        "{err}"
    );
    assert!(!err.contains("the others"), "{err}");
    assert!(names(&d.join("out")).is_empty(), "{err}");
}

#[test]
fn impossible_batches_are_refused_before_any_work() {
    let dir = inputs();
    let d = dir.path();
    std::fs::create_dir(d.join("other")).unwrap();
    let g = Path::new(SAMPLES[0]).file_name().unwrap().to_str().unwrap();
    std::fs::copy(d.join("in").join(g), d.join("other").join(g)).unwrap();
    std::fs::create_dir(d.join("empty")).unwrap();
    let cases: [&[&str]; 7] = [
        // Two inputs with the same name would overwrite each other's SVG.
        &["in", "other", "--out-dir", "out"],
        // Several inputs, or a folder, need --out-dir.
        &["in/a.png", "in/b.png", "-o", "x.svg"],
        &["in"],
        // Standard input has no name to derive.
        &["-", "--out-dir", "out"],
        // A folder without images.
        &["empty", "--out-dir", "out"],
        // Outputs of one input do not combine with --out-dir.
        &["in", "--out-dir", "out", "-o", "x.svg"],
        &["in", "--out-dir", "out", "--json", "x.json"],
    ];
    for args in cases {
        let (code, err) = cli_in(d, args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(
            !d.join("out").exists() && !d.join("x.svg").exists(),
            "{args:?}"
        );
    }
    // An output folder that cannot be made.
    std::fs::write(d.join("file"), b"").unwrap();
    let (code, err) = cli_in(d, &["in", "--out-dir", "file/out"]);
    assert_eq!(code, 1, "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
}

/// SIGINT or SIGTERM during a batch: exit 128 + the signal (or success if it was over), no
/// temporary file left in the output folder, and every drawing there whole.
#[cfg(unix)]
#[test]
fn signals_stop_a_batch_leaving_whole_files_only() {
    let dir = inputs();
    let d = dir.path();
    // Forty inputs: long enough to be stopped in the middle.
    for k in 0..40 {
        std::fs::copy(
            repo("samples/lineart_cat_symbola_h300.png"),
            d.join("in").join(format!("cat{k:02}.png")),
        )
        .unwrap();
    }
    let mut interrupted = 0;
    for (i, delay_ms) in [30u64, 80, 160, 250, 400, 700].into_iter().enumerate() {
        let out = d.join(format!("out{i}"));
        let mut child = bin()
            .current_dir(d)
            .args(["in", "--out-dir", out.to_str().unwrap(), "-q"])
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(delay_ms));
        let (sig, name) = if i % 2 == 0 { (2, "INT") } else { (15, "TERM") };
        let _ = std::process::Command::new("kill")
            .args([format!("-{name}"), child.id().to_string()])
            .status();
        let status = child.wait().unwrap();
        let left = if out.exists() {
            names(&out)
        } else {
            Vec::new()
        };
        match status.code() {
            Some(0) => assert_eq!(left.len(), 43, "{delay_ms} ms"),
            Some(c) => {
                assert_eq!(c, 128 + sig, "{delay_ms} ms");
                interrupted += 1;
            }
            None => panic!("{delay_ms} ms: killed by the signal itself"),
        }
        for name in &left {
            assert!(name.ends_with(".svg"), "{delay_ms} ms: left {name}");
            let svg = std::fs::read_to_string(out.join(name)).unwrap();
            assert!(
                svg.trim_end().ends_with("</svg>"),
                "{delay_ms} ms: {name} cut"
            );
        }
    }
    assert!(
        interrupted > 0,
        "no run was interrupted: the test proves nothing"
    );
}

//! Helpers shared by the integration tests: running the command-line tool, the bundled
//! samples, and layer values computed independently of the library.
// Each test binary uses its own subset of these.
#![allow(dead_code)]

use layertrace::{piece_outliers, Basis, Contour, OutlierRule, Outliers, Piece, Pixel};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// The tool under test: `$LAYERTRACE_BIN` when set (`.ci/run` points it at the binary as
/// shipped, `scripts/build_release.sh`), else the one Cargo built for the tests.
pub fn bin_path() -> PathBuf {
    std::env::var_os("LAYERTRACE_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_layertrace")))
}

/// A command running [`bin_path`].
pub fn bin() -> Command {
    Command::new(bin_path())
}

/// A path in the repository.
pub fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// Runs the CLI in `dir` with standard input closed; returns (exit code, stderr). Fails the
/// test if the tool panicked.
pub fn cli_in(dir: &Path, args: &[&str]) -> (i32, String) {
    let out = bin()
        .current_dir(dir)
        .args(args)
        .stdin(Stdio::null())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    (out.status.code().unwrap_or(-1), err)
}

/// The names in `dir` (temporaries included), sorted.
pub fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// The bundled `samples/*.png`, sorted (at least 15 of them).
pub fn samples() -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir("samples")
        .unwrap()
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "png").then(|| p.to_string_lossy().into_owned())
        })
        .collect();
    v.sort();
    assert!(v.len() >= 15, "samples missing: {v:?}");
    v
}

/// `a·F(p − origin)` computed with the tests' own loop, not the library's evaluation.
pub fn value(basis: &dyn Basis, origin: &[i64], a: &[i64], p: Pixel) -> i128 {
    let mut f = vec![0i64; basis.dim()];
    basis
        .lift(&[p.x as i64 - origin[0], p.y as i64 - origin[1]], &mut f)
        .unwrap();
    f.iter().zip(a).map(|(&x, &y)| x as i128 * y as i128).sum()
}

/// The pieces tile `contour` in order, and each piece's certificate holds, checked with
/// [`value`]: origin at its first point, `lower`/`upper` the extremes over its pixels, its
/// RIGHT outliers strictly above and LEFT ones strictly below. `what` names the case.
pub fn check_pieces(basis: &dyn Basis, contour: &Contour, pieces: &[Piece], what: &str) {
    let n = contour.points.len();
    assert_eq!(pieces.first().map(|p| p.first), Some(0), "{what}");
    assert_eq!(pieces.last().map(|p| p.last), Some(n - 1), "{what}");
    for w in pieces.windows(2) {
        assert_eq!(w[0].last + 1, w[1].first, "{what}");
    }
    for p in pieces {
        let cert = &p.certificate;
        let first = contour.points[p.first];
        assert_eq!(
            cert.origin,
            vec![i64::from(first.x), i64::from(first.y)],
            "{what}"
        );
        let v = |q: Pixel| value(basis, &cert.origin, &cert.coefficients, q);
        let inl: Vec<i128> = contour.points[p.first..=p.last]
            .iter()
            .map(|&q| v(q))
            .collect();
        assert_eq!(inl.iter().min(), Some(&cert.extremes.lower), "{what}");
        assert_eq!(inl.iter().max(), Some(&cert.extremes.upper), "{what}");
        let Outliers { right, left } =
            piece_outliers(&contour.points, p.first, p.last, OutlierRule::NotInPiece);
        assert!(
            right.iter().all(|&q| v(q) > cert.extremes.upper),
            "{what} right"
        );
        assert!(
            left.iter().all(|&q| v(q) < cert.extremes.lower),
            "{what} left"
        );
    }
}

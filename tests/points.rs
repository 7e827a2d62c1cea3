//! `layertrace recognize` end to end: point files in 2-D and 3-D, described and not, every
//! answer re-checked exactly here from the JSON alone (the basis is evaluated from the
//! names the JSON gives, in integer and rational arithmetic); malformed files are one-line
//! errors with exit 1; the image command line is unchanged; the article's cubic layer.

mod common;

use common::{bin, cli_in};
use layertrace::{recognize_points, Model, PointSets, PointsAnswer};
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use serde_json::Value;
use std::io::Write;
use std::path::Path;
use std::process::Stdio;

/// Runs `layertrace recognize ARGS` in `dir` with `stdin`; (exit code, stdout, stderr).
fn recognize(dir: &Path, args: &[&str], stdin: &[u8]) -> (i32, String, String) {
    let mut child = bin()
        .current_dir(dir)
        .arg("recognize")
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // A tool that exits before reading standard input closes the pipe: ignore that.
    let _ = child.stdin.take().unwrap().write_all(stdin);
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        err,
    )
}

/// The JSON of a point file.
fn file_json(s: &PointSets) -> String {
    let list = |v: &[Vec<i64>]| serde_json::to_string(v).unwrap();
    format!(
        "{{\"inliers\": {},\n \"above\": {},\n \"below\": {}}}",
        list(&s.inliers),
        list(&s.above),
        list(&s.below)
    )
}

/// A basis function given by its name (`x^2+y^2`, `x*y^2`, `z`, `1`) at `p`, exactly.
fn eval_name(name: &str, p: &[i128]) -> i128 {
    name.split('+')
        .map(|term| {
            term.split('*')
                .map(|factor| {
                    let (var, exp) = factor.split_once('^').unwrap_or((factor, "1"));
                    let exp: u32 = exp.parse().unwrap();
                    match var {
                        "1" => 1,
                        "x" => p[0].pow(exp),
                        "y" => p[1].pow(exp),
                        "z" => p[2].pow(exp),
                        v => panic!("unknown variable {v} in {name}"),
                    }
                })
                .product::<i128>()
        })
        .sum()
}

fn ints(v: &Value) -> Vec<i128> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|c| {
            // Coefficients beyond i64 would be read as doubles: make the test fail then.
            i128::from(c.as_i64().unwrap_or_else(|| panic!("{c} is not an i64")))
        })
        .collect()
}

fn int(v: &Value) -> i128 {
    i128::from(v.as_i64().unwrap_or_else(|| panic!("{v} is not an i64")))
}

/// `Σ coefficients[i] · basis_i(p − origin)`, the constant's coefficient included.
fn value(names: &[String], coefficients: &[i128], origin: &[i128], p: &[i64]) -> i128 {
    let rel: Vec<i128> = p
        .iter()
        .zip(origin)
        .map(|(a, o)| i128::from(*a) - o)
        .collect();
    assert_eq!(names.len(), coefficients.len());
    names
        .iter()
        .zip(coefficients)
        .map(|(n, c)| c * eval_name(n, &rel))
        .sum()
}

/// Checks a layer object (`layer` with origin zero, or `local`) on the sets, exactly.
fn check_layer(names: &[String], layer: &Value, origin: &[i128], s: &PointSets) {
    let a = ints(&layer["coefficients"]);
    assert_eq!(*a.last().unwrap(), 0, "the constant's coefficient is 0");
    let (lower, upper) = (int(&layer["lower"]), int(&layer["upper"]));
    let f = |p: &Vec<i64>| value(names, &a, origin, p);
    let values: Vec<i128> = s.inliers.iter().map(f).collect();
    assert!(values.iter().all(|v| lower <= *v && *v <= upper));
    assert_eq!(values.iter().min(), Some(&lower));
    assert_eq!(values.iter().max(), Some(&upper));
    let above: Option<i128> = s.above.iter().map(f).min();
    let below: Option<i128> = s.below.iter().map(f).max();
    assert!(above.is_none_or(|v| v > upper), "{above:?} > {upper}");
    assert!(below.is_none_or(|v| v < lower), "{below:?} < {lower}");
    assert_eq!(above, layer["above"].as_i64().map(i128::from));
    assert_eq!(below, layer["below"].as_i64().map(i128::from));
}

/// Checks a witness exactly: weights ≥ 0 summing to 1, `Σ λ d = 0` in the lifted space,
/// every pair made of an inlier and an outlier of the named side.
fn check_witness(names: &[String], w: &Value, s: &PointSets) {
    let origin = ints(&w["origin"]);
    let terms = w["terms"].as_array().unwrap();
    assert!(!terms.is_empty());
    let n = names.len();
    let mut sum = vec![BigRational::zero(); n];
    let mut total = BigRational::zero();
    let point = |v: &Value| -> Vec<i64> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|c| c.as_i64().unwrap())
            .collect()
    };
    for t in terms {
        let weight: BigRational = t["weight"].as_str().unwrap().parse().unwrap();
        assert!(!weight.is_negative());
        total += &weight;
        let (inl, out) = (point(&t["inlier"]), point(&t["outlier"]));
        assert!(s.inliers.contains(&inl));
        let above = match t["side"].as_str().unwrap() {
            "above" => true,
            "below" => false,
            other => panic!("side {other}"),
        };
        assert!(if above { &s.above } else { &s.below }.contains(&out));
        for (k, name) in names.iter().enumerate() {
            let one = |p: &[i64]| {
                let rel: Vec<i128> = p
                    .iter()
                    .zip(&origin)
                    .map(|(a, o)| i128::from(*a) - o)
                    .collect();
                eval_name(name, &rel)
            };
            let d = if above {
                one(&out) - one(&inl)
            } else {
                one(&inl) - one(&out)
            };
            sum[k] += &weight * BigRational::from_integer(d.into());
        }
    }
    assert!(total.is_one(), "weights sum to {total}");
    assert!(sum.iter().all(Zero::is_zero), "Σλd = {sum:?}");
}

/// Runs the CLI on `s` and checks its answer exactly; returns whether it is described.
fn recognized(dir: &Path, s: &PointSets, model: &str) -> bool {
    std::fs::write(dir.join("p.json"), file_json(s)).unwrap();
    let (code, out, err) = recognize(dir, &["p.json", "--model", model, "-q"], b"");
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["format"], "layertrace-recognition/1");
    assert_eq!(v["model"], model);
    let names: Vec<String> = v["basis"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap().to_string())
        .collect();
    assert_eq!(names.last().map(String::as_str), Some("1"));
    assert_eq!(v["inliers"], s.inliers.len());
    assert_eq!(v["above"], s.above.len());
    assert_eq!(v["below"], s.below.len());
    assert_eq!(v["stats"]["queries"], 1);
    match v["result"].as_str().unwrap() {
        "described" => {
            let d = s.inliers[0].len();
            check_layer(&names, &v["layer"], &vec![0; d], s);
            let origin = ints(&v["local"]["origin"]);
            check_layer(&names, &v["local"], &origin, s);
            assert!(v.get("witness").is_none());
            // The inliers alone: their thinnest layer is no thicker than this one.
            let c: Vec<BigInt> = ints(&v["layer"]["coefficients"])
                .iter()
                .map(|&x| BigInt::from(x))
                .collect();
            let values: Vec<BigInt> = s.inliers.iter().map(|p| big_value(&names, &c, p)).collect();
            let alone =
                recognize_points(&PointSets::new(s.inliers.clone()), model.parse().unwrap())
                    .unwrap();
            let PointsAnswer::Thinnest(t) = &alone.answer else {
                panic!("{model}: no thinnest layer");
            };
            if let Some(w) = width(&values, &c[..c.len() - 1]) {
                assert!(t.thickness <= w, "{model}: {} > {w}", t.thickness);
            }
            true
        }
        "not described" => {
            check_witness(&names, &v["witness"], s);
            assert!(v.get("layer").is_none());
            false
        }
        r => panic!("result {r}"),
    }
}

/// A small deterministic generator: integers in `-range..=range`.
fn rng(seed: u64) -> impl FnMut(i64) -> i64 {
    let mut s = seed;
    move |range| {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 33) % (2 * range as u64 + 1)) as i64 - range
    }
}

/// The points of a box split by `f` into the layer `lo ≤ f ≤ hi`, above and below.
fn split(
    points: impl Iterator<Item = Vec<i64>>,
    f: impl Fn(&[i64]) -> i64,
    lo: i64,
    hi: i64,
) -> PointSets {
    let mut s = PointSets::default();
    for p in points {
        let v = f(&p);
        if v < lo {
            s.below.push(p);
        } else if v > hi {
            s.above.push(p);
        } else {
            s.inliers.push(p);
        }
    }
    s
}

fn square(c: i64, r: i64) -> impl Iterator<Item = Vec<i64>> {
    (c - r..=c + r).flat_map(move |x| (c - r..=c + r).map(move |y| vec![x, y]))
}

fn cube(r: i64) -> impl Iterator<Item = Vec<i64>> {
    (-r..=r).flat_map(move |x| (-r..=r).flat_map(move |y| (-r..=r).map(move |z| vec![x, y, z])))
}

#[test]
fn random_2d_layers_are_described_and_broken_ones_proven_either_way() {
    let dir = tempfile::tempdir().unwrap();
    let mut next = rng(19);
    let mut counts = [0; 2];
    for round in 0..6 {
        // A digital line and a digital conic with random coefficients, away from (0, 0).
        let c = next(5000);
        let (a, b) = (next(9), next(9).abs() + 1);
        let line = split(
            square(c, 7),
            |p| a * p[0] + b * p[1],
            a * c + b * c,
            a * c + b * c + b.abs().max(a.abs()),
        );
        let (p, q) = (next(4).abs() + 1, next(4).abs() + 1);
        let conic = split(
            square(c, 7),
            |v| p * (v[0] - c).pow(2) + q * (v[1] - c).pow(2) + (v[0] - c) * (v[1] - c),
            20,
            20 + 4 * (p + q) + 8,
        );
        for (s, model) in [(&line, "line"), (&conic, "conic")] {
            assert!(recognized(dir.path(), s, model), "round {round} {model}");
            // Some points moved to the wrong side: decided either way, with its proof.
            let mut broken = s.clone();
            for _ in 0..3 {
                let i = (next(1000).unsigned_abs() as usize) % broken.inliers.len();
                let moved = broken.inliers.swap_remove(i);
                if next(1) > 0 {
                    broken.above.push(moved);
                } else {
                    broken.below.push(moved);
                }
            }
            counts[usize::from(recognized(dir.path(), &broken, model))] += 1;
        }
    }
    // Points moved into the other side's territory break most of them (each answer, either
    // way, was checked above).
    assert!(counts[0] > 0, "{counts:?}");
}

#[test]
fn a_circle_band_is_no_line_and_a_quadric_layer_is_no_plane() {
    let dir = tempfile::tempdir().unwrap();
    let disc = split(square(0, 9), |p| p[0] * p[0] + p[1] * p[1], 30, 45);
    assert!(!recognized(dir.path(), &disc, "line"));
    assert!(recognized(dir.path(), &disc, "circle"));
    let shell = split(
        cube(6),
        |p| 4 * p[0] * p[0] + 9 * p[1] * p[1] + 16 * p[2] * p[2] + 3 * p[0] * p[2],
        100,
        150,
    );
    assert!(recognized(dir.path(), &shell, "quadric3"));
    assert!(recognized(dir.path(), &shell, "poly3:2"));
    assert!(!recognized(dir.path(), &shell, "poly3:1"));
    // A point both inlier and outlier: not described, whatever the model.
    let mut twice = shell.clone();
    twice.below.push(twice.inliers[3].clone());
    assert!(!recognized(dir.path(), &twice, "poly3:3"));
}

#[test]
fn standard_input_output_file_and_the_input_protected() {
    let dir = tempfile::tempdir().unwrap();
    let s = split(square(3, 4), |p| 2 * p[0] - 3 * p[1], -2, 1);
    let text = file_json(&s);
    let (code, out, err) = recognize(dir.path(), &["-", "--model", "line"], text.as_bytes());
    assert_eq!(code, 0, "{err}");
    assert!(
        err.starts_with("<stdin>: ") && err.contains("described"),
        "{err}"
    );
    let (code, none, _) = recognize(
        dir.path(),
        &["-", "-m", "line", "-o", "a.json", "-q"],
        text.as_bytes(),
    );
    assert_eq!((code, none.as_str()), (0, ""));
    assert_eq!(
        std::fs::read_to_string(dir.path().join("a.json")).unwrap(),
        out
    );
    // The output may not be the input; nothing is changed then.
    std::fs::write(dir.path().join("p.json"), &text).unwrap();
    let (code, _, err) = recognize(dir.path(), &["p.json", "-m", "line", "-o", "./p.json"], b"");
    assert_eq!(code, 1, "{err}");
    assert_eq!(
        std::fs::read_to_string(dir.path().join("p.json")).unwrap(),
        text
    );
    // Without outliers: the thinnest layer, without a warning: the line through both points.
    let (code, out, err) = recognize(
        dir.path(),
        &["-", "-m", "line"],
        b"{\"inliers\": [[1, 2], [3, 5]]}",
    );
    assert_eq!(code, 0);
    assert!(!err.contains("warning"), "{err}");
    assert!(err.contains("thinnest layer, thickness 0"), "{err}");
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["thinnest"], true);
    assert_eq!(v["thickness"], "0");
    assert_eq!(v["layer"]["coefficients"], serde_json::json!([3, -2, 0]));
    assert_eq!(
        (v["layer"]["lower"].clone(), v["layer"]["upper"].clone()),
        ((-1).into(), (-1).into())
    );
}

#[test]
fn malformed_files_are_one_line_errors_with_exit_1() {
    let dir = tempfile::tempdir().unwrap();
    let cases: &[(&str, &str, &[&str])] = &[
        ("not json at all", "line", &["not valid JSON", "line 1"]),
        ("", "line", &["no data"]),
        (
            "{\"inliers\": [[1, 2],\n [3, 4, 5]]}",
            "line",
            &["inliers[1] has 3 coordinates", "line 2"],
        ),
        (
            "{\"inliers\": [[1, 2]],\n \"below\": [[0.5, 2]]}",
            "line",
            &["below[0][0]", "not an integer", "line 2"],
        ),
        (
            "{\"inliers\": [[1, 99999999999999999999]]}",
            "line",
            &["inliers[0][1]", "64-bit"],
        ),
        (
            "{\"inliers\": [[1, -9223372036854775809]]}",
            "line",
            &["inliers[0][1]", "64-bit"],
        ),
        ("{\"above\": [[1, 2]]}", "line", &["missing \"inliers\""]),
        (
            "{\"inliers\": \"all\"}",
            "line",
            &["\"inliers\" to be a list"],
        ),
        (
            "{\"inliers\": [[1, true]]}",
            "line",
            &["inliers[0][1] to be an integer"],
        ),
        (
            "{\"inliers\": [[1, 2]], \"outliers\": []}",
            "line",
            &["unknown member \"outliers\""],
        ),
        ("{\"inliers\": []}", "line", &["no inliers"]),
        (
            "{\"inliers\": [[1, 2, 3]]}",
            "conic",
            &["3-D", "model conic takes 2-D", "quadric3"],
        ),
        ("{\"inliers\": [[1, 2]]}", "poly3:2", &["2-D", "takes 3-D"]),
        ("{\"inliers\": [[1]]}", "line", &["1-D", "takes 2-D"]),
        (
            "{\"inliers\": [[0, 0]], \"above\": [[4000000000000, 0]]}",
            "conic",
            &["above[0]", "overflows 64-bit"],
        ),
    ];
    for (text, model, parts) in cases {
        std::fs::write(dir.path().join("bad.json"), text).unwrap();
        let (code, out, err) = recognize(dir.path(), &["bad.json", "--model", model], b"");
        assert_eq!(code, 1, "{text}: {err}");
        assert_eq!(out, "", "{text}");
        assert_eq!(err.lines().count(), 1, "{text}: {err}");
        assert!(err.starts_with("layertrace: bad.json: "), "{err}");
        for part in *parts {
            assert!(err.contains(part), "{text}: {err} lacks {part:?}");
        }
    }
    let (code, _, err) = recognize(dir.path(), &["missing.json", "--model", "line"], b"");
    assert_eq!(code, 1);
    assert!(err.contains("cannot read missing.json"), "{err}");
    // Bad arguments: exit 2.
    for args in [
        &["bad.json"][..],
        &["bad.json", "--model", "spline"],
        &["bad.json", "-m", "line", "--bogus"],
    ] {
        let (code, _, err) = recognize(dir.path(), args, b"");
        assert_eq!(code, 2, "{args:?}: {err}");
    }
}

#[test]
fn the_image_command_line_is_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let (code, err) = cli_in(dir.path(), &["recognize", "--help"]);
    assert_eq!(code, 0, "{err}");
    let out = bin().args(["recognize", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&out.stdout);
    assert!(
        help.contains("--model") && help.contains("layertrace recognize"),
        "{help}"
    );
    // An image named `recognize` is vectorized when named as a path.
    std::fs::copy(
        common::repo("samples/glyph_g_liberationserif_cap120.png"),
        dir.path().join("recognize"),
    )
    .unwrap();
    let (code, err) = cli_in(dir.path(), &["./recognize", "-o", "g.svg", "-q"]);
    assert_eq!(code, 0, "{err}");
    assert!(dir.path().join("g.svg").exists());
    // 3-D models are still refused for images, pointing to the subcommand.
    let (code, err) = cli_in(
        dir.path(),
        &["./recognize", "-o", "g.svg", "--model", "quadric3"],
    );
    assert_eq!(code, 2);
    assert!(err.contains("layertrace recognize"), "{err}");
}

/// The article's cubic layer `L ≤ −748631400x³ − … + 623242620000z ≤ L + 910277121600`,
/// `L = 3739455720000`: its middle terms are not in the issue, so `x·y²` and `y³` terms
/// of our own stand for them (as in `examples/paper_3d.rs`). Digitized in a box with its
/// 26-neighbours as outliers, it is recognized by poly3:3, exactly.
#[test]
fn the_papers_cubic_layer_is_recognized() {
    const L: i64 = 3_739_455_720_000;
    const W: i64 = 910_277_121_600;
    let f = |p: &[i64]| {
        let (x, y, z) = (p[0], p[1], p[2]);
        -748_631_400 * x.pow(3) + 1_122_947_100 * x * y * y - 311_929_750 * y.pow(3)
            + 623_242_620_000 * z
    };
    let r = 16;
    let mut layer = std::collections::HashSet::new();
    for x in -r..=r {
        for y in -r..=r {
            for z in -30..=30 {
                let v = f(&[x, y, z]);
                if (L..=L + W).contains(&v) {
                    layer.insert(vec![x, y, z]);
                }
            }
        }
    }
    let mut s = PointSets::default();
    let mut seen = std::collections::HashSet::new();
    for p in &layer {
        s.inliers.push(p.clone());
        for d in cube(1) {
            let q: Vec<i64> = p.iter().zip(&d).map(|(a, b)| a + b).collect();
            if layer.contains(&q) || !seen.insert(q.clone()) {
                continue;
            }
            // (A neighbour outside the box may be in the layer: it is neither.)
            match f(&q) {
                v if v > L + W => s.above.push(q),
                v if v < L => s.below.push(q),
                _ => {}
            }
        }
    }
    s.inliers.sort();
    assert!(s.inliers.len() > 600, "{}", s.inliers.len());
    let res = recognize_points(&s, Model::Poly3(3)).unwrap();
    let PointsAnswer::Described {
        layer: Some(layer), ..
    } = &res.answer
    else {
        panic!("the cubic layer is not described: {:?}", res.answer);
    };
    let basis = Model::Poly3(3).basis();
    let v = |p: &Vec<i64>| layer.value(&basis, p).unwrap();
    assert!(s
        .inliers
        .iter()
        .all(|p| layer.lower <= v(p) && v(p) <= layer.upper));
    assert!(s.above.iter().all(|p| v(p) > layer.upper));
    assert!(s.below.iter().all(|p| v(p) < layer.lower));
    // And through the command line, checked from the JSON alone.
    let dir = tempfile::tempdir().unwrap();
    assert!(recognized(dir.path(), &s, "poly3:3"));
    // The inliers alone: a thinnest cubic layer whose exact coefficients are beyond 64 bits,
    // read from the JSON text and checked on every point in big integers.
    let (_, c, t) = thinnest(dir.path(), &s.inliers, "poly3:3");
    assert!(c.iter().any(|x| x.bits() > 64), "{c:?}");
    assert!(t.is_positive());
}

/// The integers of a list or number member of the one-line object `object` in the answer's
/// text, as big integers (serde_json would read those beyond 64 bits as doubles).
fn big_member(text: &str, object: &str, member: &str) -> Vec<BigInt> {
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with(&format!("\"{object}\": {{")))
        .unwrap_or_else(|| panic!("no {object} in {text}"));
    let key = format!("\"{member}\": ");
    let rest = &line[line.find(&key).unwrap() + key.len()..];
    let rest = rest.strip_prefix('[').map_or_else(
        || &rest[..rest.find([',', '}']).unwrap()],
        |r| &r[..r.find(']').unwrap()],
    );
    rest.split(',').map(|v| v.trim().parse().unwrap()).collect()
}

/// A layer without outliers through the CLI, checked from the JSON alone: the inliers
/// within the bounds (both reached, evaluated from the basis' names), the coefficients
/// without a common divisor, the thickness `(upper − lower) / max |c_i|` as written.
/// Returns the basis' names, the non-constant coefficients and the thickness.
fn thinnest(
    dir: &Path,
    inliers: &[Vec<i64>],
    model: &str,
) -> (Vec<String>, Vec<BigInt>, BigRational) {
    let s = PointSets::new(inliers.to_vec());
    std::fs::write(dir.join("t.json"), file_json(&s)).unwrap();
    let (code, out, err) = recognize(dir, &["t.json", "--model", model, "-q"], b"");
    assert_eq!(code, 0, "{err}");
    assert_eq!(err, "");
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["result"], "described");
    assert_eq!(v["thinnest"], true);
    assert_eq!(v["normalisation"], "max-abs");
    assert!(v.get("local").is_none() && v.get("witness").is_none());
    assert!(v["layer"]["above"].is_null() && v["layer"]["below"].is_null());
    let names: Vec<String> = v["basis"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap().to_string())
        .collect();
    let mut c = big_member(&out, "layer", "coefficients");
    assert_eq!(
        c.pop(),
        Some(BigInt::zero()),
        "the constant's coefficient is 0"
    );
    let lower = big_member(&out, "layer", "lower").remove(0);
    let upper = big_member(&out, "layer", "upper").remove(0);
    let values: Vec<BigInt> = inliers.iter().map(|p| big_value(&names, &c, p)).collect();
    assert!(values.iter().all(|x| lower <= *x && *x <= upper), "{model}");
    assert_eq!(values.iter().min(), Some(&lower));
    assert_eq!(values.iter().max(), Some(&upper));
    assert!(c.iter().fold(BigInt::zero(), |g, x| g.gcd(x)).is_one());
    let thickness: BigRational = v["thickness"].as_str().unwrap().parse().unwrap();
    assert_eq!(thickness, width(&values, &c).unwrap());
    (names, c, thickness)
}

/// `Σ c_i · basis_i(p)` over the non-constant functions, exactly.
fn big_value(names: &[String], c: &[BigInt], p: &[i64]) -> BigInt {
    let p: Vec<i128> = p.iter().map(|&x| i128::from(x)).collect();
    c.iter()
        .zip(names)
        .map(|(a, n)| a * BigInt::from(eval_name(n, &p)))
        .sum()
}

/// `(max − min) / max |c_i|` over the values; `None` for `c = 0`.
fn width(values: &[BigInt], c: &[BigInt]) -> Option<BigRational> {
    let norm = c.iter().map(BigInt::abs).max().filter(|n| !n.is_zero())?;
    let range = values.iter().max()? - values.iter().min()?;
    Some(BigRational::new(range, norm))
}

/// Without outliers, lines: the thickness written is the L∞-thinnest strip's, found by brute
/// force (its normal is orthogonal to an edge of the convex hull, so to some pair of points).
#[test]
fn without_outliers_the_thinnest_line_matches_brute_force() {
    let dir = tempfile::tempdir().unwrap();
    let mut next = rng(1998);
    for round in 0..25 {
        let count = 2 + next(15).unsigned_abs() as usize;
        let (cx, cy, r) = (next(100_000), next(100_000), 1 + next(30).abs());
        let points: Vec<Vec<i64>> = (0..count)
            .map(|_| vec![cx + next(r), cy + next(r)])
            .collect();
        let (_, _, t) = thinnest(dir.path(), &points, "line");
        let mut best: Option<BigRational> = None;
        for p in &points {
            for q in &points {
                let c = [BigInt::from(q[1] - p[1]), BigInt::from(p[0] - q[0])];
                let values: Vec<BigInt> =
                    points.iter().map(|x| &c[0] * x[0] + &c[1] * x[1]).collect();
                if let Some(w) = width(&values, &c) {
                    best = Some(best.map_or(w.clone(), |b| b.min(w)));
                }
            }
        }
        assert_eq!(
            Some(t),
            best.or(Some(BigRational::zero())),
            "round {round}: {points:?}"
        );
    }
}

/// Without outliers, digitized circles and conics and a 3-D quadric shell: the layer holds
/// every point (checked from the JSON), and no coefficient vector of a random family (near
/// the one found, and anywhere) gives a thinner layer.
#[test]
fn without_outliers_no_random_direction_is_thinner() {
    let dir = tempfile::tempdir().unwrap();
    let mut next = rng(2014);
    let circle = split(
        square(40, 9),
        |p| (p[0] - 41).pow(2) + (p[1] - 38).pow(2),
        30,
        50,
    )
    .inliers;
    let conic = split(
        square(-7, 9),
        |p| 3 * (p[0] + 7).pow(2) + 2 * (p[1] + 5).pow(2) - (p[0] + 7) * (p[1] + 5),
        60,
        85,
    )
    .inliers;
    let shell = split(
        cube(6),
        |p| 4 * p[0] * p[0] + 9 * p[1] * p[1] + 16 * p[2] * p[2] + 3 * p[0] * p[2],
        100,
        150,
    )
    .inliers;
    for (points, model) in [(&circle, "circle"), (&conic, "conic"), (&shell, "quadric3")] {
        assert!(points.len() > 30, "{model}");
        let (names, c, t) = thinnest(dir.path(), points, model);
        assert!(t.is_positive(), "{model}");
        let mut tried = 0;
        for k in 0..400 {
            let spread = if k % 2 == 0 { 3 } else { 1000 };
            let d: Vec<BigInt> = c.iter().map(|x| x * 100 + next(spread)).collect();
            let values: Vec<BigInt> = points.iter().map(|p| big_value(&names, &d, p)).collect();
            if let Some(w) = width(&values, &d) {
                assert!(w >= t, "{model}: {d:?} gives {w} < {t}");
                tried += 1;
            }
        }
        assert!(tried > 300);
    }
}

/// Without outliers, points on one curve (or surface) of the model: thickness 0.
#[test]
fn without_outliers_points_on_a_curve_have_thickness_zero() {
    let dir = tempfile::tempdir().unwrap();
    let line: Vec<Vec<i64>> = (0..12).map(|k| vec![1000 + 5 * k, -300 - 3 * k]).collect();
    let circle = split(square(0, 13), |p| p[0] * p[0] + p[1] * p[1], 169, 169).inliers;
    let plane: Vec<Vec<i64>> = cube(3)
        .map(|p| vec![p[0], p[1], 2 * p[0] - 3 * p[1] + 7])
        .collect();
    for (points, model) in [(&line, "line"), (&circle, "circle"), (&plane, "poly3:1")] {
        let (_, c, t) = thinnest(dir.path(), points, model);
        assert!(t.is_zero(), "{model}: {t}");
        assert!(c.iter().any(|x| !x.is_zero()));
    }
}

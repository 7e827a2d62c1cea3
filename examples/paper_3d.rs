//! The 3-D examples that open the article: an ellipsoidal and a cubic Digital Level Layer,
//! digitized in a box, recognized, checked exactly, and written as coloured point clouds:
//! `cargo run --release --example paper_3d -- [OUT_DIR]` (default `target/paper_3d`).
//!
//! For each layer `L ≤ f ≤ U`: the inliers are the integer points of the box in the layer;
//! the outliers are their 26-neighbours outside it, above (`f > U`) or below (`f < L`). The
//! example recognizes them (quadric3 for the ellipsoid, poly3:3 for the cubic), then a random
//! half of every set, then the inliers alone (no outliers: the thinnest layer holding them,
//! by exact linear programming), then the sets with one inlier of the middle declared above
//! (no longer described: a witness), and checks each layer on every point and each witness
//! exactly.
//! It writes `OUT_DIR/NAME.ply` (ASCII PLY, one vertex per point: inliers blue, points above
//! red, below green; MeshLab, CloudCompare or Blender open it) and `OUT_DIR/NAME.json`, the
//! point file for `layertrace recognize OUT_DIR/NAME.json --model poly3:3`.
//!
//! **What is the article's and what is ours.** The cubic layer has the form the article
//! gives, `3739455720000 ≤ −748631400x³ − … + 623242620000z ≤ 3739455720000 + 910277121600`,
//! with these very numbers; its middle terms (the "…") could not be found (the article's text
//! was not available here), so `+1122947100·x·y² − 311929750·y³` of our own stand for them.
//! The ellipsoid `14400 ≤ 36x² + 24xy + 64y² + 100z² ≤ 16800` is ours too (the article shows
//! its ellipsoidal and hyperboloidal layers as pictures): axes about 20, 15 and 12, a
//! thickness of about one voxel along the steepest axis.

use layertrace::{
    recognize_points, write_atomic, BigInt, BigRational, Model, PointSets, PointsAnswer,
    PointsRecognition,
};
use std::collections::HashSet;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

/// A layer to digitize: its function, bounds, box and model.
struct Example {
    name: &'static str,
    f: fn(i64, i64, i64) -> i128,
    lower: i128,
    upper: i128,
    /// Half-widths of the box around (0, 0, 0).
    half: [i64; 3],
    model: Model,
}

fn ellipsoid(x: i64, y: i64, z: i64) -> i128 {
    let (x, y, z) = (i128::from(x), i128::from(y), i128::from(z));
    36 * x * x + 24 * x * y + 64 * y * y + 100 * z * z
}

fn cubic(x: i64, y: i64, z: i64) -> i128 {
    let (x, y, z) = (i128::from(x), i128::from(y), i128::from(z));
    -748_631_400 * x * x * x + 1_122_947_100 * x * y * y - 311_929_750 * y * y * y
        + 623_242_620_000 * z
}

/// The layer's points in the box, and their 26-neighbours above and below it.
fn digitize(e: &Example) -> PointSets {
    let inside = |p: &[i64]| (e.lower..=e.upper).contains(&(e.f)(p[0], p[1], p[2]));
    let [hx, hy, hz] = e.half;
    let mut layer = Vec::new();
    for x in -hx..=hx {
        for y in -hy..=hy {
            for z in -hz..=hz {
                if inside(&[x, y, z]) {
                    layer.push(vec![x, y, z]);
                }
            }
        }
    }
    let mut sets = PointSets::new(layer);
    let mut seen: HashSet<Vec<i64>> = sets.inliers.iter().cloned().collect();
    for p in &sets.inliers {
        for d in 0..27 {
            let q = vec![p[0] + d % 3 - 1, p[1] + d / 3 % 3 - 1, p[2] + d / 9 - 1];
            let v = (e.f)(q[0], q[1], q[2]);
            // A neighbour outside the box may lie in the layer: it is neither.
            if (e.lower..=e.upper).contains(&v) || !seen.insert(q.clone()) {
                continue;
            }
            if v > e.upper {
                sets.above.push(q);
            } else {
                sets.below.push(q);
            }
        }
    }
    sets
}

/// Recognizes `sets`, checks the answer exactly on every point, prints a line.
fn run(what: &str, sets: &PointSets, model: Model) -> Result<PointsRecognition, String> {
    let start = Instant::now();
    let r = recognize_points(sets, model).map_err(|e| e.to_string())?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    let basis = model.basis();
    let answer = match &r.answer {
        PointsAnswer::Described {
            layer: Some(layer), ..
        } => {
            let v = |p: &Vec<i64>| layer.value(&basis, p).ok_or("no value");
            for p in &sets.inliers {
                let x = v(p)?;
                if x < layer.lower || x > layer.upper {
                    return Err(format!("{what}: inlier {p:?} outside the layer"));
                }
            }
            for (set, above) in [(&sets.above, true), (&sets.below, false)] {
                for p in set {
                    let x = v(p)?;
                    if (above && x <= layer.upper) || (!above && x >= layer.lower) {
                        return Err(format!("{what}: outlier {p:?} on the wrong side"));
                    }
                }
            }
            "described, checked on every point".to_string()
        }
        PointsAnswer::NotDescribed(w) => {
            if !w.verify(&basis) {
                return Err(format!("{what}: the witness does not hold"));
            }
            format!("not described, witness of {} pairs checked", w.pairs.len())
        }
        PointsAnswer::Thinnest(t) => {
            let layer = &t.layer;
            for p in &sets.inliers {
                let x = layer.value(&basis, p).ok_or("no value")?;
                if x < layer.lower || x > layer.upper {
                    return Err(format!("{what}: inlier {p:?} outside the layer"));
                }
            }
            let w = &t.work;
            format!(
                "thinnest layer, thickness {} (≈ {:.4}), checked on every point; {} programs ({} stopped early), {} pivots, {} rounds",
                t.thickness,
                ratio(&t.thickness),
                w.programs,
                w.pruned,
                w.pivots,
                w.rounds
            )
        }
        other => return Err(format!("{what}: unexpected answer {other:?}")),
    };
    println!(
        "  {what}: {} inliers, {} above, {} below: {answer} ({ms:.0} ms, {} float iterations, {} exact fallbacks)",
        sets.inliers.len(),
        sets.above.len(),
        sets.below.len(),
        r.stats.float_iterations,
        r.stats.exact_fallbacks
    );
    Ok(r)
}

/// An exact fraction as a float, for reading.
fn ratio(r: &BigRational) -> f64 {
    let f = |v: &BigInt| v.to_string().parse::<f64>().unwrap_or(f64::NAN);
    f(r.numer()) / f(r.denom())
}

/// The equation of a described recognition, `lower ≤ Σ c·f ≤ upper`.
fn equation(r: &PointsRecognition) -> String {
    let Some(layer) = r.layer() else {
        return String::new();
    };
    let mut s = String::new();
    for (c, name) in layer.coefficients.iter().zip(&r.basis) {
        if *c != BigInt::default() {
            let sign = if *c < BigInt::default() { "" } else { "+" };
            let _ = write!(s, " {sign}{c}·{name}");
        }
    }
    format!("{} ≤{s} ≤ {}", layer.lower, layer.upper)
}

/// A random half of each set (deterministic).
fn random_half(sets: &PointSets, seed: u64) -> PointSets {
    let mut s = seed;
    let mut keep = |v: &Vec<Vec<i64>>| -> Vec<Vec<i64>> {
        v.iter()
            .filter(|_| {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                s >> 63 == 1
            })
            .cloned()
            .collect()
    };
    PointSets::new(keep(&sets.inliers))
        .with_above(keep(&sets.above))
        .with_below(keep(&sets.below))
}

/// The ASCII PLY of the three sets, coloured.
fn ply(sets: &PointSets, comment: &str) -> String {
    let n = sets.inliers.len() + sets.above.len() + sets.below.len();
    let mut s = format!(
        "ply\nformat ascii 1.0\ncomment {comment}\ncomment blue: inliers, red: above, green: below\nelement vertex {n}\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
    );
    for (set, rgb) in [
        (&sets.inliers, "40 90 200"),
        (&sets.above, "220 50 40"),
        (&sets.below, "40 170 60"),
    ] {
        for p in set {
            let _ = writeln!(s, "{} {} {} {rgb}", p[0], p[1], p[2]);
        }
    }
    s
}

/// The point file of the sets.
fn json(sets: &PointSets) -> String {
    let list = |v: &Vec<Vec<i64>>| {
        let items: Vec<String> = v
            .iter()
            .map(|p| format!("[{},{},{}]", p[0], p[1], p[2]))
            .collect();
        format!("[{}]", items.join(","))
    };
    format!(
        "{{\"inliers\": {},\n \"above\": {},\n \"below\": {}}}\n",
        list(&sets.inliers),
        list(&sets.above),
        list(&sets.below)
    )
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args_os()
        .nth(1)
        .map_or_else(|| PathBuf::from("target/paper_3d"), PathBuf::from);
    std::fs::create_dir_all(&out)?;
    let examples = [
        Example {
            name: "ellipsoid",
            f: ellipsoid,
            lower: 14_400,
            upper: 16_800,
            half: [24, 18, 15],
            model: Model::Quadric3,
        },
        Example {
            name: "cubic",
            f: cubic,
            lower: 3_739_455_720_000,
            upper: 3_739_455_720_000 + 910_277_121_600,
            half: [20, 20, 40],
            model: Model::Poly3(3),
        },
    ];
    for e in &examples {
        println!(
            "{} layer, {} ≤ f ≤ {}, model {}:",
            e.name, e.lower, e.upper, e.model
        );
        let sets = digitize(e);
        let r = run("all points", &sets, e.model)?;
        println!("  layer found: {}", equation(&r));
        run("a random half", &random_half(&sets, 2014), e.model)?;
        // The inliers alone: the thinnest layer of the model holding them.
        let alone = PointSets::new(sets.inliers.clone());
        let r = run("the inliers alone", &alone, e.model)?;
        println!("  thinnest layer: {}", equation(&r));
        // The inlier nearest the layer's middle value, declared above.
        let mut broken = sets.clone();
        let mid = (e.lower + e.upper) / 2;
        let k = (0..broken.inliers.len())
            .min_by_key(|&k| {
                let p = &broken.inliers[k];
                ((e.f)(p[0], p[1], p[2]) - mid).abs()
            })
            .unwrap_or(0);
        let moved = broken.inliers.swap_remove(k);
        broken.above.push(moved);
        run("its middle inlier declared above", &broken, e.model)?;
        let comment = format!("layertrace examples/paper_3d.rs: {} layer", e.name);
        write_atomic(
            &out.join(format!("{}.ply", e.name)),
            ply(&sets, &comment).as_bytes(),
        )?;
        write_atomic(
            &out.join(format!("{}.json", e.name)),
            json(&sets).as_bytes(),
        )?;
        println!("  wrote {}/{}.ply and .json", out.display(), e.name);
    }
    Ok(())
}

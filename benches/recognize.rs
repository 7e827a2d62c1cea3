//! Recognition speed: digitized circle and ellipse arcs grown point by point (their
//! 4-neighbours as outliers), for each 2D basis. Criterion's throughput is in added points,
//! so `time / points` is the cost per added point.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use layertrace::{decompose_points, Basis, Model, OutlierRule, Pixel, Recognizer};
use std::hint::black_box;
use std::sync::Arc;

/// A digital curve: dense samples of `point(t)`, rounded to pixels, consecutive duplicates
/// dropped (8-connected because samples are much closer than a pixel).
fn digitize(point: impl Fn(f64) -> (f64, f64), t0: f64, t1: f64) -> Vec<Pixel> {
    let steps = 200_000;
    let mut out: Vec<Pixel> = Vec::new();
    for i in 0..=steps {
        let t = t0 + (t1 - t0) * i as f64 / steps as f64;
        let (x, y) = point(t);
        let p = Pixel::new(x.floor() as i32, y.floor() as i32);
        if out.last() != Some(&p) {
            // Drop corner-cutting duplicates: keep the path 8-connected and thin.
            if out.len() >= 2 && out[out.len() - 2].is_8_adjacent(p) {
                out.pop();
            }
            out.push(p);
        }
    }
    out
}

fn arcs() -> Vec<(&'static str, Vec<Pixel>)> {
    let circle = digitize(
        |t| (500.0 + 300.0 * t.cos(), 500.0 + 300.0 * t.sin()),
        0.0,
        std::f64::consts::FRAC_PI_2,
    );
    let (a, b, th) = (320.0f64, 140.0f64, 0.5f64);
    let ellipse = digitize(
        |t| {
            let (x, y) = (a * t.cos(), b * t.sin());
            (
                500.0 + x * th.cos() - y * th.sin(),
                500.0 + x * th.sin() + y * th.cos(),
            )
        },
        0.0,
        std::f64::consts::PI,
    );
    vec![
        ("circle_r300_quarter", circle),
        ("ellipse_320x140_half", ellipse),
    ]
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("grow");
    group.sample_size(10);
    for (name, arc) in arcs() {
        assert!(arc.windows(2).all(|w| w[0].is_8_adjacent(w[1])));
        group.throughput(Throughput::Elements(arc.len() as u64));
        for model in [
            Model::Line,
            Model::Circle,
            Model::Conic,
            Model::Poly(3),
            Model::Poly(4),
        ] {
            let basis: Arc<dyn Basis> = Arc::new(model.basis());
            group.bench_with_input(BenchmarkId::new(model.name(), name), &arc, |bch, arc| {
                let mut rec = Recognizer::new(basis.clone(), &[0, 0]).expect("2D basis");
                bch.iter(|| {
                    black_box(decompose_points(arc, &mut rec, OutlierRule::NotInPiece).len())
                });
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

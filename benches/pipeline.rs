//! Speed of every stage (loading, tracing, decomposition per model, SVG export, fidelity
//! rasterization) on a small glyph, a ~1000×1000 page of glyphs and a 3000×3000 image with
//! many shapes; and decomposition of digital disc borders of 10³ to 10⁶ pixels on one
//! thread (throughput in contour pixels: flat time per pixel shows linear cost). Compare
//! stages and images as ratios within one run.

#[path = "../examples/common/disc.rs"]
mod disc;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use layertrace::{
    compare, decompose, load_path, rasterize_svg, svg_document, trace, Contour, Convention,
    LoadOptions, Model, OutlierRule, SvgOptions,
};
use std::hint::black_box;
use std::path::{Path, PathBuf};

/// A 1000×1000 page tiled with the bundled glyph and word samples.
fn make_page() -> PathBuf {
    let tiles = [
        "samples/word_Layers_dejavusans-bold_cap40.png",
        "samples/digits_liberationsans_cap40.png",
        "samples/glyph_g_liberationserif_cap120.png",
        "samples/glyph_S_dejavusans_cap120.png",
        "samples/glyph_at_dejavusans_cap40.png",
    ];
    let mut page = image::GrayImage::from_pixel(1000, 1000, image::Luma([255]));
    let (mut x, mut y, mut row_h) = (0u32, 0u32, 0u32);
    'fill: loop {
        for t in tiles {
            let img = image::open(t).expect("bundled sample").to_luma8();
            if x + img.width() > 1000 {
                x = 0;
                y += row_h;
                row_h = 0;
            }
            if y + img.height() > 1000 {
                break 'fill;
            }
            image::imageops::replace(&mut page, &img, i64::from(x), i64::from(y));
            x += img.width();
            row_h = row_h.max(img.height());
        }
    }
    let path = std::env::temp_dir().join("layertrace-bench-page.png");
    page.save(&path).expect("temporary file");
    path
}

fn bench(c: &mut Criterion) {
    let inputs = [
        (
            "glyph_g",
            PathBuf::from("samples/glyph_g_liberationserif_cap120.png"),
        ),
        ("page1000", make_page()),
        (
            "shapes3000",
            PathBuf::from("samples/syn_big3000_many_shapes.png"),
        ),
    ];
    let opts = LoadOptions::default();
    let mut g = c.benchmark_group("stage");
    g.sample_size(10);
    for (name, path) in &inputs {
        let mask = load_path(Path::new(path), &opts).expect("input").mask;
        let pixels = u64::from(mask.width()) * u64::from(mask.height());
        g.throughput(Throughput::Elements(pixels));
        g.bench_function(BenchmarkId::new("load", name), |b| {
            b.iter(|| black_box(load_path(path, &opts).expect("input")))
        });
        g.bench_function(BenchmarkId::new("trace", name), |b| {
            b.iter(|| black_box(trace(&mask, Convention::Default)))
        });
        let contours = trace(&mask, Convention::Default);
        for model in [Model::Line, Model::Circle, Model::Conic] {
            g.bench_function(BenchmarkId::new(format!("decompose_{model}"), name), |b| {
                b.iter(|| black_box(decompose(contours.clone(), model, OutlierRule::NotInPiece)))
            });
        }
        let d = decompose(contours.clone(), Model::Conic, OutlierRule::NotInPiece);
        let svg_opts = SvgOptions::default();
        g.bench_function(BenchmarkId::new("svg_conic", name), |b| {
            b.iter(|| black_box(svg_document(&d, mask.width(), mask.height(), &svg_opts)))
        });
        let svg = svg_document(&d, mask.width(), mask.height(), &svg_opts).svg;
        g.bench_function(BenchmarkId::new("fidelity", name), |b| {
            b.iter(|| {
                let actual = rasterize_svg(&svg, mask.width(), mask.height()).expect("svg");
                black_box(compare(&mask, &actual))
            })
        });
    }
    g.finish();
}

/// Decomposition of one disc border per size and model, single thread.
fn discs(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("thread pool");
    let mut g = c.benchmark_group("disc_border");
    g.sample_size(10);
    for r in [180.0, 1800.0, 18_000.0, 180_000.0] {
        let points = disc::disc_border(r);
        g.throughput(Throughput::Elements(points.len() as u64));
        for model in [Model::Line, Model::Circle, Model::Conic] {
            let contours = vec![Contour {
                points: points.clone(),
                hole: false,
                closed: true,
            }];
            g.bench_function(BenchmarkId::new(model.to_string(), points.len()), |b| {
                b.iter(|| {
                    let c = contours.clone();
                    black_box(pool.install(|| decompose(c, model, OutlierRule::NotInPiece)))
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench, discs);
criterion_main!(benches);

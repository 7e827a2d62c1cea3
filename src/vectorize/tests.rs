//! Tests of the one-call entry point against the stages called one by one.

use super::*;
use crate::bitmap::Threshold;
use crate::decompose::decompose;
use crate::export::svg::{svg_document, SvgOptions};
use crate::model::Model;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// A ring and a bar: an outer border with a hole, and a second shape.
fn shapes() -> Mask {
    Mask::from_fn(40, 30, |x, y| {
        let (dx, dy) = (x as f64 - 14.5, y as f64 - 14.5);
        let r2 = dx * dx + dy * dy;
        (40.0..=144.0).contains(&r2) || ((31..36).contains(&x) && (4..26).contains(&y))
    })
}

#[test]
fn same_as_the_stages_called_one_by_one() {
    let mask = shapes();
    for model in [Model::Line, Model::Circle, Model::Conic] {
        let out = vectorize(&mask, &Options::default().model(model).fidelity(true)).unwrap();
        let d = decompose(
            trace(&mask, Convention::Default),
            model,
            OutlierRule::NotInPiece,
        );
        let svg = svg_document(&d, 40, 30, &SvgOptions::default());
        assert_eq!(out.svg_text(), svg.svg, "{model}");
        assert_eq!(out.decomposition.piece_count(), d.piece_count());
        let f = out.fidelity.unwrap();
        assert_eq!(f.report.differing, 0, "{model}");
        assert_eq!(f.rendered, mask);
        assert!(out.json.is_none() && out.picture.is_none());
    }
}

#[test]
fn bytes_and_mask_inputs_agree() {
    let mask = shapes();
    // The mask as a PNG, black ink on white.
    let img = image::GrayImage::from_fn(40, 30, |x, y| {
        image::Luma([if mask.get(x.into(), y.into()) { 0 } else { 255 }])
    });
    let mut png = Vec::new();
    img.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let from_bytes = vectorize(&png, &Options::default().json(true)).unwrap();
    let from_mask = vectorize(&mask, &Options::default()).unwrap();
    assert_eq!(from_bytes.mask, mask);
    assert_eq!(from_bytes.threshold, 128);
    assert_eq!(from_bytes.svg_text(), from_mask.svg_text());
    assert!(from_bytes.json.unwrap().contains("\"threshold\": 128"));

    // Otsu on a two-level image picks a threshold between the levels.
    let otsu = vectorize(&png, &Options::default().threshold(Threshold::Otsu)).unwrap();
    assert_eq!(otsu.mask, mask);
    assert!((1..=255).contains(&otsu.threshold));
    // Inverted, the background becomes the foreground.
    let inv = vectorize(&png, &Options::default().invert(true).no_svg()).unwrap();
    assert_eq!(
        inv.mask.count_foreground(),
        40 * 30 - mask.count_foreground()
    );
    assert!(inv.svg.is_none() && inv.svg_text().is_empty());
}

#[test]
fn pool_and_progress() {
    let mask = shapes();
    let pool = Arc::new(
        rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap(),
    );
    let seen = Arc::new(Mutex::new(Vec::new()));
    let calls = Arc::new(AtomicU64::new(0));
    let (s, c) = (seen.clone(), calls.clone());
    let options = Options::default().pool(pool).progress(Arc::new(move |p| {
        c.fetch_add(1, Ordering::Relaxed);
        s.lock().unwrap().push(p);
    }));
    let out = vectorize(&mask, &options).unwrap();
    assert_eq!(
        out.svg_text(),
        vectorize(&mask, &Options::default()).unwrap().svg_text()
    );
    let seen = seen.lock().unwrap();
    let contours = out.decomposition.contours.len() as u64;
    assert_eq!(contours, 3);
    for stage in [Stage::Decompose, Stage::Draw] {
        let done = seen
            .iter()
            .filter(|p| p.stage == stage)
            .map(|p| p.done)
            .max();
        assert_eq!(done, Some(contours), "{stage:?}");
        assert!(seen
            .iter()
            .all(|p| p.total == contours && p.done <= p.total));
    }
    // One thread: each stage counts up, and is told at most once per task or group of
    // contours.
    for stage in [Stage::Decompose, Stage::Draw] {
        let done: Vec<u64> = seen
            .iter()
            .filter(|p| p.stage == stage)
            .map(|p| p.done)
            .collect();
        assert!(done.windows(2).all(|w| w[0] < w[1]), "{stage:?}: {done:?}");
    }
    // The decomposition tells once per task (at most 256 contours, and at least 64 tasks
    // when there are that many contours), the drawing once per group of 4096 contours.
    let tasks = contours.min(64) + contours / 256 + 1;
    assert!(calls.load(Ordering::Relaxed) <= tasks + contours / 4096 + 1);
}

#[test]
fn picture_and_limits() {
    let mask = shapes();
    let out = vectorize(&mask, &Options::default().no_svg().picture(Some(2))).unwrap();
    let png = out.picture.unwrap();
    let img = image::load_from_memory(&png).unwrap();
    assert_eq!((img.width(), img.height()), (80, 60));

    // Too little memory for the work after tracing: refused, naming the input.
    let e = vectorize(&mask, &Options::default().max_memory(1000)).unwrap_err();
    assert!(matches!(e, Error::NeedsMemory { .. }), "{e}");
    assert!(e.to_string().contains("<mask>"), "{e}");

    // A picture too large for max_pixels is refused, not drawn.
    let e = vectorize(&mask, &Options::default().picture(Some(3000))).unwrap_err();
    assert!(
        matches!(e, Error::PictureTooLarge { scale: 3000, .. }),
        "{e}"
    );

    // A corrupt file is an error, not a panic.
    let e = vectorize(&b"\x89PNG\r\n\x1a\nnot really"[..], &Options::default()).unwrap_err();
    assert!(e.to_string().contains("<memory>"), "{e}");
}

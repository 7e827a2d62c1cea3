//! Arbitrary small bitmaps (first two bytes: width and height up to 32, then the bits)
//! through tracing and decomposition with every model and both conventions; every piece's
//! certificate is re-checked.
#![no_main]

use layertrace::{
    decompose, piece_outliers, trace, Convention, Mask, Model, OutlierRule, Pixel,
};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if data.len() < 2 {
        return;
    }
    let (w, h) = (u32::from(data[0] % 32) + 1, u32::from(data[1] % 32) + 1);
    let bits = &data[2..];
    let mask = Mask::from_fn(w, h, |x, y| {
        let i = (y * w + x) as usize;
        bits.get(i / 8).is_some_and(|b| b >> (i % 8) & 1 == 1)
    });
    for (convention, rule) in [
        (Convention::Default, OutlierRule::NotInPiece),
        (Convention::Ipol, OutlierRule::Any),
    ] {
        let contours = trace(&mask, convention);
        for model in [Model::Line, Model::Circle, Model::Conic, Model::Poly(3)] {
            let d = decompose(contours.clone(), model, rule);
            assert_eq!(d.stats.undecided, 0);
            let basis = model.basis();
            for (c, pieces) in d.contours.iter().zip(&d.pieces) {
                for p in pieces {
                    let cert = &p.certificate;
                    let v = |q: &Pixel| cert.value(&basis, &[q.x as i64, q.y as i64]).unwrap();
                    for q in &c.points[p.first..=p.last] {
                        assert!(cert.lower <= v(q) && v(q) <= cert.upper);
                    }
                    let (r, l) = piece_outliers(&c.points, p.first, p.last, rule);
                    assert!(r.iter().all(|q| v(q) > cert.upper));
                    assert!(l.iter().all(|q| v(q) < cert.lower));
                }
            }
        }
    }
});

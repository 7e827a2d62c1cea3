//! The largest-margin lines of small straight segments, remembered by shape: noise and
//! halftones draw the same few segments (a pixel or two with the pixels beside them) tens
//! of thousands of times.
//!
//! [`max_margin_direction`] in the line basis works on the side sets relative to the
//! segment's first pixel, in exact integer arithmetic up to its last `f64` steps, so its
//! answer depends only on the two lists of offsets (in their order): two segments of the
//! same shape get the same direction and level, bit for bit, wherever they are. A memo keyed
//! by those offsets returns what the solver would; nothing else changes.

use crate::model::Basis;
use crate::pixel::Pixel;
use crate::recognize::{max_margin_direction, MarginDirection};
use std::cell::RefCell;

/// Most side pixels (both lists together) of a remembered segment: the shapes that repeat
/// are small (a segment of a few pixels has about twice as many beside it).
const MAX_PIXELS: usize = 16;

/// Entries kept on one thread before the memo starts again: bounds its memory (a few MB)
/// on images whose small segments are all different.
const MAX_ENTRIES: usize = 1 << 16;

/// The offsets of a segment's side pixels from its first pixel, lower list first.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
struct Key {
    /// Lengths of the two lists.
    lengths: [u8; 2],
    /// `dx, dy` of each pixel, the lower list's then the upper's; zero after them.
    offsets: [i8; 2 * MAX_PIXELS],
}

impl Key {
    /// Returns None if the lists are too long or an offset does not fit in `i8`.
    fn new(origin: Pixel, low: &[Pixel], high: &[Pixel]) -> Option<Key> {
        if low.len() + high.len() > MAX_PIXELS {
            return None;
        }
        let mut offsets = [0i8; 2 * MAX_PIXELS];
        for (k, p) in low.iter().chain(high).enumerate() {
            offsets[2 * k] = i8::try_from(i64::from(p.x) - i64::from(origin.x)).ok()?;
            offsets[2 * k + 1] = i8::try_from(i64::from(p.y) - i64::from(origin.y)).ok()?;
        }
        Some(Key {
            lengths: [low.len() as u8, high.len() as u8],
            offsets,
        })
    }
}

thread_local! {
    /// The directions found on this thread, by shape.
    static MEMO: RefCell<rustc_hash::FxHashMap<Key, Option<MarginDirection>>> =
        RefCell::new(rustc_hash::FxHashMap::default());
}

/// [`max_margin_direction`] of `low` and `high` relative to `origin`, unscaled, in `line`
/// (the line model's basis), remembered for small sets (see the module documentation).
pub(super) fn line_margin(
    line: &dyn Basis,
    origin: Pixel,
    low: &[Pixel],
    high: &[Pixel],
) -> Option<MarginDirection> {
    let solve = || {
        let xy = |p: &Pixel| [i64::from(p.x), i64::from(p.y)];
        let (low, high): (Vec<[i64; 2]>, Vec<[i64; 2]>) =
            (low.iter().map(xy).collect(), high.iter().map(xy).collect());
        max_margin_direction(line, &xy(&origin), &low, &high, false)
    };
    let Some(key) = Key::new(origin, low, high) else {
        return solve();
    };
    MEMO.with(|memo| {
        if let Some(found) = memo.borrow().get(&key) {
            return found.clone();
        }
        let found = solve();
        let mut memo = memo.borrow_mut();
        if memo.len() >= MAX_ENTRIES {
            memo.clear();
        }
        memo.insert(key, found.clone());
        found
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Model;
    use proptest::prelude::*;

    proptest! {
        /// The remembered answer is the solver's, wherever the segment is: random points
        /// split by a random line (mostly separable, so the answers differ from case to
        /// case), solved at several places, the memo filled by the cases before.
        #[test]
        fn remembered_is_solved(
            points in proptest::collection::vec((-4i32..4, -4i32..4), 2..14),
            line in (-3i32..=3, -3i32..=3, -6i32..6),
            at in proptest::collection::vec((-3000i32..3000, -3000i32..3000), 1..4),
        ) {
            let basis = Model::Line.basis();
            let (a, b, c) = line;
            // Never zero: the constant is odd, the rest even.
            let side = |&(x, y): &(i32, i32)| 2 * (a * x + b * y) + 2 * c + 1 > 0;
            let high: Vec<(i32, i32)> = points.iter().copied().filter(side).collect();
            let low: Vec<(i32, i32)> = points.iter().copied().filter(|p| !side(p)).collect();
            for (ox, oy) in at {
                let origin = Pixel::new(ox, oy);
                let moved = |set: &[(i32, i32)]| -> Vec<Pixel> {
                    set.iter().map(|&(x, y)| Pixel::new(ox + x, oy + y)).collect()
                };
                let (l, h) = (moved(&low), moved(&high));
                let xy = |p: &Pixel| [i64::from(p.x), i64::from(p.y)];
                let li: Vec<[i64; 2]> = l.iter().map(xy).collect();
                let hi: Vec<[i64; 2]> = h.iter().map(xy).collect();
                let direct = max_margin_direction(&basis, &xy(&origin), &li, &hi, false);
                // Twice: the first may fill the memo, the second reads it.
                prop_assert_eq!(&line_margin(&basis, origin, &l, &h), &direct);
                prop_assert_eq!(&line_margin(&basis, origin, &l, &h), &direct);
            }
        }

        /// Two segments share a key exactly when their side lists, relative to their first
        /// pixels, are the same.
        #[test]
        fn keys_tell_shapes_apart(
            a in proptest::collection::vec((-2i32..2, -2i32..2), 1..6),
            b in proptest::collection::vec((-2i32..2, -2i32..2), 1..6),
            split in (0usize..6, 0usize..6),
            origin in (-100i32..100, -100i32..100, -100i32..100, -100i32..100),
        ) {
            let (o1, o2) = (Pixel::new(origin.0, origin.1), Pixel::new(origin.2, origin.3));
            let place = |o: Pixel, set: &[(i32, i32)]| -> Vec<Pixel> {
                set.iter().map(|&(x, y)| Pixel::new(o.x + x, o.y + y)).collect()
            };
            let (pa, pb) = (place(o1, &a), place(o2, &b));
            let (sa, sb) = (split.0.min(pa.len()), split.1.min(pb.len()));
            let ka = Key::new(o1, &pa[..sa], &pa[sa..]).unwrap();
            let kb = Key::new(o2, &pb[..sb], &pb[sb..]).unwrap();
            prop_assert_eq!(ka == kb, sa == sb && a == b);
        }
    }
}

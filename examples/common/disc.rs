//! Digital disc borders for the scaling example and the disc benchmark (included by
//! `#[path]`): one 8-connected closed contour of about `5.66 r` pixels, built directly.

use layertrace::Pixel;
use std::collections::HashSet;

/// The border (pixels inside with a 4-neighbour outside) of the disc of pixel centres within
/// `r` of the corner (0, 0), counter-clockwise on screen from the angle −π.
pub fn disc_border(r: f64) -> Vec<Pixel> {
    // Highest inside row of column x (centres symmetric about y = −1/2), if any.
    let top = |x: i64| -> Option<i64> {
        let fx = x as f64 + 0.5;
        (fx.abs() <= r).then(|| ((r * r - fx * fx).sqrt() - 0.5).floor() as i64)
    };
    let ri = r.ceil() as i64 + 1;
    let mut set = HashSet::new();
    for x in -ri..=ri {
        let Some(t) = top(x) else { continue };
        if t < -1 - t {
            continue; // empty column
        }
        let lowest = match (top(x - 1), top(x + 1)) {
            (Some(a), Some(b)) => a.min(b).max(-1 - t - 1) + 1,
            _ => -1 - t, // an outermost column: all border
        };
        for y in lowest.min(t)..=t {
            set.insert(Pixel::new(x as i32, y as i32));
            set.insert(Pixel::new(x as i32, (-1 - y) as i32));
        }
    }
    let mut v: Vec<Pixel> = set.into_iter().collect();
    let angle = |p: &Pixel| -((p.y as f64 + 0.5).atan2(p.x as f64 + 0.5));
    v.sort_by_cached_key(|p| OrderedAngle(angle(p)));
    v
}

/// An angle ordered by `f64::total_cmp`.
#[derive(PartialEq)]
struct OrderedAngle(f64);

impl Eq for OrderedAngle {}

impl PartialOrd for OrderedAngle {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for OrderedAngle {
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&o.0)
    }
}

//! The contour points nearest to pixels the render check found wrong, where the remedies apply.

use crate::pixel::Pixel;

/// The squared distance between two pixels.
fn distance2(p: Pixel, q: Pixel) -> i64 {
    let (dx, dy) = (i64::from(p.x - q.x), i64::from(p.y - q.y));
    dx * dx + dy * dy
}

/// Indices of the contour points nearest to each of `pixels` (each index once, ascending).
/// With the contour's crack polygon as the reference of
/// [`super::render_check::misplaced_pixels`] — exactly the pixels the contour encloses — a
/// path that differs nowhere paints exactly those, so the nonzero sum of all contours'
/// paths is the image: this catches a curve cutting a pixel of a neighbouring contour too,
/// not only the contour's own pixels and the background beside them.
pub(crate) fn nearest_points(points: &[Pixel], pixels: &[Pixel]) -> Vec<usize> {
    let mut out: Vec<usize> = if pixels.len() * points.len() <= NEAREST_SCAN {
        pixels
            .iter()
            .filter_map(|&q| (0..points.len()).min_by_key(|&i| distance2(points[i], q)))
            .collect()
    } else {
        let cells = Cells::new(points);
        pixels
            .iter()
            .filter_map(|&q| cells.nearest(points, q))
            .collect()
    };
    out.sort_unstable();
    out.dedup();
    out
}

/// Up to this many point–pixel pairs, [`nearest_points`] compares them all.
const NEAREST_SCAN: usize = 4096;

/// Side (pixels) of the square cells [`Cells`] sorts points into.
const CELL: i32 = 8;

/// A contour's point indices by square cell of [`CELL`] pixels, for nearest-point queries.
struct Cells {
    map: crate::pixel::PixelMap<Vec<usize>>,
    /// Smallest and largest cell coordinates holding a point.
    lo: Pixel,
    hi: Pixel,
}

impl Cells {
    fn cell(p: Pixel) -> Pixel {
        Pixel::new(p.x.div_euclid(CELL), p.y.div_euclid(CELL))
    }

    fn new(points: &[Pixel]) -> Cells {
        let mut map = crate::pixel::PixelMap::<Vec<usize>>::default();
        let (mut lo, mut hi) = (
            Pixel::new(i32::MAX, i32::MAX),
            Pixel::new(i32::MIN, i32::MIN),
        );
        for (i, &p) in points.iter().enumerate() {
            let c = Cells::cell(p);
            lo = Pixel::new(lo.x.min(c.x), lo.y.min(c.y));
            hi = Pixel::new(hi.x.max(c.x), hi.y.max(c.y));
            map.entry(c).or_default().push(i);
        }
        Cells { map, lo, hi }
    }

    /// The index of the point nearest to `q` (Euclidean; the smallest index among equals,
    /// as a scan of all points finds), searching rings of cells round `q`'s: a point in a
    /// cell outside ring `r` differs from `q` by more than `r · CELL` in x or in y.
    fn nearest(&self, points: &[Pixel], q: Pixel) -> Option<usize> {
        let c = Cells::cell(q);
        let mut best: Option<(i64, usize)> = None;
        let far = [
            c.x.abs_diff(self.lo.x),
            c.x.abs_diff(self.hi.x),
            c.y.abs_diff(self.lo.y),
            c.y.abs_diff(self.hi.y),
        ]
        .into_iter()
        .max()?;
        for r in 0..=far as i32 {
            for cy in c.y - r..=c.y + r {
                let edge_row = cy == c.y - r || cy == c.y + r;
                let mut cx = c.x - r;
                while cx <= c.x + r {
                    if let Some(ids) = self.map.get(&Pixel::new(cx, cy)) {
                        for &i in ids {
                            let key = (distance2(points[i], q), i);
                            if best.is_none_or(|b| key < b) {
                                best = Some(key);
                            }
                        }
                    }
                    cx += if edge_row || r == 0 { 1 } else { 2 * r };
                }
            }
            if let Some((d, _)) = best {
                let reach = i64::from(r) * i64::from(CELL) + 1;
                if d < reach * reach {
                    break;
                }
            }
        }
        best.map(|(_, i)| i)
    }
}

/// Indices of the contour points within `radius` (in x and in y) of any of `pixels`.
pub(crate) fn points_near(points: &[Pixel], pixels: &[Pixel], radius: i32) -> Vec<usize> {
    (0..points.len())
        .filter(|&i| {
            let p = points[i];
            pixels
                .iter()
                .any(|q| (p.x - q.x).abs() <= radius && (p.y - q.y).abs() <= radius)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(300))]
        /// The cell search finds the point a scan of all points finds (ties included: many
        /// repeated points on a small range), near the points and far from them.
        #[test]
        fn cells_find_what_a_scan_finds(
            pts in proptest::collection::vec((-40i32..40, -40i32..40), 1..60),
            qs in proptest::collection::vec((-120i32..120, -120i32..120), 1..20),
        ) {
            let points: Vec<Pixel> = pts.iter().map(|&(x, y)| Pixel::new(x, y)).collect();
            let cells = Cells::new(&points);
            for &(x, y) in &qs {
                let q = Pixel::new(x, y);
                let scan = (0..points.len()).min_by_key(|&i| {
                    let (dx, dy) = (i64::from(points[i].x - x), i64::from(points[i].y - y));
                    dx * dx + dy * dy
                });
                proptest::prop_assert_eq!(cells.nearest(&points, q), scan);
            }
        }
    }
}

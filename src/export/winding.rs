//! Winding numbers of a closed path at pixel centres, row by row: the exporter's check that
//! every contour pixel, and the background beside it, is on the right side of its own path.

use kurbo::{BezPath, Point};

/// The `x` where the `y`-monotone part `t0..t1` of `seg` (from height `ya`) crosses the
/// height `yc`: the Illinois variant of regula falsi, which keeps the root bracketed and
/// converges superlinearly (a few evaluations where bisection takes fifty).
fn crossing_x(seg: kurbo::PathSeg, t0: f64, t1: f64, ya: f64, yc: f64) -> f64 {
    use kurbo::ParamCurve;
    let (mut a, mut b) = (t0, t1);
    let (mut fa, mut fb) = (ya - yc, seg.eval(t1).y - yc);
    let mut side = 0;
    for _ in 0..60 {
        if fa == fb || (b - a).abs() <= 1e-12 {
            break;
        }
        let t = ((a * fb - b * fa) / (fb - fa)).clamp(a.min(b), a.max(b));
        let ft = seg.eval(t).y - yc;
        if ft == 0.0 {
            return seg.eval(t).x;
        }
        if (ft < 0.0) == (fa < 0.0) {
            a = t;
            fa = ft;
            if side == -1 {
                fb /= 2.0;
            }
            side = -1;
        } else {
            b = t;
            fb = ft;
            if side == 1 {
                fa /= 2.0;
            }
            side = 1;
        }
        if fa.abs().min(fb.abs()) <= 1e-12 {
            break;
        }
    }
    let t = if fa.abs() <= fb.abs() { a } else { b };
    seg.eval(t).x
}

/// Winding numbers at pixel centres, from the crossings of the path with each row's
/// centre line `y = r + ½`, computed once per row: the winding number at `(x, r + ½)` is
/// the sum of the directions (±1) of the crossings left of `x`.
///
/// Each segment is cut at its extrema into `y`-monotone pieces; a piece from `y_a` to `y_b`
/// crosses the centre line `y_c` when `min(y_a, y_b) ≤ y_c < max(y_a, y_b)` (half-open, so a
/// vertex on the line is counted once when the path passes through it, and zero or twice
/// with opposite signs when it turns there), at the parameter found by bisection.
pub(crate) struct RowWinding {
    first_row: i64,
    /// Per row: the crossings' `x`, sorted, with the running sum of directions.
    rows: Vec<Vec<(f64, i32)>>,
}

impl RowWinding {
    /// Largest number of rows indexed (a guard for degenerate, huge coordinates).
    const MAX_ROWS: i64 = 1 << 24;

    pub(crate) fn new(path: &BezPath) -> RowWinding {
        use kurbo::{ParamCurve, ParamCurveExtrema};
        let segs: Vec<kurbo::PathSeg> = path.segments().collect();
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for seg in &segs {
            let b = seg.bounding_box();
            lo = lo.min(b.y0);
            hi = hi.max(b.y1);
        }
        if !(lo.is_finite() && hi.is_finite()) {
            return RowWinding {
                first_row: 0,
                rows: Vec::new(),
            };
        }
        // Rows whose centre line can be crossed: r + ½ in [lo, hi].
        let first_row = (lo - 0.5).ceil() as i64;
        let last_row = ((hi - 0.5).floor() as i64).min(first_row + Self::MAX_ROWS - 1);
        let count = (last_row - first_row + 1).max(0) as usize;
        let mut rows: Vec<Vec<(f64, i32)>> = vec![Vec::new(); count];
        for seg in &segs {
            let mut cuts = vec![0.0];
            cuts.extend(seg.extrema().into_iter().filter(|t| *t > 0.0 && *t < 1.0));
            cuts.push(1.0);
            cuts.sort_by(f64::total_cmp);
            for w in cuts.windows(2) {
                let (t0, t1) = (w[0], w[1]);
                // The segment's own end points where they are meant (an evaluation at 1 can
                // miss the end by an ulp, and a vertex on a centre line would then count twice
                // or not at all).
                let y_at = |t: f64| {
                    if t == 0.0 {
                        seg.start().y
                    } else if t == 1.0 {
                        seg.end().y
                    } else {
                        seg.eval(t).y
                    }
                };
                let (ya, yb) = (y_at(t0), y_at(t1));
                if ya == yb {
                    continue;
                }
                // kurbo's sign convention: downward crossings (on screen, y growing) count +1.
                let dir = if yb > ya { -1 } else { 1 };
                let (ymin, ymax) = (ya.min(yb), ya.max(yb));
                let r0 = ((ymin - 0.5).ceil() as i64).max(first_row);
                let r1 = ((ymax - 0.5).ceil() as i64 - 1).min(last_row);
                for r in r0..=r1 {
                    let yc = r as f64 + 0.5;
                    if !(ymin <= yc && yc < ymax) {
                        continue;
                    }
                    let x = match seg {
                        kurbo::PathSeg::Line(l) => {
                            l.p0.x + (l.p1.x - l.p0.x) * ((yc - l.p0.y) / (l.p1.y - l.p0.y))
                        }
                        _ => crossing_x(*seg, t0, t1, ya, yc),
                    };
                    rows[(r - first_row) as usize].push((x, dir));
                }
            }
        }
        for row in &mut rows {
            row.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut sum = 0;
            for c in row.iter_mut() {
                sum += c.1;
                c.1 = sum;
            }
        }
        RowWinding { first_row, rows }
    }

    /// The winding number at the pixel centre `p` (`p.y` = row + ½).
    pub(crate) fn winding(&self, p: Point) -> i32 {
        let r = (p.y - 0.5).round() as i64 - self.first_row;
        if r < 0 {
            return 0;
        }
        let Some(row) = self.rows.get(r as usize) else {
            return 0;
        };
        match row.partition_point(|c| c.0 < p.x) {
            0 => 0,
            k => row[k - 1].1,
        }
    }
}

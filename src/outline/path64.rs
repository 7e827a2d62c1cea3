//! tiny-skia's cuts of a cubic monotonic in x and y where it crosses a vertical or
//! horizontal line, in `f64`: its private `path64` module (`cubic64.rs`, `quad64.rs`,
//! `line_cubic_intersections.rs`, `point64.rs`, `mod.rs`, from Skia's path ops) and
//! `path_geometry::chop_mono_cubic_at_x/_y`, ported from tiny-skia 0.12 / Skia
//! (BSD-3-Clause, Copyright 2012 Google Inc., 2020 Yevhenii Reizner), operation for
//! operation, for [`super::curve_clip`].
//!
//! The roots of the cubic's coordinate less the line's come from the cubic's real roots
//! (`roots_valid_t`); when one of them does not put the point on the line (within
//! `f64::EPSILON`), they come from a binary search between the cubic's extrema and
//! inflections instead (`search_roots`). The cubic is then cut at the first root, in `f64`,
//! and the points rounded to `f32`.

use tiny_skia_path::{Point as SkPoint, Scalar, SCALAR_MAX};

/// `f32::EPSILON / 2` in `f64` (Skia's `FLT_EPSILON_HALF`).
const FLT_EPSILON_HALF: f64 = (f32::EPSILON / 2.0) as f64;
/// `f32::EPSILON³` in `f64` (Skia's `FLT_EPSILON_CUBED`).
const FLT_EPSILON_CUBED: f64 = (f32::EPSILON * f32::EPSILON * f32::EPSILON) as f64;
/// `1 / f32::EPSILON` in `f64` (Skia's `FLT_EPSILON_INVERSE`).
const FLT_EPSILON_INVERSE: f64 = 1.0 / f32::EPSILON as f64;
/// π (Skia's path ops spell it `3.141592653589793`, the same `f64`).
const PI: f64 = std::f64::consts::PI;

/// `value` pinned to `[min, max]`, `max` for a NaN (tiny-skia's `Scalar64::bound`).
fn bound(value: f64, min: f64, max: f64) -> f64 {
    max.min(value).max(min)
}

/// Whether `value` lies between `a` and `b`, in either order (`Scalar64::between`).
fn between(value: f64, a: f64, b: f64) -> bool {
    (a - value) * (b - value) <= 0.0
}

/// `Scalar64::approximately_zero`.
fn approximately_zero(v: f64) -> bool {
    v.abs() < f64::EPSILON
}

/// `Scalar64::approximately_zero_or_more`.
fn approximately_zero_or_more(v: f64) -> bool {
    v > -f64::EPSILON
}

/// `Scalar64::approximately_one_or_less`.
fn approximately_one_or_less(v: f64) -> bool {
    v < 1.0 + f64::EPSILON
}

/// `Scalar64::approximately_zero_when_compared_to`.
fn approximately_zero_when_compared_to(v: f64, other: f64) -> bool {
    v == 0.0 || v.abs() < (other * (f32::EPSILON as f64)).abs()
}

/// `Scalar64::approximately_equal`.
fn approximately_equal(a: f64, b: f64) -> bool {
    approximately_zero(a - b)
}

/// `Scalar64::approximately_equal_half`.
fn approximately_equal_half(a: f64, b: f64) -> bool {
    a - b < FLT_EPSILON_HALF
}

/// `Scalar64::almost_dequal_ulps`: within 16 `f32` ulps (relatively, beyond `f32`'s range).
fn almost_dequal_ulps(a: f64, b: f64) -> bool {
    if a.abs() < SCALAR_MAX as f64 && b.abs() < SCALAR_MAX as f64 {
        (a as f32).almost_dequal_ulps(b as f32)
    } else {
        (a - b).abs() / a.abs().max(b.abs()) < (f32::EPSILON * 16.0) as f64
    }
}

/// tiny-skia's `cube_root`: 0 near 0, else three steps of Halley's method from Kahan's
/// bit-hack estimate.
fn cube_root(x: f64) -> f64 {
    if x.abs() < FLT_EPSILON_CUBED {
        return 0.0;
    }
    let d = x.abs();
    // `cbrt_5d`: the high word divided by 3 plus a bias, the low word 0.
    let hi = (d.to_bits() >> 32) as u32;
    let mut a = f64::from_bits(u64::from(hi / 3 + 715094163) << 32);
    for _ in 0..3 {
        let a3 = a * a * a;
        a = a * (a3 + d + d) / (a3 + a3 + d);
    }
    if x < 0.0 {
        -a
    } else {
        a
    }
}

/// `a + (b − a) t`.
fn interp(a: f64, b: f64, t: f64) -> f64 {
    a + (b - a) * t
}

/// Keeps the roots `s[..real_roots]` within `[0, 1]` (approximately, then pinned), each
/// once, in `t` (`quad64::push_valid_ts`); their count.
fn push_valid_ts(s: &[f64], real_roots: usize, t: &mut [f64]) -> usize {
    let mut found = 0;
    'outer: for &v in &s[..real_roots] {
        if approximately_zero_or_more(v) && approximately_one_or_less(v) {
            let v = bound(v, 0.0, 1.0);
            for &u in &t[..found] {
                if approximately_equal(u, v) {
                    continue 'outer;
                }
            }
            t[found] = v;
            found += 1;
        }
    }
    found
}

/// The roots of `a t² + b t + c` within `[0, 1]` (`quad64::roots_valid_t`).
fn quad_roots_valid_t(a: f64, b: f64, c: f64, t: &mut [f64]) -> usize {
    let mut s = [0.0; 3];
    let real_roots = quad_roots_real(a, b, c, &mut s);
    push_valid_ts(&s, real_roots, t)
}

/// The real roots of `a t² + b t + c` (`quad64::roots_real`).
fn quad_roots_real(a: f64, b: f64, c: f64, s: &mut [f64; 3]) -> usize {
    if a == 0.0 {
        return handle_zero(b, c, s);
    }
    let p = b / (2.0 * a);
    let q = c / a;
    if approximately_zero(a) && (p.abs() > FLT_EPSILON_INVERSE || q.abs() > FLT_EPSILON_INVERSE) {
        return handle_zero(b, c, s);
    }
    // Normal form: x² + p x + q = 0.
    let p2 = p * p;
    if !almost_dequal_ulps(p2, q) && p2 < q {
        return 0;
    }
    let mut sqrt_d = 0.0;
    if p2 > q {
        sqrt_d = (p2 - q).sqrt();
    }
    s[0] = sqrt_d - p;
    s[1] = -sqrt_d - p;
    1 + usize::from(!almost_dequal_ulps(s[0], s[1]))
}

/// The root of `b t + c` (`quad64::handle_zero`).
fn handle_zero(b: f64, c: f64, s: &mut [f64; 3]) -> usize {
    if approximately_zero(b) {
        s[0] = 0.0;
        usize::from(c == 0.0)
    } else {
        s[0] = -c / b;
        1
    }
}

/// The polynomial coefficients `(A, B, C, D)` of the cubic whose Bézier coordinates are
/// `src[0], src[2], src[4], src[6]` (`cubic64::coefficients`).
fn coefficients(src: &[f64]) -> (f64, f64, f64, f64) {
    let mut a = src[6];
    let mut b = src[4] * 3.0;
    let mut c = src[2] * 3.0;
    let d = src[0];
    a -= d - c + b;
    b += 3.0 * d - 2.0 * c;
    c -= 3.0 * d;
    (a, b, c, d)
}

/// The roots of `a t³ + b t² + c t + d` within `[0, 1]`, roots just beyond its ends taken
/// as the ends (`cubic64::roots_valid_t`).
fn roots_valid_t(a: f64, b: f64, c: f64, d: f64, t: &mut [f64; 3]) -> usize {
    let mut s = [0.0; 3];
    let real_roots = roots_real(a, b, c, d, &mut s);
    let mut found = push_valid_ts(&s, real_roots, t);
    'outer: for &v in &s[..real_roots] {
        if !approximately_one_or_less(v) && between(v, 1.0, 1.00005) {
            for &u in &t[..found] {
                if approximately_equal(u, 1.0) {
                    continue 'outer;
                }
            }
            t[found] = 1.0;
            found += 1;
        } else if !approximately_zero_or_more(v) && between(v, -0.00005, 0.0) {
            for &u in &t[..found] {
                if approximately_equal(u, 0.0) {
                    continue 'outer;
                }
            }
            t[found] = 0.0;
            found += 1;
        }
    }
    found
}

/// The real roots of `a t³ + b t² + c t + d` (`cubic64::roots_real`, from Numeric
/// Solutions 5.6).
fn roots_real(a: f64, b: f64, c: f64, d: f64, s: &mut [f64; 3]) -> usize {
    if approximately_zero(a)
        && approximately_zero_when_compared_to(a, b)
        && approximately_zero_when_compared_to(a, c)
        && approximately_zero_when_compared_to(a, d)
    {
        // A quadratic.
        return quad_roots_real(b, c, d, s);
    }
    if approximately_zero_when_compared_to(d, a)
        && approximately_zero_when_compared_to(d, b)
        && approximately_zero_when_compared_to(d, c)
    {
        // 0 is a root.
        let mut num = quad_roots_real(a, b, c, s);
        if s[..num].iter().any(|&v| approximately_zero(v)) {
            return num;
        }
        s[num] = 0.0;
        num += 1;
        return num;
    }
    if approximately_zero(a + b + c + d) {
        // 1 is a root.
        let mut num = quad_roots_real(a, a + b, -d, s);
        if s[..num].iter().any(|&v| almost_dequal_ulps(v, 1.0)) {
            return num;
        }
        s[num] = 1.0;
        num += 1;
        return num;
    }
    let (a, b, c) = {
        let inv_a = 1.0 / a;
        (b * inv_a, c * inv_a, d * inv_a)
    };
    let a2 = a * a;
    let q = (a2 - b * 3.0) / 9.0;
    let r = (2.0 * a2 * a - 9.0 * a * b + 27.0 * c) / 54.0;
    let r2 = r * r;
    let q3 = q * q * q;
    let r2_minus_q3 = r2 - q3;
    let adiv3 = a / 3.0;
    let mut offset = 0;
    if r2_minus_q3 < 0.0 {
        // Three real roots.
        let theta = bound(r / q3.sqrt(), -1.0, 1.0).acos();
        let neg2_root_q = -2.0 * q.sqrt();
        let mut rr = neg2_root_q * (theta / 3.0).cos() - adiv3;
        s[offset] = rr;
        offset += 1;
        rr = neg2_root_q * ((theta + 2.0 * PI) / 3.0).cos() - adiv3;
        if !almost_dequal_ulps(s[0], rr) {
            s[offset] = rr;
            offset += 1;
        }
        rr = neg2_root_q * ((theta - 2.0 * PI) / 3.0).cos() - adiv3;
        if !almost_dequal_ulps(s[0], rr) && (offset == 1 || !almost_dequal_ulps(s[1], rr)) {
            s[offset] = rr;
            offset += 1;
        }
    } else {
        // One real root.
        let sqrt_r2_minus_q3 = r2_minus_q3.sqrt();
        let mut a = r.abs() + sqrt_r2_minus_q3;
        a = cube_root(a);
        if r > 0.0 {
            a = -a;
        }
        if a != 0.0 {
            a += q / a;
        }
        let mut r2 = a - adiv3;
        s[offset] = r2;
        offset += 1;
        if almost_dequal_ulps(r2, q3) {
            r2 = -a / 2.0 - adiv3;
            if !almost_dequal_ulps(s[0], r2) {
                s[offset] = r2;
                offset += 1;
            }
        }
    }
    offset
}

/// Where the cubic of Bézier coordinates `src[0], src[2], src[4], src[6]` turns, within
/// `[0, 1]` (`cubic64::find_extrema`).
fn find_extrema(src: &[f64], t_values: &mut [f64]) -> usize {
    let (a, b, c, d) = (src[0], src[2], src[4], src[6]);
    let a2 = d - a + 3.0 * (b - c);
    let b2 = 2.0 * (a - b - b + c);
    let c2 = b - a;
    quad_roots_valid_t(a2, b2, c2, t_values)
}

/// A cubic in `f64` (`Cubic64`): its points as `[x, y]`.
struct Cubic64 {
    points: [[f64; 2]; 4],
}

impl Cubic64 {
    /// The coordinates `x0, y0, x1, y1, …` (`as_f64_slice`).
    fn as_f64_slice(&self) -> [f64; 8] {
        let p = &self.points;
        [
            p[0][0], p[0][1], p[1][0], p[1][1], p[2][0], p[2][1], p[3][0], p[3][1],
        ]
    }

    /// The point at `t` (`point_at_t`).
    fn point_at_t(&self, t: f64) -> [f64; 2] {
        if t == 0.0 {
            return self.points[0];
        }
        if t == 1.0 {
            return self.points[3];
        }
        let one_t = 1.0 - t;
        let one_t2 = one_t * one_t;
        let a = one_t2 * one_t;
        let b = 3.0 * one_t2 * t;
        let t2 = t * t;
        let c = 3.0 * one_t * t2;
        let d = t2 * t;
        let p = &self.points;
        let at = |k: usize| a * p[0][k] + b * p[1][k] + c * p[2][k] + d * p[3][k];
        [at(0), at(1)]
    }

    /// The roots found by binary search between the `extrema` first of `extreme_ts`, the
    /// inflections, 0 and 1, on `axis` (0: x, 1: y) (`search_roots`).
    fn search_roots(
        &self,
        mut extrema: usize,
        axis_intercept: f64,
        axis: usize,
        extreme_ts: &mut [f64; 6],
        valid_roots: &mut [f64; 3],
    ) -> usize {
        extrema += self.find_inflections(&mut extreme_ts[extrema..]);
        extreme_ts[extrema] = 0.0;
        extrema += 1;
        extreme_ts[extrema] = 1.0;
        // (NaNs compare equal, as Skia's sort takes them.)
        extreme_ts[0..extrema]
            .sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        let mut valid_count = 0;
        let mut index = 0;
        while index < extrema {
            let min = extreme_ts[index];
            index += 1;
            let max = extreme_ts[index];
            if min == max {
                continue;
            }
            let new_t = self.binary_search(min, max, axis_intercept, axis);
            if new_t >= 0.0 {
                if valid_count >= 3 {
                    return 0;
                }
                valid_roots[valid_count] = new_t;
                valid_count += 1;
            }
        }
        valid_count
    }

    /// The cubic's inflections within `[0, 1]` (`find_inflections`).
    fn find_inflections(&self, t_values: &mut [f64]) -> usize {
        let p = &self.points;
        let ax = p[1][0] - p[0][0];
        let ay = p[1][1] - p[0][1];
        let bx = p[2][0] - 2.0 * p[1][0] + p[0][0];
        let by = p[2][1] - 2.0 * p[1][1] + p[0][1];
        let cx = p[3][0] + 3.0 * (p[1][0] - p[2][0]) - p[0][0];
        let cy = p[3][1] + 3.0 * (p[1][1] - p[2][1]) - p[0][1];
        quad_roots_valid_t(
            bx * cy - by * cx,
            ax * cy - ay * cx,
            ax * by - ay * bx,
            t_values,
        )
    }

    /// The `t` in `[min, max]` where the cubic crosses `axis_intercept` on `axis`, −1 when
    /// the search stops finding none (`binary_search`).
    fn binary_search(&self, min: f64, max: f64, axis_intercept: f64, axis: usize) -> f64 {
        let mut t = (min + max) / 2.0;
        let mut step = (t - min) / 2.0;
        let mut cubic_at_t = self.point_at_t(t);
        let mut calc_pos = cubic_at_t[axis];
        let mut calc_dist = calc_pos - axis_intercept;
        loop {
            let prior_t = min.max(t - step);
            let less_pt = self.point_at_t(prior_t);
            if approximately_equal_half(less_pt[0], cubic_at_t[0])
                && approximately_equal_half(less_pt[1], cubic_at_t[1])
            {
                return -1.0;
            }
            let less_dist = less_pt[axis] - axis_intercept;
            let last_step = step;
            step /= 2.0;
            let ok = if calc_dist > 0.0 {
                calc_dist > less_dist
            } else {
                calc_dist < less_dist
            };
            if ok {
                t = prior_t;
            } else {
                let next_t = t + last_step;
                if next_t > max {
                    return -1.0;
                }
                let more_pt = self.point_at_t(next_t);
                if approximately_equal_half(more_pt[0], cubic_at_t[0])
                    && approximately_equal_half(more_pt[1], cubic_at_t[1])
                {
                    return -1.0;
                }
                let more_dist = more_pt[axis] - axis_intercept;
                let ok = if calc_dist > 0.0 {
                    calc_dist <= more_dist
                } else {
                    calc_dist >= more_dist
                };
                if ok {
                    continue;
                }
                t = next_t;
            }
            cubic_at_t = self.point_at_t(t);
            calc_pos = cubic_at_t[axis];
            calc_dist = calc_pos - axis_intercept;
            if approximately_equal(calc_pos, axis_intercept) {
                break;
            }
        }
        t
    }

    /// The cubic cut at `t`: the two cubics' seven points (`chop_at`).
    fn chop_at(&self, t: f64) -> [[f64; 2]; 7] {
        let p = &self.points;
        let mut dst = [[0.0; 2]; 7];
        for k in 0..2 {
            if t == 0.5 {
                dst[0][k] = p[0][k];
                dst[1][k] = (p[0][k] + p[1][k]) / 2.0;
                dst[2][k] = (p[0][k] + 2.0 * p[1][k] + p[2][k]) / 4.0;
                dst[3][k] = (p[0][k] + 3.0 * (p[1][k] + p[2][k]) + p[3][k]) / 8.0;
                dst[4][k] = (p[1][k] + 2.0 * p[2][k] + p[3][k]) / 4.0;
                dst[5][k] = (p[2][k] + p[3][k]) / 2.0;
                dst[6][k] = p[3][k];
            } else {
                let ab = interp(p[0][k], p[1][k], t);
                let bc = interp(p[1][k], p[2][k], t);
                let cd = interp(p[2][k], p[3][k], t);
                let abc = interp(ab, bc, t);
                let bcd = interp(bc, cd, t);
                let abcd = interp(abc, bcd, t);
                dst[0][k] = p[0][k];
                dst[1][k] = ab;
                dst[2][k] = abc;
                dst[3][k] = abcd;
                dst[4][k] = bcd;
                dst[5][k] = cd;
                dst[6][k] = p[3][k];
            }
        }
        dst
    }

    /// Where the cubic crosses `axis_intercept` on `axis` (0: x, `vertical_intersect`; 1:
    /// y, `horizontal_intersect`): the roots in `roots`, their count.
    fn intersect(&self, axis_intercept: f64, axis: usize, roots: &mut [f64; 3]) -> usize {
        let all = self.as_f64_slice();
        let (a, b, c, mut d) = coefficients(&all[axis..]);
        d -= axis_intercept;
        let count = roots_valid_t(a, b, c, d, roots);
        let off = roots[..count]
            .iter()
            .any(|&t| !approximately_equal(self.point_at_t(t)[axis], axis_intercept));
        if !off {
            return count;
        }
        let mut extreme_ts = [0.0; 6];
        let extrema = find_extrema(&all[axis..], &mut extreme_ts);
        self.search_roots(extrema, axis_intercept, axis, &mut extreme_ts, roots)
    }
}

/// tiny-skia's `cubic_dchop_at_intercept`: `src` cut where it crosses `intercept` on
/// `axis` (0: the vertical line `x = intercept`, 1: the horizontal one), the two cubics'
/// seven points in `dst`; false (and `dst` untouched) when no crossing is found.
fn dchop_at_intercept(
    src: &[SkPoint; 4],
    intercept: f32,
    axis: usize,
    dst: &mut [SkPoint; 7],
) -> bool {
    let cubic = Cubic64 {
        points: src.map(|p| [f64::from(p.x), f64::from(p.y)]),
    };
    let mut roots = [0.0; 3];
    let count = cubic.intersect(f64::from(intercept), axis, &mut roots);
    if count == 0 {
        return false;
    }
    let pair = cubic.chop_at(roots[0]);
    for (d, p) in dst.iter_mut().zip(pair) {
        *d = SkPoint::from_xy(p[0] as f32, p[1] as f32);
    }
    true
}

/// tiny-skia's `path_geometry::chop_mono_cubic_at_x`.
pub(super) fn chop_mono_cubic_at_x(src: &[SkPoint; 4], x: f32, dst: &mut [SkPoint; 7]) -> bool {
    dchop_at_intercept(src, x, 0, dst)
}

/// tiny-skia's `path_geometry::chop_mono_cubic_at_y`.
pub(super) fn chop_mono_cubic_at_y(src: &[SkPoint; 4], y: f32, dst: &mut [SkPoint; 7]) -> bool {
    dchop_at_intercept(src, y, 1, dst)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_roots() {
        assert!((cube_root(27.0) - 3.0).abs() < 1e-12);
        assert!((cube_root(-8.0) + 2.0).abs() < 1e-12);
        assert_eq!(cube_root(1e-25), 0.0);
    }

    #[test]
    fn the_roots_of_a_cubic_within_the_unit_interval() {
        // (t − 0.2)(t − 0.5)(t − 0.9) and (t − 0.5)(t − 3)(t + 2).
        let mut t = [0.0; 3];
        let n = roots_valid_t(1.0, -1.6, 0.73, -0.09, &mut t);
        let mut found = t[..n].to_vec();
        found.sort_by(f64::total_cmp);
        assert_eq!(found.len(), 3);
        for (a, b) in found.iter().zip([0.2, 0.5, 0.9]) {
            assert!((a - b).abs() < 1e-9, "{found:?}");
        }
        let n = roots_valid_t(1.0, -1.5, -5.5, 3.0, &mut t);
        assert_eq!(n, 1);
        assert!((t[0] - 0.5).abs() < 1e-9);
        // Just beyond 1: taken as 1.
        let n = roots_valid_t(0.0, 0.0, 1.0, -1.00001, &mut t);
        assert_eq!((n, t[0]), (1, 1.0));
    }

    #[test]
    fn monotonic_cubics_cut_where_they_cross_a_line() {
        let p = |x: f32, y: f32| SkPoint::from_xy(x, y);
        // x = 6t − 3: the root t = 1/2 is exact, and the cut at it too.
        let src = [p(-3.0, 0.0), p(-1.0, 3.0), p(1.0, 6.0), p(3.0, 10.0)];
        let mut dst = [SkPoint::zero(); 7];
        assert!(chop_mono_cubic_at_x(&src, 0.0, &mut dst));
        assert_eq!((dst[0], dst[6]), (src[0], src[3]));
        assert_eq!(dst[3], p(0.0, 4.625));
        // Nowhere near the line: no cut, `dst` untouched.
        let mut untouched = [SkPoint::zero(); 7];
        assert!(!chop_mono_cubic_at_x(&src, 20.0, &mut untouched));
        assert_eq!(untouched, [SkPoint::zero(); 7]);
    }

    #[test]
    fn searches_along_increasing_cubics_find_nothing() {
        // x = t³ + 9t − 4: its root in `f64` (0.4358…) puts the point 1e-16 or so off x = 0,
        // more than `f64::EPSILON`, so tiny-skia searches between the extrema and
        // inflections; its `approximately_equal_half` has no `abs` (Skia's has), so a point
        // at a smaller `t` of a cubic increasing in x and y always looks the same and the
        // search gives up: no cut (the clipper then takes `mono_cubic_closest_t`).
        let p = |x: f32, y: f32| SkPoint::from_xy(x, y);
        let src = [p(-4.0, 0.0), p(-1.0, 3.0), p(2.0, 6.0), p(6.0, 10.0)];
        let mut dst = [SkPoint::zero(); 7];
        assert!(!chop_mono_cubic_at_x(&src, 0.0, &mut dst));
        assert!(!approximately_equal_half(1.0, 0.0));
        assert!(approximately_equal_half(0.0, 1.0));
    }
}

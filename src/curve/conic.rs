//! Conics `a x² + b xy + c y² + d x + e y + f = 0`: their kind and the parameters of
//! ellipses, parabolas and hyperbolas.

use super::kind::CurveKind;
use kurbo::{Point, Vec2};
use std::f64::consts::PI;

/// The conic `a x² + b xy + c y² + d x + e y + f = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conic {
    /// Coefficient of `x²`.
    pub a: f64,
    /// Coefficient of `xy`.
    pub b: f64,
    /// Coefficient of `y²`.
    pub c: f64,
    /// Coefficient of `x`.
    pub d: f64,
    /// Coefficient of `y`.
    pub e: f64,
    /// Constant term.
    pub f: f64,
}

/// Relative tolerance on the discriminant `b² − 4ac` against `b² + 4|ac|` (parabola test).
const DISC_EPS: f64 = 1e-10;
/// Relative tolerance on the centred constant term (degeneracy test of central conics).
const CENTRE_EPS: f64 = 1e-10;
/// Relative tolerance on `|a − c|` and `|b|` against `|a| + |c|` (circle test).
const CIRCLE_EPS: f64 = 1e-12;
/// Relative tolerance on the linear part along a parabola's axis (degeneracy test).
const PARABOLA_EPS: f64 = 1e-10;

/// The eigen-decomposition of a conic's quadratic part, plus its centre when central.
struct Principal {
    /// Angle of the first eigenvector `(cos θ, sin θ)`.
    theta: f64,
    /// Eigenvalue along `θ`.
    l1: f64,
    /// Eigenvalue along `θ + π/2`.
    l2: f64,
}

/// An ellipse (or circle) as [`Conic::ellipse_params`] gives it: the curve
/// `{centre + R(rotation) (radii.x cos φ, radii.y sin φ)}`, the SVG arc convention.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EllipseParams {
    /// The centre.
    pub centre: Point,
    /// `(rx, ry)`, `rx` along the axis at angle `rotation`.
    pub radii: Vec2,
    /// The angle of the `rx` axis, in `(−π/2, π/2]`.
    pub rotation: f64,
}

/// A parabola as [`Conic::parabola_params`] gives it: `v = u² / (4 focal_length)` in the
/// frame of the vertex with `v` along `axis`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParabolaParams {
    /// The vertex.
    pub vertex: Point,
    /// The unit axis direction, pointing into the parabola (towards the focus).
    pub axis: Vec2,
    /// The vertex-to-focus distance.
    pub focal_length: f64,
}

/// A hyperbola as [`Conic::hyperbola_params`] gives it: the curve
/// `{centre + R(rotation) (±a cosh s, b sinh s)}` with `(a, b) = semi_axes`; the branches are
/// the two signs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HyperbolaParams {
    /// The centre.
    pub centre: Point,
    /// `(a, b)`: `a` transverse (through the vertices), `b` conjugate.
    pub semi_axes: Vec2,
    /// The angle of the transverse axis.
    pub rotation: f64,
}

impl Conic {
    /// The conic with the given coefficients.
    #[inline]
    pub const fn new(a: f64, b: f64, c: f64, d: f64, e: f64, f: f64) -> Conic {
        Conic { a, b, c, d, e, f }
    }

    fn is_finite(&self) -> bool {
        [self.a, self.b, self.c, self.d, self.e, self.f]
            .iter()
            .all(|v| v.is_finite())
    }

    /// The value at `p`.
    pub fn eval(&self, p: Point) -> f64 {
        let (x, y) = (p.x, p.y);
        self.a * x * x + self.b * x * y + self.c * y * y + self.d * x + self.e * y + self.f
    }

    /// The gradient at `p`.
    pub fn gradient(&self, p: Point) -> Vec2 {
        Vec2::new(
            2.0 * self.a * p.x + self.b * p.y + self.d,
            self.b * p.x + 2.0 * self.c * p.y + self.e,
        )
    }

    /// The determinant of the symmetric matrix
    /// `[[a, b/2, d/2], [b/2, c, e/2], [d/2, e/2, f]]`; zero exactly for degenerate conics.
    pub fn determinant(&self) -> f64 {
        let Conic { a, b, c, d, e, f } = *self;
        a * (c * f - e * e / 4.0) - b / 2.0 * (b * f / 2.0 - e * d / 4.0)
            + d / 2.0 * (b * e / 4.0 - c * d / 2.0)
    }

    /// Eigen-decomposition of `[[a, b/2], [b/2, c]]`: `λ1 = m + r` along `θ = ½ atan2(b, a − c)`,
    /// `λ2 = m − r` along `θ + π/2`, with `m = (a + c)/2`, `r = hypot((a − c)/2, b/2)`.
    fn principal(&self) -> Principal {
        let m = 0.5 * (self.a + self.c);
        let r = (0.5 * (self.a - self.c)).hypot(0.5 * self.b);
        Principal {
            theta: 0.5 * self.b.atan2(self.a - self.c),
            l1: m + r,
            l2: m - r,
        }
    }

    /// Centre `(x0, y0)` (where the gradient vanishes) and the value there, for central
    /// conics, together with the scale `|f| + (|d x0| + |e y0|)/2` of that value's terms.
    fn centre(&self) -> Option<(Point, f64, f64)> {
        let Conic { a, b, c, d, e, f } = *self;
        let det2 = 4.0 * a * c - b * b;
        if det2 == 0.0 {
            return None;
        }
        let x0 = (b * e - 2.0 * c * d) / det2;
        let y0 = (b * d - 2.0 * a * e) / det2;
        let value = f + 0.5 * (d * x0 + e * y0);
        let scale = f.abs() + 0.5 * ((d * x0).abs() + (e * y0).abs());
        Some((Point::new(x0, y0), value, scale))
            .filter(|(p, v, s)| p.is_finite() && v.is_finite() && s.is_finite())
    }

    /// The kind of conic.
    ///
    /// Tolerances (all relative, so that scaling the equation does not change the answer;
    /// integer coefficients of moderate size are classified exactly):
    /// * no quadratic part (`a = b = c = 0` exactly): [`CurveKind::Line`] if `(d, e) ≠ 0`;
    /// * `|b² − 4ac| ≤ 1e-10 (b² + 4|ac|)`: parabola-like; it is [`CurveKind::Parabola`] unless
    ///   the linear part across the axis, `|(d, e)·t|` (`t` the unit axis direction), is at most
    ///   `1e-10 |(d, e)|` — then the 3×3 determinant vanishes: parallel or double lines, or empty;
    /// * otherwise the conic is central; translating to the centre leaves the constant
    ///   `f' = f + (d x0 + e y0)/2` (proportional to the 3×3 determinant), taken as zero when
    ///   `|f'| ≤ 1e-10 (|f| + (|d x0| + |e y0|)/2)`. Then `b² − 4ac > 0` gives
    ///   [`CurveKind::Hyperbola`] (or two crossing lines if `f' = 0`), and `b² − 4ac < 0` gives
    ///   a real ellipse only when `f'` has the sign opposite to `a + c` (else the locus is empty
    ///   or a single point). The ellipse is a [`CurveKind::Circle`] when
    ///   `|a − c|, |b| ≤ 1e-12 (|a| + |c|)`, in particular when `a == c` and `b == 0`.
    pub fn classify(&self) -> CurveKind {
        if !self.is_finite() {
            return CurveKind::Degenerate;
        }
        let Conic { a, b, c, d, e, .. } = *self;
        if a == 0.0 && b == 0.0 && c == 0.0 {
            return if d != 0.0 || e != 0.0 {
                CurveKind::Line
            } else {
                CurveKind::Degenerate
            };
        }
        let disc = b * b - 4.0 * a * c;
        if disc.abs() <= DISC_EPS * (b * b + 4.0 * (a * c).abs()) {
            return if self.parabola_frame().is_some() {
                CurveKind::Parabola
            } else {
                CurveKind::Degenerate
            };
        }
        let Some((_, value, scale)) = self.centre() else {
            return CurveKind::Degenerate;
        };
        if value.abs() <= CENTRE_EPS * scale {
            return CurveKind::Degenerate;
        }
        if disc > 0.0 {
            return CurveKind::Hyperbola;
        }
        if value * (a + c) > 0.0 {
            return CurveKind::Degenerate;
        }
        let s = a.abs() + c.abs();
        if (a - c).abs() <= CIRCLE_EPS * s && b.abs() <= CIRCLE_EPS * s {
            CurveKind::Circle
        } else {
            CurveKind::Ellipse
        }
    }

    /// The centre, radii `(rx, ry)` and rotation angle `θ` of an ellipse or circle: the curve is
    /// `{centre + R(θ) (rx cos φ, ry sin φ)}`, which is exactly the SVG arc convention
    /// (`rx` along the axis rotated by `x_rotation = θ`). `θ ∈ (−π/2, π/2]`.
    ///
    /// Returns `None` unless [`Conic::classify`] gives `Circle` or `Ellipse`.
    ///
    /// Solved here: `kurbo::Ellipse` is built from a centre, radii and rotation (or an
    /// affine map) and has no implicit equation to start from.
    pub fn ellipse_params(&self) -> Option<EllipseParams> {
        if !matches!(self.classify(), CurveKind::Circle | CurveKind::Ellipse) {
            return None;
        }
        let (centre, value, _) = self.centre()?;
        let pr = self.principal();
        let rx = (-value / pr.l1).sqrt();
        let ry = (-value / pr.l2).sqrt();
        (rx.is_finite() && ry.is_finite() && rx > 0.0 && ry > 0.0).then_some(EllipseParams {
            centre,
            radii: Vec2::new(rx, ry),
            rotation: pr.theta,
        })
    }

    /// Frame of a parabola: unit vector `n` across the axis, its eigenvalue `λ`, and the
    /// components `D = (d, e)·n`, `E = (d, e)·t` with `t = n⊥` along the axis.
    fn parabola_frame(&self) -> Option<(Vec2, f64, f64, f64)> {
        let pr = self.principal();
        let (theta, lambda) = if pr.l1.abs() >= pr.l2.abs() {
            (pr.theta, pr.l1)
        } else {
            (pr.theta + 0.5 * PI, pr.l2)
        };
        let n = Vec2::from_angle(theta);
        let t = n.turn_90();
        let lin = Vec2::new(self.d, self.e);
        let (dd, ee) = (lin.dot(n), lin.dot(t));
        if lambda == 0.0 || ee.abs() <= PARABOLA_EPS * lin.hypot() || ee == 0.0 {
            return None;
        }
        Some((n, lambda, dd, ee))
    }

    /// The vertex, the unit axis direction pointing into the parabola (towards the focus),
    /// and the focal length `p` (vertex-to-focus distance; the parabola is `v = u² / (4p)` in
    /// the frame of the vertex with `v` along the axis).
    ///
    /// Returns `None` unless [`Conic::classify`] gives `Parabola`.
    pub fn parabola_params(&self) -> Option<ParabolaParams> {
        if self.classify() != CurveKind::Parabola {
            return None;
        }
        let (n, lambda, dd, ee) = self.parabola_frame()?;
        let t = n.turn_90();
        // λ u² + D u + E v + f = 0 with u = n·p, v = t·p.
        let u0 = -dd / (2.0 * lambda);
        let v0 = -(lambda * u0 * u0 + dd * u0 + self.f) / ee;
        let vertex = (n * u0 + t * v0).to_point();
        let axis = if -lambda / ee > 0.0 { t } else { -t };
        let p = (ee / (4.0 * lambda)).abs();
        (vertex.is_finite() && p.is_finite()).then_some(ParabolaParams {
            vertex,
            axis,
            focal_length: p,
        })
    }

    /// The centre, semi-axes `(a, b)` (`a` transverse, through the vertices; `b` conjugate) and
    /// the angle of the transverse axis: the curve is
    /// `{centre + R(θ) (±a cosh s, b sinh s)}`; the branches are the two signs.
    ///
    /// Returns `None` unless [`Conic::classify`] gives `Hyperbola`.
    pub fn hyperbola_params(&self) -> Option<HyperbolaParams> {
        if self.classify() != CurveKind::Hyperbola {
            return None;
        }
        let (centre, value, _) = self.centre()?;
        let pr = self.principal();
        // λ1 > 0 > λ2 in the frame rotated by θ: λ1 x'² + λ2 y'² + value = 0.
        let (semi, angle) = if value < 0.0 {
            (
                Vec2::new((-value / pr.l1).sqrt(), (value / pr.l2).sqrt()),
                pr.theta,
            )
        } else {
            (
                Vec2::new((-value / pr.l2).sqrt(), (value / pr.l1).sqrt()),
                pr.theta + 0.5 * PI,
            )
        };
        semi.is_finite().then_some(HyperbolaParams {
            centre,
            semi_axes: semi,
            rotation: angle,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_util::*;
    use crate::curve::Polynomial;
    use proptest::prelude::*;
    use std::f64::consts::TAU;

    #[test]
    fn classify_known_conics() {
        use CurveKind::*;
        // (x − 3)² + (y + 2)² = 25, and scaled.
        let circle = Conic::new(1.0, 0.0, 1.0, -6.0, 4.0, -12.0);
        assert_eq!(circle.classify(), Circle);
        let scaled = Conic::new(7.0, 0.0, 7.0, -42.0, 28.0, -84.0);
        assert_eq!(scaled.classify(), Circle);
        let EllipseParams {
            centre: c,
            radii: r,
            ..
        } = circle.ellipse_params().unwrap();
        assert_point_close(c, Point::new(3.0, -2.0), 1e-12, "circle centre");
        assert_close(r.x, 5.0, 1e-12, "circle rx");
        assert_close(r.y, 5.0, 1e-12, "circle ry");
        // Integer rotated ellipse 5x² + 6xy + 5y² = 8 (45°, radii 1 and 2).
        assert_eq!(
            Conic::new(5.0, 6.0, 5.0, 0.0, 0.0, -8.0).classify(),
            Ellipse
        );
        // Rotated ellipses of several angles and aspect ratios, integer-scaled.
        for (k, &(rx, ry)) in [(10.0, 4.0), (7.0, 6.5), (30.0, 3.0), (5.0, 5.5)]
            .iter()
            .enumerate()
        {
            for th in [0.0, 0.3, 1.0, 2.2, -0.7] {
                let centre = Point::new(40.0 + k as f64, 17.0);
                let e = round_conic(ellipse_conic(centre, rx, ry, th, 1e6));
                assert_eq!(e.classify(), Ellipse, "ellipse {rx} {ry} {th}: {e:?}");
            }
        }
        // Parabolas: (x + y)² − 8x + 8y = 0, y = x²/4 and its rotations.
        assert_eq!(
            Conic::new(1.0, 2.0, 1.0, -8.0, 8.0, 0.0).classify(),
            Parabola
        );
        assert_eq!(
            Conic::new(1.0, 0.0, 0.0, 0.0, -4.0, 0.0).classify(),
            Parabola
        );
        for th in [0.1, 0.5, 1.3, 2.0, 3.0] {
            let k = rotated_parabola(th, Point::new(5.0, -3.0));
            assert_eq!(k.classify(), Parabola, "parabola {th}: {k:?}");
        }
        // Hyperbolas.
        assert_eq!(
            Conic::new(0.0, 1.0, 0.0, 0.0, 0.0, -1.0).classify(),
            Hyperbola
        );
        assert_eq!(
            Conic::new(1.0, 0.0, -1.0, 0.0, 0.0, -1.0).classify(),
            Hyperbola
        );
        assert_eq!(
            Conic::new(4.0, 0.0, -9.0, -8.0, 36.0, -68.0).classify(),
            Hyperbola
        );
        // Degenerate: crossing lines, (x − y − 1)(2x + y + 3), parallel lines, double line,
        // empty, point, constant.
        assert_eq!(
            Conic::new(1.0, 0.0, -1.0, 0.0, 0.0, 0.0).classify(),
            Degenerate
        );
        assert_eq!(
            Conic::new(2.0, -1.0, -1.0, 1.0, -4.0, -3.0).classify(),
            Degenerate
        );
        assert_eq!(
            Conic::new(1.0, 2.0, 1.0, 0.0, 0.0, -1.0).classify(),
            Degenerate
        );
        assert_eq!(
            Conic::new(1.0, -2.0, 1.0, 0.0, 0.0, 0.0).classify(),
            Degenerate
        );
        assert_eq!(
            Conic::new(1.0, 0.0, 1.0, 0.0, 0.0, 1.0).classify(),
            Degenerate
        );
        assert_eq!(
            Conic::new(1.0, 0.0, 1.0, 0.0, 0.0, 0.0).classify(),
            Degenerate
        );
        assert_eq!(
            Conic::new(1.0, 2.0, 1.0, 2.0, 2.0, 1.0).classify(),
            Degenerate
        );
        assert_eq!(
            Conic::new(0.0, 0.0, 0.0, 0.0, 0.0, 1.0).classify(),
            Degenerate
        );
        assert_eq!(
            Conic::new(0.0, 0.0, 0.0, f64::NAN, 0.0, 1.0).classify(),
            Degenerate
        );
        // Lines.
        assert_eq!(Conic::new(0.0, 0.0, 0.0, 1.0, -2.0, 5.0).classify(), Line);
        for k in [
            Conic::new(1.0, 0.0, -1.0, 0.0, 0.0, 0.0),
            Conic::new(2.0, -1.0, -1.0, 1.0, -4.0, -3.0),
            Conic::new(1.0, -2.0, 1.0, 0.0, 0.0, 0.0),
        ] {
            assert_close(k.determinant(), 0.0, 0.0, "degenerate determinant");
        }
        assert!(circle.determinant() != 0.0);
    }

    #[test]
    fn parabola_and_hyperbola_params() {
        for th in [0.0, 0.4, 1.7, -2.5] {
            let v = Point::new(5.0, -3.0);
            let k = rotated_parabola(th, v);
            let ParabolaParams {
                vertex,
                axis,
                focal_length: p,
            } = k.parabola_params().unwrap();
            assert_point_close(vertex, v, 1e-9, "parabola vertex");
            // Opens towards +y' = (−sin, cos).
            assert_point_close(
                axis.to_point(),
                Point::new(-th.sin(), th.cos()),
                1e-9,
                "parabola axis",
            );
            assert_close(p, 1.0, 1e-9, "focal length");
        }
        // (x − 1)²/9 − (y − 2)²/4 = 1 → 4x² − 9y² − 8x + 36y − 68 = 0.
        let h = Conic::new(4.0, 0.0, -9.0, -8.0, 36.0, -68.0);
        let HyperbolaParams {
            centre: c,
            semi_axes: semi,
            rotation: angle,
        } = h.hyperbola_params().unwrap();
        assert_point_close(c, Point::new(1.0, 2.0), 1e-12, "hyperbola centre");
        assert_close(semi.x, 3.0, 1e-12, "transverse");
        assert_close(semi.y, 2.0, 1e-12, "conjugate");
        assert_close(angle.sin(), 0.0, 1e-12, "transverse along x");
        // Swapped: (y − 2)²/4 − (x − 1)²/9 = 1.
        let h2 = Conic::new(-4.0, 0.0, 9.0, 8.0, -36.0, 68.0 - 72.0);
        let HyperbolaParams {
            centre: c,
            semi_axes: semi,
            rotation: angle,
        } = h2.hyperbola_params().unwrap();
        assert_point_close(c, Point::new(1.0, 2.0), 1e-12, "hyperbola centre");
        assert_close(semi.x, 2.0, 1e-12, "transverse");
        assert_close(semi.y, 3.0, 1e-12, "conjugate");
        assert_close(angle.cos(), 0.0, 1e-12, "transverse along y");
        assert_eq!(h.ellipse_params(), None);
        assert_eq!(h.parabola_params(), None);
    }

    /// An integer conic, coefficients in [−20, 20]: any, or built to be a circle, a
    /// parabola (square of a linear form plus a linear part) or a pair of lines, so that
    /// the exact cases of every kind come up.
    fn integer_conic() -> impl Strategy<Value = Conic> {
        let k = || -20i32..=20;
        let any = (k(), k(), k(), k(), k(), k()).prop_map(|(a, b, c, d, e, f)| (a, b, c, d, e, f));
        let circle = (1i32..=5, k(), k(), k()).prop_map(|(a, d, e, f)| (a, 0, a, d, e, f));
        let parabola = (-4i32..=4, -4i32..=4, k(), k(), k())
            .prop_map(|(u, v, d, e, f)| (u * u, 2 * u * v, v * v, d, e, f));
        let lines = (
            (-4i32..=4, -4i32..=4, -4i32..=4),
            (-4i32..=4, -4i32..=4, -4i32..=4),
        )
            .prop_map(|((p, q, r), (s, t, w))| {
                (
                    p * s,
                    p * t + q * s,
                    q * t,
                    p * w + r * s,
                    q * w + r * t,
                    r * w,
                )
            });
        prop_oneof![any, circle, parabola, lines].prop_map(|(a, b, c, d, e, f)| {
            let x = f64::from;
            Conic::new(x(a), x(b), x(c), x(d), x(e), x(f))
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        #[test]
        fn ellipse_params_recover_ellipses(
            centre in (0.0..300.0f64, 0.0..300.0f64).prop_map(|(x, y)| Point::new(x, y)),
            (rx, ry) in (1.0..80.0f64, 1.0..80.0f64),
            th in -PI..PI,
            scale in 0.1..1e4f64,
        ) {
            let k = ellipse_conic(centre, rx, ry, th, scale);
            let EllipseParams {
                centre: c,
                radii: r,
                rotation: a,
            } = k
                .ellipse_params()
                .unwrap_or_else(|| panic!("not an ellipse: {k:?}"));
            assert_point_close(c, centre, 1e-8 * (1.0 + centre.to_vec2().hypot()), "centre");
            let (lo, hi) = (rx.min(ry), rx.max(ry));
            assert_close(r.x.min(r.y), lo, 1e-8 * hi, "small radius");
            assert_close(r.x.max(r.y), hi, 1e-8 * hi, "large radius");
            // As point sets: the recovered ellipse lies on the conic, up to rounding that
            // grows with the aspect ratio (radii 79.2 and 1.0 at scale 2066: 3.7e-7 px).
            let poly = Polynomial::from(k);
            for i in 0..32 {
                let p = ellipse_point(c, r.x, r.y, a, i as f64 * TAU / 32.0);
                assert_le(
                    poly.distance_estimate(p),
                    1e-9 * hi * (hi / lo),
                    "recovered ellipse on conic",
                );
            }
        }

        /// The kind does not change when the equation is multiplied by a positive factor
        /// (any, not only powers of two: the tolerances are relative).
        #[test]
        fn classification_is_invariant_under_scaling(
            k in integer_conic(),
            scale in prop_oneof![1e-3..1e3f64, (-10i32..=10).prop_map(|e| 2f64.powi(e))],
        ) {
            let scaled = Conic::new(
                k.a * scale,
                k.b * scale,
                k.c * scale,
                k.d * scale,
                k.e * scale,
                k.f * scale,
            );
            prop_assert_eq!(scaled.classify(), k.classify(), "{:?} times {}", k, scale);
        }
    }
}

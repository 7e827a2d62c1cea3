//! Implicit curves `f(x, y) = 0` and exact SVG paths along them.
//!
//! A border piece of a shape is described by a bivariate [`Polynomial`] `f` of degree at most
//! [`MAX_DEGREE`]; the part of the level curve `f = 0` between two points is turned into SVG
//! path commands by [`level_curve_path`]:
//!
//! * lines become one `L`,
//! * circles and ellipses become exact `A` arcs ([`kurbo::SvgArc`]),
//! * parabolas become one exact quadratic Bézier `Q` (a parabola arc *is* a quadratic Bézier),
//! * hyperbolas, degenerate conics and curves of degree > 2 are traced numerically and fitted
//!   by cubic Béziers `C` whose measured distance to the true curve is reported.
//!
//! All coordinates are absolute SVG coordinates, where pixel `(x, y)` is the unit square
//! `[x, x+1] × [y, y+1]`. Distances are in pixels.

use crate::pixel::{Pixel, PixelMap};
use kurbo::{Arc, CubicBez, ParamCurve, ParamCurveNearest, PathEl, Point, QuadBez, SvgArc, Vec2};
use std::f64::consts::{PI, TAU};

/// The highest degree a [`Polynomial`] can have.
pub const MAX_DEGREE: u32 = 6;

/// Number of coefficients of a dense polynomial of degree [`MAX_DEGREE`].
const N_COEFFS: usize = ((MAX_DEGREE + 1) * (MAX_DEGREE + 2) / 2) as usize;

/// Guide points farther than this (in pixels) from the curve make [`level_curve_path`] fail.
pub const GUIDE_MAX_DISTANCE: f64 = 2.0;

/// `from` and `to` farther than this (in pixels) from the curve make [`level_curve_path`] fail.
const ENDPOINT_MAX_DISTANCE: f64 = 0.01;

/// Largest step (in pixels) of the numerical tracer used by [`level_curve_path`].
const TRACE_STEP: f64 = 0.25;

/// Largest arc length between consecutive points of a hyperbola's trace
/// ([`hyperbola_trace`]), in pixels.
const HYPERBOLA_STEP: f64 = 0.25;

/// Largest turn of the tangent between consecutive points of a hyperbola's trace, in
/// radians.
const HYPERBOLA_TURN: f64 = 0.1;

/// Tolerance (in pixels) used by [`PathCommand::to_path_els`] to approximate arcs by cubics.
pub const ARC_FLATTEN_TOLERANCE: f64 = 1e-3;

/// Index of the monomial `x^a y^b` in the dense triangular coefficient array.
#[inline]
fn index(a: u32, b: u32) -> usize {
    let k = (a + b) as usize;
    k * (k + 1) / 2 + b as usize
}

/// The highest total degree with a non-zero coefficient in dense triangular storage.
fn top_degree(c: &[f64; N_COEFFS]) -> usize {
    (0..=MAX_DEGREE as usize)
        .rev()
        .find(|&k| (0..=k).any(|b| c[k * (k + 1) / 2 + b] != 0.0))
        .unwrap_or(0)
}

/// Binomial coefficient `n choose k` as `f64` (exact for `n ≤ MAX_DEGREE`).
fn binomial(n: u32, k: u32) -> f64 {
    let mut r = 1.0;
    for i in 0..k {
        r = r * f64::from(n - i) / f64::from(i + 1);
    }
    r
}

/// A bivariate polynomial `f(x, y) = Σ c_ab x^a y^b` of degree at most [`MAX_DEGREE`],
/// with `f64` coefficients in absolute (SVG) coordinates.
///
/// The curve described is the zero set `f = 0`.
///
/// Besides the absolute coefficients, a polynomial built by [`Polynomial::from_local`] keeps
/// its local coefficients and origin, and [`Polynomial::eval`] and [`Polynomial::gradient`]
/// work in that local frame: a sextic around `(800, 600)` has absolute coefficients up to
/// ~1e18, whose rounding alone would move the curve by ~1e-4 px. Equality (`==`) compares
/// this stored representation, frame included.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Polynomial {
    /// Absolute coefficients, dense triangular storage, see [`index`].
    coeffs: [f64; N_COEFFS],
    /// Origin of the evaluation frame.
    origin: Point,
    /// Highest total degree with a non-zero local coefficient (bounds the evaluation loops).
    top: usize,
    /// Coefficients in the evaluation frame: `f = Σ local_ab (x − ox)^a (y − oy)^b`.
    local: [f64; N_COEFFS],
}

impl Polynomial {
    /// The polynomial `Σ c x^a y^b` over the given `(a, b, c)` terms (repeated monomials add up).
    ///
    /// Returns `None` if a term has degree `a + b > MAX_DEGREE` or a non-finite coefficient.
    pub fn new(terms: &[(u32, u32, f64)]) -> Option<Polynomial> {
        let mut coeffs = [0.0; N_COEFFS];
        for &(a, b, c) in terms {
            if a.checked_add(b)? > MAX_DEGREE || !c.is_finite() {
                return None;
            }
            coeffs[index(a, b)] += c;
        }
        Some(Polynomial::absolute(coeffs)).filter(Polynomial::is_finite)
    }

    /// The polynomial `g(x, y) = Σ c_i (x − x0)^a_i (y − y0)^b_i − level`, expanded into
    /// absolute coordinates with the binomial theorem, where `origin = (x0, y0)` and
    /// `monomials[i] = (a_i, b_i)`, `coefficients[i] = c_i`.
    ///
    /// The recognizer works in local coordinates centred at a pixel; the exporter calls this
    /// with `origin = (x0 + 0.5, y0 + 0.5)` to move to SVG space.
    ///
    /// Returns `None` if the two slices differ in length, a monomial has degree above
    /// [`MAX_DEGREE`], or an input or an expanded coefficient is not finite.
    pub fn from_local(
        monomials: &[(u32, u32)],
        coefficients: &[f64],
        origin: Point,
        level: f64,
    ) -> Option<Polynomial> {
        if monomials.len() != coefficients.len()
            || !origin.is_finite()
            || !level.is_finite()
            || coefficients.iter().any(|c| !c.is_finite())
        {
            return None;
        }
        let mut coeffs = [0.0; N_COEFFS];
        let mut local = [0.0; N_COEFFS];
        let mut xp = [1.0; MAX_DEGREE as usize + 1];
        let mut yp = [1.0; MAX_DEGREE as usize + 1];
        for k in 1..xp.len() {
            xp[k] = xp[k - 1] * -origin.x;
            yp[k] = yp[k - 1] * -origin.y;
        }
        for (&(a, b), &c) in monomials.iter().zip(coefficients) {
            if a.checked_add(b)? > MAX_DEGREE {
                return None;
            }
            local[index(a, b)] += c;
            // (x − x0)^a = Σ_i C(a, i) x^i (−x0)^(a−i), likewise for y.
            for i in 0..=a {
                let cx = c * binomial(a, i) * xp[(a - i) as usize];
                for j in 0..=b {
                    coeffs[index(i, j)] += cx * binomial(b, j) * yp[(b - j) as usize];
                }
            }
        }
        coeffs[0] -= level;
        local[0] -= level;
        Some(Polynomial {
            coeffs,
            origin,
            top: top_degree(&local),
            local,
        })
        .filter(Polynomial::is_finite)
    }

    /// The polynomial with these absolute coefficients, evaluated in absolute coordinates.
    fn absolute(coeffs: [f64; N_COEFFS]) -> Polynomial {
        Polynomial {
            coeffs,
            origin: Point::ZERO,
            top: top_degree(&coeffs),
            local: coeffs,
        }
    }

    fn is_finite(&self) -> bool {
        self.coeffs.iter().chain(&self.local).all(|c| c.is_finite())
    }

    /// The coefficient of `x^a y^b` (0 when `a + b > MAX_DEGREE`).
    pub fn coefficient(&self, a: u32, b: u32) -> f64 {
        match a.checked_add(b) {
            Some(k) if k <= MAX_DEGREE => self.coeffs[index(a, b)],
            _ => 0.0,
        }
    }

    /// The non-zero terms `(a, b, c)` meaning `c x^a y^b`, by increasing total degree.
    pub fn terms(&self) -> Vec<(u32, u32, f64)> {
        let mut out = Vec::new();
        for k in 0..=MAX_DEGREE {
            for b in 0..=k {
                let c = self.coeffs[index(k - b, b)];
                if c != 0.0 {
                    out.push((k - b, b, c));
                }
            }
        }
        out
    }

    /// The total degree: the largest `a + b` with a non-zero coefficient (0 for constants).
    pub fn degree(&self) -> u32 {
        (0..=MAX_DEGREE)
            .rev()
            .find(|&k| (0..=k).any(|b| self.local[index(k - b, b)] != 0.0))
            .unwrap_or(0)
    }

    fn powers(p: Point) -> ([f64; 7], [f64; 7]) {
        // (Only powers up to the degree in use are read.)
        let mut xp = [1.0; 7];
        let mut yp = [1.0; 7];
        for k in 1..7 {
            xp[k] = xp[k - 1] * p.x;
            yp[k] = yp[k - 1] * p.y;
        }
        (xp, yp)
    }

    /// The value `f(p)`.
    pub fn eval(&self, p: Point) -> f64 {
        let (xp, yp) = Self::powers((p - self.origin).to_point());
        let mut s = 0.0;
        for k in 0..=self.top {
            for b in 0..=k {
                s += self.local[k * (k + 1) / 2 + b] * xp[k - b] * yp[b];
            }
        }
        s
    }

    /// The gradient `∇f(p) = (∂f/∂x, ∂f/∂y)`.
    pub fn gradient(&self, p: Point) -> Vec2 {
        let (xp, yp) = Self::powers((p - self.origin).to_point());
        let (mut gx, mut gy) = (0.0, 0.0);
        for k in 1..=self.top {
            for b in 0..=k {
                let a = k - b;
                let c = self.local[k * (k + 1) / 2 + b];
                if a > 0 {
                    gx += c * a as f64 * xp[a - 1] * yp[b];
                }
                if b > 0 {
                    gy += c * b as f64 * xp[a] * yp[b - 1];
                }
            }
        }
        Vec2::new(gx, gy)
    }

    /// The value and the gradient at `p` together (one evaluation of the powers of `p`).
    pub fn value_and_gradient(&self, p: Point) -> (f64, Vec2) {
        if self.top <= 2 {
            // Lines and conics (every border curve of those models), written out.
            let d = p - self.origin;
            let (x, y) = (d.x, d.y);
            let c = &self.local;
            let v = c[0] + x * (c[1] + c[3] * x + c[4] * y) + y * (c[2] + c[5] * y);
            let gx = c[1] + 2.0 * c[3] * x + c[4] * y;
            let gy = c[2] + c[4] * x + 2.0 * c[5] * y;
            return (v, Vec2::new(gx, gy));
        }
        let (xp, yp) = Self::powers((p - self.origin).to_point());
        let (mut v, mut gx, mut gy) = (self.local[0], 0.0, 0.0);
        for k in 1..=self.top {
            for b in 0..=k {
                let a = k - b;
                let c = self.local[k * (k + 1) / 2 + b];
                v += c * xp[a] * yp[b];
                if a > 0 {
                    gx += c * a as f64 * xp[a - 1] * yp[b];
                }
                if b > 0 {
                    gy += c * b as f64 * xp[a] * yp[b - 1];
                }
            }
        }
        (v, Vec2::new(gx, gy))
    }

    /// The first-order (Sampson) distance estimate `|f(p)| / |∇f(p)|` from `p` to the curve.
    ///
    /// Infinite where the gradient vanishes and `f(p) ≠ 0`.
    pub fn distance_estimate(&self, p: Point) -> f64 {
        let (v, g) = self.value_and_gradient(p);
        if v == 0.0 {
            return 0.0;
        }
        v.abs() / g.hypot()
    }

    /// The conic `a x² + b xy + c y² + d x + e y + f`.
    ///
    /// Returns `None` if the degree is above 2.
    pub fn as_conic(&self) -> Option<Conic> {
        if self.degree() > 2 {
            return None;
        }
        Some(Conic {
            a: self.coefficient(2, 0),
            b: self.coefficient(1, 1),
            c: self.coefficient(0, 2),
            d: self.coefficient(1, 0),
            e: self.coefficient(0, 1),
            f: self.coefficient(0, 0),
        })
    }
}

impl From<Conic> for Polynomial {
    fn from(k: Conic) -> Polynomial {
        let mut coeffs = [0.0; N_COEFFS];
        coeffs[index(2, 0)] = k.a;
        coeffs[index(1, 1)] = k.b;
        coeffs[index(0, 2)] = k.c;
        coeffs[index(1, 0)] = k.d;
        coeffs[index(0, 1)] = k.e;
        coeffs[index(0, 0)] = k.f;
        Polynomial::absolute(coeffs)
    }
}

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

/// The geometric kind of a [`Conic`], see [`Conic::classify`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ConicKind {
    /// No quadratic part: `d x + e y + f = 0` with `(d, e) ≠ 0`.
    Line,
    /// An ellipse with equal radii.
    Circle,
    /// A non-degenerate real ellipse that is not a circle.
    Ellipse,
    /// A non-degenerate parabola.
    Parabola,
    /// A non-degenerate hyperbola.
    Hyperbola,
    /// Everything else: empty real locus, a single point, two crossing lines, two parallel
    /// lines, a double line, or a constant (or non-finite) equation.
    Degenerate,
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
    /// * no quadratic part (`a = b = c = 0` exactly): [`ConicKind::Line`] if `(d, e) ≠ 0`;
    /// * `|b² − 4ac| ≤ 1e-10 (b² + 4|ac|)`: parabola-like; it is [`ConicKind::Parabola`] unless
    ///   the linear part across the axis, `|(d, e)·t|` (`t` the unit axis direction), is at most
    ///   `1e-10 |(d, e)|` — then the 3×3 determinant vanishes: parallel or double lines, or empty;
    /// * otherwise the conic is central; translating to the centre leaves the constant
    ///   `f' = f + (d x0 + e y0)/2` (proportional to the 3×3 determinant), taken as zero when
    ///   `|f'| ≤ 1e-10 (|f| + (|d x0| + |e y0|)/2)`. Then `b² − 4ac > 0` gives
    ///   [`ConicKind::Hyperbola`] (or two crossing lines if `f' = 0`), and `b² − 4ac < 0` gives
    ///   a real ellipse only when `f'` has the sign opposite to `a + c` (else the locus is empty
    ///   or a single point). The ellipse is a [`ConicKind::Circle`] when
    ///   `|a − c|, |b| ≤ 1e-12 (|a| + |c|)`, in particular when `a == c` and `b == 0`.
    pub fn classify(&self) -> ConicKind {
        if !self.is_finite() {
            return ConicKind::Degenerate;
        }
        let Conic { a, b, c, d, e, .. } = *self;
        if a == 0.0 && b == 0.0 && c == 0.0 {
            return if d != 0.0 || e != 0.0 {
                ConicKind::Line
            } else {
                ConicKind::Degenerate
            };
        }
        let disc = b * b - 4.0 * a * c;
        if disc.abs() <= DISC_EPS * (b * b + 4.0 * (a * c).abs()) {
            return if self.parabola_frame().is_some() {
                ConicKind::Parabola
            } else {
                ConicKind::Degenerate
            };
        }
        let Some((_, value, scale)) = self.centre() else {
            return ConicKind::Degenerate;
        };
        if value.abs() <= CENTRE_EPS * scale {
            return ConicKind::Degenerate;
        }
        if disc > 0.0 {
            return ConicKind::Hyperbola;
        }
        if value * (a + c) > 0.0 {
            return ConicKind::Degenerate;
        }
        let s = a.abs() + c.abs();
        if (a - c).abs() <= CIRCLE_EPS * s && b.abs() <= CIRCLE_EPS * s {
            ConicKind::Circle
        } else {
            ConicKind::Ellipse
        }
    }

    /// The centre, radii `(rx, ry)` and rotation angle `θ` of an ellipse or circle: the curve is
    /// `{centre + R(θ) (rx cos φ, ry sin φ)}`, which is exactly the SVG arc convention
    /// (`rx` along the axis rotated by `x_rotation = θ`). `θ ∈ (−π/2, π/2]`.
    ///
    /// Returns `None` unless [`Conic::classify`] gives `Circle` or `Ellipse`.
    pub fn ellipse_params(&self) -> Option<(Point, Vec2, f64)> {
        if !matches!(self.classify(), ConicKind::Circle | ConicKind::Ellipse) {
            return None;
        }
        let (centre, value, _) = self.centre()?;
        let pr = self.principal();
        let rx = (-value / pr.l1).sqrt();
        let ry = (-value / pr.l2).sqrt();
        (rx.is_finite() && ry.is_finite() && rx > 0.0 && ry > 0.0).then_some((
            centre,
            Vec2::new(rx, ry),
            pr.theta,
        ))
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
    pub fn parabola_params(&self) -> Option<(Point, Vec2, f64)> {
        if self.classify() != ConicKind::Parabola {
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
        (vertex.is_finite() && p.is_finite()).then_some((vertex, axis, p))
    }

    /// The centre, semi-axes `(a, b)` (`a` transverse, through the vertices; `b` conjugate) and
    /// the angle of the transverse axis: the curve is
    /// `{centre + R(θ) (±a cosh s, b sinh s)}`; the branches are the two signs.
    ///
    /// Returns `None` unless [`Conic::classify`] gives `Hyperbola`.
    pub fn hyperbola_params(&self) -> Option<(Point, Vec2, f64)> {
        if self.classify() != ConicKind::Hyperbola {
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
        semi.is_finite().then_some((centre, semi, angle))
    }
}

/// One SVG path command, in absolute coordinates; the start point is the end of the previous
/// command.
#[derive(Clone, Copy, Debug)]
pub enum PathCommand {
    /// `L x y`.
    Line(Point),
    /// `A rx ry x_rotation large_arc sweep x y`, exact elliptical arc.
    Arc(SvgArc),
    /// `Q x1 y1 x y`: control point, end point.
    Quad(Point, Point),
    /// `C x1 y1 x2 y2 x y`: two control points, end point.
    Cubic(Point, Point, Point),
}

impl PartialEq for PathCommand {
    fn eq(&self, other: &PathCommand) -> bool {
        use PathCommand::*;
        match (*self, *other) {
            (Line(p), Line(q)) => p == q,
            (Quad(a, p), Quad(b, q)) => a == b && p == q,
            (Cubic(a1, a2, p), Cubic(b1, b2, q)) => a1 == b1 && a2 == b2 && p == q,
            (Arc(a), Arc(b)) => {
                a.from == b.from
                    && a.to == b.to
                    && a.radii == b.radii
                    && a.x_rotation == b.x_rotation
                    && a.large_arc == b.large_arc
                    && a.sweep == b.sweep
            }
            _ => false,
        }
    }
}

impl PathCommand {
    /// The end point.
    pub fn end(&self) -> Point {
        match *self {
            PathCommand::Line(p) | PathCommand::Quad(_, p) | PathCommand::Cubic(_, _, p) => p,
            PathCommand::Arc(a) => a.to,
        }
    }

    /// Converts to kurbo path elements (without the initial `MoveTo`), starting at `start`.
    ///
    /// Arcs go through [`kurbo::Arc::from_svg_arc`] (with `from` replaced by `start`) and are
    /// approximated by cubics within [`ARC_FLATTEN_TOLERANCE`]; an arc that SVG treats as a
    /// straight line becomes a `LineTo`.
    pub fn to_path_els(&self, start: Point) -> Vec<PathEl> {
        match *self {
            PathCommand::Line(p) => vec![PathEl::LineTo(p)],
            PathCommand::Quad(c, p) => vec![PathEl::QuadTo(c, p)],
            PathCommand::Cubic(c1, c2, p) => vec![PathEl::CurveTo(c1, c2, p)],
            PathCommand::Arc(a) => {
                let svg = SvgArc { from: start, ..a };
                match Arc::from_svg_arc(&svg) {
                    Some(arc) => arc.append_iter(ARC_FLATTEN_TOLERANCE).collect(),
                    None => vec![PathEl::LineTo(a.to)],
                }
            }
        }
    }
}

/// Newton iteration along the gradient towards `f = 0`, starting at `p`.
///
/// Returns `None` if it leaves the disc of radius `max_distance` around `p`, meets a vanishing
/// gradient off the curve, or does not converge.
fn newton_to_curve(poly: &Polynomial, p: Point, max_distance: f64) -> Option<Point> {
    let mut q = p;
    for _ in 0..64 {
        let (v, g) = poly.value_and_gradient(q);
        if v == 0.0 {
            return Some(q);
        }
        let g2 = g.hypot2();
        if g2 <= 0.0 || !g2.is_finite() || !v.is_finite() {
            return None;
        }
        let step = g * (v / g2);
        q -= step;
        if (q - p).hypot() > max_distance {
            return None;
        }
        if step.hypot() <= 1e-13 * (1.0 + q.to_vec2().hypot()) {
            return Some(q);
        }
    }
    (poly.distance_estimate(q) <= 1e-7).then_some(q)
}

/// For a conic (degree ≤ 2): the point of the curve on the gradient line through `p`,
/// nearest to `p` on the side where `|f|` decreases, as `(t, q)` with `t = |q − p|`.
///
/// Along that line `f` is a quadratic in the distance travelled: with `w` the unit vector
/// down the gradient (towards `f = 0`), `f(p + t w)·sign(f(p)) = |f| − t |∇f| +
/// t² s wᵀHw / 2` (`s = sign f(p)`, `H` the constant Hessian), whose smallest positive root
/// is `2|f| / (|∇f| + √(|∇f|² − 2 s wᵀHw |f|))`.
///
/// Returns `None` for higher degrees, a vanishing or non-finite gradient, or no point of
/// the curve on that line.
fn conic_foot(poly: &Polynomial, p: Point) -> Option<(f64, Point)> {
    if poly.top > 2 {
        return None;
    }
    let (v, g) = poly.value_and_gradient(p);
    if v == 0.0 {
        return Some((0.0, p));
    }
    let gn = g.hypot();
    if !(gn > 0.0 && gn.is_finite() && v.is_finite()) {
        return None;
    }
    let u = g / gn;
    let c = &poly.local;
    let uhu = 2.0 * (c[3] * u.x * u.x + c[4] * u.x * u.y + c[5] * u.y * u.y);
    let a = v.abs();
    let disc = gn * gn - 2.0 * v.signum() * uhu * a;
    if disc < 0.0 {
        return None;
    }
    let t = 2.0 * a / (gn + disc.sqrt());
    Some((t, p - u * (t * v.signum())))
}

/// An upper bound on the distance from `p` to the curve. For conics, the distance to the
/// [`conic_foot`] (closed form). Otherwise `|p − q| + r` for the first point `q` of the
/// Newton iteration towards `f = 0` (as in [`newton_to_curve`]) whose first-order distance
/// `r = |f(q)| / |∇f(q)|` is below 1e-9 px (so `r` is the distance to the curve up to terms
/// of order `r²`): one iteration fewer than running Newton to convergence.
///
/// Returns `None` where [`newton_to_curve`] would fail (leaving the disc of radius
/// `max_distance`, a vanishing gradient, no convergence).
fn distance_bound(poly: &Polynomial, p: Point, max_distance: f64) -> Option<f64> {
    if let Some((t, _)) = conic_foot(poly, p) {
        return (t <= max_distance).then_some(t);
    }
    let mut q = p;
    for _ in 0..64 {
        let (v, g) = poly.value_and_gradient(q);
        let g2 = g.hypot2();
        if v == 0.0 {
            return Some((q - p).hypot());
        }
        if g2 <= 0.0 || !g2.is_finite() || !v.is_finite() {
            return None;
        }
        let r = v.abs() / g2.sqrt();
        let d = (q - p).hypot();
        if r <= 1e-9 {
            return Some(d + r);
        }
        q -= g * (v / g2);
        if (q - p).hypot() > max_distance {
            return None;
        }
    }
    None
}

/// The unit tangent `∇f⊥ / |∇f|` (rotated +90°), if the gradient does not vanish.
fn unit_tangent(poly: &Polynomial, p: Point) -> Option<Vec2> {
    let g = poly.gradient(p);
    let n = g.hypot();
    (n > 0.0 && n.is_finite()).then(|| Vec2::new(-g.y / n, g.x / n))
}

/// The point of the curve `poly = 0` closest to `point`, if within `max_distance`.
///
/// Newton steps along the gradient reach the curve; then the point slides along the tangent
/// until `point − q` is normal to the curve (linear convergence, fast where the distance is
/// small compared to the radius of curvature).
///
/// Returns `None` if no point of the curve is found within `max_distance`, or on non-finite
/// input.
pub fn project(poly: &Polynomial, point: Point, max_distance: f64) -> Option<Point> {
    if !point.is_finite() || max_distance.is_nan() || max_distance < 0.0 {
        return None;
    }
    let reach = 2.0 * max_distance + 1e-9;
    let mut q = newton_to_curve(poly, point, reach)?;
    let mut best = q;
    let mut best_d = (q - point).hypot();
    for _ in 0..100 {
        let Some(t) = unit_tangent(poly, q) else {
            break;
        };
        let s = (point - q).dot(t);
        if s.abs() <= 1e-12 * (1.0 + best_d) {
            break;
        }
        let Some(q2) = newton_to_curve(poly, q + t * s, reach) else {
            break;
        };
        q = q2;
        let d = (q - point).hypot();
        if d < best_d {
            best = q;
            best_d = d;
        }
    }
    (best_d <= max_distance).then_some(best)
}

/// The intersection point of `p = 0` and `q = 0` closest to `near`, within `max_distance`.
///
/// Runs Newton's method on the 2×2 system from `near`, from the projections of `near` on both
/// curves and from 16 points on two circles around `near`; keeps the converged solutions
/// (each curve within 1e-7 by [`Polynomial::distance_estimate`]).
///
/// Returns `None` if no intersection is found within `max_distance`, or on non-finite input.
pub fn intersect_near(
    p: &Polynomial,
    q: &Polynomial,
    near: Point,
    max_distance: f64,
) -> Option<Point> {
    if !near.is_finite() || max_distance < 0.0 || !max_distance.is_finite() {
        return None;
    }
    let mut starts = vec![near];
    starts.extend(project(p, near, max_distance));
    starts.extend(project(q, near, max_distance));
    for r in [0.5 * max_distance, max_distance] {
        for k in 0..8 {
            starts.push(near + Vec2::from_angle(f64::from(k) * PI / 4.0) * r);
        }
    }
    let mut best: Option<(Point, f64)> = None;
    for s in starts {
        let Some(x) = newton_system(p, q, s, near, max_distance) else {
            continue;
        };
        let d = (x - near).hypot();
        if d <= max_distance && best.is_none_or(|(_, bd)| d < bd) {
            best = Some((x, d));
        }
    }
    best.map(|(x, _)| x)
}

fn newton_system(
    p: &Polynomial,
    q: &Polynomial,
    start: Point,
    near: Point,
    max_distance: f64,
) -> Option<Point> {
    let mut x = start;
    for _ in 0..80 {
        let ((fp, gp), (fq, gq)) = (p.value_and_gradient(x), q.value_and_gradient(x));
        if fp == 0.0 && fq == 0.0 {
            break;
        }
        let det = gp.x * gq.y - gp.y * gq.x;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let step = Vec2::new((gq.y * fp - gp.y * fq) / det, (gp.x * fq - gq.x * fp) / det);
        if !step.is_finite() {
            return None;
        }
        x -= step;
        if (x - near).hypot() > 2.0 * max_distance + 1e-9 {
            return None;
        }
        if step.hypot() <= 1e-13 * (1.0 + x.to_vec2().hypot()) {
            break;
        }
    }
    (p.distance_estimate(x) <= 1e-7 && q.distance_estimate(x) <= 1e-7).then_some(x)
}

/// The part of the level curve `poly = 0` from `from` to `to`, as SVG path commands, with the
/// measured maximal distance between the emitted path and the true curve (0 for the exact
/// forms: lines, circular and elliptical arcs, parabola arcs).
///
/// `from` and `to` lie on the curve (within ~1e-6); `guide` are points near the curve (within
/// [`GUIDE_MAX_DISTANCE`]), in path order, telling which part of the curve is meant: which way
/// round a closed curve, which branch of a hyperbola. When `from == to` on a closed curve the
/// whole curve is meant (for ellipses two arcs are emitted, of a third and two thirds of a turn; for traced curves the guide must
/// go round).
///
/// * degree 1: one [`PathCommand::Line`];
/// * circle / ellipse: one exact [`PathCommand::Arc`] whose direction is the one agreeing best
///   with the guide (angular distance of the guide points outside the arc plus backward
///   motion between consecutive points; ties go to the shorter arc);
/// * parabola: one exact [`PathCommand::Quad`] whose control point is the intersection of the
///   tangents at `from` and `to`;
/// * hyperbola (same branch), degenerate conics and degree > 2: the curve is traced from
///   `from` to `to` through the guide points' projections (predictor along the tangent,
///   Newton corrector, step ≤ 0.25 px), then fitted by cubic Béziers tangent to the curve at
///   their ends (tangent lengths by least squares, or a third of the arc length, whichever is
///   closer), subdivided until the distance to the true curve, measured both ways at samples
///   with Newton projections, is at most `tolerance`.
///
/// Returns `None` for non-finite input, a non-positive `tolerance`, a constant polynomial,
/// `from`/`to` not on the curve (within 0.01), a guide point whose projection fails or (for
/// parabolas) lies farther than [`GUIDE_MAX_DISTANCE`] from the arc, points on different
/// hyperbola branches, a trace that does not reach `to`, or a trace step that no cubic
/// follows within `tolerance` (it jumps the gap between two branches by a saddle).
#[allow(clippy::neg_cmp_op_on_partial_ord)] // `!(d <= max)` also rejects NaN distances.
pub fn level_curve_path(
    poly: &Polynomial,
    from: Point,
    to: Point,
    guide: &[Point],
    tolerance: f64,
) -> Option<(Vec<PathCommand>, f64)> {
    if !from.is_finite()
        || !to.is_finite()
        || guide.iter().any(|g| !g.is_finite())
        || tolerance <= 0.0
        || !tolerance.is_finite()
        || !poly.is_finite()
    {
        return None;
    }
    if poly.degree() == 0
        || !(poly.distance_estimate(from) <= ENDPOINT_MAX_DISTANCE)
        || !(poly.distance_estimate(to) <= ENDPOINT_MAX_DISTANCE)
    {
        return None;
    }
    if let Some(conic) = poly.as_conic() {
        match conic.classify() {
            ConicKind::Line => {
                let cmds = if from == to {
                    Vec::new()
                } else {
                    vec![PathCommand::Line(to)]
                };
                return Some((cmds, 0.0));
            }
            ConicKind::Circle | ConicKind::Ellipse => {
                if let Some(sagitta) = flat_arc(&conic, from, to, guide, tolerance) {
                    let cmds = if from == to {
                        Vec::new()
                    } else {
                        vec![PathCommand::Line(to)]
                    };
                    return Some((cmds, sagitta));
                }
                return ellipse_path(&conic, from, to, guide).map(|c| (c, 0.0));
            }
            ConicKind::Parabola => return parabola_path(&conic, from, to, guide).map(|c| (c, 0.0)),
            ConicKind::Hyperbola => {
                let params = conic.hyperbola_params()?;
                let (centre, _, angle) = params;
                let axis = Vec2::from_angle(angle);
                if (from - centre).dot(axis) * (to - centre).dot(axis) < 0.0 {
                    return None; // different branches
                }
                let trace = hyperbola_trace(poly, params, from, to, guide)
                    .or_else(|| trace_curve(poly, from, to, guide))?;
                return fit_cubics(poly, &trace, tolerance);
            }
            ConicKind::Degenerate => {}
        }
    }
    let trace = trace_curve(poly, from, to, guide)?;
    fit_cubics(poly, &trace, tolerance)
}

/// A circle or ellipse so large next to the piece that the chord `from → to` is within
/// `tolerance` of the arc: returns the bound on their distance, the sagitta
/// `ρ − √(ρ² − c²/4)` for the chord length `c` and the smallest radius of curvature
/// `ρ = b²/a`.
///
/// Such curves come from nearly straight pieces (radii of 10⁴–10²² px), where the angles an
/// exact arc needs lose their precision. Only when the chord is not empty and shorter than
/// `ρ`, every guide point lies beside it — within [`GUIDE_MAX_DISTANCE`] of the segment,
/// and projecting onto its line within one pixel of its ends — and the guide path is no
/// longer than `1.5 c + 2`, so that the piece runs along the short arc; returns `None`
/// otherwise (in particular for a piece that goes round a small curve).
fn flat_arc(conic: &Conic, from: Point, to: Point, guide: &[Point], tolerance: f64) -> Option<f64> {
    let (_, radii, _) = conic.ellipse_params()?;
    let (a, b) = (radii.x.max(radii.y), radii.x.min(radii.y));
    let rho = b * b / a;
    let chord = to - from;
    let c = chord.hypot();
    if !(c > 0.0 && c < rho) {
        return None;
    }
    // ρ − √(ρ² − c²/4), without the cancellation.
    let sagitta = c * c / 4.0 / (rho + (rho * rho - c * c / 4.0).sqrt());
    let beside = guide.iter().all(|&g| {
        let along = (g - from).dot(chord) / c;
        (-1.0..=c + 1.0).contains(&along) && segment_distance(g, from, to) <= GUIDE_MAX_DISTANCE
    });
    // A pixel path along a chord is at most √2 times as long (plus its ends); one that goes
    // round a small curve is far longer.
    let mut length = 0.0;
    let mut prev = from;
    for &g in guide.iter().chain(std::iter::once(&to)) {
        length += (g - prev).hypot();
        prev = g;
    }
    let along_chord = length <= 1.5 * c + 2.0;
    (sagitta <= tolerance && beside && along_chord).then_some(sagitta)
}

/// Exact elliptical arc(s) from `from` to `to`, going the way the guide says.
fn ellipse_path(
    conic: &Conic,
    from: Point,
    to: Point,
    guide: &[Point],
) -> Option<Vec<PathCommand>> {
    let (centre, radii, theta) = conic.ellipse_params()?;
    let rot = Vec2::from_angle(theta);
    let angle = |p: Point| {
        let v = p - centre;
        let x = v.dot(rot);
        let y = rot.cross(v);
        (y / radii.y).atan2(x / radii.x)
    };
    let at = |phi: f64| {
        let (s, c) = phi.sin_cos();
        let v = Vec2::new(radii.x * c, radii.y * s);
        centre + Vec2::new(v.x * rot.x - v.y * rot.y, v.x * rot.y + v.y * rot.x)
    };
    let full = (to - from).hypot() <= 1e-9 * (radii.x + radii.y);
    let phi0 = angle(from);
    let phi1 = angle(to);
    let span_pos = if full {
        TAU
    } else {
        (phi1 - phi0).rem_euclid(TAU)
    };
    let wrap = |x: f64| {
        // into (−π, π]
        let r = (x + PI).rem_euclid(TAU) - PI;
        if r == -PI {
            PI
        } else {
            r
        }
    };
    let mut angles = vec![phi0];
    angles.extend(guide.iter().map(|&g| angle(g)));
    angles.push(if full { phi0 } else { phi1 });
    let cost = |dir: f64| {
        let span = if full || dir > 0.0 {
            span_pos
        } else {
            TAU - span_pos
        };
        let mut c = 0.0;
        // Angular distance of guide points outside the arc.
        for &psi in &angles[1..angles.len() - 1] {
            let u = (dir * (psi - phi0)).rem_euclid(TAU);
            if u > span {
                c += (u - span).min(TAU - u);
            }
        }
        // Backward motion between consecutive points (not for the full turn's closing pair).
        for w in angles.windows(2) {
            c += (-dir * wrap(w[1] - w[0])).max(0.0);
        }
        c
    };
    let (cp, cn) = (cost(1.0), cost(-1.0));
    let dir = if (cp - cn).abs() <= 1e-12 {
        if full || span_pos <= PI {
            1.0
        } else {
            -1.0
        }
    } else if cp < cn {
        1.0
    } else {
        -1.0
    };
    let sweep = dir > 0.0;
    if full {
        // Not two half turns: an SVG arc whose chord is a diameter is ill-conditioned.
        let mid = at(phi0 + dir * TAU / 3.0);
        let arc = |a: Point, b: Point, large_arc: bool| {
            PathCommand::Arc(SvgArc {
                from: a,
                to: b,
                radii,
                x_rotation: theta,
                large_arc,
                sweep,
            })
        };
        return Some(vec![arc(from, mid, false), arc(mid, to, true)]);
    }
    let span = if sweep { span_pos } else { TAU - span_pos };
    Some(vec![PathCommand::Arc(SvgArc {
        from,
        to,
        radii,
        x_rotation: theta,
        large_arc: span > PI,
        sweep,
    })])
}

/// The exact quadratic Bézier of the parabola arc from `from` to `to`.
fn parabola_path(
    conic: &Conic,
    from: Point,
    to: Point,
    guide: &[Point],
) -> Option<Vec<PathCommand>> {
    if from == to {
        return Some(Vec::new());
    }
    let (g0, g1) = (conic.gradient(from), conic.gradient(to));
    // g0·(Q − from) = 0 and g1·(Q − to) = 0.
    let det = g0.cross(g1);
    if det.abs() <= 1e-14 * g0.hypot() * g1.hypot() {
        return None;
    }
    let (r0, r1) = (g0.dot(from.to_vec2()), g1.dot(to.to_vec2()));
    let ctrl = Point::new((r0 * g1.y - r1 * g0.y) / det, (g0.x * r1 - g1.x * r0) / det);
    if !ctrl.is_finite() {
        return None;
    }
    let quad = QuadBez::new(from, ctrl, to);
    let guide_ok = guide
        .iter()
        .all(|&g| quad.nearest(g, 1e-9).distance_sq <= GUIDE_MAX_DISTANCE * GUIDE_MAX_DISTANCE);
    guide_ok.then(|| vec![PathCommand::Quad(ctrl, to)])
}

/// A traced polyline on the curve with unit tangents in the direction of travel.
struct Trace {
    pts: Vec<Point>,
    tans: Vec<Vec2>,
}

/// The trace of a hyperbola arc from its parametrisation `centre + R(θ)(σ a cosh s, b sinh s)`
/// (`(centre, (a, b), θ)` as [`Conic::hyperbola_params`] gives them), with points at most [`HYPERBOLA_STEP`] apart in arc length
/// and [`HYPERBOLA_TURN`] in direction, and exact tangents, instead of marching along the
/// curve: between two points of one branch the arc
/// is unique. The parameter of a point of the curve is `asinh(v / b)`, `v` its coordinate
/// along the conjugate axis.
///
/// Returns `None` (the caller then marches with [`trace_curve`]) where the parametrisation
/// is not precise (coordinates beyond 1e8 px, or the middle trace point more than 1e-6 px
/// off the curve, as for huge, nearly parabolic hyperbolas), where `from == to`, or where a
/// guide point does not lie along the arc: its point of the curve ([`conic_foot`], else
/// [`project`]) must be within [`GUIDE_MAX_DISTANCE`], on the branch, and within
/// 1 + 2 [`GUIDE_MAX_DISTANCE`] px of arc length of the arc; or where the trace needs more
/// than four times the points of an arc of 3 times the guide's path plus 20 px (a safety
/// cap, as the marcher's).
#[allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x <= y)` also rejects NaN.
fn hyperbola_trace(
    poly: &Polynomial,
    (centre, semi, angle): (Point, Vec2, f64),
    from: Point,
    to: Point,
    guide: &[Point],
) -> Option<Trace> {
    if from == to {
        return None;
    }
    let (axis, across) = (Vec2::from_angle(angle), Vec2::from_angle(angle).turn_90());
    let (a, b) = (semi.x, semi.y);
    let local = |p: Point| ((p - centre).dot(axis), (p - centre).dot(across));
    let (u0, v0) = local(from);
    let (u1, v1) = local(to);
    let sigma = if u0 + u1 >= 0.0 { 1.0 } else { -1.0 };
    let (s0, s1) = ((v0 / b).asinh(), (v1 / b).asinh());
    let reach = centre.to_vec2().hypot() + a * s0.abs().max(s1.abs()).cosh();
    if !(reach <= 1e8) {
        return None;
    }
    let dir = if s1 >= s0 { 1.0 } else { -1.0 };
    // Speed |P′(s)| and unit tangent from (sinh s, cosh s).
    let speed = |(sh, ch): (f64, f64)| ((a * sh).powi(2) + (b * ch).powi(2)).sqrt();
    let tangent = |(sh, ch): (f64, f64)| {
        let t = axis * (sigma * a * sh) + across * (b * ch);
        t * (dir / t.hypot())
    };
    let sinh_cosh = |s: f64| (s.sinh(), s.cosh());
    let (lo, hi) = (s0.min(s1), s0.max(s1));
    for &g in guide {
        let q = match conic_foot(poly, g) {
            Some((d, q)) if d <= GUIDE_MAX_DISTANCE => q,
            _ => project(poly, g, GUIDE_MAX_DISTANCE)?,
        };
        let (u, v) = local(q);
        let sq = (v / b).asinh();
        let slack = (1.0 + 2.0 * GUIDE_MAX_DISTANCE) / speed(sinh_cosh(sq));
        if u * sigma < 0.0 || sq < lo - slack || sq > hi + slack {
            return None;
        }
    }
    // As in trace_curve, no arc longer than 3 times the guide's path plus 20 px; the
    // branch turns by less than π in all.
    let max_len = 3.0 * guide_length(from, guide, to) + 20.0;
    let max_points = (4.0 * (max_len / HYPERBOLA_STEP + PI / HYPERBOLA_TURN)) as usize + 2;
    let mut pts = vec![from];
    let mut tans = vec![tangent(sinh_cosh(s0))];
    // Steps in s: the arc length is ∫|P′| ds and the tangent turns by ∫ ab / |P′|² ds, with
    // the speed |P′(s)| = |(a sinh s, b cosh s)| monotonic on each side of the vertex
    // (s = 0): bounding by the speeds at both ends of a step (or at the vertex, if the
    // step crosses it) keeps it within
    // HYPERBOLA_STEP of length and HYPERBOLA_TURN of turn. e = exp(s) is carried by
    // multiplication, for cosh and sinh without further calls.
    let (mut s, mut e) = (s0, s0.exp());
    let from_exp = |e: f64| (0.5 * (e - 1.0 / e), 0.5 * (e + 1.0 / e));
    let speed_at = |e: f64| speed(from_exp(e));
    let step_for =
        |fast: f64, slow: f64| (HYPERBOLA_STEP / fast).min(HYPERBOLA_TURN * slow * slow / (a * b));
    loop {
        if pts.len() > max_points {
            return None;
        }
        let v = speed_at(e);
        let trial = step_for(v, v);
        let v_far = speed_at(e * (dir * trial).exp());
        // Across the vertex the slowest point is the vertex, where |P′| = b.
        let crosses = s * (s + dir * trial) <= 0.0;
        let slow = if crosses { b } else { v.min(v_far) };
        let ds = step_for(v.max(v_far), slow);
        // The rest in one step if it fits, else in two halves if it fits in two.
        let rest = (s1 - s) * dir;
        if !(rest > ds) {
            break;
        }
        let ds = if rest < 2.0 * ds { 0.5 * rest } else { ds };
        s += dir * ds;
        e *= (dir * ds).exp();
        let (sh, ch) = from_exp(e);
        pts.push(centre + axis * (sigma * a * ch) + across * (b * sh));
        tans.push(tangent((sh, ch)));
    }
    if pts.len() > 2 && !(poly.distance_estimate(pts[pts.len() / 2]) <= 1e-6) {
        return None;
    }
    pts.push(to);
    tans.push(tangent(sinh_cosh(s1)));
    Some(Trace { pts, tans })
}

/// Length of the polyline `from`, `guide…`, `to`.
fn guide_length(from: Point, guide: &[Point], to: Point) -> f64 {
    let mut len = 0.0;
    let mut prev = from;
    for &p in guide.iter().chain(std::iter::once(&to)) {
        len += (p - prev).hypot();
        prev = p;
    }
    len
}

/// Distance from `p` to the segment `[a, b]`.
fn segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let ab = b - a;
    let l2 = ab.hypot2();
    let t = if l2 > 0.0 {
        ((p - a).dot(ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * t)).hypot()
}

/// Marches along the curve from `from` to `to`, passing the projections of the guide points.
fn trace_curve(poly: &Polynomial, from: Point, to: Point, guide: &[Point]) -> Option<Trace> {
    let start = project(poly, from, ENDPOINT_MAX_DISTANCE)?;
    let end = project(poly, to, ENDPOINT_MAX_DISTANCE)?;
    let targets: Vec<Point> = guide
        .iter()
        .map(|&g| project(poly, g, GUIDE_MAX_DISTANCE))
        .collect::<Option<_>>()?;
    let guide_len = guide_length(from, guide, to);
    if from == to && targets.is_empty() {
        return Some(Trace {
            pts: vec![from],
            tans: vec![Vec2::ZERO],
        });
    }
    // Guide points close to the ends may project just outside the piece: not required.
    let mut visited: Vec<bool> = targets
        .iter()
        .map(|&w| (w - start).hypot() <= 1.0 || (w - end).hypot() <= 1.0)
        .collect();
    let mut unvisited = visited.iter().filter(|&&v| !v).count();
    // The targets by unit cell, so that each step only looks at the targets near it (a
    // piece may have thousands of them).
    let cell = |p: Point| Pixel::new(p.x.floor() as i32, p.y.floor() as i32);
    let mut grid: PixelMap<Vec<usize>> = PixelMap::default();
    for (k, &w) in targets.iter().enumerate() {
        if !visited[k] {
            grid.entry(cell(w)).or_default().push(k);
        }
    }
    // Initial orientation: towards the first waypoint not too close to the start.
    let first = targets
        .iter()
        .chain(std::iter::once(&end))
        .find(|&&w| (w - start).hypot() > 0.5)
        .or_else(|| {
            targets
                .iter()
                .chain(std::iter::once(&end))
                .max_by(|a, b| (**a - start).hypot().total_cmp(&(**b - start).hypot()))
        })
        .copied()?;
    let towards = first - start;
    let mut t = match unit_tangent(poly, start) {
        Some(t) if t.dot(towards) >= 0.0 => t,
        Some(t) => -t,
        None => towards.normalize(),
    };
    if !t.is_finite() {
        return None;
    }
    let mut pts = vec![from];
    let mut tans = vec![t];
    let mut p = start;
    let mut h = TRACE_STEP;
    let mut travelled = 0.0;
    let max_len = 3.0 * guide_len + 20.0;
    let mut iterations = 0usize;
    loop {
        iterations += 1;
        if travelled > max_len || iterations > 1_000_000 {
            return None;
        }
        let q0 = p + t * h;
        let accepted = newton_to_curve(poly, q0, h).and_then(|q| {
            let tq = match unit_tangent(poly, q) {
                Some(tq) if tq.dot(t) >= 0.0 => tq,
                Some(tq) => -tq,
                None => t,
            };
            let ok =
                (q - q0).hypot() <= 0.3 * h && tq.dot(t) >= 0.3f64.cos() && (q - p).dot(t) > 0.0;
            ok.then_some((q, tq))
        });
        let Some((q, tq)) = accepted else {
            h *= 0.5;
            if h < 1e-9 {
                return None;
            }
            continue;
        };
        let near = (0.2 * h).max(1e-6);
        if unvisited > 0 {
            let (lo, hi) = (
                cell(Point::new(p.x.min(q.x) - near, p.y.min(q.y) - near)),
                cell(Point::new(p.x.max(q.x) + near, p.y.max(q.y) + near)),
            );
            for cy in lo.y..=hi.y {
                for cx in lo.x..=hi.x {
                    let Some(ks) = grid.get(&Pixel::new(cx, cy)) else {
                        continue;
                    };
                    for &k in ks {
                        if !visited[k] && segment_distance(targets[k], p, q) <= near {
                            visited[k] = true;
                            unvisited -= 1;
                        }
                    }
                }
            }
        }
        let step_len = (q - p).hypot();
        if unvisited == 0
            && travelled + step_len >= 0.5 * guide_len
            && segment_distance(end, p, q) <= near
        {
            let t_end = match unit_tangent(poly, end) {
                Some(te) if te.dot(tq) >= 0.0 => te,
                Some(te) => -te,
                None => tq,
            };
            pts.push(to);
            tans.push(t_end);
            return Some(Trace { pts, tans });
        }
        travelled += step_len;
        pts.push(q);
        tans.push(tq);
        p = q;
        t = tq;
        h = (1.5 * h).min(TRACE_STEP);
    }
}

/// Cubic candidates over the trace points `i..=j`, both with the end tangents of the trace:
/// the Hermite cubic with tangent lengths a third of the arc length, and (when it is well
/// posed) the least-squares one whose two tangent lengths minimise the squared distances to
/// the trace points at their chord-length parameters (Schneider's method).
fn candidates(trace: &Trace, i: usize, j: usize) -> Vec<CubicBez> {
    let pts = &trace.pts[i..=j];
    let mut cum = Vec::with_capacity(pts.len());
    let mut len = 0.0;
    cum.push(0.0);
    for w in pts.windows(2) {
        len += (w[1] - w[0]).hypot();
        cum.push(len);
    }
    let (p0, p3) = (pts[0], pts[pts.len() - 1]);
    let (t0, t1) = (trace.tans[i], -trace.tans[j]);
    let mut out = vec![CubicBez::new(
        p0,
        p0 + t0 * (len / 3.0),
        p3 + t1 * (len / 3.0),
        p3,
    )];
    if pts.len() < 4 || len <= 0.0 {
        return out;
    }
    let (mut c00, mut c01, mut c11, mut x0, mut x1) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (p, &l) in pts.iter().zip(&cum) {
        let t = l / len;
        let mt = 1.0 - t;
        let (b0, b1, b2, b3) = (mt * mt * mt, 3.0 * t * mt * mt, 3.0 * t * t * mt, t * t * t);
        let (a1, a2) = (t0 * b1, t1 * b2);
        c00 += a1.dot(a1);
        c01 += a1.dot(a2);
        c11 += a2.dot(a2);
        let r = *p - (p0.to_vec2() * (b0 + b1) + p3.to_vec2() * (b2 + b3)).to_point();
        x0 += r.dot(a1);
        x1 += r.dot(a2);
    }
    let det = c00 * c11 - c01 * c01;
    if det.abs() > 1e-12 * c00 * c11 {
        let alpha = (x0 * c11 - x1 * c01) / det;
        let beta = (c00 * x1 - c01 * x0) / det;
        if alpha > 1e-3 * len && beta > 1e-3 * len && alpha < len && beta < len {
            out.push(CubicBez::new(p0, p0 + t0 * alpha, p3 + t1 * beta, p3));
        }
    }
    out
}

/// An upper bound on the distance between a cubic and the curve, in both directions: from
/// cubic samples to the curve (the point of the curve that Newton steps along the gradient
/// reach from the sample), and from the trace points `i..=j` to the cubic (the point of the
/// cubic that Newton's method on `(B(t) − p)·B′(t) = 0` reaches from the previous trace
/// point's parameter). Both are distances to actual points of the other curve, hence upper
/// bounds of the true distances; for the small distances a fit accepts they are within
/// `O(d²κ)` of them.
///
/// Stops early, returning a value above `cutoff`, once the bound exceeds `cutoff`.
fn cubic_error(
    poly: &Polynomial,
    c: &CubicBez,
    trace: &Trace,
    i: usize,
    j: usize,
    tol: f64,
    cutoff: f64,
) -> f64 {
    let mut err: f64 = 0.0;
    // 23 samples at k/24, the coarse ones first (a bad fit is usually worst mid-way, so
    // the cutoff is met early).
    const ORDER: [u8; 23] = [
        12, 6, 18, 3, 9, 15, 21, 1, 2, 4, 5, 7, 8, 10, 11, 13, 14, 16, 17, 19, 20, 22, 23,
    ];
    for k in ORDER {
        let s = c.eval(f64::from(k) / 24.0);
        match distance_bound(poly, s, 4.0 * tol + 1.0) {
            Some(d) => err = err.max(d),
            None => return f64::INFINITY,
        }
        if err > cutoff {
            return err;
        }
    }
    // Trace points, at most about 64 of them, evenly spread, in order along the cubic.
    // Power form B(u) = ((c3 u + c2) u + c1) u + c0, for cheap B, B′ and B″.
    let (p0, p1, p2, p3) = (
        c.p0.to_vec2(),
        c.p1.to_vec2(),
        c.p2.to_vec2(),
        c.p3.to_vec2(),
    );
    let c1 = (p1 - p0) * 3.0;
    let c2 = (p2 - p1 * 2.0 + p0) * 3.0;
    let c3 = p3 - p0 + (p1 - p2) * 3.0;
    let stride = ((j - i) / 64).max(1);
    let mut t = 0.0;
    for &p in trace.pts[i + 1..j].iter().step_by(stride) {
        let q = p.to_vec2() - p0;
        let mut best = f64::INFINITY;
        let mut u: f64 = t;
        for _ in 0..8 {
            let r = ((c3 * u + c2) * u + c1) * u - q;
            let d = r.hypot2();
            if d < best {
                best = d;
                t = u;
            }
            if d <= err * err {
                break; // this point cannot raise the maximum
            }
            let v1 = (c3 * (3.0 * u) + c2 * 2.0) * u + c1;
            let v2 = c3 * (6.0 * u) + c2 * 2.0;
            let g = r.dot(v1);
            let h = v1.hypot2() + r.dot(v2);
            let next = if h > 0.0 {
                u - g / h
            } else {
                u - g.signum() * 0.05
            };
            let next = next.clamp(0.0, 1.0);
            if (next - u).abs() <= 1e-9 {
                break;
            }
            u = next;
        }
        err = err.max(best.sqrt());
        if err > cutoff {
            return err;
        }
    }
    err
}

/// The better of the [`candidates`] over the trace points `i..=j`, with its error bound
/// (see [`cubic_error`]; above `cutoff` only says that no candidate is within `cutoff`).
fn best_fit(
    poly: &Polynomial,
    trace: &Trace,
    i: usize,
    j: usize,
    tol: f64,
    cutoff: f64,
) -> (CubicBez, f64) {
    let mut cands = candidates(trace, i, j).into_iter();
    let first = cands
        .next()
        .unwrap_or_else(|| CubicBez::new(trace.pts[i], trace.pts[i], trace.pts[j], trace.pts[j]));
    let first_err = cubic_error(poly, &first, trace, i, j, tol, cutoff);
    cands.fold((first, first_err), |best, c| {
        let err = cubic_error(poly, &c, trace, i, j, tol, cutoff.min(best.1));
        if err < best.1 {
            (c, err)
        } else {
            best
        }
    })
}

/// Piecewise cubic fit of a trace within `tol`; returns the commands and the maximal error.
///
/// Greedy: from each start, the farthest trace point reachable by one cubic within `tol` is
/// found by galloping then bisection.
///
/// Returns None if a single trace step cannot be fitted within `tol`: where the trace
/// crosses the gap between two branches by a saddle of `f`, its chord is off the curve.
fn fit_cubics(poly: &Polynomial, trace: &Trace, tol: f64) -> Option<(Vec<PathCommand>, f64)> {
    let n = trace.pts.len();
    let mut out = Vec::new();
    let mut max_err: f64 = 0.0;
    let mut i = 0;
    while i + 1 < n {
        // Gallop: double the reach while one cubic fits, then bisect. Invariant: the fit to
        // `lo` is acceptable (`best`; or lo = i + 1, not yet measured), the fit to `hi` is
        // not.
        let mut lo = i + 1;
        let mut best = None;
        let mut hi = None;
        let mut step = 8;
        // The rest of the trace first: one cubic often suffices for a whole piece, and a
        // failing try stops at the cutoff.
        if n - 1 > i + step {
            let fit = best_fit(poly, trace, i, n - 1, tol, tol);
            if fit.1 <= tol {
                lo = n - 1;
                best = Some(fit);
            } else {
                hi = Some(n - 1);
            }
        }
        while lo < n - 1 && hi.is_none_or(|h| i + step < h) {
            let j = (i + step).min(n - 1);
            let fit = best_fit(poly, trace, i, j, tol, tol);
            if fit.1 <= tol {
                lo = j;
                best = Some(fit);
                step *= 2;
            } else {
                hi = Some(j);
                break;
            }
        }
        if let Some(mut hi) = hi {
            while hi - lo > 1 {
                let mid = (lo + hi) / 2;
                let fit = best_fit(poly, trace, i, mid, tol, tol);
                if fit.1 <= tol {
                    lo = mid;
                    best = Some(fit);
                } else {
                    hi = mid;
                }
            }
        }
        let best = match best {
            Some(best) => best,
            None => Some(best_fit(poly, trace, i, lo, tol, tol)).filter(|fit| fit.1 <= tol)?,
        };
        let end = lo;
        max_err = max_err.max(best.1);
        out.push(PathCommand::Cubic(best.0.p1, best.0.p2, best.0.p3));
        i = end;
    }
    Some((out, max_err))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Small deterministic xorshift generator, so that tests need no extra crate.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn range(&mut self, lo: f64, hi: f64) -> f64 {
            lo + (hi - lo) * self.next()
        }
    }

    #[track_caller]
    fn assert_close(actual: f64, expected: f64, tol: f64, what: &str) {
        assert!(
            (actual - expected).abs() <= tol,
            "{what}: got {actual}, expected {expected} (difference {}, tolerance {tol})",
            (actual - expected).abs()
        );
    }

    #[track_caller]
    fn assert_le(value: f64, bound: f64, what: &str) {
        assert!(value <= bound, "{what}: got {value}, bound {bound}");
    }

    #[track_caller]
    fn assert_point_close(actual: Point, expected: Point, tol: f64, what: &str) {
        let d = (actual - expected).hypot();
        assert!(
            d <= tol,
            "{what}: got {actual:?}, expected {expected:?} (distance {d}, tolerance {tol})"
        );
    }

    /// The ellipse with centre `c`, radii `rx, ry`, rotation `th`, times `scale`.
    fn ellipse_conic(c: Point, rx: f64, ry: f64, th: f64, scale: f64) -> Conic {
        let (s, co) = th.sin_cos();
        let (ia, ib) = (1.0 / (rx * rx), 1.0 / (ry * ry));
        let a = co * co * ia + s * s * ib;
        let b = 2.0 * co * s * (ia - ib);
        let cc = s * s * ia + co * co * ib;
        let d = -2.0 * a * c.x - b * c.y;
        let e = -b * c.x - 2.0 * cc * c.y;
        let f = a * c.x * c.x + b * c.x * c.y + cc * c.y * c.y - 1.0;
        Conic::new(
            a * scale,
            b * scale,
            cc * scale,
            d * scale,
            e * scale,
            f * scale,
        )
    }

    fn ellipse_point(c: Point, rx: f64, ry: f64, th: f64, phi: f64) -> Point {
        let v = Vec2::new(rx * phi.cos(), ry * phi.sin());
        let (s, co) = th.sin_cos();
        c + Vec2::new(co * v.x - s * v.y, s * v.x + co * v.y)
    }

    fn round_conic(k: Conic) -> Conic {
        Conic::new(
            k.a.round(),
            k.b.round(),
            k.c.round(),
            k.d.round(),
            k.e.round(),
            k.f.round(),
        )
    }

    /// Points of the path every `1/n` of each command's parameter (arcs via kurbo).
    fn sample_path(start: Point, cmds: &[PathCommand], n: usize) -> Vec<Point> {
        let mut out = vec![start];
        let mut cur = start;
        for cmd in cmds {
            for k in 1..=n {
                let t = k as f64 / n as f64;
                out.push(match *cmd {
                    PathCommand::Line(p) => cur.lerp(p, t),
                    PathCommand::Quad(c, p) => QuadBez::new(cur, c, p).eval(t),
                    PathCommand::Cubic(c1, c2, p) => CubicBez::new(cur, c1, c2, p).eval(t),
                    PathCommand::Arc(a) => Arc::from_svg_arc(&a).unwrap().eval(t),
                });
            }
            cur = cmd.end();
        }
        out
    }

    fn min_distance(p: Point, pts: &[Point]) -> f64 {
        pts.windows(2)
            .map(|w| segment_distance(p, w[0], w[1]))
            .fold(f64::INFINITY, f64::min)
    }

    // ---------------------------------------------------------------- polynomials

    /// `n` random monomials `x^a y^b` of degree at most 6.
    fn random_monomials(rng: &mut Rng, n: usize) -> Vec<(u32, u32)> {
        (0..n)
            .map(|_| {
                let k = (rng.next() * 7.0) as u32;
                let b = (rng.next() * (k + 1) as f64) as u32;
                (k - b, b)
            })
            .collect()
    }

    #[test]
    fn from_local_agrees_with_direct_evaluation() {
        let mut rng = Rng(0x1234_5678_9abc_def1);
        let mut worst: f64 = 0.0;
        let mut worst_abs: f64 = 0.0;
        for _ in 0..200 {
            let n = 1 + (rng.next() * 8.0) as usize;
            let monomials = random_monomials(&mut rng, n);
            let coefficients: Vec<f64> = (0..n).map(|_| rng.range(-20.0, 20.0).round()).collect();
            let origin = Point::new(
                rng.range(0.0, 100.0).floor() + 0.5,
                rng.range(0.0, 100.0).floor() + 0.5,
            );
            let level = rng.range(-50.0, 50.0).round();
            let poly = Polynomial::from_local(&monomials, &coefficients, origin, level).unwrap();
            for _ in 0..10 {
                let p = origin + Vec2::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
                let (dx, dy) = (p.x - origin.x, p.y - origin.y);
                let mut direct = -level;
                let mut scale = level.abs();
                for (&(a, b), &c) in monomials.iter().zip(&coefficients) {
                    let term = c * dx.powi(a as i32) * dy.powi(b as i32);
                    direct += term;
                    // Magnitude of the absolute-coordinate expansion, for the rounding bound.
                    scale += c.abs()
                        * (p.x.abs() + origin.x).powi(a as i32)
                        * (p.y.abs() + origin.y).powi(b as i32);
                }
                let got = poly.eval(p);
                let (v, g) = poly.value_and_gradient(p);
                assert_close(v, got, 1e-15 * scale, "value_and_gradient: value");
                let g1 = poly.gradient(p);
                assert_close(g.x, g1.x, 1e-15 * scale, "value_and_gradient: ∂x");
                assert_close(g.y, g1.y, 1e-15 * scale, "value_and_gradient: ∂y");
                // The absolute expansion, evaluated term by term in absolute coordinates.
                let absolute: f64 = poly
                    .terms()
                    .iter()
                    .map(|&(a, b, c)| c * p.x.powi(a as i32) * p.y.powi(b as i32))
                    .sum();
                worst_abs = worst_abs.max((absolute - direct).abs() / scale);
                assert_close(absolute, direct, 1e-13 * scale, "absolute expansion");
                worst = worst.max((got - direct).abs() / scale);
                assert_close(got, direct, 1e-13 * scale, "from_local eval");
            }
        }
        eprintln!("from_local: worst error relative to term scale {worst:e} (local frame), {worst_abs:e} (absolute expansion)");
    }

    #[test]
    fn polynomial_basics() {
        let p = Polynomial::new(&[(2, 0, 1.0), (0, 2, 1.0), (0, 0, -25.0), (1, 1, 0.0)]).unwrap();
        assert_eq!(p.degree(), 2);
        assert_eq!(p.terms(), vec![(0, 0, -25.0), (2, 0, 1.0), (0, 2, 1.0)]);
        assert_close(p.eval(Point::new(3.0, 4.0)), 0.0, 0.0, "on circle");
        let g = p.gradient(Point::new(3.0, 4.0));
        assert_point_close(g.to_point(), Point::new(6.0, 8.0), 0.0, "gradient");
        assert_eq!(Polynomial::new(&[(7, 0, 1.0)]), None);
        assert_eq!(Polynomial::new(&[(1, 0, f64::NAN)]), None);
        assert_eq!(
            Polynomial::from_local(&[(1, 0)], &[1.0, 2.0], Point::ZERO, 0.0),
            None
        );
        assert_eq!(
            Polynomial::from_local(&[(1, 0)], &[1.0], Point::new(f64::INFINITY, 0.0), 0.0),
            None
        );
        assert_eq!(Polynomial::new(&[(0, 0, 3.0)]).unwrap().degree(), 0);
        // Gradient by finite differences on a sextic.
        let q = Polynomial::new(&[
            (6, 0, 0.5),
            (3, 3, -1.0),
            (1, 4, 2.0),
            (0, 1, 3.0),
            (0, 0, 1.0),
        ])
        .unwrap();
        let x = Point::new(0.7, -1.3);
        let h = 1e-6;
        let g = q.gradient(x);
        let gx = (q.eval(x + Vec2::new(h, 0.0)) - q.eval(x - Vec2::new(h, 0.0))) / (2.0 * h);
        let gy = (q.eval(x + Vec2::new(0.0, h)) - q.eval(x - Vec2::new(0.0, h))) / (2.0 * h);
        assert_close(g.x, gx, 1e-6, "df/dx");
        assert_close(g.y, gy, 1e-6, "df/dy");
        assert_eq!(q.as_conic(), None);
    }

    // ---------------------------------------------------------------- classification

    #[test]
    fn classify_known_conics() {
        use ConicKind::*;
        // (x − 3)² + (y + 2)² = 25, and scaled.
        let circle = Conic::new(1.0, 0.0, 1.0, -6.0, 4.0, -12.0);
        assert_eq!(circle.classify(), Circle);
        let scaled = Conic::new(7.0, 0.0, 7.0, -42.0, 28.0, -84.0);
        assert_eq!(scaled.classify(), Circle);
        let (c, r, _) = circle.ellipse_params().unwrap();
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

    /// y' = x'²/4 (focal length 1), rotated by `th`, vertex at `v`, times 4.
    fn rotated_parabola(th: f64, v: Point) -> Conic {
        // x' = cos(x − vx) + sin(y − vy), y' = −sin(x − vx) + cos(y − vy); x'² − 4 y' = 0.
        let (s, c) = th.sin_cos();
        let poly = Polynomial::from_local(
            &[(2, 0), (1, 1), (0, 2), (1, 0), (0, 1)],
            &[c * c, 2.0 * c * s, s * s, 4.0 * s, -4.0 * c],
            v,
            0.0,
        )
        .unwrap();
        poly.as_conic().unwrap()
    }

    #[test]
    fn parabola_and_hyperbola_params() {
        for th in [0.0, 0.4, 1.7, -2.5] {
            let v = Point::new(5.0, -3.0);
            let k = rotated_parabola(th, v);
            let (vertex, axis, p) = k.parabola_params().unwrap();
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
        let (c, semi, angle) = h.hyperbola_params().unwrap();
        assert_point_close(c, Point::new(1.0, 2.0), 1e-12, "hyperbola centre");
        assert_close(semi.x, 3.0, 1e-12, "transverse");
        assert_close(semi.y, 2.0, 1e-12, "conjugate");
        assert_close(angle.sin(), 0.0, 1e-12, "transverse along x");
        // Swapped: (y − 2)²/4 − (x − 1)²/9 = 1.
        let h2 = Conic::new(-4.0, 0.0, 9.0, 8.0, -36.0, 68.0 - 72.0);
        let (c, semi, angle) = h2.hyperbola_params().unwrap();
        assert_point_close(c, Point::new(1.0, 2.0), 1e-12, "hyperbola centre");
        assert_close(semi.x, 2.0, 1e-12, "transverse");
        assert_close(semi.y, 3.0, 1e-12, "conjugate");
        assert_close(angle.cos(), 0.0, 1e-12, "transverse along y");
        assert_eq!(h.ellipse_params(), None);
        assert_eq!(h.parabola_params(), None);
    }

    #[test]
    fn ellipse_params_recover_ellipses() {
        let mut rng = Rng(0xfeed_beef_1234_5678);
        let mut worst: f64 = 0.0;
        for _ in 0..300 {
            let centre = Point::new(rng.range(0.0, 300.0), rng.range(0.0, 300.0));
            let (rx, ry) = (rng.range(1.0, 80.0), rng.range(1.0, 80.0));
            let th = rng.range(-PI, PI);
            let scale = rng.range(0.1, 1e4);
            let k = ellipse_conic(centre, rx, ry, th, scale);
            let (c, r, a) = k
                .ellipse_params()
                .unwrap_or_else(|| panic!("not an ellipse: {k:?}"));
            assert_point_close(c, centre, 1e-8 * (1.0 + centre.to_vec2().hypot()), "centre");
            let (lo, hi) = (rx.min(ry), rx.max(ry));
            assert_close(r.x.min(r.y), lo, 1e-8 * hi, "small radius");
            assert_close(r.x.max(r.y), hi, 1e-8 * hi, "large radius");
            // As point sets: the recovered ellipse lies on the conic.
            let poly = Polynomial::from(k);
            for i in 0..32 {
                let p = ellipse_point(c, r.x, r.y, a, i as f64 * TAU / 32.0);
                let d = poly.distance_estimate(p);
                worst = worst.max(d);
                assert_le(d, 1e-9 * hi, "recovered ellipse on conic");
            }
        }
        eprintln!("ellipse_params: worst |f|/|grad f| on recovered ellipse {worst:e}");
    }

    // ---------------------------------------------------------------- arcs

    #[test]
    fn ellipse_arcs_go_the_guided_way() {
        let mut rng = Rng(0x0bad_cafe_dead_f00d);
        let mut worst: f64 = 0.0;
        for case in 0..400 {
            let centre = Point::new(rng.range(20.0, 300.0), rng.range(20.0, 300.0));
            let (rx, ry) = (rng.range(3.0, 60.0), rng.range(3.0, 60.0));
            let th = rng.range(-PI, PI);
            let mut k = ellipse_conic(centre, rx, ry, th, rx * ry);
            if case % 4 == 0 {
                k = round_conic(ellipse_conic(centre, rx, ry, th, 1e6));
            }
            let poly = Polynomial::from(k);
            // The intended arc, in the recovered parametrisation (robust to the rounding).
            let (c, r, a) = k.ellipse_params().unwrap();
            let phi0 = rng.range(-PI, PI);
            let magnitude = rng.range(0.1, TAU - 0.1);
            let sweep = if case % 2 == 0 { magnitude } else { -magnitude };
            let from = ellipse_point(c, r.x, r.y, a, phi0);
            let to = ellipse_point(c, r.x, r.y, a, phi0 + sweep);
            // Guide: pixel-like points along the intended arc, up to 0.4 px off the curve.
            let n_guide = ((magnitude * r.x.max(r.y)) as usize).clamp(1, 200);
            let guide: Vec<Point> = (0..n_guide)
                .map(|i| {
                    let phi = phi0 + sweep * (i as f64 + 0.5) / n_guide as f64;
                    let p = ellipse_point(c, r.x, r.y, a, phi);
                    let n = poly.gradient(p).normalize();
                    p + n * rng.range(-0.4, 0.4)
                })
                .collect();
            let (cmds, err) = level_curve_path(&poly, from, to, &guide, 0.05).unwrap();
            assert_eq!(err, 0.0);
            assert_eq!(cmds.len(), 1);
            let PathCommand::Arc(svg) = cmds[0] else {
                panic!("expected an arc, got {cmds:?}");
            };
            let arc = Arc::from_svg_arc(&svg).unwrap();
            assert_close(
                arc.sweep_angle,
                sweep,
                1e-6,
                "sweep angle (direction and size)",
            );
            for i in 0..=64 {
                let p = arc.eval(i as f64 / 64.0);
                let d = poly.distance_estimate(p);
                worst = worst.max(d);
                assert_le(d, 1e-6, "arc sample on the conic");
            }
            let samples = sample_path(from, &cmds, 256);
            for g in &guide {
                assert_le(min_distance(*g, &samples), 0.45, "guide near the arc");
            }
        }
        eprintln!("ellipse arcs: worst |f|/|grad f| of arc samples {worst:e}");
    }

    #[test]
    fn integer_local_ellipse_far_from_origin() {
        // As the exporter builds it: integer coefficients on a local basis centred at a pixel,
        // 9 (x − x0)² − 4 (x − x0)(y − y0) + 6 (y − y0)² + 3 (x − x0) − 2 (y − y0) = 400.
        let origin = Point::new(913.5, 707.5);
        let poly = Polynomial::from_local(
            &[(2, 0), (1, 1), (0, 2), (1, 0), (0, 1)],
            &[9.0, -4.0, 6.0, 3.0, -2.0],
            origin,
            400.0,
        )
        .unwrap();
        let k = poly.as_conic().unwrap();
        assert_eq!(k.classify(), ConicKind::Ellipse);
        let (c, r, a) = k.ellipse_params().unwrap();
        for sweep in [1.0, -2.5, 5.0] {
            let from = project(&poly, ellipse_point(c, r.x, r.y, a, 0.3), 1e-3).unwrap();
            let to = project(&poly, ellipse_point(c, r.x, r.y, a, 0.3 + sweep), 1e-3).unwrap();
            let guide: Vec<Point> = (1..20)
                .map(|i| ellipse_point(c, r.x, r.y, a, 0.3 + sweep * i as f64 / 20.0))
                .collect();
            let (cmds, _) = level_curve_path(&poly, from, to, &guide, 0.05).unwrap();
            let PathCommand::Arc(svg) = cmds[0] else {
                panic!("{cmds:?}")
            };
            let arc = Arc::from_svg_arc(&svg).unwrap();
            assert_close(arc.sweep_angle, sweep, 1e-6, "far ellipse sweep");
            for i in 0..=32 {
                assert_le(
                    poly.distance_estimate(arc.eval(i as f64 / 32.0)),
                    1e-6,
                    "far ellipse arc on curve",
                );
            }
        }
    }

    #[test]
    fn full_turn_emits_two_arcs() {
        let centre = Point::new(50.0, 40.0);
        let k = ellipse_conic(centre, 20.0, 8.0, 0.5, 160.0);
        let poly = Polynomial::from(k);
        let (c, r, a) = k.ellipse_params().unwrap();
        for dir in [1.0, -1.0] {
            let from = ellipse_point(c, r.x, r.y, a, 1.0);
            let guide: Vec<Point> = (1..40)
                .map(|i| ellipse_point(c, r.x, r.y, a, 1.0 + dir * TAU * i as f64 / 40.0))
                .collect();
            let (cmds, _) = level_curve_path(&poly, from, from, &guide, 0.05).unwrap();
            assert_eq!(cmds.len(), 2);
            let mut total = 0.0;
            let mut cur = from;
            for cmd in &cmds {
                let PathCommand::Arc(svg) = *cmd else {
                    panic!("{cmd:?}")
                };
                assert_point_close(svg.from, cur, 1e-12, "arc chaining");
                let arc = Arc::from_svg_arc(&svg).unwrap();
                total += arc.sweep_angle;
                for i in 0..=16 {
                    assert_le(
                        poly.distance_estimate(arc.eval(i as f64 / 16.0)),
                        1e-6,
                        "full turn on conic",
                    );
                }
                cur = svg.to;
            }
            assert_point_close(cur, from, 0.0, "closes");
            assert_close(total, dir * TAU, 1e-9, "total sweep");
            // The kurbo conversion chains as well.
            let els: Vec<PathEl> = cmds.iter().flat_map(|c| c.to_path_els(from)).collect();
            assert!(!els.is_empty());
        }
    }

    #[test]
    fn parabola_gives_exact_quad() {
        let mut worst: f64 = 0.0;
        for (i, th) in [0.0, 0.3, 1.1, 2.0, -2.7].into_iter().enumerate() {
            let v = Point::new(60.0 + i as f64, 30.0);
            let k = rotated_parabola(th, v);
            let poly = Polynomial::from(k);
            let (s, c) = th.sin_cos();
            // Local point (u, u²/4) → absolute.
            let at = |u: f64| {
                let (x, y) = (u, u * u / 4.0);
                v + Vec2::new(c * x - s * y, s * x + c * y)
            };
            let (u0, u1) = (-7.0 + i as f64, 5.0);
            let guide: Vec<Point> = (1..20)
                .map(|j| at(u0 + (u1 - u0) * j as f64 / 20.0))
                .collect();
            let (cmds, err) = level_curve_path(&poly, at(u0), at(u1), &guide, 0.05).unwrap();
            assert_eq!(err, 0.0);
            assert!(
                matches!(cmds.as_slice(), [PathCommand::Quad(_, p)] if *p == at(u1)),
                "{cmds:?}"
            );
            for p in sample_path(at(u0), &cmds, 64) {
                let rel =
                    poly.eval(p).abs() / (poly.gradient(p).hypot() * (1.0 + p.to_vec2().hypot()));
                worst = worst.max(rel);
                assert_le(rel, 1e-9, "quad sample on parabola (relative)");
            }
            // Guide on another part of the parabola: rejected.
            let far = [at(u1 + 10.0)];
            assert!(level_curve_path(&poly, at(u0), at(u1), &far, 0.05).is_none());
        }
        eprintln!("parabola quads: worst relative |f|/|grad f| {worst:e}");
    }

    // ---------------------------------------------------------------- fitted curves

    /// Checks a fitted path: starts at `from`, ends at `to`, samples within `tol` of the curve,
    /// guide points near it; returns the measured max distance.
    #[track_caller]
    fn check_fit(
        poly: &Polynomial,
        from: Point,
        to: Point,
        guide: &[Point],
        tol: f64,
    ) -> (Vec<PathCommand>, f64) {
        let (cmds, err) = level_curve_path(poly, from, to, guide, tol).expect("path");
        assert_le(err, tol, "reported error");
        assert!(!cmds.is_empty());
        assert!(
            cmds.iter().all(|c| matches!(c, PathCommand::Cubic(..))),
            "{cmds:?}"
        );
        assert_point_close(cmds.last().unwrap().end(), to, 0.0, "path ends at to");
        let samples = sample_path(from, &cmds, 64);
        let mut measured: f64 = 0.0;
        for &p in &samples {
            let q = project(poly, p, 1.0).expect("sample near the curve");
            measured = measured.max((q - p).hypot());
        }
        assert_le(measured, tol, "sampled distance to the true curve");
        for g in guide {
            let gp = project(poly, *g, 2.0).unwrap();
            // Guide points near the ends may project just outside the piece.
            if (gp - from).hypot() > 1.0 && (gp - to).hypot() > 1.0 {
                let d = min_distance(gp, &samples);
                assert_le(d, tol + 0.05, "guide projection near the path");
            }
        }
        (cmds, measured)
    }

    /// The hyperbola `(x′/a)² − (y′/b)² = 1` in the frame rotated by `th` about `centre`,
    /// and its parametrisation: branch `sign` (±1), parameter `t`.
    fn rotated_hyperbola(
        a: f64,
        b: f64,
        th: f64,
        centre: Point,
    ) -> (Polynomial, impl Fn(f64, f64) -> Point) {
        let (s, c) = th.sin_cos();
        let poly = Polynomial::from_local(
            &[(2, 0), (1, 1), (0, 2)],
            &[
                c * c / (a * a) - s * s / (b * b),
                2.0 * c * s * (1.0 / (a * a) + 1.0 / (b * b)),
                s * s / (a * a) - c * c / (b * b),
            ],
            centre,
            1.0,
        )
        .unwrap();
        assert_eq!(poly.as_conic().unwrap().classify(), ConicKind::Hyperbola);
        let at = move |sign: f64, t: f64| {
            let (x, y) = (sign * a * t.cosh(), b * t.sinh());
            centre + Vec2::new(c * x - s * y, s * x + c * y)
        };
        (poly, at)
    }

    #[test]
    fn hyperbola_fit() {
        // (x' /3)² − (y'/2)² = 1 in pixels×4, rotated by 0.6, centred at (80, 50).
        let (poly, at) = rotated_hyperbola(12.0, 8.0, 0.6, Point::new(80.0, 50.0));
        let mut worst: f64 = 0.0;
        for sign in [1.0, -1.0] {
            let (t0, t1) = (-1.5, 2.0);
            let guide: Vec<Point> = (1..60)
                .map(|j| at(sign, t0 + (t1 - t0) * j as f64 / 60.0))
                .collect();
            let (cmds, measured) = check_fit(&poly, at(sign, t0), at(sign, t1), &guide, 0.05);
            worst = worst.max(measured);
            eprintln!(
                "hyperbola branch {sign}: {} cubics, max distance {measured:e}",
                cmds.len()
            );
        }
        // Different branches.
        assert!(level_curve_path(&poly, at(1.0, 0.0), at(-1.0, 0.0), &[], 0.05).is_none());
        eprintln!("hyperbola fit: worst sampled distance {worst:e}");
    }

    #[test]
    fn hyperbola_trace_is_on_the_curve_and_fine_enough() {
        // Semi-axes from the glyph_S piece the marching tracer failed on (a ≈ 0.96,
        // b ≈ 1.25, an arc far out along the asymptotes), and a wider one.
        for (a, b, th, t0, t1) in [
            (0.96, 1.25, 2.57, -2.5, 0.4),
            (12.0, 8.0, 0.6, -1.5, 2.0),
            (20.9, 5.1, 0.09, 0.3, -0.8),
        ] {
            let centre = Point::new(40.0, 30.0);
            let (poly, at2) = rotated_hyperbola(a, b, th, centre);
            let params = poly.as_conic().unwrap().hyperbola_params().unwrap();
            let at = |t: f64| at2(1.0, t);
            let guide: Vec<Point> = (1..40)
                .map(|j| at(t0 + (t1 - t0) * j as f64 / 40.0))
                .collect();
            let tr = hyperbola_trace(&poly, params, at(t0), at(t1), &guide).expect("trace");
            assert_point_close(tr.pts[0], at(t0), 0.0, "starts at from");
            assert_point_close(*tr.pts.last().unwrap(), at(t1), 0.0, "ends at to");
            for (k, w) in tr.pts.windows(2).enumerate() {
                assert_le(
                    poly.distance_estimate(w[1]),
                    1e-9,
                    "trace point on the curve",
                );
                assert_le((w[1] - w[0]).hypot(), HYPERBOLA_STEP + 1e-9, "step length");
                let (ta, tb) = (tr.tans[k], tr.tans[k + 1]);
                assert_close(ta.hypot(), 1.0, 1e-12, "unit tangent");
                assert_le(
                    ta.cross(tb).abs().asin(),
                    HYPERBOLA_TURN + 1e-9,
                    "turn per step",
                );
                assert!((w[1] - w[0]).dot(ta) > 0.0, "tangent along the travel");
            }
            // A guide on the other branch, or beyond the arc, is refused.
            let mirrored: Vec<Point> = guide.iter().map(|&g| centre - (g - centre)).collect();
            assert!(hyperbola_trace(&poly, params, at(t0), at(t1), &mirrored).is_none());
            let beyond = [at(t1 + (t1 - t0))];
            assert!(hyperbola_trace(&poly, params, at(t0), at(t1), &beyond).is_none());
            check_fit(&poly, at(t0), at(t1), &guide, 0.05);
        }
    }

    #[test]
    fn a_trace_step_across_a_saddle_is_not_fitted() {
        // x² − y² = 0.01: the branches' vertices (±0.1, 0) face each other across the
        // saddle at the origin; a trace step from one to the other runs 0.1 px off the curve.
        let poly =
            Polynomial::from_local(&[(2, 0), (0, 2)], &[1.0, -1.0], Point::ORIGIN, 0.01).unwrap();
        let (p, q) = (Point::new(-0.1, 0.0), Point::new(0.1, 0.0));
        assert_le(poly.distance_estimate(p), 1e-12, "on the curve");
        let across = Trace {
            pts: vec![p, q],
            tans: vec![Vec2::new(1.0, 0.0); 2],
        };
        assert!(fit_cubics(&poly, &across, 0.05).is_none());
        // The same step is accepted at a tolerance above the gap.
        let (cmds, err) = fit_cubics(&poly, &across, 0.2).expect("fits at 0.2 px");
        assert_eq!(cmds.len(), 1);
        assert_le(err, 0.2, "stated error");
    }

    /// 10 Y² − X³ + 300 X − 5000 = 0, i.e. y² = x³ − 3x + 5 at scale 10, around (50, 60).
    fn cubic_curve() -> (Polynomial, impl Fn(f64) -> Point) {
        let origin = Point::new(50.0, 60.0);
        let poly = Polynomial::from_local(
            &[(0, 2), (3, 0), (1, 0)],
            &[10.0, -1.0, 300.0],
            origin,
            5000.0,
        )
        .unwrap();
        let at =
            move |x: f64| origin + Vec2::new(10.0 * x, 10.0 * (x * x * x - 3.0 * x + 5.0).sqrt());
        (poly, at)
    }

    #[test]
    fn cubic_fit() {
        let (poly, at) = cubic_curve();
        assert_eq!(poly.degree(), 3);
        let (x0, x1) = (-2.0, 3.0);
        let guide: Vec<Point> = (1..80)
            .map(|j| at(x0 + (x1 - x0) * j as f64 / 80.0))
            .collect();
        let (cmds, measured) = check_fit(&poly, at(x0), at(x1), &guide, 0.05);
        eprintln!(
            "cubic fit: {} cubics, max distance {measured:e}",
            cmds.len()
        );
        // Reverse direction.
        let rev: Vec<Point> = guide.iter().rev().copied().collect();
        let (_, measured) = check_fit(&poly, at(x1), at(x0), &rev, 0.05);
        eprintln!("cubic fit reversed: max distance {measured:e}");
        // No curve near the guide.
        let off = [at(0.0) + Vec2::new(30.0, 0.0)];
        assert!(level_curve_path(&poly, at(x0), at(x1), &off, 0.05).is_none());
    }

    #[test]
    fn quartic_fit_both_ways_and_full_loop() {
        // x⁴ + y⁴ = 20⁴ around (100, 100).
        let origin = Point::new(100.0, 100.0);
        let r = 20.0f64;
        let poly =
            Polynomial::from_local(&[(4, 0), (0, 4)], &[1.0, 1.0], origin, r.powi(4)).unwrap();
        let at = |phi: f64| {
            let (s, c) = phi.sin_cos();
            let k = r / (c.powi(4) + s.powi(4)).powf(0.25);
            origin + Vec2::new(k * c, k * s)
        };
        for (phi0, sweep) in [(0.0, PI / 2.0), (0.0, -1.5 * PI), (1.0, TAU), (2.0, -TAU)] {
            let from = at(phi0);
            let to = at(phi0 + sweep);
            let guide: Vec<Point> = (1..100)
                .map(|j| at(phi0 + sweep * j as f64 / 100.0))
                .collect();
            let (cmds, measured) = check_fit(&poly, from, to, &guide, 0.05);
            let samples = sample_path(from, &cmds, 64);
            // The complementary part is not covered.
            if sweep.abs() < TAU {
                let other = at(phi0 + sweep + sweep.signum() * (TAU - sweep.abs()) / 2.0);
                assert!(min_distance(other, &samples) > 1.0, "wrong way round");
            }
            eprintln!(
                "quartic {phi0} {sweep}: {} cubics, max distance {measured:e}",
                cmds.len()
            );
        }
    }

    /// Pixel-like guide: points of the curve pushed up to `noise` along the normal, plus
    /// points overshooting both ends by half a pixel.
    fn noisy_guide(poly: &Polynomial, pts: &[Point], noise: f64, rng: &mut Rng) -> Vec<Point> {
        let mut out = Vec::new();
        let first = pts[0];
        let last = pts[pts.len() - 1];
        let t0 = unit_tangent(poly, first).unwrap();
        let t0 = if t0.dot(pts[1] - first) > 0.0 {
            t0
        } else {
            -t0
        };
        out.push(first - t0 * 0.5);
        for &p in &pts[1..pts.len() - 1] {
            let n = poly.gradient(p).normalize();
            out.push(p + n * rng.range(-noise, noise));
        }
        let t1 = unit_tangent(poly, last).unwrap();
        let t1 = if t1.dot(last - pts[pts.len() - 2]) > 0.0 {
            t1
        } else {
            -t1
        };
        out.push(last + t1 * 0.5);
        out
    }

    #[test]
    fn sextic_far_from_origin_with_noisy_guides() {
        // x⁶ + y⁶ = 10⁶ around (800.5, 600.5): absolute coefficients up to ~1e18.
        let origin = Point::new(800.5, 600.5);
        let r = 10.0f64;
        let poly =
            Polynomial::from_local(&[(6, 0), (0, 6)], &[1.0, 1.0], origin, r.powi(6)).unwrap();
        assert_eq!(poly.degree(), 6);
        let at = |phi: f64| {
            let (s, c) = phi.sin_cos();
            let k = r / (c.powi(6) + s.powi(6)).powf(1.0 / 6.0);
            origin + Vec2::new(k * c, k * s)
        };
        let mut rng = Rng(0x5eed_5eed_5eed_5eed);
        for (phi0, sweep) in [(0.2, 2.0), (0.2, -3.0), (-1.0, TAU)] {
            let exact: Vec<Point> = (0..=60)
                .map(|j| at(phi0 + sweep * j as f64 / 60.0))
                .collect();
            let guide = noisy_guide(&poly, &exact, 0.45, &mut rng);
            let (cmds, measured) = check_fit(&poly, exact[0], exact[60], &guide, 0.05);
            let samples = sample_path(exact[0], &cmds, 64);
            for p in &exact {
                assert_le(min_distance(*p, &samples), 0.05, "intended part covered");
            }
            eprintln!(
                "sextic {phi0} {sweep}: {} cubics, max distance {measured:e}",
                cmds.len()
            );
        }
    }

    #[test]
    fn noisy_guides_on_cubic_and_ellipse() {
        let mut rng = Rng(0x1111_2222_3333_4444);
        let (poly, at) = cubic_curve();
        let exact: Vec<Point> = (0..=50).map(|j| at(-2.0 + 5.0 * j as f64 / 50.0)).collect();
        let guide = noisy_guide(&poly, &exact, 0.45, &mut rng);
        let (_, measured) = check_fit(&poly, exact[0], exact[50], &guide, 0.05);
        eprintln!("cubic, noisy guide: max distance {measured:e}");
        // Ellipse, small and large arcs, guide overshooting both ends.
        let centre = Point::new(30.0, 20.0);
        let k = ellipse_conic(centre, 12.0, 5.0, 0.3, 60.0);
        let epoly = Polynomial::from(k);
        for sweep in [0.4, -0.4, 4.0, -4.0] {
            let exact: Vec<Point> = (0..=30)
                .map(|j| ellipse_point(centre, 12.0, 5.0, 0.3, 1.0 + sweep * j as f64 / 30.0))
                .collect();
            let guide = noisy_guide(&epoly, &exact, 0.45, &mut rng);
            let (cmds, _) = level_curve_path(&epoly, exact[0], exact[30], &guide, 0.05).unwrap();
            let PathCommand::Arc(svg) = cmds[0] else {
                panic!("{cmds:?}")
            };
            let arc = Arc::from_svg_arc(&svg).unwrap();
            assert_close(arc.sweep_angle, sweep, 1e-6, "noisy guide sweep");
        }
    }

    #[test]
    fn line_pair_traced_through_crossing() {
        // (x − y)(x + y) = 0 shifted to (30, 30); follow y = x through the crossing.
        let o = Point::new(30.0, 30.0);
        let poly = Polynomial::from_local(&[(2, 0), (0, 2)], &[1.0, -1.0], o, 0.0).unwrap();
        assert_eq!(poly.as_conic().unwrap().classify(), ConicKind::Degenerate);
        let from = o + Vec2::new(-5.0, -5.0);
        let to = o + Vec2::new(5.0, 5.0);
        let guide: Vec<Point> = (1..10)
            .map(|i| from + Vec2::new(i as f64, i as f64))
            .collect();
        let (_, measured) = check_fit(&poly, from, to, &guide, 0.05);
        assert_le(measured, 1e-6, "straight piece");
        // Empty locus: nothing to trace.
        let empty = Polynomial::from(Conic::new(1.0, 0.0, 1.0, 0.0, 0.0, 1.0));
        assert!(level_curve_path(&empty, Point::ZERO, Point::new(1.0, 0.0), &[], 0.05).is_none());
    }

    #[test]
    fn double_line_and_two_ovals() {
        // (x − y)² = 0: the gradient vanishes on the curve itself.
        let o = Point::new(12.5, 7.5);
        let double =
            Polynomial::from_local(&[(2, 0), (1, 1), (0, 2)], &[1.0, -2.0, 1.0], o, 0.0).unwrap();
        let from = o + Vec2::new(-4.0, -4.0);
        let to = o + Vec2::new(4.0, 4.0);
        let guide: Vec<Point> = (1..8)
            .map(|i| from + Vec2::new(i as f64 + 0.3, i as f64))
            .collect();
        let (cmds, err) = level_curve_path(&double, from, to, &guide, 0.05).unwrap();
        assert_le(err, 0.05, "double line error");
        assert_point_close(cmds.last().unwrap().end(), to, 0.0, "double line end");
        for p in sample_path(from, &cmds, 32) {
            assert_le(segment_distance(p, from, to), 1e-6, "double line straight");
        }
        // Two circles of radius 2 as one quartic: (x² + y² − 4)((x − 10)² + y² − 4).
        let c1 = Polynomial::from(Conic::new(1.0, 0.0, 1.0, 0.0, 0.0, -4.0));
        let mut terms = Vec::new();
        // (x² + y² − 4)(x² + y² − 20x + 96), expanded.
        let p1 = [(2, 0, 1.0), (0, 2, 1.0), (0, 0, -4.0)];
        let p2 = [(2, 0, 1.0), (0, 2, 1.0), (1, 0, -20.0), (0, 0, 96.0)];
        for &(a1, b1, k1) in &p1 {
            for &(a2, b2, k2) in &p2 {
                terms.push((a1 + a2, b1 + b2, k1 * k2));
            }
        }
        let ovals = Polynomial::new(&terms).unwrap();
        let circle_at = |cx: f64, phi: f64| Point::new(cx + 2.0 * phi.cos(), 2.0 * phi.sin());
        for phi in [0.0, 1.0, 2.5] {
            assert_le(
                ovals.distance_estimate(circle_at(0.0, phi)),
                1e-12,
                "first oval",
            );
            assert_le(
                ovals.distance_estimate(circle_at(10.0, phi)),
                1e-12,
                "second oval",
            );
            assert_le(c1.distance_estimate(circle_at(0.0, phi)), 1e-12, "circle");
        }
        let (from, to) = (circle_at(0.0, 0.0), circle_at(0.0, 2.0));
        let own: Vec<Point> = (1..10).map(|i| circle_at(0.0, 0.2 * i as f64)).collect();
        check_fit(&ovals, from, to, &own, 0.05);
        let other: Vec<Point> = (1..10).map(|i| circle_at(10.0, 0.2 * i as f64)).collect();
        assert!(level_curve_path(&ovals, from, to, &other, 0.05).is_none());
    }

    #[test]
    fn long_sextic_loop_is_fast_enough() {
        // x⁶ + y⁶ = 200⁶ around (400.5, 300.5): a closed curve ~1500 px long.
        let origin = Point::new(400.5, 300.5);
        let r = 200.0f64;
        let poly =
            Polynomial::from_local(&[(6, 0), (0, 6)], &[1.0, 1.0], origin, r.powi(6)).unwrap();
        let at = |phi: f64| {
            let (s, c) = phi.sin_cos();
            origin + Vec2::new(c, s) * (r / (c.powi(6) + s.powi(6)).powf(1.0 / 6.0))
        };
        let guide: Vec<Point> = (1..1200)
            .map(|j| at(0.3 + TAU * j as f64 / 1200.0))
            .collect();
        let start = std::time::Instant::now();
        let (cmds, measured) = check_fit(&poly, at(0.3), at(0.3), &guide, 0.05);
        let elapsed = start.elapsed();
        eprintln!(
            "long sextic loop: {} cubics, max distance {measured:e}, {elapsed:?} (with checks)",
            cmds.len()
        );
        assert!(elapsed.as_secs_f64() < 20.0, "too slow: {elapsed:?}");
    }

    #[test]
    fn path_els_follow_the_commands() {
        let k = ellipse_conic(Point::new(40.0, 30.0), 15.0, 6.0, 0.8, 90.0);
        let poly = Polynomial::from(k);
        let (c, r, a) = k.ellipse_params().unwrap();
        let from = ellipse_point(c, r.x, r.y, a, 0.5);
        let to = ellipse_point(c, r.x, r.y, a, 4.0);
        let guide: Vec<Point> = (1..20)
            .map(|i| ellipse_point(c, r.x, r.y, a, 0.5 + 3.5 * i as f64 / 20.0))
            .collect();
        let (cmds, _) = level_curve_path(&poly, from, to, &guide, 0.05).unwrap();
        let mut path = kurbo::BezPath::new();
        path.move_to(from);
        let mut cur = from;
        for cmd in &cmds {
            path.extend(cmd.to_path_els(cur));
            cur = cmd.end();
        }
        let segs: Vec<kurbo::PathSeg> = path.segments().collect();
        assert!(!segs.is_empty());
        assert_point_close(segs.last().unwrap().end(), to, 1e-9, "kurbo path end");
        for seg in &segs {
            for i in 0..=8 {
                let d = poly.distance_estimate(seg.eval(i as f64 / 8.0));
                assert_le(
                    d,
                    2.0 * ARC_FLATTEN_TOLERANCE,
                    "flattened arc near the ellipse",
                );
            }
        }
        // Lines, quads and cubics map one to one.
        let p = Point::new(1.0, 2.0);
        assert_eq!(
            PathCommand::Line(p).to_path_els(Point::ZERO),
            vec![PathEl::LineTo(p)]
        );
        assert_eq!(
            PathCommand::Quad(p, p).to_path_els(Point::ZERO),
            vec![PathEl::QuadTo(p, p)]
        );
        assert_eq!(
            PathCommand::Cubic(p, p, p).to_path_els(Point::ZERO),
            vec![PathEl::CurveTo(p, p, p)]
        );
    }

    #[test]
    fn random_inputs_do_not_panic() {
        let mut rng = Rng(0xdead_beef_0bad_f00d);
        let start = std::time::Instant::now();
        let mut found = 0;
        for case in 0..300 {
            let n = 1 + (rng.next() * 10.0) as usize;
            let monomials = random_monomials(&mut rng, n);
            let coefficients: Vec<f64> = (0..n).map(|_| rng.range(-10.0, 10.0).round()).collect();
            let origin = Point::new(
                rng.range(0.0, 50.0).floor() + 0.5,
                rng.range(0.0, 50.0).floor() + 0.5,
            );
            let poly =
                Polynomial::from_local(&monomials, &coefficients, origin, rng.range(-5.0, 5.0))
                    .unwrap();
            let q = Polynomial::from_local(
                &[(1, 0), (0, 1)],
                &[rng.range(-1.0, 1.0), 1.0],
                origin,
                0.0,
            )
            .unwrap();
            let near = origin + Vec2::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
            let _ = intersect_near(&poly, &q, near, 2.0);
            let (Some(from), Some(to)) = (
                project(&poly, near, 3.0),
                project(
                    &poly,
                    near + Vec2::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0)),
                    3.0,
                ),
            ) else {
                continue;
            };
            let guide: Vec<Point> = (1..5).map(|i| from.lerp(to, i as f64 / 5.0)).collect();
            let guide = if case % 2 == 0 { guide } else { Vec::new() };
            if let Some((cmds, err)) = level_curve_path(&poly, from, to, &guide, 0.05) {
                found += 1;
                assert!(err.is_finite(), "{err}");
                if let Some(last) = cmds.last() {
                    assert_point_close(last.end(), to, 0.0, "random path end");
                }
            }
        }
        let huge = Point::new(1e300, -1e300);
        let line = Polynomial::new(&[(1, 0, 1.0), (0, 0, -1.0)]).unwrap();
        assert!(level_curve_path(&line, huge, huge, &[], 0.05).is_none());
        let _ = project(&line, huge, 1.0);
        let _ = intersect_near(&line, &line, huge, 1.0);
        eprintln!("random inputs: {found} paths found, {:?}", start.elapsed());
    }

    #[test]
    fn lines_and_bad_input() {
        let line = Polynomial::new(&[(1, 0, 1.0), (0, 1, 1.0), (0, 0, -10.0)]).unwrap();
        let (cmds, err) = level_curve_path(
            &line,
            Point::new(0.0, 10.0),
            Point::new(10.0, 0.0),
            &[],
            0.05,
        )
        .unwrap();
        assert_eq!(cmds, vec![PathCommand::Line(Point::new(10.0, 0.0))]);
        assert_eq!(err, 0.0);
        let nan = Point::new(f64::NAN, 0.0);
        assert!(level_curve_path(&line, nan, Point::new(10.0, 0.0), &[], 0.05).is_none());
        assert!(level_curve_path(
            &line,
            Point::new(0.0, 10.0),
            Point::new(10.0, 0.0),
            &[nan],
            0.05
        )
        .is_none());
        assert!(level_curve_path(
            &line,
            Point::new(0.0, 10.0),
            Point::new(10.0, 0.0),
            &[],
            0.0
        )
        .is_none());
        assert!(level_curve_path(
            &line,
            Point::new(0.0, 10.0),
            Point::new(10.0, 0.0),
            &[],
            f64::NAN
        )
        .is_none());
        // Endpoints off the curve.
        let off = Point::new(0.0, 10.5);
        assert!(level_curve_path(&line, off, Point::new(10.0, 0.0), &[], 0.05).is_none());
        let circle = Polynomial::from(Conic::new(1.0, 0.0, 1.0, 0.0, 0.0, -25.0));
        assert!(level_curve_path(
            &circle,
            Point::new(3.0, 4.1),
            Point::new(5.0, 0.0),
            &[],
            0.05
        )
        .is_none());
        let constant = Polynomial::new(&[(0, 0, 1.0)]).unwrap();
        assert!(level_curve_path(&constant, Point::ZERO, Point::ZERO, &[], 0.05).is_none());
        assert!(project(&line, nan, 1.0).is_none());
        assert!(intersect_near(&line, &line, nan, 1.0).is_none());
        assert!(intersect_near(&line, &line, Point::ZERO, f64::INFINITY).is_none());
    }

    // ---------------------------------------------------------------- intersections

    /// A huge circle through a short chord is drawn as that chord, within the tolerance; a
    /// piece running round a circle whose ends are close is not.
    #[test]
    fn flat_arcs_become_chords() {
        // The circle of radius r through the origin, centred at (0, r).
        let circle = |r: f64| Polynomial::from(Conic::new(1.0, 0.0, 1.0, 0.0, -2.0 * r, 0.0));
        let from = Point::new(0.0, 0.0);
        let x1: f64 = 40.0;
        let guide: Vec<Point> = (1..40).map(|x| Point::new(f64::from(x), 0.3)).collect();
        // Radius 1e9: the chord to (40, ~0) is within the tolerance.
        let r = 1e9;
        let to = Point::new(x1, r - (r * r - x1 * x1).sqrt());
        let (cmds, err) = level_curve_path(&circle(r), from, to, &guide, 0.01).unwrap();
        assert_eq!(cmds, vec![PathCommand::Line(to)]);
        assert_le(err, 40.0 * 40.0 / (8.0 * r) * 1.01, "sagitta");
        // Too tight a tolerance for the sagitta of a radius-1000 circle: an exact arc.
        let r = 1000.0;
        let to = Point::new(x1, r - (r * r - x1 * x1).sqrt());
        let (cmds, _) = level_curve_path(&circle(r), from, to, &guide, 0.1).unwrap();
        assert!(matches!(cmds[..], [PathCommand::Arc(_)]), "{cmds:?}");
        // Round a circle of radius 10 from (0, 0) back near it: the guide is not beside the
        // chord, so the arc goes round.
        let r = 10.0;
        let at = |phi: f64| Point::new(r * phi.sin(), r - r * phi.cos());
        let (from, to) = (at(0.0), at(-0.05));
        let guide: Vec<Point> = (1..60).map(|i| at(f64::from(i) * 0.1)).collect();
        let (cmds, _) = level_curve_path(&circle(r), from, to, &guide, 0.05).unwrap();
        assert!(
            cmds.iter().all(|c| matches!(c, PathCommand::Arc(_))),
            "{cmds:?}"
        );
        // Tiny circles, where every point is within 2 px of any chord: once round from a
        // point back to it, and the long way round between two close points.
        let r = 0.9;
        let at = |phi: f64| Point::new(r * phi.sin(), r - r * phi.cos());
        let guide: Vec<Point> = (1..20).map(|i| at(f64::from(i) * 0.3)).collect();
        let (cmds, _) = level_curve_path(&circle(r), at(0.0), at(0.0), &guide, 0.05).unwrap();
        assert!(!cmds.is_empty(), "a full turn is not an empty path");
        assert!(
            cmds.iter().all(|c| matches!(c, PathCommand::Arc(_))),
            "{cmds:?}"
        );
        let r = 1.0;
        let at = |phi: f64| Point::new(r * phi.sin(), r - r * phi.cos());
        let guide: Vec<Point> = (1..20).map(|i| at(f64::from(i) * 0.3)).collect();
        let (cmds, _) = level_curve_path(&circle(r), at(0.0), at(-0.3), &guide, 0.05).unwrap();
        assert!(
            cmds.iter().all(|c| matches!(c, PathCommand::Arc(_))),
            "{cmds:?}"
        );
    }

    /// The closed-form bound on conics: a point of the curve (so at least the distance to
    /// the curve) and, for points near the curve, within second order of that distance.
    #[test]
    fn conic_distance_bound() {
        let mut rng = Rng(0x0dd_b1a5_ed5e_ed01);
        let mut checked = 0;
        for _ in 0..300 {
            let k = Conic::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-20.0, 20.0),
                rng.range(-20.0, 20.0),
                rng.range(-100.0, 100.0),
            );
            let poly = Polynomial::from(k);
            for i in 0..10 {
                let mut p = Point::new(rng.range(-15.0, 15.0), rng.range(-15.0, 15.0));
                if i % 2 == 1 {
                    // Near the curve: a point of it moved along the normal.
                    let Some(q) = project(&poly, p, 10.0) else {
                        continue;
                    };
                    let n = poly.gradient(q).normalize();
                    p = q + n * rng.range(-0.05, 0.05);
                }
                let Some(on) = project(&poly, p, 3.0) else {
                    continue;
                };
                let d = (on - p).hypot();
                let Some(bound) = distance_bound(&poly, p, 10.0) else {
                    continue;
                };
                assert!(
                    bound >= d - 1e-9,
                    "bound {bound} below the distance {d} at {p:?}"
                );
                if d < 0.05 {
                    checked += 1;
                    assert_le(
                        bound - d,
                        1e-3,
                        "bound close to the distance near the curve",
                    );
                }
            }
        }
        assert!(checked > 20, "only {checked} points near the curves");
    }

    #[test]
    fn intersections_and_projection() {
        let diag = Polynomial::new(&[(1, 0, 1.0), (0, 1, 1.0), (0, 0, -10.0)]).unwrap();
        let bis = Polynomial::new(&[(1, 0, 1.0), (0, 1, -1.0)]).unwrap();
        let x = intersect_near(&diag, &bis, Point::new(4.0, 6.5), 3.0).unwrap();
        assert_point_close(x, Point::new(5.0, 5.0), 1e-12, "line/line");
        assert!(intersect_near(&diag, &bis, Point::new(0.0, 0.0), 3.0).is_none());
        // Parallel lines never meet.
        let par = Polynomial::new(&[(1, 0, 1.0), (0, 1, 1.0), (0, 0, -12.0)]).unwrap();
        assert!(intersect_near(&diag, &par, Point::new(5.0, 5.0), 5.0).is_none());
        // Line y = 0 and circle (x − 3)² + y² = 25: (−2, 0) and (8, 0).
        let axis = Polynomial::new(&[(0, 1, 1.0)]).unwrap();
        let circle = Polynomial::from(Conic::new(1.0, 0.0, 1.0, -6.0, 0.0, -16.0));
        let x = intersect_near(&axis, &circle, Point::new(7.0, 1.0), 2.0).unwrap();
        assert_point_close(x, Point::new(8.0, 0.0), 1e-12, "line/circle right");
        let x = intersect_near(&circle, &axis, Point::new(-1.5, -0.5), 2.0).unwrap();
        assert_point_close(x, Point::new(-2.0, 0.0), 1e-12, "line/circle left");
        // Circle x² + y² = 25 and ellipse x²/18 + y²/32 = 1 meet at (±3, ±4).
        let c5 = Polynomial::from(Conic::new(1.0, 0.0, 1.0, 0.0, 0.0, -25.0));
        let ell = Polynomial::from(Conic::new(16.0, 0.0, 9.0, 0.0, 0.0, -288.0));
        for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
            let near = Point::new(sx * 3.3, sy * 3.8);
            let x = intersect_near(&c5, &ell, near, 1.0).unwrap();
            assert_point_close(x, Point::new(sx * 3.0, sy * 4.0), 1e-12, "circle/ellipse");
        }
        assert!(intersect_near(&c5, &ell, Point::new(3.3, 3.8), 0.1).is_none());
        // Projection on a circle.
        let p = project(&c5, Point::new(6.0, 8.0), 6.0).unwrap();
        assert_point_close(p, Point::new(3.0, 4.0), 1e-12, "projection on circle");
        assert!(project(&c5, Point::new(6.0, 8.0), 4.0).is_none());
        // Projection on the cubic curve is orthogonal.
        let (cubic, at) = cubic_curve();
        let on = at(1.0);
        let n = cubic.gradient(on).normalize();
        let p = project(&cubic, on + n * 0.7, 1.0).unwrap();
        assert_point_close(p, on, 1e-9, "projection on cubic");
    }
}

//! Bivariate polynomials `f(x, y)` of degree at most [`MAX_DEGREE`], kept in a local frame
//! for precise evaluation far from the origin.

use super::conic::Conic;
use kurbo::{Point, Vec2};

/// The highest degree a [`Polynomial`] can have.
pub const MAX_DEGREE: u32 = 6;

/// Number of coefficients of a dense polynomial of degree [`MAX_DEGREE`].
const N_COEFFS: usize = ((MAX_DEGREE + 1) * (MAX_DEGREE + 2) / 2) as usize;

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
#[derive(Clone, Debug, PartialEq)]
pub struct Polynomial {
    /// Absolute coefficients, dense triangular storage, see [`index`].
    coeffs: [f64; N_COEFFS],
    /// Origin of the evaluation frame.
    origin: Point,
    /// Highest total degree with a non-zero local coefficient (bounds the evaluation loops).
    pub(super) top: usize,
    /// Coefficients in the evaluation frame: `f = Σ local_ab (x − ox)^a (y − oy)^b`.
    pub(super) local: [f64; N_COEFFS],
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

    pub(super) fn is_finite(&self) -> bool {
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
        // Each degree's terms `c x^a y^b` in order of `b`, their products left to right; the
        // ends `x^k` and `y^k` apart, without the factors `y^0 = x^0 = 1` (multiplying by
        // one changes no bit) or the branches on `a > 0` and `b > 0` (degree 6 on noise: this
        // evaluation was 30% of the time).
        for k in 1..=self.top {
            let row = &self.local[k * (k + 1) / 2..=k * (k + 1) / 2 + k];
            let (first, last) = (row[0], row[k]);
            v += first * xp[k];
            gx += first * k as f64 * xp[k - 1];
            for b in 1..k {
                let (a, c) = (k - b, row[b]);
                v += c * xp[a] * yp[b];
                gx += c * a as f64 * xp[a - 1] * yp[b];
                gy += c * b as f64 * xp[a] * yp[b - 1];
            }
            v += last * yp[k];
            gy += last * k as f64 * yp[k - 1];
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_util::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// `from_local` evaluates as the local polynomial does, and so do its value and
        /// gradient together, its gradient, and its absolute expansion term by term, up to
        /// rounding relative to the size of the terms.
        #[test]
        fn from_local_agrees_with_direct_evaluation(
            terms in proptest::collection::vec((monomial(), -20i32..=20), 1..=8),
            (ox, oy) in (0i32..100, 0i32..100),
            level in -50i32..=50,
            offsets in proptest::collection::vec((-3.0..3.0f64, -3.0..3.0f64), 10),
        ) {
            let (monomials, coefficients): (Vec<(u32, u32)>, Vec<f64>) =
                terms.iter().map(|&(m, c)| (m, f64::from(c))).unzip();
            let origin = Point::new(f64::from(ox) + 0.5, f64::from(oy) + 0.5);
            let level = f64::from(level);
            let poly = Polynomial::from_local(&monomials, &coefficients, origin, level).unwrap();
            for (dx, dy) in offsets {
                let p = origin + Vec2::new(dx, dy);
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
                // Above degree 2 (below it, a formula of its own), to the bit: the same
                // products in the same order (the value's sum starts from the constant term
                // instead of 0 + it, which differs for −0).
                if poly.top > 2 {
                    prop_assert_eq!(g.x.to_bits(), g1.x.to_bits());
                    prop_assert_eq!(g.y.to_bits(), g1.y.to_bits());
                    if poly.local[0] != 0.0 {
                        prop_assert_eq!(v.to_bits(), got.to_bits());
                    }
                }
                // The absolute expansion, evaluated term by term in absolute coordinates.
                let absolute: f64 = poly
                    .terms()
                    .iter()
                    .map(|&(a, b, c)| c * p.x.powi(a as i32) * p.y.powi(b as i32))
                    .sum();
                assert_close(absolute, direct, 1e-13 * scale, "absolute expansion");
                assert_close(got, direct, 1e-13 * scale, "from_local eval");
            }
        }
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
}

//! A cubic Bézier in the power basis: its point and first two derivatives by Horner's rule.

use kurbo::{CubicBez, Vec2};

/// The cubic `B(u) = P0 + u (c1 + u (c2 + u c3))` of a [`CubicBez`] `P0 P1 P2 P3`, with
///
/// ```text
/// c1 = 3 (P1 − P0),   c2 = 3 (P2 − 2 P1 + P0),   c3 = P3 − P0 + 3 (P1 − P2),
/// ```
///
/// for the repeated evaluations of Newton's steps towards a nearest point: one short chain
/// of products per value, where the Bernstein form of the curve, its derivative and its
/// second derivative take three longer ones.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PowerCubic {
    /// The start point `P0`.
    pub(crate) p0: Vec2,
    c1: Vec2,
    c2: Vec2,
    c3: Vec2,
}

impl PowerCubic {
    /// The power form of `c`.
    pub(crate) fn new(c: &CubicBez) -> PowerCubic {
        let (p0, p1, p2, p3) = (
            c.p0.to_vec2(),
            c.p1.to_vec2(),
            c.p2.to_vec2(),
            c.p3.to_vec2(),
        );
        PowerCubic {
            p0,
            c1: (p1 - p0) * 3.0,
            c2: (p2 - p1 * 2.0 + p0) * 3.0,
            c3: p3 - p0 + (p1 - p2) * 3.0,
        }
    }

    /// `B(u) − P0`.
    #[inline]
    pub(crate) fn offset(&self, u: f64) -> Vec2 {
        ((self.c3 * u + self.c2) * u + self.c1) * u
    }

    /// `B′(u)`.
    #[inline]
    pub(crate) fn deriv(&self, u: f64) -> Vec2 {
        (self.c3 * (3.0 * u) + self.c2 * 2.0) * u + self.c1
    }

    /// `B″(u)`.
    #[inline]
    pub(crate) fn second_deriv(&self, u: f64) -> Vec2 {
        self.c3 * (6.0 * u) + self.c2 * 2.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{ParamCurve, ParamCurveDeriv, Point};
    use proptest::prelude::*;

    proptest! {
        /// The power form agrees with kurbo's Bernstein evaluations of the curve and its
        /// two derivatives.
        #[test]
        fn agrees_with_the_bernstein_form(
            pts in prop::collection::vec((-100.0f64..100.0, -100.0f64..100.0), 4),
            u in 0.0f64..=1.0,
        ) {
            let p: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
            let c = CubicBez::new(p[0], p[1], p[2], p[3]);
            let w = PowerCubic::new(&c);
            let near = |a: Vec2, b: Vec2| (a - b).hypot() <= 1e-9 * (1.0 + b.hypot());
            prop_assert!(near(w.p0 + w.offset(u), c.eval(u).to_vec2()));
            prop_assert!(near(w.deriv(u), c.deriv().eval(u).to_vec2()));
            prop_assert!(near(w.second_deriv(u), c.deriv().deriv().eval(u).to_vec2()));
        }
    }
}

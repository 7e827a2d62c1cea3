//! Bases of functions: the spaces in which Digital Level Layers are sought.
//!
//! A Digital Level Layer (DLL) is the set of integer points `x` with
//! `lower <= f(x) <= upper`, where `f = a_1 f_1 + … + a_n f_n` lies in the space spanned by a
//! basis `f_1, …, f_n` (the constant function is always implicitly there: it is absorbed by
//! the bounds). The recognizer only ever sees the *lifting* of a point,
//! `F(x) = (f_1(x), …, f_n(x)) ∈ Zⁿ`.
//!
//! | model | point | basis (coefficient order, constant last) |
//! |---|---|---|
//! | `line` | Z² | `x, y, 1` |
//! | `circle` | Z² | `x^2+y^2, x, y, 1` |
//! | `conic` | Z² | `x^2, x*y, y^2, x, y, 1` |
//! | `poly:D` | Z² | every monomial of degree ≤ D, highest degree first, then by descending power of `x` |
//! | `quadric3` | Z³ | `x^2, y^2, z^2, x*y, x*z, y*z, x, y, z, 1` |
//! | `poly3:D` | Z³ | every monomial of degree ≤ D in `x, y, z` |
//!
//! Liftings are computed in exact integer arithmetic (`i64`, overflow-checked): callers work
//! in coordinates relative to a local origin so that magnitudes stay small.

use std::fmt;
use std::str::FromStr;

/// A polynomial in the point's coordinates: `(coefficient, exponent per coordinate)` terms.
pub type Terms = Vec<(i64, Vec<u32>)>;

/// A space of functions Zᵈ → Z, given by its non-constant basis functions.
///
/// Implement it to recognize layers of your own family of functions; the functions must be
/// integer-valued on integer points so that the recognizer's decisions are exact.
pub trait Basis: Send + Sync + fmt::Debug {
    /// Dimension `d` of the points (2 for images).
    fn point_dim(&self) -> usize;
    /// Number `n` of non-constant basis functions.
    fn dim(&self) -> usize;
    /// Writes `F(p) = (f_1(p), …, f_n(p))` into `out` (length [`Basis::dim`]).
    ///
    /// Returns `None` if a value overflows `i64`.
    fn lift(&self, p: &[i64], out: &mut [i64]) -> Option<()>;
    /// Names of the basis functions in coefficient order, the constant `"1"` last
    /// (`dim() + 1` names).
    fn names(&self) -> Vec<String>;
    /// Each basis function as a sum of monomials `(coefficient, exponents)`, when it is a
    /// polynomial (the exporter needs it to draw level curves). Returns `None` otherwise.
    fn polynomials(&self) -> Option<Vec<Terms>> {
        None
    }
    /// [`Basis::polynomials`] borrowed, for bases that hold them (no copy per call: the
    /// exporter asks for every piece and segment). Returns `None` when the basis does not
    /// hold them; [`Basis::polynomials`] may still give them.
    fn polynomial_terms(&self) -> Option<&[Terms]> {
        None
    }
}

/// The basis functions of `basis` as polynomials ([`Basis::polynomial_terms`], else
/// [`Basis::polynomials`]), or `None` when it has none.
pub(crate) fn terms_of(basis: &dyn Basis) -> Option<std::borrow::Cow<'_, [Terms]>> {
    match basis.polynomial_terms() {
        Some(t) => Some(std::borrow::Cow::Borrowed(t)),
        None => basis.polynomials().map(std::borrow::Cow::Owned),
    }
}

/// A basis whose functions are integer polynomials, e.g. `x^2+y^2` or `x*y`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PolynomialBasis {
    point_dim: usize,
    /// Each function is a sum of `(coefficient, exponent per coordinate)`.
    functions: Vec<Terms>,
    names: Vec<String>,
    /// The functions' terms `c·xⁱ·yʲ` one after the other, when the points are planar:
    /// lifted without walking the terms' vectors.
    planar: Option<Planar>,
}

/// The terms of a planar [`PolynomialBasis`], and which model's they are.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Planar {
    terms: Vec<PlanarTerm>,
    /// The line's, circle's or conic's functions, lifted by their formulas.
    known: Option<Model>,
}

/// One term `c·xⁱ·yʲ` of a planar [`PolynomialBasis`]'s function; `last` for its function's
/// last term.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct PlanarTerm {
    c: i64,
    i: u32,
    j: u32,
    last: bool,
}

impl Planar {
    /// The terms of `functions`, whose exponent vectors have two entries.
    fn new(functions: &[Terms]) -> Planar {
        let terms: Vec<PlanarTerm> = functions
            .iter()
            .flat_map(|f| {
                f.iter().enumerate().map(|(k, (c, e))| PlanarTerm {
                    c: *c,
                    i: e[0],
                    j: e[1],
                    last: k + 1 == f.len(),
                })
            })
            .collect();
        let term = |c, i, j, last| PlanarTerm { c, i, j, last };
        let known = [Model::Line, Model::Circle, Model::Conic]
            .into_iter()
            .find(|m| {
                let expected: &[PlanarTerm] = match m {
                    Model::Line => &[term(1, 1, 0, true), term(1, 0, 1, true)],
                    Model::Circle => &[
                        term(1, 2, 0, false),
                        term(1, 0, 2, true),
                        term(1, 1, 0, true),
                        term(1, 0, 1, true),
                    ],
                    _ => &[
                        term(1, 2, 0, true),
                        term(1, 1, 1, true),
                        term(1, 0, 2, true),
                        term(1, 1, 0, true),
                        term(1, 0, 1, true),
                    ],
                };
                terms == expected
            });
        Planar { terms, known }
    }

    /// [`Basis::lift`] of `(x, y)` into `out` (at least one entry per function).
    #[inline]
    fn lift(&self, x: i64, y: i64, out: &mut [i64]) -> Option<()> {
        // The known models' formulas, checked as `lift_terms` checks them (`1·x` first, then
        // each factor, then the sum): the same values and the same overflows.
        match (self.known, &mut *out) {
            (Some(Model::Line), [fx, fy, ..]) => {
                (*fx, *fy) = (x, y);
                return Some(());
            }
            (Some(Model::Circle), [r, fx, fy, ..]) => {
                *r = x.checked_mul(x)?.checked_add(y.checked_mul(y)?)?;
                (*fx, *fy) = (x, y);
                return Some(());
            }
            (Some(Model::Conic), [xx, xy, yy, fx, fy, ..]) => {
                *xx = x.checked_mul(x)?;
                *xy = x.checked_mul(y)?;
                *yy = y.checked_mul(y)?;
                (*fx, *fy) = (x, y);
                return Some(());
            }
            _ => {}
        }
        // The same sums of the same products in the same order as `lift_terms`, so the
        // same overflows.
        let mut outs = out.iter_mut();
        let mut sum: i64 = 0;
        for t in &self.terms {
            let mut term = t.c;
            for _ in 0..t.i {
                term = term.checked_mul(x)?;
            }
            for _ in 0..t.j {
                term = term.checked_mul(y)?;
            }
            sum = sum.checked_add(term)?;
            if t.last {
                if let Some(o) = outs.next() {
                    *o = sum;
                }
                sum = 0;
            }
        }
        Some(())
    }
}

impl PolynomialBasis {
    /// A basis from explicit polynomials and their names (the constant is implicit and is
    /// named `"1"` after them).
    ///
    /// Returns `None` if a name is missing, a function is empty, an exponent vector does not
    /// have `point_dim` entries, or a function is constant.
    pub fn new(
        point_dim: usize,
        functions: Vec<Terms>,
        names: Vec<String>,
    ) -> Option<PolynomialBasis> {
        if names.len() != functions.len() || point_dim == 0 {
            return None;
        }
        for f in &functions {
            if f.is_empty() {
                return None;
            }
            if f.iter()
                .any(|(c, e)| e.len() != point_dim || (*c != 0 && e.iter().all(|&k| k == 0)))
            {
                return None;
            }
        }
        let mut names = names;
        names.push("1".to_string());
        let planar = (point_dim == 2).then(|| Planar::new(&functions));
        Some(PolynomialBasis {
            point_dim,
            functions,
            names,
            planar,
        })
    }

    /// All monomials of degree `1..=degree` in `point_dim` variables, highest degree first,
    /// then by descending power of `x`, then of `y`.
    pub fn monomials(point_dim: usize, degree: u32) -> Option<PolynomialBasis> {
        if !(1..=3).contains(&point_dim) || degree == 0 {
            return None;
        }
        let vars = ["x", "y", "z"];
        let mut functions = Vec::new();
        let mut names = Vec::new();
        for total in (1..=degree).rev() {
            for e in exponents_of_degree(point_dim, total) {
                names.push(monomial_name(&vars[..point_dim], &e));
                functions.push(vec![(1, e)]);
            }
        }
        PolynomialBasis::new(point_dim, functions, names)
    }
}

/// Exponent vectors of total degree `total`, by descending power of the first variable,
/// then of the second, …
fn exponents_of_degree(point_dim: usize, total: u32) -> Vec<Vec<u32>> {
    if point_dim == 1 {
        return vec![vec![total]];
    }
    let mut out = Vec::new();
    for first in (0..=total).rev() {
        for mut rest in exponents_of_degree(point_dim - 1, total - first) {
            rest.insert(0, first);
            out.push(rest);
        }
    }
    out
}

/// `x^2*y`, `x`, `y^3` … (exponent 1 omitted, factors of exponent 0 omitted).
fn monomial_name(vars: &[&str], exponents: &[u32]) -> String {
    let factors: Vec<String> = vars
        .iter()
        .zip(exponents)
        .filter(|(_, &e)| e > 0)
        .map(|(v, &e)| {
            if e == 1 {
                v.to_string()
            } else {
                format!("{v}^{e}")
            }
        })
        .collect();
    if factors.is_empty() {
        "1".to_string()
    } else {
        factors.join("*")
    }
}

/// [`Basis::lift`] by the functions' terms: each term's product in exact integers, checked
/// at every factor.
fn lift_terms(functions: &[Terms], p: &[i64], out: &mut [i64]) -> Option<()> {
    for (f, o) in functions.iter().zip(out.iter_mut()) {
        let mut sum: i64 = 0;
        for (c, e) in f {
            let mut term = *c;
            for (&x, &k) in p.iter().zip(e) {
                for _ in 0..k {
                    term = term.checked_mul(x)?;
                }
            }
            sum = sum.checked_add(term)?;
        }
        *o = sum;
    }
    Some(())
}

impl Basis for PolynomialBasis {
    fn point_dim(&self) -> usize {
        self.point_dim
    }

    fn dim(&self) -> usize {
        self.functions.len()
    }

    fn lift(&self, p: &[i64], out: &mut [i64]) -> Option<()> {
        if let (Some(planar), &[x, y], true) = (&self.planar, p, out.len() >= self.functions.len())
        {
            return planar.lift(x, y, out);
        }
        lift_terms(&self.functions, p, out)
    }

    fn names(&self) -> Vec<String> {
        self.names.clone()
    }

    fn polynomials(&self) -> Option<Vec<Terms>> {
        Some(self.functions.clone())
    }

    fn polynomial_terms(&self) -> Option<&[Terms]> {
        Some(&self.functions)
    }
}

/// The families of curves offered on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Model {
    /// Digital straight lines: `x, y`.
    Line,
    /// Digital circles: `x²+y², x, y`.
    Circle,
    /// Digital conics: `x², xy, y², x, y`.
    Conic,
    /// Polynomials of degree ≤ D in `x, y` (`poly:2` equals `conic`).
    Poly(u32),
    /// Quadrics in Z³ (ellipsoidal and hyperboloidal layers):
    /// `x², y², z², xy, xz, yz, x, y, z`.
    Quadric3,
    /// Polynomials of degree ≤ D in `x, y, z`.
    Poly3(u32),
}

/// The highest polynomial degree accepted by [`Model::Poly`].
pub const MAX_POLY_DEGREE: u32 = 6;

impl Model {
    /// Parses the name of a model for images (the command line's `--model`): `line`,
    /// `circle`, `conic` or `poly:D`.
    ///
    /// Returns an error naming the image models if `s` is unknown or a model of 3-D point
    /// sets (`quadric3`, `poly3:D`, which only `layertrace recognize` takes).
    ///
    /// ```
    /// use layertrace::Model;
    /// assert_eq!(Model::parse_image_model("poly:3"), Ok(Model::Poly(3)));
    /// let e = Model::parse_image_model("quadric3").unwrap_err();
    /// assert!(e.to_string().contains("3-D point sets"));
    /// ```
    pub fn parse_image_model(s: &str) -> Result<Model, ParseModelError> {
        let err = |kind| ParseModelError {
            name: s.to_string(),
            kind,
        };
        match s.parse::<Model>() {
            Ok(Model::Quadric3 | Model::Poly3(_)) => Err(err(ParseModelErrorKind::PointSetsOnly)),
            Ok(m) => Ok(m),
            Err(_) => Err(err(ParseModelErrorKind::UnknownImageModel)),
        }
    }

    /// The line model's basis, built once for the process: the drawing asks for it per
    /// contour (each build allocates its functions and names).
    pub(crate) fn line_basis() -> &'static PolynomialBasis {
        static LINE: std::sync::LazyLock<PolynomialBasis> =
            std::sync::LazyLock::new(|| Model::Line.basis());
        &LINE
    }

    /// The basis of this model.
    pub fn basis(self) -> PolynomialBasis {
        let b = match self {
            Model::Line => PolynomialBasis::monomials(2, 1),
            Model::Conic => PolynomialBasis::monomials(2, 2),
            Model::Poly(d) => PolynomialBasis::monomials(2, d.clamp(1, MAX_POLY_DEGREE)),
            Model::Poly3(d) => PolynomialBasis::monomials(3, d.clamp(1, MAX_POLY_DEGREE)),
            Model::Circle => PolynomialBasis::new(
                2,
                vec![
                    vec![(1, vec![2, 0]), (1, vec![0, 2])],
                    vec![(1, vec![1, 0])],
                    vec![(1, vec![0, 1])],
                ],
                vec!["x^2+y^2".into(), "x".into(), "y".into()],
            ),
            Model::Quadric3 => {
                let m = |e: [u32; 3]| vec![(1, e.to_vec())];
                PolynomialBasis::new(
                    3,
                    vec![
                        m([2, 0, 0]),
                        m([0, 2, 0]),
                        m([0, 0, 2]),
                        m([1, 1, 0]),
                        m([1, 0, 1]),
                        m([0, 1, 1]),
                        m([1, 0, 0]),
                        m([0, 1, 0]),
                        m([0, 0, 1]),
                    ],
                    ["x^2", "y^2", "z^2", "x*y", "x*z", "y*z", "x", "y", "z"]
                        .iter()
                        .map(|s| s.to_string())
                        .collect(),
                )
            }
        };
        // Every branch above builds a well-formed basis.
        b.unwrap_or_else(|| unreachable!("built-in bases are well formed"))
    }

    /// The name used on the command line and in JSON (`line`, `poly:3` …).
    pub fn name(self) -> String {
        match self {
            Model::Line => "line".into(),
            Model::Circle => "circle".into(),
            Model::Conic => "conic".into(),
            Model::Poly(d) => format!("poly:{d}"),
            Model::Quadric3 => "quadric3".into(),
            Model::Poly3(d) => format!("poly3:{d}"),
        }
    }
}

impl fmt::Display for Model {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

/// The error of parsing a [`Model`] name: the name is unknown, or (for
/// [`Model::parse_image_model`]) a model of 3-D point sets.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParseModelError {
    name: String,
    kind: ParseModelErrorKind,
}

/// What was wrong with the name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ParseModelErrorKind {
    /// No model has this name.
    Unknown,
    /// No model has this name, where an image model is wanted.
    UnknownImageModel,
    /// A model of 3-D point sets where an image model is wanted.
    PointSetsOnly,
}

/// The models an image can be traced with, as the errors name them.
const IMAGE_MODELS: &str = "line, circle, conic or poly:D (D = 1..=6)";
const _: () = assert!(
    MAX_POLY_DEGREE == 6,
    "IMAGE_MODELS names the largest degree"
);

impl fmt::Display for ParseModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = &self.name;
        match self.kind {
            ParseModelErrorKind::Unknown => write!(
                f,
                "unknown model '{name}': expected line, circle, conic, poly:D (D = 1..={MAX_POLY_DEGREE}), quadric3 or poly3:D"
            ),
            ParseModelErrorKind::UnknownImageModel => {
                write!(f, "unknown model '{name}': expected {IMAGE_MODELS}")
            }
            ParseModelErrorKind::PointSetsOnly => write!(
                f,
                "'{name}' is a model of 3-D point sets (layertrace recognize); images take {IMAGE_MODELS}"
            ),
        }
    }
}

impl std::error::Error for ParseModelError {}

impl FromStr for Model {
    type Err = ParseModelError;

    fn from_str(s: &str) -> Result<Model, ParseModelError> {
        let err = || ParseModelError {
            name: s.to_string(),
            kind: ParseModelErrorKind::Unknown,
        };
        let degree = |d: &str| {
            d.parse::<u32>()
                .ok()
                .filter(|d| (1..=MAX_POLY_DEGREE).contains(d))
                .ok_or_else(err)
        };
        match s {
            "line" => Ok(Model::Line),
            "circle" => Ok(Model::Circle),
            "conic" => Ok(Model::Conic),
            "quadric3" => Ok(Model::Quadric3),
            _ => {
                if let Some(d) = s.strip_prefix("poly:") {
                    Ok(Model::Poly(degree(d)?))
                } else if let Some(d) = s.strip_prefix("poly3:") {
                    Ok(Model::Poly3(degree(d)?))
                } else {
                    Err(err())
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_follow_the_documented_order() {
        assert_eq!(Model::Line.basis().names(), ["x", "y", "1"]);
        assert_eq!(Model::Circle.basis().names(), ["x^2+y^2", "x", "y", "1"]);
        assert_eq!(
            Model::Conic.basis().names(),
            ["x^2", "x*y", "y^2", "x", "y", "1"]
        );
        assert_eq!(Model::Poly(2).basis(), Model::Conic.basis());
        let p3 = Model::Poly(3).basis().names();
        assert_eq!(
            p3,
            ["x^3", "x^2*y", "x*y^2", "y^3", "x^2", "x*y", "y^2", "x", "y", "1"]
        );
        assert_eq!(Model::Poly(4).basis().dim(), 14);
        assert_eq!(Model::Quadric3.basis().dim(), 9);
        assert_eq!(Model::Poly3(2).basis().dim(), 9);
    }

    #[test]
    fn lifting_is_exact_and_checked() {
        let b = Model::Circle.basis();
        let mut out = [0; 3];
        b.lift(&[3, -4], &mut out).unwrap();
        assert_eq!(out, [25, 3, -4]);
        let c = Model::Poly(4).basis();
        let mut out = vec![0; c.dim()];
        c.lift(&[2, 3], &mut out).unwrap();
        // x^4 first, y last.
        assert_eq!(out[0], 16);
        assert_eq!(out[4], 81);
        assert_eq!(*out.last().unwrap(), 3);
        assert!(c.lift(&[1 << 20, 1 << 20], &mut out).is_none());
    }

    #[test]
    fn planar_liftings_are_those_of_the_terms() {
        // Every planar model, at coordinates small, large and near the overflows of each
        // degree: the monomials' lifting gives the terms' values and the same overflows.
        let coords = [
            0i64,
            1,
            -1,
            7,
            -300,
            46_341,
            -3_037_000_500,
            3_037_000_499,
            2_147_483_647,
            2_097_152,
            1 << 31,
            i64::MAX,
            i64::MIN,
        ];
        for model in [
            Model::Line,
            Model::Circle,
            Model::Conic,
            Model::Poly(3),
            Model::Poly(6),
        ] {
            let b = model.basis();
            let planar = b.planar.as_ref().expect("planar terms");
            assert_eq!(
                planar.known.is_some(),
                matches!(model, Model::Line | Model::Circle | Model::Conic),
                "{model}"
            );
            let (mut fast, mut slow) = (vec![0; b.dim()], vec![0; b.dim()]);
            for &x in &coords {
                for &y in &coords {
                    let f = b.lift(&[x, y], &mut fast);
                    let s = lift_terms(&b.functions, &[x, y], &mut slow);
                    assert_eq!(f, s, "{model} at ({x}, {y})");
                    if f.is_some() {
                        assert_eq!(fast, slow, "{model} at ({x}, {y})");
                    }
                }
            }
        }
    }

    #[test]
    fn parse_models() {
        for m in [
            Model::Line,
            Model::Circle,
            Model::Conic,
            Model::Poly(3),
            Model::Quadric3,
            Model::Poly3(2),
        ] {
            assert_eq!(m.name().parse::<Model>(), Ok(m));
        }
        assert!("poly:0".parse::<Model>().is_err());
        assert!("poly:99".parse::<Model>().is_err());
        assert!("spline".parse::<Model>().is_err());
    }
}

//! Recognition of point sets given as such, in 2-D and 3-D: is there a Digital Level Layer
//! of the model that holds the inliers, with the `above` points strictly above it and the
//! `below` points strictly below?
//!
//! [`recognize_points`] answers with a proof either way, checked exactly before it is
//! returned: a [`Layer`] (integer coefficients and bounds, in the points' own coordinates)
//! or a [`Witness`] (points of `D` and rational weights putting the origin in their convex
//! hull, see [`crate::Recognizer`]). [`read_point_sets`] reads the JSON files of
//! `layertrace recognize`; [`recognition_json`] writes its answer.
//!
//! Without outliers the answer is the classical recognition: the thinnest layer of the
//! model holding the inliers, computed exactly by linear programming ([`Thinnest`], defined
//! with the L∞ normalisation of the coefficients).

mod json;
mod lp;
mod thinnest;
mod translate;

pub use json::{point_sets_from_json, read_point_sets, recognition_json};
pub use thinnest::{Thinnest, ThinnestWork};

use crate::error::Error;
use crate::model::{Basis, Model};
use crate::recognize::relative::relative;
use crate::recognize::{small_certificate, Certificate, Outcome, Recognizer, Side, Stats, Witness};
use num_bigint::BigInt;
use std::sync::Arc;

/// Three sets of integer points: the inliers `S`, and the outliers `S⁺` (`above`) and `S⁻`
/// (`below`); every point has the same number of coordinates.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct PointSets {
    /// `S`: the points the layer must hold.
    pub inliers: Vec<Vec<i64>>,
    /// `S⁺`: points that must be strictly above the layer (may be empty).
    pub above: Vec<Vec<i64>>,
    /// `S⁻`: points that must be strictly below the layer (may be empty).
    pub below: Vec<Vec<i64>>,
}

impl PointSets {
    /// Inliers without outliers.
    pub fn new(inliers: Vec<Vec<i64>>) -> PointSets {
        PointSets {
            inliers,
            ..PointSets::default()
        }
    }

    /// The same inliers, with `points` as the points above.
    pub fn with_above(mut self, points: Vec<Vec<i64>>) -> PointSets {
        self.above = points;
        self
    }

    /// The same inliers, with `points` as the points below.
    pub fn with_below(mut self, points: Vec<Vec<i64>>) -> PointSets {
        self.below = points;
        self
    }

    /// The number of coordinates of the first point (`None` when there is no point).
    pub fn dimension(&self) -> Option<usize> {
        self.sets().find_map(|(_, s)| s.first()).map(Vec::len)
    }

    /// The three sets with their names in files and messages.
    fn sets(&self) -> impl Iterator<Item = (&'static str, &Vec<Vec<i64>>)> {
        [
            ("inliers", &self.inliers),
            ("above", &self.above),
            ("below", &self.below),
        ]
        .into_iter()
    }
}

/// A Digital Level Layer in the points' own coordinates:
/// `lower ≤ Σ coefficients[i] · f_i(p) ≤ upper`, the `f_i` the basis functions (the
/// constant's coefficient is zero and not listed). Exact big integers.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct Layer {
    /// One integer per non-constant basis function, in the basis' order.
    pub coefficients: Vec<BigInt>,
    /// The least value over the inliers.
    pub lower: BigInt,
    /// The greatest value over the inliers.
    pub upper: BigInt,
    /// The least value over the points above (`> upper`), `None` if there are none.
    pub above: Option<BigInt>,
    /// The greatest value over the points below (`< lower`), `None` if there are none.
    pub below: Option<BigInt>,
}

impl Layer {
    /// `Σ coefficients[i] · f_i(p)` exactly; `None` if `p` or the coefficients do not fit the
    /// basis, or the value needs the basis' polynomials and it has none.
    pub fn value(&self, basis: &dyn Basis, p: &[i64]) -> Option<BigInt> {
        translate::evaluate(basis, &self.coefficients, p)
    }
}

/// The answer of [`recognize_points`], with its proof.
#[derive(Clone, Debug)]
#[non_exhaustive]
// One answer per recognition: its size does not matter, boxing would only cost readers.
#[allow(clippy::large_enum_variant)]
pub enum PointsAnswer {
    /// The sets are separated by a layer of the model.
    Described {
        /// The layer in the points' own coordinates; `None` only for a basis of one's own
        /// that has no polynomials or whose span is not closed under translation.
        layer: Option<Layer>,
        /// The same layer as the recognizer found it, relative to a local origin (the
        /// middle of the inliers' bounding box): `lower ≤ Σ a_i f_i(p − origin) ≤ upper`,
        /// with coefficients made small as in the decomposition JSON (the largest-margin
        /// direction rounded at growing scales, the first that verifies).
        local: Certificate,
    },
    /// No layer of the model separates the sets: the witness proves it.
    NotDescribed(Witness),
    /// There are no outliers: the thinnest layer of the model holding the inliers, with
    /// its exact thickness (`(upper − lower) / max_i |coefficients_i|`, the least over every
    /// layer of the model holding them; see [`Thinnest`]).
    Thinnest(Thinnest),
}

/// What [`recognize_points`] found, and the work it took.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct PointsRecognition {
    /// The model, `None` for a basis of one's own ([`recognize_points_with`]).
    pub model: Option<Model>,
    /// The names of the basis functions in coefficient order, the constant `"1"` last.
    pub basis: Vec<String>,
    /// The number of coordinates of the points.
    pub dimension: usize,
    /// The sizes of the inliers, the points above and the points below.
    pub counts: [usize; 3],
    /// Described or not, with the proof.
    pub answer: PointsAnswer,
    /// The recognizer's counters (zero for a thinnest layer: the recognizer is not run).
    pub stats: Stats,
}

impl PointsRecognition {
    /// True when the sets are described (by a separating or a thinnest layer).
    pub fn is_described(&self) -> bool {
        matches!(
            self.answer,
            PointsAnswer::Described { .. } | PointsAnswer::Thinnest(_)
        )
    }

    /// The layer in the points' own coordinates, when there is one.
    pub fn layer(&self) -> Option<&Layer> {
        match &self.answer {
            PointsAnswer::Described { layer, .. } => layer.as_ref(),
            PointsAnswer::Thinnest(t) => Some(&t.layer),
            PointsAnswer::NotDescribed(_) => None,
        }
    }
}

/// Decides whether a layer of `model` holds `sets.inliers` with `sets.above` strictly above
/// and `sets.below` strictly below; the proof returned has been checked exactly.
///
/// ```
/// use layertrace::{recognize_points, Model, PointSets, PointsAnswer};
///
/// // The digital line 0 ≤ x − 2y ≤ 1, with a point above it and one below.
/// let sets = PointSets::new((0..10).map(|x| vec![x, x / 2]).collect())
///     .with_above(vec![vec![3, 3]])
///     .with_below(vec![vec![6, 1]]);
/// let r = recognize_points(&sets, Model::Line)?;
/// let PointsAnswer::Described { layer: Some(layer), .. } = &r.answer else { panic!() };
/// let basis = Model::Line.basis();
/// for p in &sets.inliers {
///     let v = layer.value(&basis, p).unwrap();
///     assert!(layer.lower <= v && v <= layer.upper);
/// }
/// assert!(layer.value(&basis, &[3, 3]).unwrap() > layer.upper);
/// # Ok::<(), layertrace::Error>(())
/// ```
///
/// Without outliers (`above` and `below` empty) the answer is [`PointsAnswer::Thinnest`]:
/// the layer of the model holding the inliers whose thickness
/// `(upper − lower) / max_i |coefficients_i|` is least, exactly, in the points' own
/// coordinates.
///
/// ```
/// use layertrace::{recognize_points, BigRational, Model, PointSets, PointsAnswer};
///
/// // A digital straight segment of slope 3/7: the thinnest strip is −6 ≤ −3x + 7y ≤ 0,
/// // of thickness 6/7 (the largest coefficient, the normalising one, is positive).
/// let sets = PointSets::new((0..20).map(|x| vec![x, 3 * x / 7]).collect());
/// let r = recognize_points(&sets, Model::Line)?;
/// let PointsAnswer::Thinnest(t) = &r.answer else { panic!() };
/// assert_eq!(t.thickness, BigRational::new(6.into(), 7.into()));
/// assert_eq!(t.layer.coefficients, [(-3).into(), 7.into()]);
/// assert_eq!((t.layer.lower.clone(), t.layer.upper.clone()), ((-6).into(), 0.into()));
/// # Ok::<(), layertrace::Error>(())
/// ```
///
/// Errors ([`Error::Points`], the message names the point): no inliers; a point whose
/// number of coordinates is not the model's (2 for line, circle, conic and poly:D; 3 for
/// quadric3 and poly3:D); with outliers, a point whose lifting, relative to the middle of
/// the inliers' bounding box, overflows 64-bit integers; an undecided recognition (never
/// met in the tests).
pub fn recognize_points(sets: &PointSets, model: Model) -> Result<PointsRecognition, Error> {
    let mut r = recognize_points_with(sets, Arc::new(model.basis()))?;
    r.model = Some(model);
    Ok(r)
}

/// [`recognize_points`] with a basis of one's own (see [`Basis`]).
///
/// ```
/// use layertrace::{point_sets_from_json, recognize_points_with, Model, PointsAnswer};
/// use std::sync::Arc;
/// let sets = point_sets_from_json(br#"{"inliers": [[0, 0], [2, 1], [4, 2]],
///     "above": [[0, 1]], "below": [[4, 1]]}"#)?;
/// let r = recognize_points_with(&sets, Arc::new(Model::Line.basis()))?;
/// assert!(matches!(r.answer, PointsAnswer::Described { .. }));
/// # Ok::<(), layertrace::Error>(())
/// ```
pub fn recognize_points_with(
    sets: &PointSets,
    basis: Arc<dyn Basis>,
) -> Result<PointsRecognition, Error> {
    let pd = basis.point_dim();
    let err = |m: String| Error::Points(m);
    if sets.inliers.is_empty() {
        return Err(err(
            "no inliers: the layer is sought around at least one point".into(),
        ));
    }
    for (name, set) in sets.sets() {
        if let Some((i, p)) = set.iter().enumerate().find(|(_, p)| p.len() != pd) {
            return Err(err(format!(
                "{name}[{i}] has {} coordinate{}, but the model takes {pd}-D points",
                p.len(),
                if p.len() == 1 { "" } else { "s" }
            )));
        }
    }
    if sets.above.is_empty() && sets.below.is_empty() {
        let t = thinnest::thinnest(&*basis, &sets.inliers).map_err(err)?;
        return Ok(PointsRecognition {
            model: None,
            basis: basis.names(),
            dimension: pd,
            counts: [sets.inliers.len(), 0, 0],
            answer: PointsAnswer::Thinnest(t),
            stats: Stats::default(),
        });
    }
    let origin = middle(&sets.inliers);
    // Every lifting must fit i64 (the recognizer's exact data); say which point does not.
    let mut f = vec![0; basis.dim()];
    for (name, set) in sets.sets() {
        for (i, p) in set.iter().enumerate() {
            if relative(p, &origin)
                .and_then(|rel| basis.lift(&rel, &mut f))
                .is_none()
            {
                return Err(err(format!(
                    "{name}[{i}] = {p:?}: its lifting overflows 64-bit integers (the points are too far from {origin:?}, the middle of the inliers, for this basis)"
                )));
            }
        }
    }
    let mut rec = Recognizer::new(basis.clone(), &origin)
        .ok_or_else(|| err("the origin does not fit the basis".into()))?;
    for p in &sets.inliers {
        rec.add_inlier(p);
    }
    for p in &sets.above {
        rec.add_outlier(p, Side::Upper);
    }
    for p in &sets.below {
        rec.add_outlier(p, Side::Lower);
    }
    let outcome = rec.recognize();
    let answer = match outcome {
        Outcome::Described => {
            let cert = rec
                .certificate()
                .ok_or_else(|| err("described, but no certificate (please report)".into()))?;
            let local = small_certificate(&*basis, &cert, &sets.inliers, &sets.above, &sets.below);
            let layer = translate::absolute(&*basis, &local);
            check_described(&*basis, sets, &local, layer.as_ref()).map_err(|m| {
                err(format!(
                    "the certificate failed its exact check ({m}; please report)"
                ))
            })?;
            PointsAnswer::Described { layer, local }
        }
        Outcome::NotDescribed => {
            let w = rec
                .witness()
                .cloned()
                .filter(|w| w.verify(&*basis))
                .ok_or_else(|| err("the witness failed its exact check (please report)".into()))?;
            PointsAnswer::NotDescribed(w)
        }
        _ => {
            return Err(err(
                "the recognizer could decide neither way (please report, with the file)".into(),
            ))
        }
    };
    Ok(PointsRecognition {
        model: None,
        basis: basis.names(),
        dimension: pd,
        counts: [sets.inliers.len(), sets.above.len(), sets.below.len()],
        answer,
        stats: rec.stats(),
    })
}

/// The middle of the bounding box of `points` (rounded down), a local origin near all of them.
fn middle(points: &[Vec<i64>]) -> Vec<i64> {
    let d = points.first().map_or(0, Vec::len);
    (0..d)
        .map(|k| {
            let lo = points.iter().map(|p| p[k]).min().unwrap_or(0);
            let hi = points.iter().map(|p| p[k]).max().unwrap_or(0);
            let m = (i128::from(lo) + i128::from(hi)).div_euclid(2);
            i64::try_from(m).unwrap_or(lo)
        })
        .collect()
}

/// Re-checks a certificate and its absolute layer on every point, exactly: the inliers
/// within the bounds (reached), the points above strictly above, below strictly below.
fn check_described(
    basis: &dyn Basis,
    sets: &PointSets,
    local: &Certificate,
    layer: Option<&Layer>,
) -> Result<(), String> {
    let local_value = |p: &[i64]| local.value(basis, p).map(BigInt::from);
    let bounds = |v: i128| BigInt::from(v);
    check_values(
        sets,
        local_value,
        (bounds(local.extremes.lower), bounds(local.extremes.upper)),
        (
            local.extremes.above.map(bounds),
            local.extremes.below.map(bounds),
        ),
    )
    .map_err(|m| format!("local: {m}"))?;
    if let Some(l) = layer {
        check_values(
            sets,
            |p| l.value(basis, p),
            (l.lower.clone(), l.upper.clone()),
            (l.above.clone(), l.below.clone()),
        )
        .map_err(|m| format!("absolute: {m}"))?;
    }
    Ok(())
}

/// The values of `value` on the sets are exactly the extremes given, in order.
fn check_values(
    sets: &PointSets,
    value: impl Fn(&[i64]) -> Option<BigInt>,
    (lower, upper): (BigInt, BigInt),
    (above, below): (Option<BigInt>, Option<BigInt>),
) -> Result<(), String> {
    let extremes = |set: &[Vec<i64>]| -> Result<Option<(BigInt, BigInt)>, String> {
        let mut out: Option<(BigInt, BigInt)> = None;
        for p in set {
            let v = value(p).ok_or_else(|| format!("no value at {p:?}"))?;
            out = Some(match out {
                None => (v.clone(), v),
                Some((lo, hi)) => (lo.min(v.clone()), hi.max(v)),
            });
        }
        Ok(out)
    };
    let s = extremes(&sets.inliers)?;
    if s != Some((lower.clone(), upper.clone())) {
        return Err("inliers' extremes".into());
    }
    let a = extremes(&sets.above)?.map(|(lo, _)| lo);
    let b = extremes(&sets.below)?.map(|(_, hi)| hi);
    if a != above || b != below {
        return Err("outliers' extremes".into());
    }
    if a.is_some_and(|a| a <= upper) || b.is_some_and(|b| b >= lower) {
        return Err("not separated".into());
    }
    Ok(())
}

#[cfg(test)]
mod tests;

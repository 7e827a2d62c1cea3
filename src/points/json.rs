//! Point files in, recognitions out: the JSON of `layertrace recognize`.
//!
//! [`read_point_sets`] documents the point files, [`recognition_json`] the answers. Point
//! files are read with serde's visitors (no derive), so that a bad value is reported with
//! its field and the parser's line and column; answers are derived `Serialize` types written
//! by serde_json (laid out by `export::json_layout`).

use super::{Layer, PointSets, PointsAnswer, PointsRecognition};
use crate::error::Error;
use crate::export::json::top_break;
use crate::export::json_layout::{to_text, BigNumber, Layout, List};
use crate::recognize::Side;
use num_bigint::BigInt;
use serde::de::{self, DeserializeSeed, MapAccess, SeqAccess, Visitor};
use serde::Serialize;
use std::fmt;
use std::io::Read;
use std::path::{Path, PathBuf};

/// The most coordinates a point may have in a file.
const MAX_DIMENSION: usize = 16;

/// Reads a point file (`-` for standard input).
///
/// A point file is one object:
///
/// ```text
/// {"inliers": [[x, y], …], "above": [[x, y], …], "below": [[x, y], …]}
/// ```
///
/// `"above"` and `"below"` may be empty, `null` or absent; every point has the same number
/// of coordinates, each an integer written as such (`3`, not `3.0` or `3e0`) in the 64-bit
/// range. Other members are refused (a misspelt `"abvoe"` would otherwise drop points
/// silently). The file is read with serde's visitors, so a bad value is reported with its
/// field and the parser's line and column: `inliers[3][1]: 2.5 is not an integer at line 4
/// column 12`.
///
/// Errors: [`Error::Read`] if it cannot be read, [`Error::NoData`] if it is empty,
/// [`Error::PointFile`] if it is not a point file (the message says where).
pub fn read_point_sets(path: &Path) -> Result<PointSets, Error> {
    let stdin = path == Path::new("-");
    let shown: PathBuf = if stdin { "<stdin>".into() } else { path.into() };
    let read = |source| Error::Read {
        path: shown.clone(),
        source,
    };
    let bytes = if stdin {
        let mut v = Vec::new();
        std::io::stdin().lock().read_to_end(&mut v).map_err(read)?;
        v
    } else {
        std::fs::read(path).map_err(read)?
    };
    if bytes.is_empty() {
        return Err(Error::NoData { path: shown });
    }
    parse(&bytes).map_err(|message| Error::PointFile {
        path: shown,
        message,
    })
}

/// Parses the bytes of a point file (see [`read_point_sets`]); errors name the file
/// `<memory>`.
///
/// ```
/// use layertrace::point_sets_from_json;
/// let sets = point_sets_from_json(br#"{"inliers": [[0, 0], [1, 1]], "above": [[0, 1]]}"#)?;
/// assert_eq!((sets.inliers.len(), sets.above.len(), sets.below.len()), (2, 1, 0));
/// assert!(point_sets_from_json(b"{\"inliers\": 3}").is_err());
/// # Ok::<(), layertrace::Error>(())
/// ```
pub fn point_sets_from_json(bytes: &[u8]) -> Result<PointSets, Error> {
    parse(bytes).map_err(|message| Error::PointFile {
        path: "<memory>".into(),
        message,
    })
}

/// The point sets of a file, or a one-line message naming the field and position.
fn parse(bytes: &[u8]) -> Result<PointSets, String> {
    let mut de = serde_json::Deserializer::from_slice(bytes);
    let message = |e: serde_json::Error| match e.classify() {
        serde_json::error::Category::Data => e.to_string(),
        _ => format!("not valid JSON: {e}"),
    };
    let sets = de::Deserializer::deserialize_map(&mut de, FileVisitor).map_err(message)?;
    de.end().map_err(message)?;
    Ok(sets)
}

/// The names of the three sets, in file order.
const SETS: [&str; 3] = ["inliers", "above", "below"];

/// The top-level object.
struct FileVisitor;

impl<'de> Visitor<'de> for FileVisitor {
    type Value = PointSets;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("an object with \"inliers\" (and \"above\", \"below\")")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<PointSets, A::Error> {
        let mut first: Option<First> = None;
        let mut sets: [Option<Vec<Vec<i64>>>; 3] = Default::default();
        while let Some(key) = map.next_key::<String>()? {
            let Some(k) = SETS.iter().position(|s| *s == key) else {
                return Err(de::Error::custom(format!(
                    "unknown member \"{key}\" (a point file has \"inliers\", \"above\" and \"below\")"
                )));
            };
            if sets[k].is_some() {
                return Err(de::Error::custom(format!("\"{key}\" is given twice")));
            }
            sets[k] = Some(map.next_value_seed(ListSeed {
                name: SETS[k],
                first: &mut first,
            })?);
        }
        let [inliers, above, below] = sets;
        Ok(PointSets {
            inliers: inliers.ok_or_else(|| de::Error::custom("missing \"inliers\""))?,
            above: above.unwrap_or_default(),
            below: below.unwrap_or_default(),
        })
    }
}

/// The first point read: its set, index and number of coordinates.
#[derive(Clone, Copy)]
struct First {
    name: &'static str,
    index: usize,
    dimension: usize,
}

/// A list of points (`null` is an empty list, except for the inliers).
struct ListSeed<'a> {
    name: &'static str,
    first: &'a mut Option<First>,
}

impl<'de> DeserializeSeed<'de> for ListSeed<'_> {
    type Value = Vec<Vec<i64>>;

    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for ListSeed<'_> {
    type Value = Vec<Vec<i64>>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "\"{}\" to be a list of points [[x, y], …]", self.name)
    }

    fn visit_unit<E: de::Error>(self) -> Result<Self::Value, E> {
        if self.name == SETS[0] {
            return Err(E::invalid_type(de::Unexpected::Unit, &self));
        }
        Ok(Vec::new())
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut points = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(1 << 16));
        loop {
            let index = points.len();
            let seed = PointSeed {
                name: self.name,
                index,
            };
            let Some(p) = seq.next_element_seed(seed)? else {
                break;
            };
            match *self.first {
                None => {
                    *self.first = Some(First {
                        name: self.name,
                        index,
                        dimension: p.len(),
                    })
                }
                Some(f) if f.dimension != p.len() => {
                    return Err(de::Error::custom(format!(
                        "{}[{index}] has {} coordinates, but {}[{}] has {}: every point must have the same dimension",
                        self.name,
                        p.len(),
                        f.name,
                        f.index,
                        f.dimension
                    )))
                }
                Some(_) => {}
            }
            points.push(p);
        }
        Ok(points)
    }
}

/// One point: a list of 1 to [`MAX_DIMENSION`] integers.
struct PointSeed {
    name: &'static str,
    index: usize,
}

impl<'de> DeserializeSeed<'de> for PointSeed {
    type Value = Vec<i64>;

    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for PointSeed {
    type Value = Vec<i64>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}[{}] to be a point, a list of integer coordinates [x, y] or [x, y, z]",
            self.name, self.index
        )
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut p = Vec::with_capacity(3);
        loop {
            let seed = CoordinateSeed {
                name: self.name,
                index: self.index,
                k: p.len(),
            };
            let Some(v) = seq.next_element_seed(seed)? else {
                break;
            };
            if p.len() == MAX_DIMENSION {
                return Err(de::Error::custom(format!(
                    "{}[{}] has more than {MAX_DIMENSION} coordinates",
                    self.name, self.index
                )));
            }
            p.push(v);
        }
        if p.is_empty() {
            return Err(de::Error::custom(format!(
                "{}[{}] is an empty point",
                self.name, self.index
            )));
        }
        Ok(p)
    }
}

/// One coordinate: an integer written as such, within `i64`.
struct CoordinateSeed {
    name: &'static str,
    index: usize,
    k: usize,
}

impl CoordinateSeed {
    fn at(&self) -> String {
        format!("{}[{}][{}]", self.name, self.index, self.k)
    }
}

impl<'de> DeserializeSeed<'de> for CoordinateSeed {
    type Value = i64;

    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<i64, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for CoordinateSeed {
    type Value = i64;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} to be an integer", self.at())
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<i64, E> {
        Ok(v)
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<i64, E> {
        i64::try_from(v).map_err(|_| E::custom(too_large(&self.at())))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<i64, E> {
        // serde_json gives integers beyond u64 and i64 as doubles too.
        Err(E::custom(if v.is_finite() && v.fract() == 0.0 {
            if v.abs() >= 9.2e18 {
                too_large(&self.at())
            } else {
                format!(
                    "{}: {v:?} must be written as an integer (no decimal point or exponent)",
                    self.at()
                )
            }
        } else {
            format!("{}: {v} is not an integer", self.at())
        }))
    }
}

fn too_large(at: &str) -> String {
    format!("{at} is beyond the 64-bit integer range (-2^63 to 2^63 - 1)")
}

/// A `layertrace-recognition/1` document; the members of the other answers are absent.
#[derive(Serialize)]
struct RecognitionDoc<'a> {
    format: &'static str,
    model: Option<String>,
    dimension: usize,
    basis: &'a [String],
    inliers: usize,
    above: usize,
    below: usize,
    result: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    thinnest: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    normalisation: Option<&'static str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    thickness: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    layer: Option<LayerDoc<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    local: Option<LocalDoc<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    programs: Option<ProgramsDoc>,
    #[serde(skip_serializing_if = "Option::is_none")]
    witness: Option<WitnessDoc<'a>>,
    stats: StatsDoc,
}

/// A layer in the points' own coordinates, its big integers as exact numbers.
#[derive(Serialize)]
struct LayerDoc<'a> {
    /// The layer's, then the constant's 0.
    coefficients: Vec<BigNumber<'a>>,
    lower: BigNumber<'a>,
    upper: BigNumber<'a>,
    above: Option<BigNumber<'a>>,
    below: Option<BigNumber<'a>>,
}

/// The recognizer's certificate, relative to its origin.
#[derive(Serialize)]
struct LocalDoc<'a> {
    origin: &'a [i64],
    /// The certificate's, then the constant's 0.
    coefficients: Vec<i64>,
    lower: i128,
    upper: i128,
    above: Option<i128>,
    below: Option<i128>,
}

/// The thinnest layer's linear programs.
#[derive(Serialize)]
struct ProgramsDoc {
    started: u64,
    pruned: u64,
    pivots: u64,
    rounds: u64,
    points: u64,
}

/// The proof that no layer separates the sets.
#[derive(Serialize)]
struct WitnessDoc<'a> {
    origin: &'a [i64],
    terms: Vec<TermDoc<'a>>,
}

/// One pair of the witness, with its exact weight `p/q`.
#[derive(Serialize)]
struct TermDoc<'a> {
    weight: String,
    inlier: &'a [i64],
    outlier: &'a [i64],
    side: &'static str,
}

/// The recognizer's counters.
#[derive(Serialize)]
struct StatsDoc {
    queries: u64,
    certificate_reused: u64,
    float_runs: u64,
    float_iterations: u64,
    whitened: u64,
    exact_fallbacks: u64,
    undecided: u64,
    over_budget: u64,
    work: u64,
}

/// Lines: the format, model and dimension; the basis; the three counts; the result; the
/// thinnest layer's flag, normalisation and thickness; then one line per member (and per
/// witness term).
const RECOGNITION: Layout = Layout {
    breaks: &[
        top_break("basis"),
        top_break("inliers"),
        top_break("result"),
        top_break("thinnest"),
        top_break("layer"),
        top_break("local"),
        top_break("programs"),
        top_break("witness"),
        top_break("stats"),
    ],
    lists: &[List {
        parent: "witness",
        key: "terms",
        line: "\n   ",
        first: true,
        close: "",
    }],
};

/// The layer's document: its coefficients, then the constant's 0.
fn layer_doc<'a>(l: &'a Layer, zero: &'a BigInt) -> LayerDoc<'a> {
    LayerDoc {
        coefficients: l.coefficients.iter().chain([zero]).map(BigNumber).collect(),
        lower: BigNumber(&l.lower),
        upper: BigNumber(&l.upper),
        above: l.above.as_ref().map(BigNumber),
        below: l.below.as_ref().map(BigNumber),
    }
}

/// The JSON text of a recognition.
///
/// The format, `layertrace-recognition/1`:
///
/// ```text
/// {"format": "layertrace-recognition/1", "model": "quadric3", "dimension": 3,
///  "basis": ["x^2", …, "z", "1"], "inliers": 120, "above": 80, "below": 75,
///  "result": "described",
///  "layer": {"coefficients": [… , 0], "lower": L, "upper": U, "above": A, "below": B},
///  "local": {"origin": [x0, y0, z0], "coefficients": [… , 0], "lower": l, "upper": u,
///            "above": a, "below": b},
///  "stats": {"queries": 1, …}}
/// ```
///
/// `layer`: `f(p) = Σ coefficients[i] · basis_i(p)` in the points' own coordinates, every
/// inlier has `lower ≤ f ≤ upper` (both reached), every point above `f ≥ above > upper`,
/// every point below `f ≤ below < lower` (`above`, `below` are `null` without such points).
/// `local`: the same layer as the recognizer found it, `f(p − origin)`, as in the
/// decomposition JSON. All are exact integers, as large as they need to be (beyond 2^53 a
/// reader that parses numbers as doubles, JavaScript's, rounds them; Python's does not).
/// With a basis of one's own ([`crate::recognize_points_with`]), `model` is `null`, and
/// `layer` is absent when the basis has no absolute form (see [`super::PointsAnswer`]).
///
/// When not described, `"result": "not described"` and, instead of `layer` and `local`:
///
/// ```text
///  "witness": {"origin": [x0, y0, z0], "terms": [{"weight": "3/7", "inlier": [x, y, z],
///              "outlier": [x, y, z], "side": "above"}, …]}
/// ```
///
/// The weights are exact fractions `p/q` (or integers), non-negative, summing to 1, and
/// `Σ weight · d = 0` with `d = F(outlier − origin) − F(inlier − origin)` for a term whose
/// outlier is above, `F(inlier − origin) − F(outlier − origin)` below, `F` the basis
/// functions: no layer can have every `d` on its positive side.
///
/// Without outliers (`"above": 0, "below": 0`) the answer is the thinnest layer holding the
/// inliers ([`super::Thinnest`]): `"result": "described"`, then
///
/// ```text
///  "thinnest": true, "normalisation": "max-abs", "thickness": "6/7",
///  "layer": {"coefficients": [-3, 7, 0], "lower": -6, "upper": 0, "above": null, "below": null},
///  "programs": {"started": 2, "pruned": 0, "pivots": 9, "rounds": 4, "points": 20},
/// ```
///
/// and no `local`. The thickness is `(upper − lower) / max_i |coefficients_i|` (the
/// constant's coefficient excluded: `"normalisation": "max-abs"`, the L∞ norm), an exact
/// fraction `p/q` (or an integer), the least over every layer of the model holding the
/// inliers, in the points' own coordinates; the coefficients have no common divisor and the
/// largest in absolute value is positive. `programs` counts the linear programs started (one
/// per non-constant basis function), those stopped early (already no thinner than the best),
/// the simplex pivots, the rounds of constraint generation and the distinct lifted inliers.
/// The recognizer is not run: its `stats` are zero.
pub fn recognition_json(r: &PointsRecognition) -> String {
    let zero = BigInt::default();
    let t = &r.stats;
    let mut doc = RecognitionDoc {
        format: "layertrace-recognition/1",
        model: r.model.map(|m| m.name()),
        dimension: r.dimension,
        basis: &r.basis,
        inliers: r.counts[0],
        above: r.counts[1],
        below: r.counts[2],
        result: "described",
        thinnest: None,
        normalisation: None,
        thickness: None,
        layer: None,
        local: None,
        programs: None,
        witness: None,
        stats: StatsDoc {
            queries: t.queries,
            certificate_reused: t.certificate_reused,
            float_runs: t.float_runs,
            float_iterations: t.float_iterations,
            whitened: t.whitened,
            exact_fallbacks: t.exact_fallbacks,
            undecided: t.undecided,
            over_budget: t.over_budget,
            work: t.work,
        },
    };
    match &r.answer {
        PointsAnswer::Described { layer, local } => {
            doc.layer = layer.as_ref().map(|l| layer_doc(l, &zero));
            let e = &local.extremes;
            doc.local = Some(LocalDoc {
                origin: &local.origin,
                coefficients: local.coefficients.iter().copied().chain([0]).collect(),
                lower: e.lower,
                upper: e.upper,
                above: e.above,
                below: e.below,
            });
        }
        PointsAnswer::Thinnest(t) => {
            let w = &t.work;
            doc.thinnest = Some(true);
            doc.normalisation = Some("max-abs");
            doc.thickness = Some(t.thickness.to_string());
            doc.layer = Some(layer_doc(&t.layer, &zero));
            doc.programs = Some(ProgramsDoc {
                started: w.programs,
                pruned: w.pruned,
                pivots: w.pivots,
                rounds: w.rounds,
                points: w.points,
            });
        }
        PointsAnswer::NotDescribed(w) => {
            doc.result = "not described";
            doc.witness = Some(WitnessDoc {
                origin: &w.origin,
                terms: w
                    .pairs
                    .iter()
                    .zip(w.exact_weights())
                    .map(|((inlier, outlier, side), weight)| TermDoc {
                        weight: weight.to_string(),
                        inlier,
                        outlier,
                        side: match side {
                            Side::Upper => "above",
                            Side::Lower => "below",
                        },
                    })
                    .collect(),
            });
        }
    }
    to_text(&doc, &RECOGNITION)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error(text: &str) -> String {
        parse(text.as_bytes()).unwrap_err()
    }

    #[test]
    fn reads_the_three_sets() {
        let s =
            parse(br#"{"inliers": [[1, 2], [-3, 4]], "below": [[0, 0]], "above": null}"#).unwrap();
        assert_eq!(s.inliers, [vec![1, 2], vec![-3, 4]]);
        assert!(s.above.is_empty());
        assert_eq!(s.below, [vec![0, 0]]);
        let s = parse(b"{\"inliers\": [[9223372036854775807, -9223372036854775808, 0]]}").unwrap();
        assert_eq!(s.inliers, [vec![i64::MAX, i64::MIN, 0]]);
        assert_eq!(s.dimension(), Some(3));
    }

    /// Every message names the field and the position.
    #[test]
    fn errors_name_the_field_and_line() {
        let cases: &[(&str, &[&str])] = &[
            (
                "{\"inliers\": [[1,2],\n [3, 2.5]]}",
                &["inliers[1][1]", "not an integer", "line 2"],
            ),
            (
                "{\"inliers\": [[1,2]],\n \"above\": [[1,2,3]]}",
                &["above[0] has 3", "inliers[0] has 2", "line 2"],
            ),
            (
                "{\"inliers\": [[1, 9223372036854775808]]}",
                &["inliers[0][1]", "64-bit", "line 1"],
            ),
            ("{\"inliers\": [[1, 1e30]]}", &["inliers[0][1]", "64-bit"]),
            (
                "{\"inliers\": [[1, 100000000000000000000000000]]}",
                &["inliers[0][1]", "64-bit"],
            ),
            (
                "{\"inliers\": [[1, 2.0]]}",
                &["inliers[0][1]", "written as an integer"],
            ),
            (
                "{\"inliers\": [[1, \"2\"]]}",
                &["inliers[0][1] to be an integer", "line 1"],
            ),
            ("{\"inliers\": [[]]}", &["inliers[0] is an empty point"]),
            ("{\"inliers\": [1, 2]}", &["inliers[0] to be a point"]),
            ("{\"inliers\": {}}", &["\"inliers\" to be a list"]),
            ("{\"inliers\": null}", &["\"inliers\" to be a list"]),
            ("{\"above\": [[1, 2]]}", &["missing \"inliers\""]),
            (
                "{\"inliers\": [], \"abvoe\": []}",
                &["unknown member \"abvoe\""],
            ),
            ("{\"inliers\": [], \"inliers\": []}", &["given twice"]),
            ("[[1, 2]]", &["expected an object"]),
            ("{\"inliers\": [[1, 2]]", &["not valid JSON", "line 1"]),
            ("{\"inliers\": [[1, 2]]} x", &["not valid JSON", "trailing"]),
            ("\u{1}", &["not valid JSON"]),
        ];
        for (text, parts) in cases {
            let e = error(text);
            assert!(!e.contains('\n'), "{e}");
            for part in *parts {
                assert!(e.contains(part), "{text:?}: {e:?} lacks {part:?}");
            }
        }
    }
}

//! `layertrace recognize`: the recognition of point sets read from a JSON file.
//!
//! Dispatched on the first argument (see [`super::main`]): `layertrace recognize …` runs
//! this, anything else the vectorizer as before. An image file named `recognize` is given
//! as `./recognize`.

use clap::Parser;
use layertrace::{
    read_point_sets, recognition_json, recognize_points, Error, Model, OutputSet, PointsAnswer,
};
use std::path::{Path, PathBuf};
use std::time::Instant;

const AFTER_HELP: &str = "\
Example:
  layertrace recognize points.json --model quadric3 -o answer.json

The file (or '-' for standard input) is one JSON object of integer points, each [x, y]
or [x, y, z], all of the same dimension:
  {\"inliers\": [[x, y], ...], \"above\": [[x, y], ...], \"below\": [[x, y], ...]}
\"above\" and \"below\" may be empty or absent: then the answer is the thinnest layer of
the model holding the inliers (least (upper - lower) / max |coefficient|, computed exactly
by linear programming), with \"thinnest\": true and its exact \"thickness\".

The answer (JSON, standard output unless -o) says \"described\", with the layer's exact
integer coefficients and bounds in the points' own coordinates (inliers within
lower..upper, points above strictly above, below strictly below), or \"not described\",
with a witness: pairs of an inlier and an outlier and exact fractional weights that put
the origin in the convex hull of their lifted differences. Both are checked exactly before
they are written. The recognizer's counters follow. -o writes the file whole or not at all.

Exit codes:
  0  an answer was written (described or not)
  1  bad input or output: unreadable file, not JSON, a missing or mistyped field, a
     non-integer or out-of-range coordinate, points of mixed dimensions, points whose
     dimension the model does not take, no inliers (the message names the field and line)
  2  bad command-line arguments";

/// Decide whether integer points in 2-D or 3-D are a Digital Level Layer of a model, with
/// an exact proof either way.
#[derive(Parser, Debug)]
#[command(name = "layertrace recognize", bin_name = "layertrace recognize", version,
          after_help = AFTER_HELP)]
pub struct RecognizeArgs {
    /// The point file (JSON); '-' reads standard input.
    #[arg(value_name = "FILE.json")]
    pub input: PathBuf,

    /// The model: line, circle, conic or poly:D for 2-D points; quadric3 or poly3:D for 3-D
    /// points (D = 1..6).
    #[arg(long, short, value_name = "MODEL", value_parser = parse_model)]
    pub model: Model,

    /// Write the answer to FILE instead of standard output ('-' is standard output).
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,

    /// No summary line on standard error.
    #[arg(long, short)]
    pub quiet: bool,
}

fn parse_model(s: &str) -> Result<Model, String> {
    s.parse::<Model>().map_err(|e| e.to_string())
}

/// Reads, recognizes, writes; the summary line on standard error unless `--quiet`.
pub fn run(args: &RecognizeArgs) -> Result<(), Error> {
    let start = Instant::now();
    let input = &args.input;
    let stdin = input == Path::new("-");
    let name: PathBuf = if stdin {
        "<stdin>".into()
    } else {
        input.clone()
    };
    let mut outs = OutputSet::new((!stdin).then_some(input.as_path()));
    let out = outs.add(args.output.as_deref().unwrap_or(Path::new("-")))?;
    let sets = read_point_sets(input)?;
    let dimension = sets.dimension().unwrap_or(0);
    let takes = args.model.basis();
    let takes = layertrace::Basis::point_dim(&takes);
    if dimension != 0 && dimension != takes {
        let models = if dimension == 3 {
            "quadric3 or poly3:D"
        } else {
            "line, circle, conic or poly:D"
        };
        return Err(Error::PointFile {
            path: name,
            message: format!(
                "the points are {dimension}-D, but model {} takes {takes}-D points{}",
                args.model,
                match dimension {
                    2 | 3 => format!(" (for {dimension}-D points: {models})"),
                    _ => String::new(),
                }
            ),
        });
    }
    let r = recognize_points(&sets, args.model).map_err(|e| match e {
        Error::Points(message) => Error::PointFile {
            path: name.clone(),
            message,
        },
        e => e,
    })?;
    outs.write(out, recognition_json(&r).into_bytes())?;
    outs.commit_final()?;
    let [i, a, b] = r.counts;
    if !args.quiet {
        let answer = match &r.answer {
            PointsAnswer::Described { .. } => "described".to_string(),
            PointsAnswer::Thinnest(t) => format!("thinnest layer, thickness {}", t.thickness),
            PointsAnswer::NotDescribed(w) => {
                format!("not described (witness of {} pairs)", w.pairs.len())
            }
            _ => "?".to_string(),
        };
        eprintln!(
            "{}: {i} inliers, {a} above, {b} below ({}-D), model {}: {answer}, {:.1} ms",
            name.display(),
            r.dimension,
            args.model,
            start.elapsed().as_secs_f64() * 1e3
        );
    }
    Ok(())
}

//! Pixel staircases: what a viewer sees as jaggies when zooming in.
//!
//! A *staircase* is a maximal run of at least [`MIN_RUN`] consecutive straight segments, each
//! axis-aligned and at most [`MAX_STEP`] pixels long, alternating horizontal and vertical.
//! The definition is the one of the project's shared tool `tools/staircase.py` (see
//! [`staircases`](crate::staircases) for how path data is read). This module holds the
//! counter, used on written path data by the fidelity stage and on drawings by the outline
//! (which avoids drawings with a staircase where it has a choice).

use kurbo::Point;

use crate::curve::PathCommand;

/// Fewest segments in a staircase.
pub const MIN_RUN: u64 = 4;

/// Longest step (pixels, user units) of a staircase.
pub const MAX_STEP: f64 = 2.0;

/// Staircases found in some path data.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StaircaseCount {
    /// Staircase runs.
    pub runs: u64,
    /// Segments inside those runs.
    pub segments: u64,
    /// Straight segments of the path data (closing segments included).
    pub lines: u64,
}

impl std::ops::AddAssign for StaircaseCount {
    fn add_assign(&mut self, o: Self) {
        self.runs += o.runs;
        self.segments += o.segments;
        self.lines += o.lines;
    }
}

/// Direction of a short axis-aligned segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Step {
    /// At most [`MAX_STEP`] long, horizontal.
    Horizontal,
    /// At most [`MAX_STEP`] long, vertical.
    Vertical,
}

/// The step a straight segment from `from` to `to` makes, or `None` when it is not a
/// step (too long, not axis-aligned, or empty).
pub(crate) fn step(from: Point, to: Point) -> Option<Step> {
    let (dx, dy) = ((to.x - from.x).abs(), (to.y - from.y).abs());
    if dy < 1e-9 && dx > 0.0 && dx <= MAX_STEP {
        Some(Step::Horizontal)
    } else if dx < 1e-9 && dy > 0.0 && dy <= MAX_STEP {
        Some(Step::Vertical)
    } else {
        None
    }
}

/// Counts runs while segments are fed one by one.
#[derive(Default)]
pub(crate) struct Counter {
    count: StaircaseCount,
    run: u64,
    last: Option<Step>,
}

impl Counter {
    /// Ends the current run (counted if long enough).
    fn end_run(&mut self) {
        if self.run >= MIN_RUN {
            self.count.runs += 1;
            self.count.segments += self.run;
        }
        self.run = 0;
    }

    /// Anything but a straight segment: ends the run.
    pub(crate) fn other(&mut self) {
        self.end_run();
        self.last = None;
    }

    /// A straight segment from `from` to `to`.
    pub(crate) fn line(&mut self, from: (f64, f64), to: (f64, f64)) {
        self.count.lines += 1;
        let step = step(Point::new(from.0, from.1), Point::new(to.0, to.1));
        if step.is_some() && step != self.last {
            self.run += 1;
        } else {
            self.end_run();
            if step.is_some() {
                self.run = 1;
            }
        }
        self.last = step;
    }

    /// The count, once the last run is ended.
    pub(crate) fn finish(mut self) -> StaircaseCount {
        self.end_run();
        self.count
    }
}

/// True when the closed path `M start commands Z` has a pixel staircase (as
/// [`staircases`](crate::staircases) counts them in the written path data).
pub(crate) fn has_staircase(start: Point, commands: &[PathCommand]) -> bool {
    let mut c = Counter::default();
    let xy = |p: Point| (p.x, p.y);
    let mut pen = start;
    for cmd in commands {
        match cmd {
            PathCommand::Line(p) => c.line(xy(pen), xy(*p)),
            _ => c.other(),
        }
        pen = cmd.end();
    }
    if pen != start {
        c.line(xy(pen), xy(start));
    }
    c.finish().runs > 0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fidelity::staircase::path_staircases;
    use proptest::prelude::*;

    /// A unit square drawn as three lines: its closing segment is the fourth step.
    #[test]
    fn the_closing_segment_is_a_step() {
        let p = |x: f64, y: f64| PathCommand::Line(Point::new(x, y));
        let three = [p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)];
        assert!(has_staircase(Point::ZERO, &three));
        assert_eq!(path_staircases("M0 0L1 0L1 1L0 1Z").runs, 1);
        // A curve in place of the third line breaks the run.
        let curved = [
            p(1.0, 0.0),
            p(1.0, 1.0),
            PathCommand::Quad(Point::new(0.5, 2.0), Point::new(0.0, 1.0)),
        ];
        assert!(!has_staircase(Point::ZERO, &curved));
    }

    proptest! {
        /// On a drawing, `has_staircase` says what the count of its written path data says,
        /// closing segment and curves included.
        #[test]
        fn drawing_and_written_data_agree(
            steps in prop::collection::vec((-3i32..=3, -3i32..=3, 0u8..6), 1..24),
        ) {
            let start = Point::new(10.0, 10.0);
            let mut pen = start;
            let mut commands = Vec::new();
            let mut d = String::from("M10 10");
            for &(dx, dy, kind) in &steps {
                let to = pen + kurbo::Vec2::new(f64::from(dx), f64::from(dy));
                if kind == 0 {
                    // A curve ends a run.
                    commands.push(PathCommand::Quad(pen, to));
                    d += &format!("Q{} {} {} {}", pen.x, pen.y, to.x, to.y);
                } else {
                    commands.push(PathCommand::Line(to));
                    d += &format!("L{} {}", to.x, to.y);
                }
                pen = to;
            }
            d += "Z";
            prop_assert_eq!(has_staircase(start, &commands), path_staircases(&d).runs > 0, "{}", d);
        }
    }
}

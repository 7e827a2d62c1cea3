//! The drawing of a colour partition: [`Partition`], its borders each drawn once
//! ([`PartitionBorder`], [`BorderSource`]), and each region's loops as closed paths.
//!
//! The partition itself is computed by the `vectorize` stage (`--layout partition`), which
//! cuts the borders out of the regions' outlines and checks them by rendering.

use kurbo::Point;

use super::path::ContourPath;
use crate::contour::Border;
use crate::curve::PathCommand;

/// Where a border's drawing comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BorderSource {
    /// Cut from the outline of the region on its left.
    Left,
    /// Cut from the outline of the region on its right, reversed.
    Right,
    /// Along its cracks.
    Cracks,
}

impl BorderSource {
    /// The name in the JSON: `left`, `right` or `cracks`.
    pub fn name(self) -> &'static str {
        match self {
            BorderSource::Left => "left",
            BorderSource::Right => "right",
            BorderSource::Cracks => "cracks",
        }
    }
}

/// One border of the partition and its drawing.
#[derive(Clone, Debug)]
pub struct PartitionBorder {
    /// The border's labels and cracks.
    pub border: Border,
    /// Where its drawing comes from.
    pub source: BorderSource,
    /// The drawing from its first corner (the `M` point when it starts a loop) to its last,
    /// in image coordinates, every point a multiple of `2^-grid`.
    pub commands: Vec<PathCommand>,
}

impl PartitionBorder {
    /// The first corner.
    pub fn start(&self) -> Point {
        corner(self.border.corners[0])
    }

    /// The last corner.
    pub fn end(&self) -> Point {
        corner(*self.border.corners.last().expect("a border has corners"))
    }
}

/// The borders of a partition and how each region's path uses them.
#[derive(Clone, Debug)]
pub struct Partition {
    /// The borders, each drawn once.
    pub borders: Vec<PartitionBorder>,
    /// Per palette index: the region's loops, each a list of `(border, reversed)`.
    pub loops: Vec<Vec<Vec<(usize, bool)>>>,
    /// The label of no region (the palette's length); the image's outside is one more.
    pub none: usize,
    /// Rounds of drawing and checking.
    pub rounds: usize,
}

impl Partition {
    /// The closed paths of region `k`, one per loop.
    pub fn region_paths(&self, k: usize) -> Vec<ContourPath> {
        self.loops[k]
            .iter()
            .map(|l| loop_path(&self.borders, l))
            .collect()
    }
}

/// The corner `(x, y)` as a point.
pub(crate) fn corner((x, y): (i64, i64)) -> Point {
    Point::new(x as f64, y as f64)
}

/// The path of one loop: its borders' commands in order, reversed ones backwards.
pub(crate) fn loop_path(borders: &[PartitionBorder], l: &[(usize, bool)]) -> ContourPath {
    let mut cp = ContourPath::default();
    for (i, &(b, reversed)) in l.iter().enumerate() {
        let pb = &borders[b];
        if reversed {
            if i == 0 {
                cp.start = pb.end();
            }
            cp.commands.extend(reverse(pb.start(), &pb.commands));
        } else {
            if i == 0 {
                cp.start = pb.start();
            }
            cp.commands.extend(pb.commands.iter().copied());
        }
    }
    cp
}

/// The commands from `start` drawn backwards (from their end back to `start`), with the
/// same points.
pub(crate) fn reverse(start: Point, commands: &[PathCommand]) -> Vec<PathCommand> {
    let mut out = Vec::with_capacity(commands.len());
    for (i, c) in commands.iter().enumerate().rev() {
        let to = if i == 0 { start } else { commands[i - 1].end() };
        out.push(match *c {
            PathCommand::Line(_) => PathCommand::Line(to),
            PathCommand::Quad(a, _) => PathCommand::Quad(a, to),
            PathCommand::Cubic(a, b, _) => PathCommand::Cubic(b, a, to),
            PathCommand::Arc(mut arc) => {
                std::mem::swap(&mut arc.from, &mut arc.to);
                arc.sweep = !arc.sweep;
                PathCommand::Arc(arc)
            }
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reverse_keeps_the_points() {
        let s = Point::new(0.0, 0.0);
        let c = vec![
            PathCommand::Line(Point::new(1.0, 0.0)),
            PathCommand::Cubic(
                Point::new(2.0, 0.0),
                Point::new(2.0, 1.0),
                Point::new(2.0, 2.0),
            ),
            PathCommand::Quad(Point::new(1.0, 3.0), Point::new(0.0, 2.0)),
        ];
        let r = reverse(s, &c);
        assert_eq!(
            r,
            vec![
                PathCommand::Quad(Point::new(1.0, 3.0), Point::new(2.0, 2.0)),
                PathCommand::Cubic(
                    Point::new(2.0, 1.0),
                    Point::new(2.0, 0.0),
                    Point::new(1.0, 0.0)
                ),
                PathCommand::Line(s),
            ]
        );
        assert_eq!(reverse(Point::new(0.0, 2.0), &r), c);
    }
}

//! Speck and hole removal before tracing: potrace's `turdsize` ([`Mask::clean`]).
//!
//! potrace traces every border of the bitmap into its path list and drops each path whose
//! area is at most `turdsize`, where a path's area is the number of pixels its border
//! encloses: the component or hole itself plus everything inside it. The decision for one
//! border does not depend on any other, so specks and holes are dropped simultaneously,
//! each judged on the original image. Borders nested inside a dropped border enclose fewer
//! pixels, so they are dropped too: the whole inside of a dropped border takes the value of
//! the region around it.
//!
//! Here the borders are those of [`trace`](crate::trace) in
//! [`Convention::Default`](crate::Convention::Default): 8-connected foreground components
//! and 4-connected background holes (background components that do not touch the image
//! border), outside the image being background. potrace decides the connectivity of
//! diagonal pixel pairs by its turn policy instead, so the two can differ on diagonal
//! contacts only (on the scan test case, 2089 contours against potrace's 2082 paths).

use super::index::Index;
use super::mask::Mask;

/// What [`Mask::clean`] dropped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Cleaned {
    /// The size limit that was applied: every border enclosing at most this many pixels
    /// was dropped (0: nothing was).
    pub turdsize: u64,
    /// Foreground components dropped (made background), counting those inside a dropped
    /// hole, whose pixels stay foreground: each is one border fewer to trace.
    pub components: u64,
    /// Holes dropped (filled with foreground), counting those inside a dropped component.
    pub holes: u64,
    /// Pixels whose value changed.
    pub pixels: u64,
}

impl std::fmt::Display for Cleaned {
    /// `dropped 3 components and 1 hole (17 pixels) of at most 4 px`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let plural = |n: u64, one: &'static str, many: &'static str| {
            format!("{n} {}", if n == 1 { one } else { many })
        };
        write!(
            f,
            "dropped {} and {} ({}) of at most {} px",
            plural(self.components, "component", "components"),
            plural(self.holes, "hole", "holes"),
            plural(self.pixels, "pixel", "pixels"),
            self.turdsize
        )
    }
}

/// Region flags.
const FOREGROUND: u8 = 1; // as u8::from(true)
/// A background component touching the image border: part of the outside, always kept.
const OUTSIDE: u8 = 2;
/// The region's pixels change value.
const FLIP: u8 = 4;

impl Mask {
    /// Drops every foreground component and every hole whose border encloses at most
    /// `turdsize` pixels, as potrace's `-t`/`turdsize` does; 0 changes nothing.
    ///
    /// A border's enclosed area is the number of pixels of its component or hole plus all
    /// pixels inside it (the component's holes and what they contain; the hole's islands).
    /// A dropped component becomes background, a dropped hole foreground, together with
    /// everything inside them; every other pixel keeps its value. Components are 8-connected
    /// and holes 4-connected, as [`trace`](crate::trace) sees them in
    /// [`Convention::Default`](crate::Convention::Default), so
    /// `components + holes` is exactly the number of contours that tracing finds fewer.
    ///
    /// Each border is judged on the original image, all at once (the module documentation
    /// says why); the result is cleaned already (cleaning it again drops nothing).
    ///
    /// Time is linear in the number of pixels, without recursion; memory is at most
    /// [`Mask::clean_bytes`].
    ///
    /// ```
    /// use layertrace::Mask;
    /// let mut m = Mask::from_ascii(
    ///     "
    ///     #.......
    ///     ..#####.
    ///     ..#.#.#.
    ///     ..#####.
    ///     ",
    /// );
    /// let c = m.clean(2);
    /// // The speck at the top left is dropped, the two one-pixel holes are filled.
    /// assert_eq!((c.components, c.holes, c.pixels), (1, 2, 3));
    /// assert_eq!(m.count_foreground(), 15);
    /// ```
    pub fn clean(&mut self, turdsize: u64) -> Cleaned {
        let pixels = u64::from(self.width()) * u64::from(self.height());
        if turdsize == 0 || pixels == 0 {
            return Cleaned::default();
        }
        let mut c = if pixels < u64::from(u32::MAX) {
            clean_with::<u32>(self, turdsize)
        } else {
            clean_with::<u64>(self, turdsize)
        };
        c.turdsize = turdsize;
        c
    }

    /// An upper bound of the bytes [`Mask::clean`] allocates on a `width` × `height` mask:
    /// a label per pixel, a flood-fill stack of at most one entry per pixel (twice, for the
    /// vector's growth), and three numbers per region (at most half the pixels plus a row).
    pub fn clean_bytes(width: u32, height: u32) -> u64 {
        let (w, h) = (u64::from(width), u64::from(height));
        let pixels = w * h;
        let size = if pixels < u64::from(u32::MAX) { 4 } else { 8 };
        let regions = pixels.div_ceil(2) + w + 2;
        // Vectors grow by doubling: count twice the length of those that grow.
        pixels * size + 2 * pixels * size + 2 * regions * (2 * size + 1)
    }
}

fn clean_with<L: Index>(mask: &mut Mask, turdsize: u64) -> Cleaned {
    let w = mask.width() as usize;
    let n = w * mask.height() as usize;
    // Region of every pixel; 0 while unvisited (region 0 is the outside, which has none).
    let mut labels: Vec<L> = vec![L::ZERO; n];
    // Per region: pixels enclosed by its border; parent (the region around it), later the
    // region whose value it takes; flags. Regions are numbered in raster order of their
    // first pixel, so a region's parent has a smaller number.
    let mut area: Vec<L> = vec![L::ZERO];
    let mut up: Vec<L> = vec![L::ZERO];
    let mut flags: Vec<u8> = vec![OUTSIDE];
    let mut stack: Vec<L> = Vec::new();
    for start in 0..n {
        if labels[start] != L::ZERO {
            continue;
        }
        let r = area.len();
        let value = mask.get_index(start);
        let (count, touches) = flood(mask, &mut labels, start, L::new(r), value, &mut stack);
        // The pixel above the first pixel (in raster order) of a component or hole lies
        // in the region around it: nothing of the region is above its first row, so that
        // pixel's column leads out of it without crossing it.
        let above = if start >= w {
            labels[start - w].get()
        } else {
            0
        };
        // Background touching the image border is part of the outside.
        let (parent, flag) = match (value, touches) {
            (false, true) => (0, OUTSIDE),
            _ if flags[above] & OUTSIDE != 0 => (0, u8::from(value)),
            _ => (above, u8::from(value)),
        };
        area.push(L::new(count));
        up.push(L::new(parent));
        flags.push(flag);
    }
    // Enclosed areas: children (larger numbers) first.
    for r in (1..area.len()).rev() {
        let p = up[r].get();
        area[p] = L::new(area[p].get() + area[r].get());
    }
    // Kept regions keep their value; a dropped one takes that of its nearest kept
    // ancestor (parents first: up[parent] is already that ancestor).
    let mut out = Cleaned::default();
    for r in 1..area.len() {
        if flags[r] & OUTSIDE != 0 || area[r].get() as u64 > turdsize {
            up[r] = L::new(r);
            continue;
        }
        let target = up[up[r].get()].get();
        up[r] = L::new(target);
        if flags[r] & FOREGROUND != 0 {
            out.components += 1;
        } else {
            out.holes += 1;
        }
        if (flags[target] ^ flags[r]) & FOREGROUND != 0 {
            flags[r] |= FLIP;
        }
    }
    if out.components + out.holes > 0 {
        for (i, l) in labels.iter().enumerate() {
            if flags[l.get()] & FLIP != 0 {
                mask.flip_index(i);
                out.pixels += 1;
            }
        }
    }
    out
}

/// Labels `r` the component of `start` (8-connected if `value` is foreground, 4-connected
/// otherwise); returns its pixel count and whether it touches the image border.
fn flood<L: Index>(
    mask: &Mask,
    labels: &mut [L],
    start: usize,
    r: L,
    value: bool,
    stack: &mut Vec<L>,
) -> (usize, bool) {
    let (w, h) = (mask.width() as usize, mask.height() as usize);
    let mut count = 0;
    let mut touches = false;
    labels[start] = r;
    stack.push(L::new(start));
    while let Some(j) = stack.pop() {
        let j = j.get();
        count += 1;
        let (x, y) = (j % w, j / w);
        touches |= x == 0 || y == 0 || x + 1 == w || y + 1 == h;
        for ny in y.saturating_sub(1)..=(y + 1).min(h - 1) {
            for nx in x.saturating_sub(1)..=(x + 1).min(w - 1) {
                // Background is 4-connected: no diagonal steps.
                if !value && nx != x && ny != y {
                    continue;
                }
                let q = ny * w + nx;
                if labels[q] == L::ZERO && mask.get_index(q) == value {
                    labels[q] = r;
                    stack.push(L::new(q));
                }
            }
        }
    }
    (count, touches)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bitmap::random_mask;
    use crate::contour::{trace, Convention};
    use proptest::prelude::*;
    use std::collections::VecDeque;

    /// A region of the naive model: its pixels and the pixels its border encloses.
    struct Region {
        foreground: bool,
        pixels: Vec<usize>,
        inside: Vec<bool>,
    }

    /// The components (8-connected) and holes (4-connected background not touching the
    /// border) of `m`, each with its filled set, found by breadth-first searches over the
    /// image padded with a frame of outside: the filled set is everything the outside
    /// cannot reach without crossing the region (4-steps around a component, 8-steps around
    /// a hole).
    fn regions(m: &Mask) -> Vec<Region> {
        let (w, h) = (m.width() as i64, m.height() as i64);
        let at = |x: i64, y: i64| (y * w + x) as usize;
        let steps = |eight: bool| -> Vec<(i64, i64)> {
            let mut s = vec![(1, 0), (-1, 0), (0, 1), (0, -1)];
            if eight {
                s.extend([(1, 1), (1, -1), (-1, 1), (-1, -1)]);
            }
            s
        };
        let mut seen = vec![false; (w * h) as usize];
        let mut out = Vec::new();
        for y0 in 0..h {
            for x0 in 0..w {
                if seen[at(x0, y0)] {
                    continue;
                }
                let fg = m.get(x0, y0);
                let mut pixels = vec![at(x0, y0)];
                let mut member = vec![false; (w * h) as usize];
                let mut q = VecDeque::from([(x0, y0)]);
                seen[at(x0, y0)] = true;
                member[at(x0, y0)] = true;
                let mut touches = false;
                while let Some((x, y)) = q.pop_front() {
                    touches |= x == 0 || y == 0 || x == w - 1 || y == h - 1;
                    for (dx, dy) in steps(fg) {
                        let (nx, ny) = (x + dx, y + dy);
                        if (0..w).contains(&nx)
                            && (0..h).contains(&ny)
                            && !seen[at(nx, ny)]
                            && m.get(nx, ny) == fg
                        {
                            seen[at(nx, ny)] = true;
                            member[at(nx, ny)] = true;
                            pixels.push(at(nx, ny));
                            q.push_back((nx, ny));
                        }
                    }
                }
                if !fg && touches {
                    continue; // part of the outside
                }
                // The outside's flood in the padded image, around the region.
                let (pw, ph) = (w + 2, h + 2);
                let mut out_seen = vec![false; (pw * ph) as usize];
                let mut q = VecDeque::from([(-1i64, -1i64)]);
                out_seen[0] = true;
                while let Some((x, y)) = q.pop_front() {
                    for (dx, dy) in steps(!fg) {
                        let (nx, ny) = (x + dx, y + dy);
                        if !(-1..=w).contains(&nx) || !(-1..=h).contains(&ny) {
                            continue;
                        }
                        let k = ((ny + 1) * pw + nx + 1) as usize;
                        let inside_image = (0..w).contains(&nx) && (0..h).contains(&ny);
                        if out_seen[k] || (inside_image && member[at(nx, ny)]) {
                            continue;
                        }
                        out_seen[k] = true;
                        q.push_back((nx, ny));
                    }
                }
                let inside = (0..w * h)
                    .map(|i| !out_seen[(((i / w) + 1) * pw + i % w + 1) as usize])
                    .collect();
                out.push(Region {
                    foreground: fg,
                    pixels,
                    inside,
                });
            }
        }
        out
    }

    fn area(r: &Region) -> u64 {
        r.inside.iter().filter(|&&b| b).count() as u64
    }

    /// The expected result: each pixel takes the value of the smallest kept region (filled
    /// set enclosing more than `t` pixels) whose filled set holds it, background if none.
    fn expected(m: &Mask, t: u64) -> (Mask, u64, u64) {
        let rs = regions(m);
        let w = m.width() as usize;
        let mut best: Vec<Option<(u64, bool)>> = vec![None; w * m.height() as usize];
        for r in rs.iter().filter(|r| area(r) > t) {
            let a = area(r);
            for (i, _) in r.inside.iter().enumerate().filter(|(_, &b)| b) {
                if best[i].is_none_or(|(b, _)| a < b) {
                    best[i] = Some((a, r.foreground));
                }
            }
        }
        let out = Mask::from_fn(m.width(), m.height(), |x, y| {
            best[y as usize * w + x as usize].is_some_and(|(_, fg)| fg)
        });
        let dropped = |fg: bool| {
            rs.iter()
                .filter(|r| r.foreground == fg && area(r) <= t)
                .count() as u64
        };
        (out, dropped(true), dropped(false))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// Against the naive model; the invariants of potrace's rule on the result.
        #[test]
        fn clean_matches_the_naive_model(
            w in 1u32..14,
            h in 1u32..14,
            seed in any::<u64>(),
            density in 10u64..90,
            t in 0u64..12,
        ) {
            let m = random_mask(w, h, seed, density);
            let (want, components, holes) = expected(&m, t);
            let mut got = m.clone();
            let c = got.clean(t);
            prop_assert_eq!(&got, &want, "t = {}\n{}", t, m.to_ascii());
            prop_assert_eq!((c.components, c.holes), (components, holes));
            let differing = (0..i64::from(h))
                .flat_map(|y| (0..i64::from(w)).map(move |x| (x, y)))
                .filter(|&(x, y)| got.get(x, y) != m.get(x, y))
                .count() as u64;
            prop_assert_eq!(c.pixels, differing);
            // Exactly that many borders fewer.
            let before = trace(&m, Convention::Default).len() as u64;
            let after = trace(&got, Convention::Default).len() as u64;
            prop_assert_eq!(before - after, c.components + c.holes);
            // After cleaning no border encloses t pixels or fewer; cleaning again does
            // nothing.
            prop_assert!(regions(&got).iter().all(|r| area(r) > t));
            let again = got.clone().clean(t);
            prop_assert_eq!((again.components, again.holes, again.pixels), (0, 0, 0));
            // Regions enclosing more than t pixels keep all their pixels.
            for r in regions(&m).iter().filter(|r| area(r) > t) {
                for &i in &r.pixels {
                    let (x, y) = ((i % w as usize) as i64, (i / w as usize) as i64);
                    prop_assert_eq!(got.get(x, y), r.foreground);
                }
            }
            if t == 0 {
                prop_assert_eq!(&got, &m);
                prop_assert_eq!(c, Cleaned::default());
            }
        }
    }

    #[test]
    fn enclosed_area_not_pixel_count() {
        // A diamond of 4 pixels around a 1-pixel hole encloses 5: kept at 4 (its hole is
        // filled), dropped at 5.
        let diamond = Mask::from_ascii(
            "
            .....
            ..#..
            .#.#.
            ..#..
            .....
            ",
        );
        let mut m = diamond.clone();
        let c = m.clean(4);
        assert_eq!((c.components, c.holes, c.pixels), (0, 1, 1));
        assert_eq!(m.count_foreground(), 5);
        let mut m = diamond.clone();
        let c = m.clean(5);
        assert_eq!((c.components, c.holes, c.pixels), (1, 1, 4));
        assert_eq!(m.count_foreground(), 0);
        // An island inside a small hole of a large component: the hole is filled and the
        // island dropped with it (two borders fewer; the hole's 24 pixels change).
        let mut m = Mask::from_ascii(
            "
            #######
            #.....#
            #.....#
            #..#..#
            #.....#
            #.....#
            #######
            ",
        );
        let c = m.clean(25);
        assert_eq!((c.components, c.holes, c.pixels), (1, 1, 24));
        assert_eq!(m.count_foreground(), 49);
        assert_eq!(trace(&m, Convention::Default).len(), 1);
        // Display.
        assert_eq!(
            c.to_string(),
            "dropped 1 component and 1 hole (24 pixels) of at most 25 px"
        );
    }

    #[test]
    fn border_notches_are_outside_and_bytes_bound() {
        // Background touching the image border is the outside, however small.
        let mut m = Mask::from_ascii(
            "
            ##.##
            #####
            ",
        );
        assert_eq!(
            m.clean(3),
            Cleaned {
                turdsize: 3,
                ..Cleaned::default()
            }
        );
        assert_eq!(m.count_foreground(), 9);
        // One-pixel and empty images.
        for (w, h) in [(1, 1), (0, 5), (5, 0)] {
            let mut m = Mask::from_fn(w, h, |_, _| true);
            let c = m.clean(10);
            assert_eq!(c.components, u64::from(w * h > 0));
        }
        assert!(Mask::clean_bytes(1000, 1000) >= 12_000_000);
        assert!(random_mask(64, 64, 7, 50).clean(3).components > 0);
    }
}

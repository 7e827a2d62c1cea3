//! Tests of border tracing: both conventions against an independent labelling (the
//! oracle below), on small cases, random masks and the samples.

use super::*;
use crate::bitmap::{load_path, random_mask, Compat, LoadOptions, Threshold};
use proptest::prelude::*;
use std::collections::{HashMap, HashSet};
use std::path::Path;

/// Connected-component labels of the pixels whose value is `value`, over the image
/// enlarged by `pad` pixels of background on every side (so with `pad = 1` all
/// background touching the border forms one "outside" component). Independent of the
/// code under test: a breadth-first fill. Returns labels indexed by padded coordinates
/// (`u32::MAX` for other pixels) and the number of labels.
struct Labels {
    w: i64,
    h: i64,
    pad: i64,
    label: Vec<u32>,
    count: u32,
}

impl Labels {
    fn new(mask: &Mask, value: bool, eight: bool, pad: i64) -> Labels {
        let (w, h) = (
            i64::from(mask.width()) + 2 * pad,
            i64::from(mask.height()) + 2 * pad,
        );
        let at = |x: i64, y: i64| mask.get(x - pad, y - pad);
        let mut label = vec![u32::MAX; (w * h) as usize];
        let mut count = 0;
        let mut queue = std::collections::VecDeque::new();
        for y in 0..h {
            for x in 0..w {
                if at(x, y) != value || label[(y * w + x) as usize] != u32::MAX {
                    continue;
                }
                label[(y * w + x) as usize] = count;
                queue.push_back((x, y));
                while let Some((px, py)) = queue.pop_front() {
                    for dy in -1..=1i64 {
                        for dx in -1..=1i64 {
                            if (dx, dy) == (0, 0) || (!eight && dx != 0 && dy != 0) {
                                continue;
                            }
                            let (qx, qy) = (px + dx, py + dy);
                            if qx < 0 || qy < 0 || qx >= w || qy >= h {
                                continue;
                            }
                            let i = (qy * w + qx) as usize;
                            if at(qx, qy) == value && label[i] == u32::MAX {
                                label[i] = count;
                                queue.push_back((qx, qy));
                            }
                        }
                    }
                }
                count += 1;
            }
        }
        Labels {
            w,
            h,
            pad,
            label,
            count,
        }
    }

    /// Label of image pixel `p` (padded coordinates handled here).
    fn of(&self, p: Pixel) -> Option<u32> {
        let (x, y) = (i64::from(p.x) + self.pad, i64::from(p.y) + self.pad);
        if x < 0 || y < 0 || x >= self.w || y >= self.h {
            return None;
        }
        let l = self.label[(y * self.w + x) as usize];
        (l != u32::MAX).then_some(l)
    }

    /// Whether component `l` touches the border of the (unpadded) image.
    fn touches_border(&self, l: u32, mask: &Mask) -> bool {
        let (w, h) = (mask.width() as i32, mask.height() as i32);
        (0..w).any(|x| {
            self.of(Pixel::new(x, 0)) == Some(l) || self.of(Pixel::new(x, h - 1)) == Some(l)
        }) || (0..h).any(|y| {
            self.of(Pixel::new(0, y)) == Some(l) || self.of(Pixel::new(w - 1, y)) == Some(l)
        })
    }
}

fn fg(mask: &Mask, p: Pixel) -> bool {
    mask.get(i64::from(p.x), i64::from(p.y))
}

/// Twice the signed area of the polygon through the pixel centres (positive when
/// clockwise on screen, y down).
fn area2(points: &[Pixel]) -> i64 {
    let n = points.len();
    (0..n)
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % n]);
            i64::from(a.x) * i64::from(b.y) - i64::from(b.x) * i64::from(a.y)
        })
        .sum()
}

fn first_in_raster_order(labels: &Labels, l: u32) -> Option<Pixel> {
    (0..labels.h - 2 * labels.pad)
        .flat_map(|y| (0..labels.w - 2 * labels.pad).map(move |x| Pixel::new(x as i32, y as i32)))
        .find(|&p| labels.of(p) == Some(l))
}

/// Checks every property of the Default convention; returns (outer, hole) counts.
fn check_default(mask: &Mask) -> (usize, usize) {
    let contours = trace(mask, Convention::Default);
    let comps = Labels::new(mask, true, true, 0);
    let bg = Labels::new(mask, false, false, 1); // padded: label of outside = of (-1,-1)
    let outside = bg.of(Pixel::new(-1, -1));
    let holes = (0..bg.count).filter(|&l| Some(l) != outside).count();

    let n_outer = contours.iter().filter(|c| !c.hole).count();
    let n_hole = contours.iter().filter(|c| c.hole).count();
    assert_eq!(
        n_outer, comps.count as usize,
        "outer contours vs 8-components"
    );
    assert_eq!(
        n_hole, holes,
        "hole contours vs bounded 4-connected background components"
    );

    let mut seen_comps = HashSet::new();
    let mut seen_holes = HashSet::new();
    let mut covered = HashSet::new();
    // Contours in raster order of their component's or hole's first pixel.
    let firsts: Vec<(i32, i32)> = contours
        .iter()
        .map(|c| {
            let p = c.points[0];
            let p = if c.hole { Pixel::new(p.x, p.y + 1) } else { p };
            (p.y, p.x)
        })
        .collect();
    assert!(
        firsts.windows(2).all(|w| w[0] < w[1]),
        "contours out of raster order: {firsts:?}"
    );
    for c in &contours {
        assert!(c.closed);
        let pts = &c.points;
        assert!(!pts.is_empty());
        for i in 0..pts.len() {
            let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
            if pts.len() > 1 {
                assert!(a.is_8_adjacent(b), "{a:?} -> {b:?} not 8-adjacent in {c:?}");
            }
            covered.insert(a);
        }
        let first = pts[0];
        let comp = comps.of(first).expect("contour point must be foreground");
        // The background region this border separates from the component.
        let region = if c.hole {
            let below = Pixel::new(first.x, first.y + 1);
            let h = bg
                .of(below)
                .expect("a hole border starts above a hole pixel");
            assert_ne!(Some(h), outside);
            assert!(seen_holes.insert(h), "hole traced twice");
            assert_eq!(
                first_in_raster_order(&bg, h),
                Some(below),
                "hole start rule"
            );
            h
        } else {
            assert!(seen_comps.insert(comp), "component traced twice");
            assert_eq!(
                first_in_raster_order(&comps, comp),
                Some(first),
                "outer start rule"
            );
            bg.of(Pixel::new(first.x, first.y - 1))
                .expect("above the first pixel is background")
        };
        // Points: exactly the pixels of the component with a 4-neighbour in the region.
        let got: HashSet<Pixel> = pts.iter().copied().collect();
        let mut want = HashSet::new();
        for y in 0..mask.height() as i32 {
            for x in 0..mask.width() as i32 {
                let p = Pixel::new(x, y);
                if comps.of(p) == Some(comp)
                    && p.neighbours4().iter().any(|&q| bg.of(q) == Some(region))
                {
                    want.insert(p);
                }
            }
        }
        assert_eq!(got, want, "contour {c:?}");
        // Orientation: never clockwise for outer borders, never counter-clockwise for holes.
        let a = area2(pts);
        if c.hole {
            assert!(a >= 0, "hole border must run clockwise on screen: {a}");
        } else {
            assert!(
                a <= 0,
                "outer border must run counter-clockwise on screen: {a}"
            );
        }
    }
    // Coverage: every boundary pixel is on some contour.
    for y in 0..mask.height() as i32 {
        for x in 0..mask.width() as i32 {
            let p = Pixel::new(x, y);
            let boundary = fg(mask, p) && p.neighbours4().iter().any(|&q| !fg(mask, q));
            assert_eq!(covered.contains(&p), boundary, "{p:?}");
        }
    }
    (n_outer, n_hole)
}

#[test]
fn single_pixel_and_empty() {
    assert!(trace(&Mask::new(5, 5), Convention::Default).is_empty());
    assert!(trace(&Mask::new(0, 0), Convention::Default).is_empty());
    let m = Mask::from_ascii("...\n.#.\n...");
    let c = trace(&m, Convention::Default);
    assert_eq!(c.len(), 1);
    assert_eq!(c[0].points, vec![Pixel::new(1, 1)]);
    check_default(&m);
    // A full image: one contour around the border.
    let full = Mask::from_fn(4, 3, |_, _| true);
    assert_eq!(check_default(&full), (1, 0));
    assert_eq!(trace(&full, Convention::Default)[0].points.len(), 10);
}

#[test]
fn thin_bar_goes_along_and_back() {
    let m = Mask::from_ascii(".......\n.#####.\n.......");
    let c = trace(&m, Convention::Default);
    assert_eq!(c.len(), 1);
    let pts = &c[0].points;
    // Each interior pixel is visited twice, the two ends once: 2 * 5 - 2 points.
    assert_eq!(pts.len(), 8);
    for x in 2..=4 {
        assert_eq!(pts.iter().filter(|p| p.x == x).count(), 2);
    }
    check_default(&m);
    // The start pixel is a cut vertex: the walk passes through it in the middle and
    // must not stop there.
    let m = Mask::from_ascii(".##\n#..");
    let c = trace(&m, Convention::Default);
    assert_eq!(c[0].points.len(), 4);
    assert_eq!(
        c[0].points
            .iter()
            .filter(|p| **p == Pixel::new(1, 0))
            .count(),
        2
    );
    check_default(&m);
    // Vertical bar too.
    let v = Mask::from_ascii("#\n#\n#\n#");
    assert_eq!(trace(&v, Convention::Default)[0].points.len(), 6);
}

#[test]
fn diagonal_contacts_are_one_component() {
    let m = Mask::from_ascii("#..\n.#.\n..#");
    let c = trace(&m, Convention::Default);
    assert_eq!(c.len(), 1);
    assert_eq!(c[0].points.len(), 4);
    assert_eq!(check_default(&m), (1, 0));
    // Two blocks touching at a corner.
    let m = Mask::from_ascii("##..\n##..\n..##\n..##");
    assert_eq!(check_default(&m), (1, 0));
    // A diagonal ring encloses a 4-connected hole.
    let m = Mask::from_ascii(".#.\n#.#\n.#.");
    assert_eq!(check_default(&m), (1, 1));
}

#[test]
fn holes_and_nesting() {
    let m = Mask::from_ascii(
        "
        #########
        #.......#
        #.#####.#
        #.#...#.#
        #.#.#.#.#
        #.#...#.#
        #.#####.#
        #.......#
        #########
        ",
    );
    assert_eq!(check_default(&m), (3, 2));
    let c = trace(&m, Convention::Default);
    // Raster order of first pixels: ring, its hole, inner ring, its hole, dot.
    let kinds: Vec<bool> = c.iter().map(|c| c.hole).collect();
    assert_eq!(kinds, vec![false, true, false, true, false]);
    // Thick shapes: strict orientation.
    assert!(area2(&c[0].points) < 0);
    assert!(area2(&c[1].points) > 0);
    // Two holes separated by a diagonal contact of background only.
    // Background touching only diagonally: three separate 4-connected holes.
    let m = Mask::from_ascii("#####\n#.#.#\n##.##\n#####");
    assert_eq!(check_default(&m), (1, 3));
}

#[test]
fn border_touching_shapes() {
    let m = Mask::from_ascii("##..#\n#...#\n....#\n##..#");
    assert_eq!(check_default(&m), (3, 0));
    // A bar across the image splits the background; the outside is still one region.
    let m = Mask::from_ascii("..#..\n..#..\n..#..");
    assert_eq!(check_default(&m), (1, 0));
}

#[test]
fn many_components_and_long_contours() {
    // 200 x 200 isolated pixels.
    let m = Mask::from_fn(400, 400, |x, y| x % 2 == 0 && y % 2 == 0);
    let c = trace(&m, Convention::Default);
    assert_eq!(c.len(), 40_000);
    assert!(c.iter().all(|c| c.points.len() == 1));
    // A 1-pixel line of 300 000 pixels: one contour of 2 * 300 000 - 2 points.
    let m = Mask::from_fn(300_000, 1, |_, _| true);
    let c = trace(&m, Convention::Default);
    assert_eq!(c.len(), 1);
    assert_eq!(c[0].points.len(), 599_998);
    // A large filled square and a comb with many teeth (long thin contour).
    let m = Mask::from_fn(1500, 1500, |x, y| y < 3 || x % 2 == 0);
    let c = trace(&m, Convention::Default);
    assert_eq!(c.len(), 1);
    let boundary = (0..1500i32)
        .flat_map(|y| (0..1500i32).map(move |x| Pixel::new(x, y)))
        .filter(|&p| fg(&m, p) && p.neighbours4().iter().any(|&q| !fg(&m, q)))
        .count();
    let distinct: HashSet<Pixel> = c[0].points.iter().copied().collect();
    assert_eq!(distinct.len(), boundary);
}

fn sample_counts() -> Vec<(&'static str, usize, usize)> {
    // comps/holes as listed in samples/README.md (counted by the corpus generator).
    vec![
        ("glyph_S_dejavusans_cap120", 1, 0),
        ("glyph_g_liberationserif_cap120", 1, 2),
        ("glyph_at_dejavusans_cap40", 1, 1),
        ("digits_liberationsans_cap40", 10, 6),
        ("word_Layers_dejavusans-bold_cap40", 6, 2),
        ("sil_horse_skimage", 1, 1),
        ("lineart_cat_symbola_h300", 4, 24),
        ("suits_black_dejavusans_cap120", 4, 1),
    ]
}

#[test]
fn samples_default_convention() {
    let mut cases = sample_counts();
    // Synthetic samples carry their counts in the JSON side file.
    for name in [
        "syn_tiny_blobs",
        "syn_discs_r3_to_r200",
        "syn_ellipses_rotated",
        "syn_border_touching",
        "syn_digital_circle_1px",
        "syn_fig15_ellipse_two_holes",
        "syn_polygons_sharp",
    ] {
        let text = std::fs::read_to_string(format!("samples/{name}.json")).unwrap();
        let json: serde_json::Value = serde_json::from_str(&text).unwrap();
        let m = &json["measured"];
        let comps = m["components_8conn"].as_u64().unwrap() as usize;
        let holes = m["holes_4conn"].as_u64().unwrap() as usize;
        cases.push((name, comps, holes));
    }
    for (name, comps, holes) in cases {
        let path = format!("samples/{name}.png");
        let l = load_path(Path::new(&path), &LoadOptions::default()).unwrap();
        let (o, h) = check_default(&l.mask);
        assert_eq!((o, h), (comps, holes), "{name}");
        // Thick shapes: every outer border strictly counter-clockwise, holes clockwise.
        if name.starts_with("syn_discs") || name.starts_with("syn_fig15") {
            for c in trace(&l.mask, Convention::Default) {
                let a = area2(&c.points);
                assert!(if c.hole { a > 0 } else { a < 0 }, "{name}");
            }
        }
    }
}

/// Random small masks: noise, or a union of rectangles and discs.
fn arb_mask() -> impl Strategy<Value = Mask> {
    let noise = (1u32..=24, 1u32..=24, 0u64..=100, any::<u64>())
        .prop_map(|(w, h, density, seed)| random_mask(w, h, seed, density));
    let blobs = (
        1u32..=24,
        1u32..=24,
        proptest::collection::vec(
            (0i32..24, 0i32..24, 0i32..8, any::<bool>(), any::<bool>()),
            1..8,
        ),
    )
        .prop_map(|(w, h, shapes)| {
            Mask::from_fn(w, h, |x, y| {
                let (x, y) = (x as i32, y as i32);
                let mut v = false;
                for &(cx, cy, r, disc, erase) in &shapes {
                    let inside = if disc {
                        (x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r
                    } else {
                        (x - cx).abs() <= r && (y - cy).abs() <= r / 2 + 1
                    };
                    if inside {
                        v = !erase;
                    }
                }
                v
            })
        });
    prop_oneof![noise, blobs]
}

/// Random masks wider than a word of the mask's bits (runs across words and rows that
/// start inside a word): noise of any density, or a few bars.
fn arb_wide_mask() -> impl Strategy<Value = Mask> {
    (
        60u32..=200,
        1u32..=12,
        0u32..=100,
        any::<u64>(),
        any::<bool>(),
    )
        .prop_map(|(w, h, density, seed, bars)| {
            let mut s = seed | 1;
            Mask::from_fn(w, h, |x, y| {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                if bars {
                    // Runs of length ~density crossing words, shifted row by row.
                    (x + 7 * y + (seed % 64) as u32) % (density + 2) < (density + 2) / 2
                } else {
                    (s % 100) < u64::from(density)
                }
            })
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]
    #[test]
    fn default_invariants(mask in arb_mask()) {
        check_default(&mask);
    }

    #[test]
    fn default_invariants_wide(mask in arb_wide_mask()) {
        check_default(&mask);
    }

    #[test]
    fn ipol_invariants(mask in arb_mask()) {
        check_ipol(&mask);
    }
}

// ---------------------------------------------------------------- IPOL convention

/// Checks the IPOL convention's properties; returns the number of contours.
fn check_ipol(mask: &Mask) -> usize {
    let contours = trace(mask, Convention::Ipol);
    let (w, h) = (mask.width() as i32, mask.height() as i32);
    let inside = |p: Pixel| p.x >= 0 && p.y >= 0 && p.x < w && p.y < h;
    let ink = Labels::new(mask, true, false, 0); // 4-connected ink
    let paper = Labels::new(mask, false, true, 0); // 8-connected paper
    let mut covered = HashSet::new();
    let mut outer_of: HashMap<u32, usize> = HashMap::new();
    let mut hole_of: HashMap<u32, usize> = HashMap::new();
    for c in &contours {
        let pts = &c.points;
        assert!(!pts.is_empty());
        for win in pts.windows(2) {
            assert!(win[0].is_8_adjacent(win[1]), "{:?} -> {:?}", win[0], win[1]);
        }
        for &p in pts {
            assert!(fg(mask, p));
            assert!(
                p.neighbours4().iter().any(|&q| inside(q) && !fg(mask, q)),
                "{p:?} has no paper 4-neighbour"
            );
            covered.insert(p);
        }
        if !c.closed {
            assert!(!c.hole);
            // Open chains end on the image border at both ends.
            for p in [pts[0], pts[pts.len() - 1]] {
                assert!(
                    p.x == 0 || p.y == 0 || p.x == w - 1 || p.y == h - 1,
                    "{p:?}"
                );
            }
            continue;
        }
        assert_eq!(
            pts.first(),
            pts.last(),
            "closed contours repeat their start"
        );
        let a = area2(pts);
        let first = pts[0];
        if c.hole {
            assert!(a <= 0, "holes run anticlockwise on screen");
            // The hole: the bounded paper component P such that the contour's points are
            // exactly the pixels of the start pixel's ink component C with a 4-neighbour
            // in P (the border between a 4-connected C and an 8-connected P is one cycle;
            // ink islands inside the hole are other components).
            let got: HashSet<Pixel> = pts.iter().copied().collect();
            let comp = ink.of(first);
            let border_of = |l: u32| -> HashSet<Pixel> {
                (0..w)
                    .flat_map(|x| (0..h).map(move |y| Pixel::new(x, y)))
                    .filter(|&p| {
                        ink.of(p) == comp && p.neighbours4().iter().any(|&q| paper.of(q) == Some(l))
                    })
                    .collect()
            };
            let l = pts
                .iter()
                .flat_map(|p| p.neighbours4())
                .filter_map(|q| paper.of(q))
                .find(|&l| !paper.touches_border(l, mask) && border_of(l) == got)
                .expect("a hole contour is the ink border of one hole");
            assert!(hole_of.insert(l, 1).is_none(), "hole traced twice");
            // Start rule: the ink pixel left of the topmost pixel of the hole's leftmost
            // column (unless that column is 1, whose left cracks the reference does not
            // scan).
            let leftmost_top = (0..w)
                .flat_map(|x| (0..h).map(move |y| Pixel::new(x, y)))
                .find(|&p| paper.of(p) == Some(l))
                .unwrap();
            if leftmost_top.x >= 2 {
                assert_eq!(
                    first,
                    Pixel::new(leftmost_top.x - 1, leftmost_top.y),
                    "hole start rule"
                );
            }
        } else {
            assert!(a >= 0, "outer contours run clockwise on screen");
            let l = ink.of(first).unwrap();
            assert!(!ink.touches_border(l, mask));
            let leftmost_top = (0..w)
                .flat_map(|x| (0..h).map(move |y| Pixel::new(x, y)))
                .find(|&p| ink.of(p) == Some(l));
            if leftmost_top.is_some_and(|p| p.x >= 2) {
                assert_eq!(leftmost_top, Some(first), "outer start rule");
            }
            assert!(outer_of.insert(l, 1).is_none(), "component traced twice");
        }
    }
    let closed_outer = (0..ink.count)
        .filter(|&l| !ink.touches_border(l, mask))
        .count();
    let holes = (0..paper.count)
        .filter(|&l| !paper.touches_border(l, mask))
        .count();
    assert_eq!(
        outer_of.len(),
        closed_outer,
        "closed outer contours vs inner 4-components"
    );
    assert_eq!(
        contours.iter().filter(|c| c.closed && !c.hole).count(),
        closed_outer
    );
    assert_eq!(
        hole_of.len(),
        holes,
        "hole contours vs bounded 8-connected paper"
    );
    assert_eq!(contours.iter().filter(|c| c.hole).count(), holes);
    for y in 0..h {
        for x in 0..w {
            let p = Pixel::new(x, y);
            let border = fg(mask, p) && p.neighbours4().iter().any(|&q| inside(q) && !fg(mask, q));
            assert_eq!(covered.contains(&p), border, "{p:?}");
        }
    }
    contours.len()
}

#[test]
fn ipol_small_cases() {
    // Two blocks touching at a corner: two contours (ink is 4-connected).
    let m = Mask::from_ascii("......\n.##...\n.##...\n...##.\n...##.\n......");
    assert_eq!(check_ipol(&m), 2);
    // A ring with a one-pixel hole, two pixels from the image border.
    let m = Mask::from_ascii("......\n......\n..###.\n..#.#.\n..###.\n......");
    let c = trace(&m, Convention::Ipol);
    assert_eq!(c.len(), 2);
    assert!(!c[0].hole && c[1].hole);
    assert_eq!(c[0].points.first(), Some(&Pixel::new(2, 2)));
    assert_eq!(c[1].points.first(), Some(&Pixel::new(2, 3)));
    // Clockwise: from the top-left pixel the outer contour goes right.
    assert_eq!(c[0].points[1], Pixel::new(3, 2));
    // Anticlockwise around the hole: from its left, go down.
    assert_eq!(c[1].points[1], Pixel::new(3, 4));
    assert_eq!(c[1].points.len(), 5);
    check_ipol(&m);
    // Paper touching diagonally is one (8-connected) hole; ink touching diagonally is two
    // components.
    let m = Mask::from_ascii(".......\n..####.\n..#.#..\n..##.#.\n..####.\n.......");
    check_ipol(&m);
    // In the reference's scan, cracks next to column 0 are not scanned: a hole in column 1
    // is then found before the outer contour around it.
    let m = Mask::from_ascii(".....\n.###.\n.#.#.\n.###.\n.....");
    let c = trace(&m, Convention::Ipol);
    assert_eq!(
        c.iter().map(|c| c.hole).collect::<Vec<_>>(),
        vec![true, false]
    );
    check_ipol(&m);
    // Border-touching shapes give open chains.
    let m = Mask::from_ascii("##...\n##...\n.....\n..###");
    let c = trace(&m, Convention::Ipol);
    assert_eq!(c.len(), 2);
    assert!(c.iter().all(|c| !c.closed && !c.hole));
    check_ipol(&m);
    // Single ink pixel.
    let m = Mask::from_ascii("...\n.#.\n...");
    assert_eq!(
        trace(&m, Convention::Ipol)[0].points,
        vec![Pixel::new(1, 1)]
    );
    assert!(trace(&Mask::new(1, 1), Convention::Ipol).is_empty());
    assert!(trace(&Mask::from_fn(3, 3, |_, _| true), Convention::Ipol).is_empty());
}

#[test]
fn ipol_invariants_on_samples() {
    for e in std::fs::read_dir("samples").unwrap() {
        let path = e.unwrap().path();
        if path.extension().is_some_and(|x| x == "png") {
            let l = load_path(&path, &LoadOptions::default()).unwrap();
            check_ipol(&l.mask);
            let open = trace(&l.mask, Convention::Ipol)
                .iter()
                .filter(|c| !c.closed)
                .count();
            // Only syn_border_touching has shapes cut by the image border (three).
            let expected = if path.ends_with("syn_border_touching.png") {
                3
            } else {
                0
            };
            assert_eq!(open, expected, "{}", path.display());
        }
    }
}

const IPOL: [(&str, usize); 10] = [
    ("card_suits", 4),
    ("ipol", 5),
    ("ET_head", 3),
    ("ninja_star", 1),
    ("heptagon", 1),
    ("punk_fish", 1),
    ("pif", 1),
    ("imageS", 3),
    ("disc", 1),
    ("triangle", 1),
];

fn ipol_options() -> LoadOptions {
    LoadOptions {
        threshold: Threshold::Otsu,
        compat: Compat::Ipol,
        ..LoadOptions::default()
    }
}

#[test]
fn ipol_reference_contour_counts() {
    for (name, count) in IPOL {
        let l = load_path(
            Path::new(&format!("samples/ipol/{name}.png")),
            &ipol_options(),
        )
        .unwrap();
        assert_eq!(check_ipol(&l.mask), count, "{name}");
    }
}

#[test]
fn ipol_starts_and_directions_match_reference_outputs() {
    // The reference colours each contour's first segment yellow and the following ones
    // green, blue, red, green, blue, red, ... (measured on these outputs: yellow is never
    // used again), so walking in the reference's direction colours only change along
    // yellow -> green -> blue -> red -> green. The start pixel of a closed contour
    // is repeated at the end and painted over by the last segment, so it is skipped.
    const CYCLE: [[u8; 3]; 4] = [[255, 255, 0], [0, 255, 0], [0, 0, 255], [255, 0, 0]];
    for (name, _) in IPOL {
        let l = load_path(
            Path::new(&format!("samples/ipol/{name}.png")),
            &ipol_options(),
        )
        .unwrap();
        let out = image::open(format!(
            "samples/ipol/reference_out/StraightLine_out_{name}.png"
        ))
        .unwrap()
        .to_rgb8();
        assert_eq!(out.dimensions(), (l.mask.width(), l.mask.height()));
        let colour = |p: Pixel| out.get_pixel(p.x as u32, p.y as u32).0;
        let index = |p: Pixel| CYCLE.iter().position(|&c| c == colour(p));
        for c in trace(&l.mask, Convention::Ipol) {
            let walk = if c.closed {
                &c.points[1..c.points.len() - 1]
            } else {
                &c.points[..]
            };
            assert_eq!(
                index(walk[0]),
                Some(0),
                "{name}: contour {:?} starts yellow",
                c.points[0]
            );
            for win in walk.windows(2) {
                let (a, b) = (index(win[0]).unwrap(), index(win[1]).unwrap());
                let next = if a == 3 { 1 } else { a + 1 };
                assert!(
                    b == a || b == next,
                    "{name}: {:?} -> {:?} goes backwards",
                    win[0],
                    win[1]
                );
            }
        }
        // All drawn pixels of the reference are our contour pixels (and vice versa).
        let drawn = out.pixels().filter(|p| p.0 != [255, 255, 255]).count();
        let ours: HashSet<Pixel> = trace(&l.mask, Convention::Ipol)
            .into_iter()
            .flat_map(|c| c.points)
            .collect();
        assert_eq!(drawn, ours.len(), "{name}");
        assert!(ours.iter().all(|&p| colour(p) != [255, 255, 255]), "{name}");
    }
}

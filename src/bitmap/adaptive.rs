//! Adaptive (local) threshold for scans and photographs of pages: Sauvola's rule over a
//! square window, so that a lighting gradient or a shadow does not become foreground.
//!
//! A pixel of grey level `g` is foreground iff `g < m (1 + k (s / 128 - 1))`, where `m` and
//! `s` are the mean and the standard deviation of the grey levels in the window of
//! `(2 radius + 1)²` pixels centred on it, cut by the image border (J. Sauvola,
//! M. Pietikäinen, *Adaptive document image binarization*, Pattern Recognition 33, 2000).
//! On plain paper `s` is small and the threshold about `(1 - k) m`, below the paper however
//! dark it is lit, so a white page, a gradient or a soft shadow stays background; near ink
//! `s` is large and the threshold rises towards the mean, so letters are foreground even in
//! a shadow. A shadow with a sharp edge can still leave a band of foreground along that
//! edge, up to `radius` pixels wide, where the window sees both sides.
//!
//! The window sums are those of a summed-area table, exact in `u64`, computed over a band
//! of rows that slides down the image: a running sum of each column over the window's rows
//! (one row added, one removed per step), then a prefix sum along the row. Time is
//! `O(pixels)` whatever the radius, memory four `u64` per column instead of two tables of
//! the whole image. (imageproc has Sauvola's rule, but brings in a large dependency tree
//! for one function.)

use super::mask::Mask;

/// Bytes that [`sauvola`] allocates for an image `width` pixels wide.
pub(super) fn bytes(width: u32) -> u64 {
    4 * 8 * (u64::from(width) + 1)
}

/// Sauvola's threshold from the window's sum `s`, sum of squares `q` and pixel count `n`.
#[inline]
fn threshold(s: u64, q: u64, n: u64, k: f64) -> f64 {
    let n = n.max(1);
    let mean = s as f64 / n as f64;
    // n² var = n q - s², exact (non-negative by Cauchy-Schwarz).
    let nvar = (u128::from(n) * u128::from(q)).saturating_sub(u128::from(s) * u128::from(s));
    let sd = (nvar as f64).sqrt() / n as f64;
    mean * (1.0 + k * (sd / 128.0 - 1.0))
}

/// Sets in `mask` (all background, `width` × `height`) the pixels of `grey` (row-major)
/// that are foreground by Sauvola's rule with window radius `radius` and `k` in hundredths;
/// with `invert`, the rule is applied to `255 - grey` (light ink on dark paper). Returns the
/// mean of the per-pixel thresholds, rounded, on `grey`'s levels (so `255 -` the mean on
/// the inverted levels with `invert`).
pub(super) fn sauvola(
    grey: &[u8],
    width: u32,
    height: u32,
    radius: u32,
    k: u8,
    invert: bool,
    mask: &mut Mask,
) -> u8 {
    let (w, h) = (width as usize, height as usize);
    if w == 0 || h == 0 {
        return 0;
    }
    let r = radius as usize;
    let k = f64::from(k) / 100.0;
    let level = |i: usize| {
        let g = grey.get(i).copied().unwrap_or(255);
        u64::from(if invert { 255 - g } else { g })
    };
    // Sums over the window's rows, per column.
    let mut col = vec![0u64; w];
    let mut col2 = vec![0u64; w];
    let add_row = |col: &mut [u64], col2: &mut [u64], y: usize, add: bool| {
        for x in 0..w {
            let g = level(y * w + x);
            if add {
                col[x] += g;
                col2[x] += g * g;
            } else {
                col[x] -= g;
                col2[x] -= g * g;
            }
        }
    };
    for y in 0..=r.min(h - 1) {
        add_row(&mut col, &mut col2, y, true);
    }
    // Prefix sums along the row: pre[x] = sum of col[..x].
    let mut pre = vec![0u64; w + 1];
    let mut pre2 = vec![0u64; w + 1];
    let mut total = 0.0f64;
    for y in 0..h {
        for x in 0..w {
            pre[x + 1] = pre[x] + col[x];
            pre2[x + 1] = pre2[x] + col2[x];
        }
        let rows = ((y + r).min(h - 1) - y.saturating_sub(r) + 1) as u64;
        for x in 0..w {
            let (x0, x1) = (x.saturating_sub(r), (x + r).min(w - 1));
            let n = rows * (x1 - x0 + 1) as u64;
            let t = threshold(pre[x1 + 1] - pre[x0], pre2[x1 + 1] - pre2[x0], n, k);
            total += t;
            let i = y * w + x;
            if (level(i) as f64) < t {
                mask.set_index(i);
            }
        }
        // Slide the band of rows down by one.
        if y + r + 1 < h {
            add_row(&mut col, &mut col2, y + r + 1, true);
        }
        if y >= r {
            add_row(&mut col, &mut col2, y - r, false);
        }
    }
    let mean = (total / (w * h) as f64).round().clamp(0.0, 255.0) as u8;
    if invert {
        255 - mean
    } else {
        mean
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn run(grey: &[u8], w: u32, h: u32, radius: u32, k: u8, invert: bool) -> (Mask, u8) {
        let mut m = Mask::new(w, h);
        let t = sauvola(grey, w, h, radius, k, invert, &mut m);
        (m, t)
    }

    /// The same rule with every window summed pixel by pixel.
    fn naive(grey: &[u8], w: u32, h: u32, radius: u32, k: u8) -> Mask {
        let (w, h, r) = (w as i64, h as i64, i64::from(radius));
        Mask::from_fn(w as u32, h as u32, |x, y| {
            let (x, y) = (i64::from(x), i64::from(y));
            let (mut s, mut q, mut n) = (0u64, 0u64, 0u64);
            for yy in (y - r).max(0)..=(y + r).min(h - 1) {
                for xx in (x - r).max(0)..=(x + r).min(w - 1) {
                    let g = u64::from(grey[(yy * w + xx) as usize]);
                    s += g;
                    q += g * g;
                    n += 1;
                }
            }
            f64::from(grey[(y * w + x) as usize]) < threshold(s, q, n, f64::from(k) / 100.0)
        })
    }

    proptest! {
        /// The sliding sums are the window's sums: same mask as summing every window.
        #[test]
        fn sliding_sums_match_naive(
            w in 1u32..20,
            h in 1u32..20,
            radius in 0u32..12,
            k in 0u8..=100,
            grey in proptest::collection::vec(any::<u8>(), 400),
        ) {
            let grey = &grey[..(w * h) as usize];
            let (m, _) = run(grey, w, h, radius, k, false);
            prop_assert_eq!(m, naive(grey, w, h, radius, k));
            // invert is the rule on 255 - grey.
            let neg: Vec<u8> = grey.iter().map(|g| 255 - g).collect();
            let (a, ta) = run(grey, w, h, radius, k, true);
            let (b, tb) = run(&neg, w, h, radius, k, false);
            prop_assert_eq!(a, b);
            prop_assert_eq!(ta, 255 - tb);
        }

        /// Paper lit by a gradient that keeps it at 40 or more (a deep shadow), plus mild
        /// noise, stays empty, as long as the paper darkens by less than `k m` (8 levels
        /// here) over half a window: at the image border the window is one-sided, and there
        /// the pixel is darker than its window's mean by the slope times half the window.
        /// (Near black, a step of one level is a large relative contrast, and Sauvola's rule
        /// sees ink.)
        #[test]
        fn plain_paper_stays_empty(
            base in 40u8..=255,
            slope in 0u32..6,
            noise in 0u64..4,
            seed in any::<u64>(),
            radius in 1u32..20,
        ) {
            let (w, h) = (60u32, 40u32);
            // Levels per 4 pixels; at most 6 levels of drop plus noise over `radius` pixels.
            let slope = slope
                .min((u32::from(base) - 40) / 15)
                .min((6 - noise as u32) * 4 / radius);
            let mut s = seed | 1;
            let grey: Vec<u8> = (0..w * h)
                .map(|i| {
                    s ^= s << 13;
                    s ^= s >> 7;
                    s ^= s << 17;
                    let jitter = (s % (2 * noise + 1)) as i64 - noise as i64;
                    let g = i64::from(base) - i64::from(slope) * i64::from(i % w) / 4 + jitter;
                    g.clamp(0, 255) as u8
                })
                .collect();
            let (m, _) = run(&grey, w, h, radius, 20, false);
            prop_assert_eq!(m.count_foreground(), 0);
        }
    }

    #[test]
    fn text_found_in_light_and_in_shadow() {
        // Paper 230 lit from 1.0 down to 0.35 (a shadow) along x; vertical strokes 3 px
        // wide every 16 px with reflectance 0.1 of the paper's.
        let (w, h) = (256u32, 40u32);
        let stroke = |x: u32| x % 16 < 3;
        let light = |x: u32| 0.35 + 0.65 * f64::from(x) / f64::from(w);
        let grey: Vec<u8> = (0..w * h)
            .map(|i| {
                let x = i % w;
                let r = if stroke(x) { 0.1 } else { 0.9 };
                (255.0 * r * light(x)).round() as u8
            })
            .collect();
        let (m, t) = run(&grey, w, h, 15, 20, false);
        let want = Mask::from_fn(w, h, |x, _| stroke(x));
        assert_eq!(m, want);
        assert!(t > 0 && t < 230, "{t}");
        // With a fixed threshold the shadowed paper would be ink.
        assert!(grey.iter().filter(|&&g| g < 128).count() as u64 > want.count_foreground());
    }
}

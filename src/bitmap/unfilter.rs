//! PNG rows unfiltered (the five filter types of the PNG specification, section 7.3), with
//! flat stretches done a chunk at a time.
//!
//! Each byte `x` of a row is stored as `x − predictor(a, b, c)`, where `a` is the byte one
//! pixel to the left, `b` the byte above and `c` the byte above `a` (0 outside the image):
//!
//! ```text
//! 0 None   predictor 0
//! 1 Sub    predictor a
//! 2 Up     predictor b
//! 3 Avg    predictor ⌊(a + b) / 2⌋
//! 4 Paeth  predictor the one of a, b, c nearest to a + b − c (ties: a, then b)
//! ```
//!
//! Sub, Avg and Paeth chain each byte to the one before it, one byte at a time. But where a
//! stretch of residues is 0 and the row above repeats the last pixel (`a = b` throughout),
//! every predictor is `a` and the stretch repeats the last pixel: bilevel and flat images
//! (logos, scans, maps) are mostly such stretches, and they are checked and filled a chunk of
//! some 16 bytes at a time.

/// Unfilters `cur` (a row of filtered bytes, its filter-type byte left out) in place, with
/// `prev` the row above already unfiltered (zeros for the first row) and `bpp` bytes per
/// pixel (1, 2, 3, 4, 6 or 8). Returns `None` for an unknown filter type or pixel size, or
/// rows of different lengths or not of whole pixels.
pub(super) fn unfilter(filter: u8, bpp: usize, prev: &[u8], cur: &mut [u8]) -> Option<()> {
    if prev.len() != cur.len() || bpp == 0 || !cur.len().is_multiple_of(bpp) {
        return None;
    }
    match bpp {
        1 => unfilter_bpp::<1>(filter, prev, cur),
        2 => unfilter_bpp::<2>(filter, prev, cur),
        3 => unfilter_bpp::<3>(filter, prev, cur),
        4 => unfilter_bpp::<4>(filter, prev, cur),
        6 => unfilter_bpp::<6>(filter, prev, cur),
        8 => unfilter_bpp::<8>(filter, prev, cur),
        _ => None,
    }
}

/// [`unfilter`] for `BPP` bytes per pixel.
fn unfilter_bpp<const BPP: usize>(filter: u8, prev: &[u8], cur: &mut [u8]) -> Option<()> {
    match filter {
        0 => {}
        1 => chained::<BPP, SUB>(prev, cur),
        2 => {
            // (16 bytes at a time: the plain loop was left unvectorized, 3 instructions a
            // byte.)
            let (xs, x_rest) = cur.as_chunks_mut::<16>();
            let (bs, b_rest) = prev.as_chunks::<16>();
            for (x, b) in xs.iter_mut().zip(bs) {
                for k in 0..16 {
                    x[k] = x[k].wrapping_add(b[k]);
                }
            }
            for (x, &b) in x_rest.iter_mut().zip(b_rest) {
                *x = x.wrapping_add(b);
            }
        }
        3 => chained::<BPP, AVG>(prev, cur),
        4 => chained::<BPP, PAETH>(prev, cur),
        _ => return None,
    }
    Some(())
}

const SUB: u8 = 1;
const AVG: u8 = 3;
const PAETH: u8 = 4;

/// The predictor of filter `F` (Sub, Avg or Paeth).
#[inline(always)]
fn predict<const F: u8>(a: u8, b: u8, c: u8) -> u8 {
    match F {
        SUB => a,
        AVG => ((u16::from(a) + u16::from(b)) / 2) as u8,
        // Paeth, in stb_image's branch-free form (the png crate's on x86-64): with
        // `t = 3c − a − b`, the nearest is `max(a, b)` when `t ≤ min(a, b)`, else `min(a, b)`
        // when `max(a, b) ≤ t`, else `c`.
        _ => {
            let (a, b, c) = (i16::from(a), i16::from(b), i16::from(c));
            let t = 3 * c - (a + b);
            let (lo, hi) = (a.min(b), a.max(b));
            let t0 = if hi <= t { lo } else { c };
            (if t <= lo { hi } else { t0 }) as u8
        }
    }
}

/// Whether every byte of `bytes` is 0.
#[inline(always)]
fn all_zero(bytes: &[u8]) -> bool {
    bytes.iter().fold(0, |acc, &v| acc | v) == 0
}

/// Whether `bytes` repeats the pixel `px` (`bytes.len()` a multiple of `BPP`).
#[inline(always)]
fn repeats<const BPP: usize>(bytes: &[u8], px: &[u8; BPP]) -> bool {
    bytes.chunks_exact(BPP).fold(0, |acc, q| {
        (0..BPP).fold(acc, |acc, k| acc | (q[k] ^ px[k]))
    }) == 0
}

/// Sub, Avg or Paeth (`F`) with `BPP` bytes per pixel, flat chunks filled at once (see the
/// module documentation). Sub needs only the residues to be 0; Avg and Paeth also the row
/// above to repeat the last pixel over the chunk. (Paeth's `c` does not matter: where
/// `a = b`, `p − a = p − b = a − c` and `|p − c| = 2 |a − c|`, so the predictor is `a`.)
/// Elsewhere a pixel at a time, `a` and `c` held as the png crate holds them, until a pixel
/// that may start a flat chunk.
fn chained<const BPP: usize, const F: u8>(prev: &[u8], cur: &mut [u8]) {
    // Whole pixels, about 16 bytes.
    let chunk = BPP * (16 / BPP).max(1);
    let n = cur.len();
    // The pixels left of the current one and above that (0 left of the row).
    let (mut a, mut c) = ([0u8; BPP], [0u8; BPP]);
    let mut i = 0;
    while i < n {
        if i + chunk <= n
            && all_zero(&cur[i..i + chunk])
            && (F == SUB || repeats(&prev[i..i + chunk], &a))
        {
            for x in cur[i..i + chunk].chunks_exact_mut(BPP) {
                x.copy_from_slice(&a);
            }
            i += chunk;
            c.copy_from_slice(&prev[i - BPP..i]);
            continue;
        }
        loop {
            let (x, b) = (&mut cur[i..i + BPP], &prev[i..i + BPP]);
            for k in 0..BPP {
                x[k] = x[k].wrapping_add(predict::<F>(a[k], b[k], c[k]));
            }
            a.copy_from_slice(x);
            c.copy_from_slice(b);
            i += BPP;
            // A flat chunk may start at a pixel that repeats `a`.
            if i >= n || (all_zero(&cur[i..i + BPP]) && (F == SUB || prev[i..i + BPP] == a)) {
                break;
            }
        }
    }
}

/// The specification's filters, byte by byte: what the tests compare with (and the test
/// PNG writer filters with).
#[cfg(test)]
pub(super) mod spec {
    /// The specification's predictor of filter `filter`.
    fn predictor(filter: u8, a: u8, b: u8, c: u8) -> u8 {
        match filter {
            0 => 0,
            1 => a,
            2 => b,
            3 => ((u16::from(a) + u16::from(b)) / 2) as u8,
            _ => {
                let p = i16::from(a) + i16::from(b) - i16::from(c);
                let (pa, pb, pc) = (
                    (p - i16::from(a)).abs(),
                    (p - i16::from(b)).abs(),
                    (p - i16::from(c)).abs(),
                );
                if pa <= pb && pa <= pc {
                    a
                } else if pb <= pc {
                    b
                } else {
                    c
                }
            }
        }
    }

    /// The specification's unfiltering, byte by byte.
    pub(in crate::bitmap) fn plain(filter: u8, bpp: usize, prev: &[u8], cur: &mut [u8]) {
        for i in 0..cur.len() {
            let (a, c) = if i >= bpp {
                (cur[i - bpp], prev[i - bpp])
            } else {
                (0, 0)
            };
            cur[i] = cur[i].wrapping_add(predictor(filter, a, prev[i], c));
        }
    }

    /// `line` filtered against `above` as an encoder does.
    pub(in crate::bitmap) fn filtered(
        filter: u8,
        bpp: usize,
        above: &[u8],
        line: &[u8],
    ) -> Vec<u8> {
        (0..line.len())
            .map(|i| {
                let (a, c) = if i >= bpp {
                    (line[i - bpp], above[i - bpp])
                } else {
                    (0, 0)
                };
                line[i].wrapping_sub(predictor(filter, a, above[i], c))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::spec::{filtered, plain};
    use super::*;
    use proptest::prelude::*;

    /// Bytes mostly from a few values and zeros, in runs, so that flat chunks occur and end
    /// anywhere.
    fn bytes(len: usize) -> impl Strategy<Value = Vec<u8>> {
        prop::collection::vec((0u8..4, 1usize..40), 0..12).prop_map(move |runs| {
            let mut v: Vec<u8> = runs
                .iter()
                .flat_map(|&(k, r)| std::iter::repeat_n([0, 0, 255, 7][usize::from(k)], r))
                .collect();
            v.resize(len, 0);
            v
        })
    }

    /// A filter, a pixel size, the row above and the filtered row.
    fn case() -> impl Strategy<Value = (u8, usize, Vec<u8>, Vec<u8>)> {
        (
            0u8..5,
            prop::sample::select(vec![1usize, 2, 3, 4, 6, 8]),
            0usize..60,
            any::<bool>(),
        )
            .prop_flat_map(|(filter, bpp, pixels, prev_flat)| {
                let len = pixels * bpp;
                let prev = if prev_flat {
                    Just(vec![7u8; len]).boxed()
                } else {
                    bytes(len).boxed()
                };
                (Just(filter), Just(bpp), prev, bytes(len))
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]

        #[test]
        fn unfiltering_is_the_specifications((filter, bpp, prev, filtered) in case()) {
            let mut want = filtered.clone();
            plain(filter, bpp, &prev, &mut want);
            let mut got = filtered;
            prop_assert!(unfilter(filter, bpp, &prev, &mut got).is_some());
            prop_assert_eq!(got, want);
        }

        #[test]
        fn encoded_rows_come_back((filter, bpp, prev, line) in case()) {
            // Rows of runs, filtered as encoders do: flat stretches store zeros.
            let mut got = filtered(filter, bpp, &prev, &line);
            prop_assert!(unfilter(filter, bpp, &prev, &mut got).is_some());
            prop_assert_eq!(got, line);
        }
    }

    #[test]
    fn unknown_filters_and_pixel_sizes_are_refused() {
        let mut row = [1u8, 2, 3, 4];
        assert!(unfilter(5, 1, &[0; 4], &mut row).is_none());
        assert!(unfilter(1, 5, &[0; 4], &mut row).is_none());
        assert!(unfilter(1, 3, &[0; 4], &mut row).is_none());
        assert!(unfilter(1, 1, &[0; 3], &mut row).is_none());
    }

    #[test]
    fn flat_rows_repeat_their_first_pixel() {
        // A grey row of 200 on a row of 200: every filter stores 0 after the first pixel.
        for filter in [1u8, 3, 4] {
            let prev = vec![200u8; 100];
            let mut cur = vec![0u8; 100];
            cur[0] = match filter {
                1 => 200,
                3 => 100,
                _ => 0,
            };
            unfilter(filter, 1, &prev, &mut cur).unwrap();
            assert!(cur.iter().all(|&v| v == 200), "filter {filter}: {cur:?}");
        }
    }
}

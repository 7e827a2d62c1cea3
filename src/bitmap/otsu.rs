//! Choosing the grey level threshold: a fixed value, Otsu's method, or a local threshold
//! ([`super::adaptive`]).

use num_bigint::BigUint;

/// How the grey level threshold is chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Threshold {
    /// Foreground iff grey < the given value (so `Fixed(0)` gives no foreground).
    Fixed(u8),
    /// Otsu's method: `t` is the first grey level in `0..=254` maximising the
    /// between-class variance of the two classes `grey <= t` and `grey > t`, and the
    /// foreground is `grey <= t` (reported as threshold `t + 1`). A one-level image gives
    /// `t = 0`.
    Otsu,
    /// A local threshold for scans and photographs of pages (Sauvola's rule): a pixel is
    /// foreground iff `grey < m (1 + k (s / 128 - 1))`, with `m` and `s` the mean and the
    /// standard deviation of the grey levels in the `(2 radius + 1)²` window around it (cut by
    /// the image border) and `k = k_percent / 100`. A lighting gradient, a soft shadow and a
    /// white page stay background. With [`LoadOptions::invert`](crate::LoadOptions::invert)
    /// the rule is applied to `255 - grey` (light ink on dark paper). See
    /// [`Threshold::ADAPTIVE`] for the defaults.
    Adaptive {
        /// Half the window's side, in pixels: larger than the thickest stroke, smaller than
        /// the lighting changes (the default suits text of 10 to 60 pixels).
        radius: u32,
        /// Sauvola's `k` in hundredths (0 to 100): higher drops fainter ink and more noise.
        k_percent: u8,
    },
}

impl Threshold {
    /// The default window radius of [`Threshold::Adaptive`], in pixels.
    pub const ADAPTIVE_RADIUS: u32 = 16;
    /// The default `k` of [`Threshold::Adaptive`], in hundredths.
    pub const ADAPTIVE_K_PERCENT: u8 = 20;
    /// [`Threshold::Adaptive`] with its default window radius and `k`.
    pub const ADAPTIVE: Threshold = Threshold::Adaptive {
        radius: Threshold::ADAPTIVE_RADIUS,
        k_percent: Threshold::ADAPTIVE_K_PERCENT,
    };
}

/// The error of parsing a [`Threshold`]: the one-line reason.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParseThresholdError(String);

impl std::fmt::Display for ParseThresholdError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ParseThresholdError {}

impl std::str::FromStr for Threshold {
    type Err = ParseThresholdError;

    /// `N` (0..=255), `otsu`, or `adaptive[:R[:K]]` (R 1 to 1000, K 0 to 100), as the
    /// command line's `--threshold` takes it.
    ///
    /// ```
    /// use layertrace::Threshold;
    /// assert_eq!("otsu".parse(), Ok(Threshold::Otsu));
    /// assert_eq!("100".parse(), Ok(Threshold::Fixed(100)));
    /// assert_eq!(
    ///     "adaptive:24".parse(),
    ///     Ok(Threshold::Adaptive { radius: 24, k_percent: Threshold::ADAPTIVE_K_PERCENT })
    /// );
    /// assert!("adaptive:0".parse::<Threshold>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Threshold, ParseThresholdError> {
        let fail = |m: String| Err(ParseThresholdError(m));
        if s.eq_ignore_ascii_case("otsu") {
            return Ok(Threshold::Otsu);
        }
        let mut parts = s.split(':');
        if parts
            .next()
            .is_some_and(|p| p.eq_ignore_ascii_case("adaptive"))
        {
            let mut number =
                |what: &str, range: std::ops::RangeInclusive<u32>, default: u32| match parts.next()
                {
                    None => Ok(default),
                    Some(p) => match p.trim().parse::<u32>() {
                        Ok(v) if range.contains(&v) => Ok(v),
                        _ => Err(ParseThresholdError(format!(
                            "'{s}': {what} must be a whole number from {} to {}",
                            range.start(),
                            range.end()
                        ))),
                    },
                };
            let radius = number(
                "R (the window radius)",
                1..=1000,
                Threshold::ADAPTIVE_RADIUS,
            )?;
            let k = number(
                "K (Sauvola's k in hundredths)",
                0..=100,
                u32::from(Threshold::ADAPTIVE_K_PERCENT),
            )?;
            if parts.next().is_some() {
                return fail(format!("'{s}' has too many parts: adaptive[:R[:K]]"));
            }
            return Ok(Threshold::Adaptive {
                radius,
                k_percent: k as u8,
            });
        }
        match s.parse::<u8>() {
            Ok(v) => Ok(Threshold::Fixed(v)),
            Err(_) => fail(format!(
                "'{s}' is neither a number 0..=255 nor 'otsu' nor 'adaptive[:R[:K]]'"
            )),
        }
    }
}

pub(super) fn histogram(grey: &[u8]) -> [u64; 256] {
    let mut h = [0u64; 256];
    for &g in grey {
        h[g as usize] += 1;
    }
    h
}

/// Otsu's threshold: the first `t` in `0..=254` maximising the between-class variance of
/// `{grey <= t}` and `{grey > t}`; 0 when every candidate has zero variance.
///
/// The variance is compared exactly: up to a constant factor it is
/// `(N S0 - W0 S)^2 / (W0 W1)` with `N`, `S` the pixel count and grey sum, `W0`, `S0` those of
/// the dark class and `W1 = N - W0`; fractions are compared by cross-multiplication in big
/// integers (255 candidates, so the cost is negligible).
pub(crate) fn otsu(hist: &[u64; 256]) -> u8 {
    let n: BigUint = hist.iter().map(|&c| BigUint::from(c)).sum();
    let s: BigUint = hist
        .iter()
        .enumerate()
        .map(|(g, &c)| BigUint::from(g as u64) * c)
        .sum();
    let zero = BigUint::ZERO;
    let (mut w0, mut s0) = (BigUint::ZERO, BigUint::ZERO);
    let mut best_t = 0u8;
    // Best so far as (numerator, denominator); starts at variance zero.
    let mut best = (BigUint::ZERO, BigUint::from(1u8));
    for t in 0..=254u8 {
        let c = hist[usize::from(t)];
        if c == 0 && t != 0 {
            // Same classes as t - 1: same variance, never a new first maximum.
            continue;
        }
        w0 += c;
        s0 += BigUint::from(t) * c;
        if w0 == zero || w0 == n {
            continue;
        }
        let w1 = &n - &w0;
        let (a, b) = (&n * &s0, &w0 * &s);
        let d = if a > b { a - b } else { b - a };
        let num = &d * &d;
        let den = &w0 * &w1;
        if &num * &best.1 > &best.0 * &den {
            best = (num, den);
            best_t = t;
        }
    }
    best_t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bitmap::{threshold_image, LoadOptions};
    use image::{DynamicImage, ImageBuffer, Luma};
    use proptest::prelude::*;

    /// Between-class variance for `{g <= t}` vs `{g > t}`, in floating point.
    fn variance(hist: &[u64; 256], t: usize) -> f64 {
        let n: f64 = hist.iter().map(|&c| c as f64).sum();
        let w0: f64 = hist[..=t].iter().map(|&c| c as f64).sum();
        let w1 = n - w0;
        if w0 == 0.0 || w1 == 0.0 {
            return 0.0;
        }
        let m0 = hist[..=t]
            .iter()
            .enumerate()
            .map(|(g, &c)| g as f64 * c as f64)
            .sum::<f64>()
            / w0;
        let m1 = hist[t + 1..]
            .iter()
            .enumerate()
            .map(|(g, &c)| (g + t + 1) as f64 * c as f64)
            .sum::<f64>()
            / w1;
        w0 * w1 * (m0 - m1) * (m0 - m1) / (n * n)
    }

    fn assert_otsu_is_first_max(hist: &[u64; 256]) {
        let t = usize::from(otsu(hist));
        assert!(t <= 254);
        let v = variance(hist, t);
        let best = (0..=254).map(|u| variance(hist, u)).fold(0.0, f64::max);
        assert!(v >= best * (1.0 - 1e-12), "t={t} v={v} best={best}");
        for u in 0..t {
            assert!(
                variance(hist, u) < v * (1.0 - 1e-12) || v == 0.0,
                "earlier max at {u}"
            );
        }
    }

    #[test]
    fn otsu_bimodal() {
        // Dark cluster 30..=50, light cluster 190..=210, on a 64x64 image.
        let img = ImageBuffer::from_fn(64, 64, |x, y| {
            let k = ((x * 7 + y * 13) % 21) as u8;
            Luma([if (x / 8 + y / 8) % 3 == 0 {
                30 + k
            } else {
                190 + k
            }])
        });
        let dark = img.pixels().filter(|p| p[0] <= 50).count() as u64;
        let img = DynamicImage::ImageLuma8(img);
        let opts = LoadOptions {
            threshold: Threshold::Otsu,
            ..LoadOptions::default()
        };
        let l = threshold_image(&img, &opts);
        assert!(
            (51..=190).contains(&l.threshold),
            "threshold {}",
            l.threshold
        );
        assert_eq!(l.mask.count_foreground(), dark);
        assert_otsu_is_first_max(&histogram(img.as_luma8().unwrap().as_raw()));
        // invert swaps the classes.
        let inv = threshold_image(
            &img,
            &LoadOptions {
                invert: true,
                ..opts
            },
        );
        assert_eq!(inv.mask.count_foreground(), 64 * 64 - dark);
        // Two levels: the plateau's first maximum is the dark level itself.
        let mut h = [0u64; 256];
        h[0] = 10;
        h[255] = 30;
        assert_eq!(otsu(&h), 0);
        h[0] = 0;
        assert_eq!(otsu(&h), 0, "one level: no maximum, t = 0");
    }

    proptest! {
        #[test]
        fn otsu_matches_float_first_max(
            levels in proptest::collection::vec((0usize..256, 1u64..1000), 1..12)
        ) {
            let mut h = [0u64; 256];
            for (g, c) in levels {
                h[g] += c;
            }
            assert_otsu_is_first_max(&h);
        }
    }
}

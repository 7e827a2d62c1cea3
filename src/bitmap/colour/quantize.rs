//! Colour quantization: a palette of at most `N` colours for an image with more.
//!
//! Three steps, all on the histogram of distinct colours weighted by their pixel counts:
//! 1. NeuQuant (the `color_quant` crate, already in the tree through `image`'s GIF
//!    encoder) learns a fine palette of up to 256 colours. It is made for 64 colours or
//!    more: asked for 4 it merged the red and the yellow of a logo.
//! 2. Ward's merging: the two clusters whose merging adds the least squared error
//!    (`wa·wb/(wa+wb)·d²`) are merged, into their weighted mean, until `N` are left. Rare
//!    colours (anti-aliasing blends) join a large neighbour first instead of chaining two
//!    large clusters together through them.
//! 3. A few k-means (Lloyd) steps move every colour to the mean of the colours nearest to
//!    it.
//!
//! Deterministic: no random sampling.

use rustc_hash::FxHashMap as HashMap;

use super::Colour;

/// Lloyd steps after Ward's merging.
const KMEANS_STEPS: usize = 8;

/// The size of NeuQuant's fine palette.
const FINE: usize = 256;

/// The index of the colour of `palette` nearest to `c` (squared RGB distance, the first of
/// equals); 0 for an empty palette.
pub(super) fn nearest(palette: &[Colour], c: Colour) -> usize {
    let mut best = (u32::MAX, 0);
    for (k, &p) in palette.iter().enumerate() {
        let d = p.distance2(c);
        if d < best.0 {
            best = (d, k);
        }
    }
    best.1
}

/// At most `n` (≥ 1) colours for the colours of `histogram` (colour → pixel count), none
/// repeated.
pub(super) fn palette(histogram: &HashMap<Colour, u64>, n: usize) -> Vec<Colour> {
    let mut colours: Vec<(Colour, u64)> = histogram.iter().map(|(&c, &k)| (c, k)).collect();
    // A stable order whatever the hash map's.
    colours.sort_unstable();
    if colours.len() <= n {
        return colours.into_iter().map(|c| c.0).collect();
    }
    // NeuQuant samples its input: hand it each distinct colour as often as it occurs,
    // up to a cap that keeps the sample small for large images.
    let total: u64 = colours.iter().map(|c| c.1).sum();
    let scale = (total / 200_000).max(1);
    let mut sample = Vec::new();
    for &(c, k) in &colours {
        for _ in 0..(k / scale).max(1) {
            sample.extend_from_slice(&[c.r, c.g, c.b, 255]);
        }
    }
    let nq = color_quant::NeuQuant::new(1, FINE, &sample);
    let mut fine: Vec<Colour> = nq
        .color_map_rgb()
        .chunks_exact(3)
        .map(|p| Colour::new(p[0], p[1], p[2]))
        .collect();
    fine.sort_unstable();
    fine.dedup();
    let fine = kmeans(&colours, fine, 2);
    let palette = ward(&colours, fine, n);
    kmeans(&colours, palette, KMEANS_STEPS)
}

/// The weighted sums of the colours nearest to each palette colour: `[Σr·k, Σg·k, Σb·k, Σk]`.
fn sums(colours: &[(Colour, u64)], palette: &[Colour]) -> Vec<[u64; 4]> {
    let mut sums = vec![[0u64; 4]; palette.len()];
    for &(c, k) in colours {
        let s = &mut sums[nearest(palette, c)];
        s[0] += u64::from(c.r) * k;
        s[1] += u64::from(c.g) * k;
        s[2] += u64::from(c.b) * k;
        s[3] += k;
    }
    sums
}

/// Ward's merging of the clusters of `palette` down to `n` (see the module documentation).
fn ward(colours: &[(Colour, u64)], palette: Vec<Colour>, n: usize) -> Vec<Colour> {
    // (mean as f64 triple, weight)
    let mut clusters: Vec<([f64; 3], f64)> = sums(colours, &palette)
        .iter()
        .filter(|s| s[3] > 0)
        .map(|s| {
            let w = s[3] as f64;
            ([s[0] as f64 / w, s[1] as f64 / w, s[2] as f64 / w], w)
        })
        .collect();
    while clusters.len() > n.max(1) {
        let mut best = (f64::INFINITY, 0, 1);
        for i in 0..clusters.len() {
            for j in i + 1..clusters.len() {
                let (a, b) = (&clusters[i], &clusters[j]);
                let d2: f64 = (0..3).map(|k| (a.0[k] - b.0[k]).powi(2)).sum();
                let cost = a.1 * b.1 / (a.1 + b.1) * d2;
                if cost < best.0 {
                    best = (cost, i, j);
                }
            }
        }
        let (_, i, j) = best;
        let b = clusters.remove(j);
        let a = &mut clusters[i];
        let w = a.1 + b.1;
        for k in 0..3 {
            a.0[k] = (a.0[k] * a.1 + b.0[k] * b.1) / w;
        }
        a.1 = w;
    }
    let mut out: Vec<Colour> = clusters
        .iter()
        .map(|(m, _)| {
            let v = |x: f64| x.round().clamp(0.0, 255.0) as u8;
            Colour::new(v(m[0]), v(m[1]), v(m[2]))
        })
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// Lloyd's steps on the weighted colours: each palette colour moves to the weighted mean
/// of the colours nearest to it; colours nearest to none are dropped.
fn kmeans(colours: &[(Colour, u64)], mut palette: Vec<Colour>, steps: usize) -> Vec<Colour> {
    for _ in 0..steps {
        let sums = sums(colours, &palette);
        let mean = |s: &[u64; 4], i: usize| ((s[i] + s[3] / 2) / s[3]) as u8;
        let mut next: Vec<Colour> = sums
            .iter()
            .filter(|s| s[3] > 0)
            .map(|s| Colour::new(mean(s, 0), mean(s, 1), mean(s, 2)))
            .collect();
        next.sort_unstable();
        next.dedup();
        if next == palette {
            break;
        }
        palette = next;
    }
    palette
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn at_most_n_colours_near_the_clusters() {
        // Three clusters of colours, with noise: three colours, one near each cluster.
        let mut h = HashMap::default();
        let centres = [(200u8, 30u8, 30u8), (20, 180, 40), (30, 40, 220)];
        for (i, &(r, g, b)) in centres.iter().enumerate() {
            for d in 0..12u8 {
                *h.entry(Colour::new(r + d, g + d / 2, b - d)).or_insert(0) += 10 + i as u64;
            }
        }
        for n in [1, 2, 3] {
            let p = palette(&h, n);
            assert!(!p.is_empty() && p.len() <= n, "{n}: {p:?}");
        }
        let p = palette(&h, 3);
        assert_eq!(p.len(), 3);
        for &(r, g, b) in &centres {
            let c = Colour::new(r, g, b);
            let d = p[nearest(&p, c)].distance2(c);
            assert!(d < 20 * 20, "{c} far from {p:?}");
        }
        assert_eq!(palette(&h, 3), p, "deterministic");
    }
}

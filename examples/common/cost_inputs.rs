//! The adversarial inputs of the cost checks (issue 13), shared by `make_cost` and
//! `cost_table` (included by `#[path]`): predicates `(x, y) → foreground`.

/// The checkerboard of single pixels: foreground where `x + y` is even (every foreground
/// pixel is its own one-point contour).
pub fn checker(x: u32, y: u32) -> bool {
    (x + y).is_multiple_of(2)
}

/// `n × n` pixels, each foreground with probability 1/2 (xorshift, fixed seed), row-major.
pub fn noise(n: u32) -> Vec<bool> {
    let mut seed = 2014u64;
    (0..u64::from(n) * u64::from(n))
        .map(|_| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed >> 63 == 1
        })
        .collect()
}

/// A one-pixel-wide square spiral in an `n × n` image, arms two pixels apart, row-major:
/// one component whose border is a single contour of about `n²` pixels.
pub fn spiral(n: u32) -> Vec<bool> {
    let w = n as usize;
    let mut img = vec![false; w * w];
    let (mut x0, mut y0, mut x1, mut y1) = (0usize, 0usize, w - 1, w - 1);
    let mut put = |x: usize, y: usize| img[y * w + x] = true;
    // Each ring: top row, right column, bottom row, and the left column stopping two short
    // of the top, where a one-pixel link leads into the next ring.
    loop {
        for x in x0..=x1 {
            put(x, y0);
        }
        for y in y0..=y1 {
            put(x1, y);
        }
        if y1 - y0 < 2 || x1 - x0 < 2 {
            break;
        }
        for x in x0..=x1 {
            put(x, y1);
        }
        for y in (y0 + 2)..=y1 {
            put(x0, y);
        }
        if x1 - x0 < 4 || y1 - y0 < 4 {
            break;
        }
        put(x0 + 1, y0 + 2);
        x0 += 2;
        y0 += 2;
        x1 -= 2;
        y1 -= 2;
    }
    img
}

//! SVG path data as text: numbers written exactly and compactly, each contour's commands
//! relative to the pen (also the number writer of the PDF and EPS exports).

use crate::curve::PathCommand;
use crate::outline::ContourPath;
use kurbo::Point;
use std::fmt::Write as _;

/// Appends the decimal digits of `n`, zero-padded to `width` digits (without the
/// formatting machinery: a large SVG writes millions of numbers).
fn push_digits(mut n: u64, width: usize, s: &mut String) {
    let mut buf = [0u8; 20];
    let mut k = buf.len();
    while n > 0 || buf.len() - k < width {
        k -= 1;
        buf[k] = b'0' + (n % 10) as u8;
        n /= 10;
    }
    s.extend(buf[k..].iter().map(|&b| char::from(b)));
}

/// `10^p` for the fast path of [`number`] (`powi` is a library call).
const POWERS_OF_TEN: [f64; 10] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9];

/// Formats `v` with at most `precision` decimals, trailing zeros stripped, no `-0` (also
/// the number writer of the PDF and EPS exports).
pub(crate) fn number(v: f64, precision: usize, s: &mut String) {
    if !v.is_finite() {
        s.push('0');
        return;
    }
    // Fast path: v·10^p rounded to an integer that f64 holds exactly (the same digits as
    // `format!` except, rarely, for a value within an ulp of a rounding tie).
    if let Some(&scale) = POWERS_OF_TEN.get(precision) {
        let n = (v * scale).round_ties_even();
        if n.abs() < 9.0e15 {
            let n = n as i64;
            if n < 0 {
                s.push('-');
            }
            let (scale, n) = (scale as u64, n.unsigned_abs());
            let (int, mut frac) = (n / scale, n % scale);
            push_digits(int, 1, s);
            if frac != 0 {
                let mut digits = precision;
                while frac % 10 == 0 {
                    frac /= 10;
                    digits -= 1;
                }
                s.push('.');
                push_digits(frac, digits, s);
            }
            return;
        }
    }
    let mut t = format!("{v:.precision$}");
    if t.contains('.') {
        while t.ends_with('0') {
            t.pop();
        }
        if t.ends_with('.') {
            t.pop();
        }
    }
    if t == "-0" {
        t = "0".into();
    }
    s.push_str(&t);
}

fn point(p: Point, precision: usize, s: &mut String) {
    number(p.x, precision, s);
    s.push(' ');
    number(p.y, precision, s);
}

/// Appends one number, separated from what precedes it by a space unless a command letter
/// or its own minus sign separates it.
fn push_number(v: f64, precision: usize, after_number: bool, s: &mut String) {
    let start = s.len();
    number(v, precision, s);
    // No leading zero: `.5`, `-.25` (most relative coordinates are below one pixel).
    let sign = usize::from(s[start..].starts_with('-'));
    if s[start + sign..].starts_with("0.") {
        s.remove(start + sign);
    }
    if after_number && sign == 0 {
        s.insert(start, ' ');
    }
}

/// Appends the path data (`M … Z`) of one contour, compactly: coordinates relative to the
/// pen (`l`, `h`, `v`, `q`, `c`; `M` and `A` absolute), a command letter only when it
/// changes, a space only where no minus sign separates two numbers, and no final line back
/// to the start (`Z` draws it).
///
/// Exact: every point is on the 2^-grid grid, so each difference is a dyadic number with at
/// most `precision` decimals, written exactly, and the sum a renderer forms again (in `f64`
/// in usvg, in `f32` in Skia: exact below 2^24 grid units) is the point itself.
///
/// Every absolute point (`M`, `A`) is written moved by `-shift` in x and y (an integer
/// shift keeps the points exact and the relative numbers the same).
pub(crate) fn write_path_data(cp: &ContourPath, precision: usize, shift: f64, s: &mut String) {
    if cp.commands.is_empty() {
        return;
    }
    // Room for the usual lengths at once (grown number by number, a contour's text was
    // reallocated some five times).
    let room: usize = cp
        .commands
        .iter()
        .map(|c| match c {
            PathCommand::Line(_) => 10,
            PathCommand::Quad(..) => 24,
            PathCommand::Cubic(..) => 36,
            PathCommand::Arc(_) => 48,
        })
        .sum();
    s.reserve(room + 12);
    let moved = |p: Point| Point::new(p.x - shift, p.y - shift);
    s.push('M');
    point(moved(cp.start), precision, s);
    let mut pen = cp.start;
    let mut last = 'M';
    for c in &cp.commands {
        // (letter, relative numbers)
        let mut nums = [0.0f64; 6];
        let (letter, count) = match *c {
            PathCommand::Line(p) => {
                let d = p - pen;
                if d.y == 0.0 {
                    nums[0] = d.x;
                    ('h', 1)
                } else if d.x == 0.0 {
                    nums[0] = d.y;
                    ('v', 1)
                } else {
                    nums[..2].copy_from_slice(&[d.x, d.y]);
                    ('l', 2)
                }
            }
            PathCommand::Quad(c1, p) => {
                let (a, b) = (c1 - pen, p - pen);
                nums[..4].copy_from_slice(&[a.x, a.y, b.x, b.y]);
                ('q', 4)
            }
            PathCommand::Cubic(c1, c2, p) => {
                let (a, b, e) = (c1 - pen, c2 - pen, p - pen);
                nums.copy_from_slice(&[a.x, a.y, b.x, b.y, e.x, e.y]);
                ('c', 6)
            }
            PathCommand::Arc(a) => {
                s.push('A');
                number(a.radii.x, precision, s);
                s.push(' ');
                number(a.radii.y, precision, s);
                s.push(' ');
                number(a.x_rotation.to_degrees().rem_euclid(360.0), precision, s);
                let _ = write!(s, " {} {} ", u8::from(a.large_arc), u8::from(a.sweep));
                point(moved(a.to), precision, s);
                pen = a.to;
                last = 'A';
                continue;
            }
        };
        let repeat = letter == last;
        if !repeat {
            s.push(letter);
        }
        for (k, &v) in nums[..count].iter().enumerate() {
            push_number(v, precision, repeat || k > 0, s);
        }
        last = letter;
        pen = c.end();
    }
    s.push('Z');
}

/// Drops a final line back to the start: `Z` draws it.
pub(crate) fn drop_closing_line(cp: &mut ContourPath) {
    if cp.commands.len() > 2 && cp.commands.last() == Some(&PathCommand::Line(cp.start)) {
        cp.commands.pop();
    }
}

/// Escapes the five XML special characters of an attribute value.
pub(crate) fn xml_escape(v: &str) -> String {
    let mut s = String::with_capacity(v.len());
    for ch in v.chars() {
        match ch {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&apos;"),
            c => s.push(c),
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn num(v: f64, p: usize) -> String {
        let mut s = String::new();
        number(v, p, &mut s);
        s
    }

    #[test]
    fn compact_numbers() {
        assert_eq!(num(1.5, 3), "1.5");
        assert_eq!(num(2.0, 3), "2");
        assert_eq!(num(-0.0001, 3), "0");
        assert_eq!(num(12.34567, 3), "12.346");
        assert_eq!(num(12.34567, 0), "12");
        assert_eq!(num(f64::NAN, 3), "0");
        assert_eq!(num(-3.25, 1), "-3.2");
        assert_eq!(num(-0.05, 3), "-0.05");
        assert_eq!(
            num(1e300, 3),
            format!("{:.3}", 1e300).trim_end_matches(".000")
        );
        // The integer fast path writes what `format!` writes (away from rounding ties).
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..20_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let v = ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 20_000.0;
            for p in [0, 1, 3, 6] {
                let frac = (v * 10f64.powi(p as i32)).abs().fract();
                if (frac - 0.5).abs() < 1e-6 {
                    continue;
                }
                let mut want = format!("{v:.p$}");
                if want.contains('.') {
                    want = want.trim_end_matches('0').trim_end_matches('.').to_string();
                }
                if want == "-0" {
                    want = "0".into();
                }
                assert_eq!(num(v, p), want, "{v} at precision {p}");
            }
        }
        assert_eq!(xml_escape("a\"<b>&'"), "a&quot;&lt;b&gt;&amp;&apos;");
    }
}

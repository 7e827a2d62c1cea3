//! SVG path data as text: numbers written exactly and compactly, each contour's commands
//! relative to the pen (also the number writer of the PDF and EPS exports).

use crate::curve::PathCommand;
use crate::outline::ContourPath;
use kurbo::Point;
use std::fmt::Write as _;

/// `10^p` for the fast path of [`number`] (`powi` is a library call).
const POWERS_OF_TEN: [f64; 10] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9];

/// A number's decimal digits: `-`(if `negative`) `int`.`frac` (`frac` written with
/// `frac_digits` digits, zero-padded on the left; no fraction when it is zero).
struct Decimal {
    negative: bool,
    int: u64,
    frac: u64,
    frac_digits: usize,
}

impl Decimal {
    /// `v` rounded to `precision` decimals, trailing zeros stripped, no `-0`: `v·10^p`
    /// rounded to an integer that `f64` holds exactly (the same digits as `format!` except,
    /// rarely, for a value within an ulp of a rounding tie). Returns None if `v` is not
    /// finite, `precision` is above 9 or `|v|·10^p` is 9·10^15 or more.
    fn of(v: f64, precision: usize) -> Option<Decimal> {
        let &scale = POWERS_OF_TEN.get(precision)?;
        let n = (v * scale).round_ties_even();
        if !n.is_finite() || n.abs() >= 9.0e15 {
            return None;
        }
        let n = n as i64;
        let (scale, m) = (scale as u64, n.unsigned_abs());
        let (int, mut frac) = (m / scale, m % scale);
        let mut frac_digits = precision;
        if frac != 0 {
            while frac % 10 == 0 {
                frac /= 10;
                frac_digits -= 1;
            }
        }
        Some(Decimal {
            negative: n < 0,
            int,
            frac,
            frac_digits,
        })
    }

    /// Appends the text, with `lead` (a space, or nothing) before it unless it starts with
    /// a minus sign; with `bare`, a fraction's leading zero is left out (`.5`, `-.25`).
    /// Written backwards into a buffer and appended at once (without the formatting
    /// machinery: a large SVG writes millions of numbers).
    fn push(&self, lead: bool, bare: bool, s: &mut String) {
        // 20 digits each way, a point and a sign.
        let mut buf = [0u8; 44];
        let mut k = buf.len();
        if self.frac != 0 {
            k = digits_before(self.frac, self.frac_digits, &mut buf, k);
            k -= 1;
            buf[k] = b'.';
        }
        if !(bare && self.frac != 0 && self.int == 0) {
            k = digits_before(self.int, 1, &mut buf, k);
        }
        if self.negative {
            k -= 1;
            buf[k] = b'-';
        } else if lead {
            k -= 1;
            buf[k] = b' ';
        }
        // ASCII digits, point, sign and space: always UTF-8.
        s.push_str(std::str::from_utf8(&buf[k..]).unwrap_or_default());
    }
}

/// Writes the decimal digits of `n`, zero-padded to `width` digits, into `buf` just before
/// `end`; returns where they start.
fn digits_before(mut n: u64, width: usize, buf: &mut [u8], end: usize) -> usize {
    let mut k = end;
    while n > 0 || end - k < width {
        k -= 1;
        buf[k] = b'0' + (n % 10) as u8;
        n /= 10;
    }
    k
}

/// Formats `v` with at most `precision` decimals, trailing zeros stripped, no `-0` (also
/// the number writer of the PDF and EPS exports).
pub(crate) fn number(v: f64, precision: usize, s: &mut String) {
    if !v.is_finite() {
        s.push('0');
        return;
    }
    if let Some(d) = Decimal::of(v, precision) {
        d.push(false, false, s);
        return;
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
    if let Some(d) = Decimal::of(v, precision) {
        d.push(after_number, true, s);
        return;
    }
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
                // In path data: no leading zero before a point, a space unless a minus
                // sign separates the number from the one before.
                for after_number in [false, true] {
                    let mut compact = want.replacen(
                        "0.",
                        ".",
                        usize::from(want.starts_with("0.") || want.starts_with("-0.")),
                    );
                    if after_number && !compact.starts_with('-') {
                        compact.insert(0, ' ');
                    }
                    let mut got = String::new();
                    push_number(v, p, after_number, &mut got);
                    assert_eq!(got, compact, "{v} at precision {p}");
                }
            }
        }
        let compact = |v: f64, after_number: bool| {
            let mut s = String::new();
            push_number(v, 4, after_number, &mut s);
            s
        };
        assert_eq!(compact(0.5, true), " .5");
        assert_eq!(compact(-0.25, true), "-.25");
        assert_eq!(compact(-0.0001, true), "-.0001");
        assert_eq!(compact(-0.00001, true), " 0");
        assert_eq!(compact(0.0625, false), ".0625");
        assert_eq!(compact(-12.0, false), "-12");
        assert_eq!(compact(10.5, true), " 10.5");
        assert_eq!(xml_escape("a\"<b>&'"), "a&quot;&lt;b&gt;&amp;&apos;");
    }
}

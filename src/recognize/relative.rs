//! Points relative to a local origin, `p − origin`: the one overflow policy of the
//! recognizer (checked: a coordinate that does not fit `i64` is no point of the problem).

/// `p − origin` coordinate by coordinate; `None` if a difference overflows `i64` or the
/// lengths differ.
pub(crate) fn relative(p: &[i64], origin: &[i64]) -> Option<Vec<i64>> {
    let mut out = vec![0; p.len()];
    relative_into(p, origin, &mut out)?;
    Some(out)
}

/// [`relative`] into `out` (whose length must be `p`'s), reusing its allocation; `None`,
/// with `out` partly written, on overflow or a length mismatch.
pub(crate) fn relative_into(p: &[i64], origin: &[i64], out: &mut [i64]) -> Option<()> {
    if p.len() != origin.len() || out.len() != p.len() {
        return None;
    }
    for (r, (a, b)) in out.iter_mut().zip(p.iter().zip(origin)) {
        *r = a.checked_sub(*b)?;
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn differences_and_overflow() {
        assert_eq!(relative(&[5, -3], &[2, 4]), Some(vec![3, -7]));
        assert_eq!(relative(&[i64::MIN, 0], &[1, 0]), None);
        assert_eq!(relative(&[i64::MAX], &[-1]), None);
        assert_eq!(relative(&[1, 2], &[1]), None);
        let mut out = [0; 2];
        assert_eq!(relative_into(&[0, 0], &[-4, 9], &mut out), Some(()));
        assert_eq!(out, [4, -9]);
    }
}

//! tiny-skia's cuts of quadratics and cubics where they turn in y (and, where its edge
//! clipper runs, in x), in `f32`, as its edge builder makes them before it sets up each
//! part's edges ([`super::edges`]): tiny-skia's code (BSD-3-Clause, Copyright 2006 The
//! Android Open Source Project, 2020 Yevhenii Reizner), with its geometry helpers called
//! from `tiny-skia-path`.

use tiny_skia_path::path_geometry::{
    chop_cubic_at2, chop_quad_at, find_unit_quad_roots, new_t_values, valid_unit_divide,
};
use tiny_skia_path::{NormalizedF32Exclusive, Point as SkPoint};

/// A point's coordinate along `axis` (0: x, 1: y).
fn coord(p: SkPoint, axis: usize) -> f32 {
    if axis == 0 {
        p.x
    } else {
        p.y
    }
}

/// Sets a point's coordinate along `axis` (0: x, 1: y).
fn set_coord(p: &mut SkPoint, axis: usize, v: f32) {
    if axis == 0 {
        p.x = v;
    } else {
        p.y = v;
    }
}

/// tiny-skia's `chop_quad_at_y_extrema` (`axis` 1) and `chop_quad_at_x_extrema` (`axis`
/// 0): 0 for one quadratic in `dst[0..3]`, 1 for two in `dst[0..5]`, each monotonic along
/// the axis.
fn chop_quad_at_extrema(src: &[SkPoint; 3], dst: &mut [SkPoint; 5], axis: usize) -> usize {
    let (a, mut b, c) = (
        coord(src[0], axis),
        coord(src[1], axis),
        coord(src[2], axis),
    );
    let ab = a - b;
    let bc = if ab < 0.0 { -(b - c) } else { b - c };
    if ab == 0.0 || bc < 0.0 {
        if let Some(t) = valid_unit_divide(a - b, a - b - b + c) {
            chop_quad_at(src, t, dst);
            // Flatten the double extremum.
            let m = coord(dst[2], axis);
            set_coord(&mut dst[1], axis, m);
            set_coord(&mut dst[3], axis, m);
            return 1;
        }
        b = if (a - b).abs() < (b - c).abs() { a } else { c };
    }
    dst[..3].copy_from_slice(src);
    set_coord(&mut dst[0], axis, a);
    set_coord(&mut dst[1], axis, b);
    set_coord(&mut dst[2], axis, c);
    0
}

/// tiny-skia's `chop_quad_at_y_extrema`.
pub(super) fn chop_quad_at_y_extrema(src: &[SkPoint; 3], dst: &mut [SkPoint; 5]) -> usize {
    chop_quad_at_extrema(src, dst, 1)
}

/// tiny-skia's `chop_quad_at_x_extrema`.
pub(super) fn chop_quad_at_x_extrema(src: &[SkPoint; 3], dst: &mut [SkPoint; 5]) -> usize {
    chop_quad_at_extrema(src, dst, 0)
}

/// tiny-skia's `chop_cubic_at_y_extrema` (`axis` 1) and `chop_cubic_at_x_extrema` (`axis`
/// 0): the number of cuts (0 to 2), the cubics in `dst[0..4]`, `dst[3..7]`, `dst[6..10]`,
/// each monotonic along the axis.
fn chop_cubic_at_extrema(src: &[SkPoint; 4], dst: &mut [SkPoint; 10], axis: usize) -> usize {
    let [a, b, c, d] = src.map(|p| coord(p, axis));
    let mut t_values = new_t_values();
    let roots = find_unit_quad_roots(
        d - a + 3.0 * (b - c),
        2.0 * (a - b - b + c),
        b - a,
        &mut t_values,
    );
    let t_values = &t_values[..roots];
    chop_cubic_at(src, t_values, dst);
    // Flatten the extrema.
    if !t_values.is_empty() {
        let m = coord(dst[3], axis);
        set_coord(&mut dst[2], axis, m);
        set_coord(&mut dst[4], axis, m);
        if t_values.len() == 2 {
            let m = coord(dst[6], axis);
            set_coord(&mut dst[5], axis, m);
            set_coord(&mut dst[7], axis, m);
        }
    }
    t_values.len()
}

/// tiny-skia's `chop_cubic_at_y_extrema`.
pub(super) fn chop_cubic_at_y_extrema(src: &[SkPoint; 4], dst: &mut [SkPoint; 10]) -> usize {
    chop_cubic_at_extrema(src, dst, 1)
}

/// tiny-skia's `chop_cubic_at_x_extrema`.
pub(super) fn chop_cubic_at_x_extrema(src: &[SkPoint; 4], dst: &mut [SkPoint; 10]) -> usize {
    chop_cubic_at_extrema(src, dst, 0)
}

/// tiny-skia's `chop_cubic_at`: `src` cut at the increasing `t_values`.
fn chop_cubic_at(src: &[SkPoint; 4], t_values: &[NormalizedF32Exclusive], dst: &mut [SkPoint]) {
    let Some(&first) = t_values.first() else {
        dst[..4].copy_from_slice(src);
        return;
    };
    let mut t = first;
    let mut tmp = *src;
    let mut offset = 0;
    for i in 0..t_values.len() {
        chop_cubic_at2(&tmp, t, &mut dst[offset..]);
        if i == t_values.len() - 1 {
            break;
        }
        offset += 3;
        tmp.copy_from_slice(&dst[offset..offset + 4]);
        match valid_unit_divide(
            t_values[i + 1].get() - t_values[i].get(),
            1.0 - t_values[i].get(),
        ) {
            Some(n) => t = n,
            None => {
                dst[offset + 4] = tmp[3];
                dst[offset + 5] = tmp[3];
                dst[offset + 6] = tmp[3];
                break;
            }
        }
    }
}

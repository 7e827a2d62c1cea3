//! tiny-skia's own fill of a contour's path and its reference reversed, in a mask the size
//! of the render check's window (where [`super::scan`] does not apply: the path leaves the
//! window, or has arcs), with the masks' buffers reused.

use super::render_check::{Reference, Window};
use crate::curve::PathCommand;
use kurbo::Point;
use std::cell::RefCell;

thread_local! {
    /// Buffers of finished renders, reused by the next ones on the same thread. A contour's
    /// window is often above malloc's mmap threshold (128 KiB), and a fresh mapping costs a
    /// page fault per 4 KiB: 12% of the whole run on the shared samples before they were
    /// reused.
    static SPARE: RefCell<Vec<Vec<u8>>> = const { RefCell::new(Vec::new()) };
}

/// Most buffers kept per thread, and the largest kept (bytes): a huge contour's windows are
/// rare, and keeping them would hold their memory to the end of the run.
const SPARE_COUNT: usize = 6;
const SPARE_MAX_BYTES: usize = 1 << 22;

/// `len` zero bytes, in a reused buffer when one is spare. Spare buffers are zero over their
/// length (see [`take_painted`]), so only a longer tail is written.
fn zeroed(len: usize) -> Vec<u8> {
    let mut v = SPARE.with(|s| s.borrow_mut().pop()).unwrap_or_default();
    if v.len() >= len {
        v.truncate(len);
    } else {
        v.resize(len, 0);
    }
    v
}

/// Gives a buffer, zero over its whole length, back for [`zeroed`] to reuse.
fn recycle(v: Vec<u8>) {
    if v.capacity() == 0 || v.capacity() > SPARE_MAX_BYTES {
        return;
    }
    SPARE.with(|s| {
        let mut s = s.borrow_mut();
        if s.len() < SPARE_COUNT {
            s.push(v);
        }
    });
}

/// Appends to `painted_at` the indices (row-major in `win`) of the pixels tiny-skia itself
/// paints filling the path and `reference` reversed in a mask that is exactly `win`, curves
/// drawn `clipped` or not (see [`super::render_check::painted_in`]); false when tiny-skia
/// cannot fill the path.
pub(super) fn painted(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    win: &Window,
    clipped: bool,
    painted_at: &mut Vec<usize>,
) -> bool {
    let (width, height) = (win.x1 - win.x0, win.y1 - win.y0);
    let size = u32::try_from(width)
        .ok()
        .zip(u32::try_from(height).ok())
        .and_then(|(w, h)| tiny_skia::IntSize::from_wh(w, h));
    let Some(size) = size else {
        return false;
    };
    let len = (width * height) as usize;
    let painted = difference_path(
        reference,
        start,
        commands,
        win.x0 as f64,
        win.y0 as f64,
        clipped,
    )
    .and_then(|path| {
        let mut mask = tiny_skia::Mask::from_vec(zeroed(len), size)?;
        mask.fill_path(
            &path,
            tiny_skia::FillRule::Winding,
            false,
            tiny_skia::Transform::identity(),
        );
        Some(mask.take())
    });
    let Some(mut painted) = painted else {
        return false;
    };
    take_painted(&mut painted, painted_at);
    recycle(painted);
    true
}

/// Appends the indices of the non-zero bytes of `mask` to `at`, in order, and zeroes them:
/// the buffer goes back to [`recycle`] all zero without being written whole (a fill paints
/// few pixels of its window).
fn take_painted(mask: &mut [u8], at: &mut Vec<usize>) {
    // Blocks of 64 bytes tested by an OR without early exit, which the compiler
    // vectorizes (a byte-by-byte `all` was three quarters of this function's own time).
    for (block, bytes) in mask.chunks_mut(64).enumerate() {
        if bytes.iter().fold(0u8, |a, &b| a | b) == 0 {
            continue;
        }
        for (k, b) in bytes.iter_mut().enumerate() {
            if *b != 0 {
                at.push(block * 64 + k);
                *b = 0;
            }
        }
    }
}

/// The path translated by `(−dx, −dy)` (whole pixels: exact for grid points) as tiny-skia's,
/// followed by `reference` reversed, and — for the `clipped` way of drawing curves — a flat
/// sliver just outside the window, which paints nothing but puts the path's bounds outside
/// the mask, so that tiny-skia runs its edge clipper on every edge. `None` when tiny-skia
/// refuses the path (not finite).
fn difference_path(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    dx: f64,
    dy: f64,
    clipped: bool,
) -> Option<tiny_skia::Path> {
    let f = |p: Point| ((p.x - dx) as f32, (p.y - dy) as f32);
    let verbs = commands.len() + reference.vertices.len() + 6;
    let mut pb = tiny_skia::PathBuilder::with_capacity(verbs, verbs * 3);
    let (x, y) = f(start);
    pb.move_to(x, y);
    let mut pen = start;
    for c in commands {
        match *c {
            PathCommand::Line(p) => {
                let (x, y) = f(p);
                pb.line_to(x, y);
            }
            PathCommand::Quad(a, p) => {
                let ((ax, ay), (x, y)) = (f(a), f(p));
                pb.quad_to(ax, ay, x, y);
            }
            PathCommand::Cubic(a, b, p) => {
                let ((ax, ay), (bx, by), (x, y)) = (f(a), f(b), f(p));
                pb.cubic_to(ax, ay, bx, by, x, y);
            }
            PathCommand::Arc(_) => {
                for el in c.to_path_els(pen) {
                    match el {
                        kurbo::PathEl::CurveTo(a, b, p) => {
                            let ((ax, ay), (bx, by), (x, y)) = (f(a), f(b), f(p));
                            pb.cubic_to(ax, ay, bx, by, x, y);
                        }
                        kurbo::PathEl::LineTo(p) => {
                            let (x, y) = f(p);
                            pb.line_to(x, y);
                        }
                        _ => {}
                    }
                }
            }
        }
        pen = c.end();
    }
    pb.close();
    let (x, y) = f(reference.start);
    pb.move_to(x, y);
    for &p in reference.vertices.iter().rev() {
        let (x, y) = f(p);
        pb.line_to(x, y);
    }
    pb.close();
    if clipped {
        pb.move_to(-1.0, -1.0);
        pb.line_to(-0.5, -1.0);
        pb.close();
    }
    pb.finish()
}

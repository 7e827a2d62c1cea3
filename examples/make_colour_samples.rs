//! Draws the colour samples of `samples/` (see samples/README.md): a four-colour logo on
//! transparency with and without anti-aliasing, a 16-colour pixel-art sprite, a chart and a
//! photo-like image. Deterministic (no clock, a fixed xorshift seed); CC0.
//!
//! `cargo run --release --example make_colour_samples [DIR]` (default `samples/`).

use image::{Rgba, RgbaImage};
use std::path::{Path, PathBuf};
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Rect, Transform};

/// The pixmap as straight (not premultiplied) RGBA.
fn to_image(p: &Pixmap) -> RgbaImage {
    RgbaImage::from_fn(p.width(), p.height(), |x, y| {
        let c = p.pixel(x, y).unwrap().demultiply();
        Rgba([c.red(), c.green(), c.blue(), c.alpha()])
    })
}

fn paint(rgb: u32, anti_alias: bool) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(
        (rgb >> 16) as u8,
        (rgb >> 8) as u8,
        rgb as u8,
        255,
    ));
    p.anti_alias = anti_alias;
    p
}

fn circle(cx: f32, cy: f32, r: f32) -> tiny_skia::Path {
    PathBuilder::from_circle(cx, cy, r).unwrap()
}

fn polygon(points: &[(f32, f32)]) -> tiny_skia::Path {
    let mut b = PathBuilder::new();
    b.move_to(points[0].0, points[0].1);
    for &(x, y) in &points[1..] {
        b.line_to(x, y);
    }
    b.close();
    b.finish().unwrap()
}

/// A ring (disc with a hole) of the given radii.
fn ring(cx: f32, cy: f32, outer: f32, inner: f32) -> tiny_skia::Path {
    let mut b = PathBuilder::new();
    b.push_circle(cx, cy, outer);
    b.push_circle(cx, cy, inner);
    b.finish().unwrap()
}

/// Four colours on transparency: a green triangle under a blue ring (touching, and the ring
/// has a hole with a yellow disc inside it, apart from the ring), a red rounded bar over
/// both.
fn logo(anti_alias: bool) -> RgbaImage {
    let mut p = Pixmap::new(160, 120).unwrap();
    let id = Transform::identity();
    let tri = polygon(&[(88.0, 12.0), (154.0, 18.0), (118.0, 78.0)]);
    p.fill_path(
        &tri,
        &paint(0x2e9e44, anti_alias),
        FillRule::Winding,
        id,
        None,
    );
    let r = ring(62.0, 58.0, 44.5, 21.3);
    p.fill_path(
        &r,
        &paint(0x1f4e9c, anti_alias),
        FillRule::EvenOdd,
        id,
        None,
    );
    let mut b = PathBuilder::new();
    b.move_to(92.0, 82.0);
    b.line_to(146.0, 78.0);
    b.quad_to(156.0, 92.0, 146.0, 106.0);
    b.line_to(96.0, 110.0);
    b.quad_to(84.0, 96.0, 92.0, 82.0);
    b.close();
    p.fill_path(
        &b.finish().unwrap(),
        &paint(0xd62828, anti_alias),
        FillRule::Winding,
        id,
        None,
    );
    p.fill_path(
        &circle(62.3, 57.6, 13.7),
        &paint(0xf2c318, anti_alias),
        FillRule::Winding,
        id,
        None,
    );
    to_image(&p)
}

/// A xorshift generator: the samples do not depend on any crate's random numbers.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// Uniform in [-1, 1).
    fn signed(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// A 32 × 32 sprite in the 16 colours of the PICO-8 palette: a symmetric creature with an
/// outline, shading bands, eyes and speckles, on an opaque dark background.
fn sprite() -> RgbaImage {
    const PALETTE: [u32; 16] = [
        0x000000, 0x1d2b53, 0x7e2553, 0x008751, 0xab5236, 0x5f574f, 0xc2c3c7, 0xfff1e8, 0xff004d,
        0xffa300, 0xffec27, 0x00e436, 0x29adff, 0x83769c, 0xff77a8, 0xffccaa,
    ];
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let n = 32usize;
    let mut grid = vec![1usize; n * n];
    let body = |x: f64, y: f64| {
        let (dx, dy) = ((x - 15.5) / 12.0, (y - 17.0) / 13.0);
        dx * dx + dy * dy <= 1.0 || ((x - 15.5).abs() < 3.0 && y < 6.0 && y > 1.0)
    };
    for y in 0..n {
        for x in 0..n / 2 {
            let (fx, fy) = (x as f64, y as f64);
            let c = if body(fx, fy) {
                let edge = [(1, 0), (0, 1), (-1, 0), (0, -1)]
                    .iter()
                    .any(|&(dx, dy)| !body(fx + dx as f64, fy + dy as f64));
                if edge {
                    0
                } else {
                    let band = [3, 11, 12, 13, 14, 9, 10][(y * 7) / n];
                    match rng.next() % 13 {
                        0 => 2,
                        1 => 4,
                        2 => 5,
                        3 => 6,
                        4 => 15,
                        _ => band,
                    }
                }
            } else {
                1
            };
            grid[y * n + x] = c;
            grid[y * n + (n - 1 - x)] = c;
        }
    }
    // Eyes (white with a red pupil) and a mouth.
    for (x, y, c) in [
        (10, 13, 7),
        (11, 13, 7),
        (10, 14, 7),
        (11, 14, 8),
        (20, 13, 7),
        (21, 13, 7),
        (21, 14, 7),
        (20, 14, 8),
        (13, 22, 0),
        (14, 23, 0),
        (15, 23, 0),
        (16, 23, 0),
        (17, 23, 0),
        (18, 22, 0),
    ] {
        grid[y * n + x] = c;
    }
    RgbaImage::from_fn(n as u32, n as u32, |x, y| {
        let c = PALETTE[grid[y as usize * n + x as usize]];
        Rgba([(c >> 16) as u8, (c >> 8) as u8, c as u8, 255])
    })
}

/// A chart on white, anti-aliased: bars in three colours on dark grey axes, and a pie of
/// four slices.
fn chart() -> RgbaImage {
    let mut p = Pixmap::new(200, 140).unwrap();
    p.fill(Color::WHITE);
    let id = Transform::identity();
    let colours = [0x4e79a7, 0xf28e2b, 0x59a14f, 0xe15759];
    for (k, h) in [62.0f32, 95.0, 40.0, 78.0, 55.0].iter().enumerate() {
        let x = 14.0 + 18.0 * k as f32;
        let r = Rect::from_xywh(x, 120.0 - h, 12.5, *h).unwrap();
        p.fill_rect(r, &paint(colours[k % 3], true), id, None);
    }
    let axis = paint(0x333333, true);
    p.fill_rect(
        Rect::from_xywh(8.0, 120.0, 98.0, 1.5).unwrap(),
        &axis,
        id,
        None,
    );
    p.fill_rect(
        Rect::from_xywh(8.0, 16.0, 1.5, 105.5).unwrap(),
        &axis,
        id,
        None,
    );
    let (cx, cy, r) = (152.0f32, 70.0f32, 38.0f32);
    let mut start = -std::f32::consts::FRAC_PI_2;
    for (k, share) in [0.38f32, 0.27, 0.2, 0.15].iter().enumerate() {
        let end = start + share * std::f32::consts::TAU;
        let mut b = PathBuilder::new();
        b.move_to(cx, cy);
        let steps = 48;
        for i in 0..=steps {
            let a = start + (end - start) * i as f32 / steps as f32;
            b.line_to(cx + r * a.cos(), cy + r * a.sin());
        }
        b.close();
        p.fill_path(
            &b.finish().unwrap(),
            &paint(colours[k], true),
            FillRule::Winding,
            id,
            None,
        );
        start = end;
    }
    to_image(&p)
}

/// A photograph-like image: a sky gradient, a hill with a shaded gradient, a soft sun, a
/// house, and noise on every pixel.
fn photo_like() -> RgbaImage {
    let (w, h) = (128u32, 96u32);
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    RgbaImage::from_fn(w, h, |x, y| {
        let (fx, fy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
        let t = fy / f64::from(h);
        let mut c = [70.0 + 120.0 * t, 130.0 + 90.0 * t, 220.0 - 20.0 * t];
        let sun = ((fx - 98.0).powi(2) + (fy - 22.0).powi(2)).sqrt();
        let glow = (1.0 - (sun - 9.0) / 6.0).clamp(0.0, 1.0);
        for (v, s) in c.iter_mut().zip([255.0, 230.0, 120.0]) {
            *v += (s - *v) * glow;
        }
        let hill = 62.0 + 12.0 * (fx / 21.0).sin() + 6.0 * (fx / 7.0).cos();
        if fy > hill {
            let d = ((fy - hill) / 30.0).min(1.0);
            c = [60.0 + 40.0 * d, 150.0 - 60.0 * d, 50.0 + 10.0 * d];
        }
        if (24.0..52.0).contains(&fx) && (50.0..74.0).contains(&fy) {
            c = [190.0 - (fx - 24.0), 50.0, 40.0];
        }
        let roof = 50.0 - (14.0 - (fx - 38.0).abs()) * 0.8;
        if (22.0..54.0).contains(&fx) && fy < 50.0 && fy >= roof {
            c = [90.0, 60.0, 40.0];
        }
        let n = 12.0;
        let px = c.map(|v| (v + n * rng.signed()).round().clamp(0.0, 255.0) as u8);
        Rgba([px[0], px[1], px[2], 255])
    })
}

fn main() {
    let dir = std::env::args()
        .nth(1)
        .map_or_else(|| PathBuf::from("samples"), PathBuf::from);
    let save = |name: &str, img: &RgbaImage| {
        let path = Path::new(&dir).join(name);
        img.save(&path)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        println!("{}", path.display());
    };
    save("colour_logo_aa.png", &logo(true));
    save("colour_logo_crisp.png", &logo(false));
    save("colour_sprite_pico8_32.png", &sprite());
    save("colour_chart_aa.png", &chart());
    save("colour_photo_like.png", &photo_like());
}

//! A zoomed picture of an SVG over its input, to look at what layertrace draws:
//! `cargo run --release --example zoom -- INPUT.png OUTPUT.svg PICTURE.png [X Y W H [SCALE]]`.
//!
//! The input's foreground pixels are light grey squares, the SVG is filled translucent blue
//! as resvg draws it without anti-aliasing (crispEdges: the pixels a user gets), and its
//! outline is stroked in red, anti-aliased at the zoom, so stairs and curves show.

use layertrace::{load_path, LoadOptions};
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 4 {
        return Err("usage: zoom INPUT.png OUTPUT.svg PICTURE.png [X Y W H [SCALE]]".into());
    }
    let mask = load_path(&PathBuf::from(&args[1]), &LoadOptions::default())?.mask;
    let svg = std::fs::read_to_string(&args[2])?;
    let num = |i: usize, d: f32| -> f32 { args.get(i).and_then(|s| s.parse().ok()).unwrap_or(d) };
    let (x0, y0) = (num(4, 0.0), num(5, 0.0));
    let (w, h) = (
        num(6, mask.width() as f32 - x0),
        num(7, mask.height() as f32 - y0),
    );
    // Clamped to the image.
    let (x0, y0) = (
        x0.clamp(0.0, mask.width() as f32),
        y0.clamp(0.0, mask.height() as f32),
    );
    let (w, h) = (
        w.clamp(1.0, mask.width() as f32 - x0),
        h.clamp(1.0, mask.height() as f32 - y0),
    );
    let k = num(8, 4.0);
    let (pw, ph) = ((w * k).ceil() as u32, (h * k).ceil() as u32);
    let mut pix = tiny_skia::Pixmap::new(pw, ph).ok_or("picture too large")?;
    pix.fill(tiny_skia::Color::WHITE);
    let mut grey = tiny_skia::Paint::default();
    grey.set_color_rgba8(200, 200, 200, 255);
    for y in y0 as i64..(y0 + h) as i64 {
        for x in x0 as i64..(x0 + w) as i64 {
            if mask.get(x, y) {
                let r = tiny_skia::Rect::from_xywh(
                    (x as f32 - x0) * k,
                    (y as f32 - y0) * k,
                    k - 1.0,
                    k - 1.0,
                );
                if let Some(r) = r {
                    pix.fill_rect(r, &grey, tiny_skia::Transform::identity(), None);
                }
            }
        }
    }
    let opts = usvg::Options {
        shape_rendering: usvg::ShapeRendering::CrispEdges,
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(&svg, &opts)?;
    // The pixels resvg paints at 1:1, scaled up as blocks.
    let mut one = tiny_skia::Pixmap::new(mask.width(), mask.height()).ok_or("size")?;
    resvg::render(&tree, tiny_skia::Transform::identity(), &mut one.as_mut());
    let mut blue = tiny_skia::Paint::default();
    blue.set_color_rgba8(40, 90, 230, 90);
    for y in y0 as u32..(y0 + h) as u32 {
        for x in x0 as u32..(x0 + w) as u32 {
            if one.pixel(x, y).is_some_and(|p| p.alpha() > 0) {
                if let Some(r) =
                    tiny_skia::Rect::from_xywh((x as f32 - x0) * k, (y as f32 - y0) * k, k, k)
                {
                    pix.fill_rect(r, &blue, tiny_skia::Transform::identity(), None);
                }
            }
        }
    }
    let ts = tiny_skia::Transform::from_row(k, 0.0, 0.0, k, -x0 * k, -y0 * k);
    let mut red = tiny_skia::Paint::default();
    red.set_color_rgba8(220, 20, 20, 255);
    red.anti_alias = true;
    let stroke = tiny_skia::Stroke {
        width: 1.5 / k,
        ..tiny_skia::Stroke::default()
    };
    fn walk(g: &usvg::Group, f: &mut dyn FnMut(&usvg::Path)) {
        for n in g.children() {
            match n {
                usvg::Node::Path(p) => f(p),
                usvg::Node::Group(g) => walk(g, f),
                _ => {}
            }
        }
    }
    walk(tree.root(), &mut |p| {
        pix.stroke_path(p.data(), &red, &stroke, ts, None);
    });
    pix.save_png(&args[3])?;
    Ok(())
}

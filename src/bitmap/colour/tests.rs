//! Tests of the colour regions: exact palettes, quantization bounds, transparency.

use super::*;
use image::Rgba;
use proptest::prelude::*;

fn image_of(w: u32, h: u32, px: &[[u8; 4]]) -> RgbaImage {
    RgbaImage::from_fn(w, h, |x, y| Rgba(px[(y * w + x) as usize]))
}

#[test]
fn transparency_and_the_alpha_mask() {
    let px = [
        [255, 255, 255, 255],
        [255, 255, 255, 0],
        [255, 255, 255, 127],
        [10, 20, 30, 128],
    ];
    let img = image_of(2, 2, &px);
    let r = colour_regions(&img, 4);
    assert!(r.exact);
    // Equal counts: ordered by value, (10, 20, 30) first.
    assert_eq!(r.image.get(0, 0), Some(1));
    assert_eq!(r.image.colour(0, 0), Some(Colour::new(255, 255, 255)));
    assert_eq!((r.image.get(1, 0), r.image.get(0, 1)), (None, None));
    assert_eq!(r.image.colour(1, 1), Some(Colour::new(10, 20, 30)));
    assert_eq!(r.image.counts(), vec![1, 1]);
    assert_eq!(alpha_mask(&img).to_ascii(), "#.\n.#\n");
    assert!(has_transparency(&img));
    assert_eq!(Colour::new(255, 8, 170).to_string(), "#ff08aa");
}

#[test]
fn decoding_errors_are_errors() {
    let e = decode_rgba(b"not an image at all", Path::new("x"), 100, 1 << 30).unwrap_err();
    assert!(!e.to_string().contains('\n'));
    assert!(decode_rgba(b"", Path::new("x"), 100, 1 << 30).is_err());
    let img = image_of(3, 3, &[[1, 2, 3, 255]; 9]);
    let mut bytes = Cursor::new(Vec::new());
    img.write_to(&mut bytes, image::ImageFormat::Png).unwrap();
    let bytes = bytes.into_inner();
    assert_eq!(
        decode_rgba(&bytes, Path::new("x"), 9, 1 << 30).unwrap(),
        img
    );
    assert!(matches!(
        decode_rgba(&bytes, Path::new("x"), 8, 1 << 30),
        Err(Error::TooLarge { .. })
    ));
}

fn small_image(max_colours: usize) -> impl Strategy<Value = RgbaImage> {
    (1u32..12, 1u32..12).prop_flat_map(move |(w, h)| {
        let colours = prop::collection::vec(any::<[u8; 4]>(), 1..=max_colours);
        (
            colours,
            prop::collection::vec(any::<prop::sample::Index>(), (w * h) as usize),
        )
            .prop_map(move |(colours, picks)| {
                let px: Vec<[u8; 4]> = picks
                    .iter()
                    .map(|i| colours[i.index(colours.len())])
                    .collect();
                image_of(w, h, &px)
            })
    })
}

proptest! {
    /// With at most N distinct colours, every opaque pixel keeps its colour exactly and
    /// every other pixel is in no region.
    #[test]
    fn few_colours_are_kept_exactly(img in small_image(6)) {
        let r = colour_regions(&img, 6);
        prop_assert!(r.exact);
        prop_assert_eq!(r.fringe, 0);
        for (x, y, p) in img.enumerate_pixels() {
            let got = r.image.colour(i64::from(x), i64::from(y));
            let want = (p[3] >= OPAQUE_ALPHA).then(|| Colour::new(p[0], p[1], p[2]));
            prop_assert_eq!(got, want);
        }
        // Ordered by decreasing pixel count.
        let counts = r.image.counts();
        prop_assert!(counts.windows(2).all(|w| w[0] >= w[1]));
        prop_assert!(counts.iter().all(|&n| n > 0));
    }

    /// Quantized: at most N colours, every one used, the same pixels opaque.
    #[test]
    fn quantized_within_n(img in small_image(40), n in 1u16..6) {
        let r = colour_regions(&img, n);
        prop_assert!(r.image.palette().len() <= usize::from(n));
        prop_assert!(r.image.counts().iter().all(|&k| k > 0));
        let opaque = r.image.mask_where(|_| true);
        prop_assert_eq!(opaque, alpha_mask(&img));
    }
}

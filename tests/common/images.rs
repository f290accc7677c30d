//! The one image comparison of the tests: per-pixel differences (the largest channel difference),
//! the worst pixel, the pixels beyond a threshold; failures name the worst pixel with both values
//! and write both images (via `save_failure`).

use std::fmt::{Debug, Display};

/// The largest channel difference of two pixels given as channel slices of one length.
pub fn channel_difference(a: &[f32], b: &[f32]) -> f32 {
    assert_eq!(a.len(), b.len(), "pixels of different channel counts");
    let differences = a.iter().zip(b).map(|(a, b)| (a - b).abs());
    differences.fold(0.0, f32::max)
}

/// The largest f32 not above `t`: an f32 difference exceeds it exactly when it exceeds `t` (for
/// tolerances of comparisons made in f64).
pub fn f32_at_most(t: f64) -> f32 {
    let rounded = t as f32;
    if f64::from(rounded) > t {
        rounded.next_down()
    } else {
        rounded
    }
}

/// A pixel the comparison reads: f32 channels as they are, u8 channels in 1/255 steps.
pub trait Pixel: Copy + Debug {
    /// The largest channel difference from `other`.
    fn difference(self, other: Self) -> f32;
    /// The pixel as RGBA8, for a written failure image (one channel: grey; no alpha: opaque).
    fn rgba8(self) -> [u8; 4];
}

fn rgba8_of(channels: &[u8]) -> [u8; 4] {
    match channels {
        [v] => [*v, *v, *v, 255],
        _ => [0, 1, 2, 3].map(|c| {
            channels
                .get(c)
                .copied()
                .unwrap_or(if c == 3 { 255 } else { 0 })
        }),
    }
}

impl<const N: usize> Pixel for [f32; N] {
    fn difference(self, other: Self) -> f32 {
        channel_difference(&self, &other)
    }
    fn rgba8(self) -> [u8; 4] {
        rgba8_of(&self.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8))
    }
}

impl Pixel for f32 {
    fn difference(self, other: Self) -> f32 {
        [self].difference([other])
    }
    fn rgba8(self) -> [u8; 4] {
        [self].rgba8()
    }
}

impl<const N: usize> Pixel for [u8; N] {
    fn difference(self, other: Self) -> f32 {
        let differences = self.iter().zip(other).map(|(a, b)| a.abs_diff(b));
        differences.max().map_or(0.0, f32::from)
    }
    fn rgba8(self) -> [u8; 4] {
        rgba8_of(&self)
    }
}

impl Pixel for u8 {
    fn difference(self, other: Self) -> f32 {
        [self].difference([other])
    }
    fn rgba8(self) -> [u8; 4] {
        [self].rgba8()
    }
}

/// A value compared bit for bit: any difference in its bits counts, −0 against 0 and NaNs too
/// (as at least the smallest normal float).
#[derive(Clone, Copy, Debug)]
pub struct Exact(pub f32);

impl Pixel for Exact {
    fn difference(self, other: Self) -> f32 {
        if self.0.to_bits() == other.0.to_bits() {
            0.0
        } else {
            self.0.difference(other.0).max(f32::MIN_POSITIVE)
        }
    }
    fn rgba8(self) -> [u8; 4] {
        self.0.rgba8()
    }
}

/// The pixels of an RGBA8 picture, row by row.
pub fn rgba8_pixels(picture: &image::RgbaImage) -> Vec<[u8; 4]> {
    picture.pixels().map(|p| p.0).collect()
}

/// The pixels of a read-back texture of four channels, row by row.
pub fn texels(texture: &hatchery_gpu::TextureData) -> Vec<[f32; 4]> {
    assert_eq!(texture.channels, 4, "a texture of four channels");
    let texels = texture.data.chunks_exact(4);
    texels.map(|c| [c[0], c[1], c[2], c[3]]).collect()
}

/// How two images of one size differ over the compared pixels.
#[derive(Debug)]
pub struct ImageDiff {
    /// The largest difference (0 when nothing differs) and its pixel: the first in row order.
    pub worst: f32,
    pub index: usize,
    pub x: u32,
    pub y: u32,
    /// The compared pixels whose difference exceeds the threshold, in row order.
    pub over: Vec<usize>,
    /// How many pixels were compared, and the sum of their differences.
    pub compared: usize,
    pub sum: f64,
    pub width: u32,
}

impl ImageDiff {
    /// Fails with `why`, naming the worst pixel with both values; writes both images first.
    pub fn fail<P: Pixel>(&self, name: &str, got: &[P], want: &[P], why: impl Display) -> ! {
        let picture = |pixels: &[P]| {
            let height = (pixels.len() / self.width as usize) as u32;
            image::RgbaImage::from_fn(self.width, height, |x, y| {
                image::Rgba(pixels[(y * self.width + x) as usize].rgba8())
            })
        };
        let got_path = super::save_failure(&format!("{name}_got"), &picture(got));
        let want_path = super::save_failure(&format!("{name}_want"), &picture(want));
        let at = |pixels: &[P]| match pixels.get(self.index) {
            Some(p) => format!("{p:?}"),
            None => "nothing".to_owned(),
        };
        panic!(
            "{name}: {why}; worst pixel ({}, {}) differs by {}: got {}, want {}; images \
             written to {} and {}",
            self.x,
            self.y,
            self.worst,
            at(got),
            at(want),
            got_path.display(),
            want_path.display()
        );
    }
}

/// Compares the pixels `which` selects (by index, row order) of two images `width` pixels
/// wide, counting those that differ by more than `threshold`.
pub fn diff_images<P: Pixel>(
    got: &[P],
    want: &[P],
    width: u32,
    which: impl Fn(usize) -> bool,
    threshold: f32,
) -> ImageDiff {
    assert_eq!(got.len(), want.len(), "images of different sizes");
    assert!(
        width > 0 && got.len().is_multiple_of(width as usize),
        "{} pixels are no whole rows of {width}",
        got.len()
    );
    let mut diff = ImageDiff {
        worst: 0.0,
        index: 0,
        x: 0,
        y: 0,
        over: Vec::new(),
        compared: 0,
        sum: 0.0,
        width,
    };
    for i in (0..got.len()).filter(|&i| which(i)) {
        let d = got[i].difference(want[i]);
        diff.compared += 1;
        diff.sum += f64::from(d);
        if d > threshold {
            diff.over.push(i);
        }
        if d > diff.worst {
            (diff.worst, diff.index) = (d, i);
        }
    }
    diff.x = (diff.index % width as usize) as u32;
    diff.y = (diff.index / width as usize) as u32;
    diff
}

/// Fails unless every pixel is within `tolerance`.
pub fn assert_images_close<P: Pixel>(
    name: &str,
    got: &[P],
    want: &[P],
    width: u32,
    tolerance: f32,
) {
    assert_images_close_where(name, got, want, width, tolerance, |_| true);
}

/// Fails unless the pixels `which` selects (at least one) are within `tolerance`.
pub fn assert_images_close_where<P: Pixel>(
    name: &str,
    got: &[P],
    want: &[P],
    width: u32,
    tolerance: f32,
    which: impl Fn(usize) -> bool,
) {
    let diff = diff_images(got, want, width, which, tolerance);
    assert!(diff.compared > 0, "{name}: no pixels compared");
    if !diff.over.is_empty() {
        let why = format!(
            "{} of {} pixels differ by more than {tolerance}",
            diff.over.len(),
            diff.compared
        );
        diff.fail(name, got, want, why);
    }
}

/// The largest channel difference between two RGBA8 pictures of one size, and where:
/// (difference, x, y).
pub fn worst_channel(a: &image::RgbaImage, b: &image::RgbaImage) -> (u8, u32, u32) {
    assert_eq!(
        a.dimensions(),
        b.dimensions(),
        "pictures of different sizes"
    );
    let diff = diff_images(&rgba8_pixels(a), &rgba8_pixels(b), a.width(), |_| true, 0.0);
    (diff.worst as u8, diff.x, diff.y)
}

/// Fails unless two images of single values, `width` values a row (pixels × channels), are bit
/// for bit equal.
pub fn assert_images_identical(name: &str, got: &[f32], want: &[f32], width: u32) {
    let exact = |values: &[f32]| values.iter().map(|&v| Exact(v)).collect::<Vec<_>>();
    assert_images_close(name, &exact(got), &exact(want), width, 0.0);
}

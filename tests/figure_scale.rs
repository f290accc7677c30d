//! Resolution-independent figures (issue 24, item 6): `hatchery render --scale 2` is the figure
//! designed at `--size` rendered at twice the resolution — hatching cells, line widths, label
//! sizes and the layout's spacing all in pixels of the designed figure — so, brought back to the
//! design size, it is the 1× picture.
//!
//! The comparison: the 2× picture averaged over 2×2 blocks, both pictures then seen through a
//! Gaussian blur of σ = 1.5 design pixels (a binary halftone and a box-filtered one differ at
//! every ink edge; the blur compares the tone and where the lines are, not the anti-aliasing).
//! Tolerance: mean luminance within 1/255 and a mean channel difference under 3.5/255, 6.5/255 for
//! hatching strokes (measured at 400×300: default.ron 2.6/255, tone 0.04/255; pip_styles 0.6/255;
//! hatching_brain 5.2/255, tone 0.13/255 — its strokes start at the same mesh vertices but are
//! integrated through a curvature field sampled at the render's pixels). The same render at 2×
//! size without `--scale` (patterns sized in output pixels: the complaint) is 8.5, 2.6 and
//! 19.7/255 away, and the test asks for at least twice the scaled render's difference.

mod common;

use image::RgbaImage;
use std::path::{Path, PathBuf};

const SIZE: (u32, u32) = (400, 300);
const TONE_LIMIT: f64 = 1.0;

/// Renders `graph` with `-o dir/name.png` (the SVG beside it when the graph has a SaveSvg).
fn render(graph: &str, dir: &Path, name: &str, size: (u32, u32), scale: f64) -> PathBuf {
    let png = dir.join(format!("{name}.png"));
    let out = common::hatchery(&[
        "render",
        graph,
        "-o",
        png.to_str().unwrap(),
        "--size",
        &format!("{}x{}", size.0, size.1),
        "--scale",
        &scale.to_string(),
    ]);
    assert!(
        out.status.success(),
        "hatchery render {graph} --scale {scale} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    png
}

/// Mean of each 2×2 block (straight alpha over white, as the figure is seen on paper).
fn halve(picture: &RgbaImage) -> RgbaImage {
    let (w, h) = (picture.width() / 2, picture.height() / 2);
    RgbaImage::from_fn(w, h, |x, y| {
        let mut sum = [0f64; 4];
        for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let p = on_paper(picture.get_pixel(2 * x + dx, 2 * y + dy));
            for c in 0..4 {
                sum[c] += p[c] as f64;
            }
        }
        image::Rgba(sum.map(|s| (s / 4.0).round() as u8))
    })
}

fn on_paper(p: &image::Rgba<u8>) -> [u8; 4] {
    let a = p[3] as f64 / 255.0;
    let over = |c: u8| (c as f64 * a + 255.0 * (1.0 - a)).round() as u8;
    [over(p[0]), over(p[1]), over(p[2]), 255]
}

/// (mean channel difference, mean luminance difference), /255, after the blur.
fn compare(a: &RgbaImage, b: &RgbaImage) -> (f64, f64) {
    assert_eq!(a.dimensions(), b.dimensions());
    let paper = |p: &RgbaImage| {
        RgbaImage::from_fn(p.width(), p.height(), |x, y| {
            image::Rgba(on_paper(p.get_pixel(x, y)))
        })
    };
    let (a, b) = (
        image::imageops::blur(&paper(a), 1.5),
        image::imageops::blur(&paper(b), 1.5),
    );
    let n = (a.width() * a.height()) as f64;
    let (mut diff, mut tone) = (0.0, 0.0);
    for (p, q) in a.pixels().zip(b.pixels()) {
        for c in 0..3 {
            diff += (p[c] as f64 - q[c] as f64).abs();
            tone += p[c] as f64 - q[c] as f64;
        }
    }
    (diff / (3.0 * n), (tone / (3.0 * n)).abs())
}

fn check(graph: &str, mean_limit: f64) {
    let dir = tempfile::tempdir().unwrap();
    let one = common::read_png(&render(graph, dir.path(), "one", SIZE, 1.0));
    let two = common::read_png(&render(graph, dir.path(), "two", SIZE, 2.0));
    assert_eq!(
        two.dimensions(),
        (2 * SIZE.0, 2 * SIZE.1),
        "--scale 2 doubles the frame"
    );
    let naive = common::read_png(&render(
        graph,
        dir.path(),
        "naive",
        (2 * SIZE.0, 2 * SIZE.1),
        1.0,
    ));
    let (mean, tone) = compare(&one, &halve(&two));
    let (naive_mean, _) = compare(&one, &halve(&naive));
    println!(
        "{graph}: --scale 2 vs 1x: mean {mean:.2}/255, tone {tone:.2}/255; 2x size unscaled: \
         mean {naive_mean:.2}/255"
    );
    if mean > mean_limit || tone > TONE_LIMIT {
        let saved = common::save_failure(&format!("figure_scale_{graph}_2x"), &two);
        panic!(
            "{graph}: --scale 2 brought to 1x is {mean:.2}/255 from the 1x figure (tone \
             {tone:.2}/255; limits {mean_limit}, {TONE_LIMIT}); the 2x picture: {}",
            saved.display()
        );
    }
    assert!(
        naive_mean > 2.0 * mean,
        "{graph}: rendering at 2x size without --scale ({naive_mean:.2}/255) should differ \
         from the figure clearly more than --scale 2 ({mean:.2}/255)"
    );
}

#[test]
fn scale_two_is_the_designed_figure_at_twice_the_resolution() {
    // Halftone, silhouettes, hidden lines and labels with their layout.
    check("graphs/default.ron", 3.5);
}

/// Every `name="number"` attribute of an SVG file, in order.
fn numbers(svg: &Path, name: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(svg).unwrap();
    let key = format!("{name}=\"");
    text.split(&key)
        .skip(1)
        .filter_map(|rest| rest.split('"').next()?.parse().ok())
        .collect()
}

#[test]
fn scale_two_doubles_the_svg_lengths() {
    // default.ron writes its SVG beside the PNG: line widths and label sizes double.
    let dir = tempfile::tempdir().unwrap();
    let one = render("graphs/default.ron", dir.path(), "one", SIZE, 1.0).with_extension("svg");
    let two = render("graphs/default.ron", dir.path(), "two", SIZE, 2.0).with_extension("svg");
    for name in ["stroke-width", "font-size"] {
        let (a, b) = (numbers(&one, name), numbers(&two, name));
        assert!(!a.is_empty(), "{}: no {name} in the SVG", one.display());
        let doubled: Vec<f64> = a.iter().map(|v| 2.0 * v).collect();
        assert!(
            doubled.len() == b.len() && doubled.iter().zip(&b).all(|(x, y)| (x - y).abs() < 2e-3),
            "{name}: 1x {a:?}, --scale 2 {b:?}"
        );
    }
}

#[test]
fn scale_two_keeps_perturbed_silhouettes() {
    check("graphs/pip_styles.ron", 3.5);
}

#[test]
fn scale_two_keeps_hatching_strokes() {
    // The MNI T1 from ../shared/data.
    check("graphs/hatching_brain.ron", 6.5);
}

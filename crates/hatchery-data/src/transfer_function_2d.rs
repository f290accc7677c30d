//! Two-dimensional transfer functions (Kniss et al. 2002, as extended by Svakhine, Jang, Ebert &
//! Gaither 2005 §3.3): colour and opacity over the data value × a second coordinate — the
//! gradient magnitude (a fraction of the volume's largest) or the Laplacian (data units per
//! voxel², second differences in voxel space) — drawn by widgets (rectangles and Kniss's
//! triangles) and baked into a [`LUT_SIZE`] × [`ROWS`] table.
//!
//! Widgets are written as text, entries separated by `;` or newlines:
//!
//! - `rect V0..V1 x S0..S1: r g b a` — constant colour and opacity for values in [V0, V1] and
//!   second coordinates in [S0, S1];
//! - `tri C x S0..S1 width W: r g b a` — Kniss's triangle: apex at value C and second coordinate
//!   S0, widening linearly to W (data units) at S1; the opacity falls linearly from `a` at the
//!   centre line to 0 at the edges, so a boundary's arc in value × gradient magnitude is
//!   selected where it is steep.
//!
//! Where widgets overlap the opacity is the largest of theirs and the colour their
//! opacity-weighted mean; where none is, the entry is (0, 0, 0, 0). Colours are straight (not
//! premultiplied), as in [`crate::transfer_function::TransferFunction1D`].

use crate::DataError;
use crate::transfer_function::{LUT_SIZE, lut_position};
use crate::volume::VolumeData;
use glam::Vec3;

/// Rows of the table (positions along the second axis).
pub const ROWS: usize = LUT_SIZE;

/// What the second coordinate is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SecondAxis {
    /// |∇f| divided by the volume's largest gradient magnitude, in [0, 1].
    GradientMagnitude,
    /// ∇²f by second differences in voxel space (data units per voxel²).
    Laplacian,
    /// The value of a second scalar field on the same grid (its data units; Svakhine et al.
    /// 2005 §3.3's U₂: another simulation variable, or a vector field's |U| or |∇×U|).
    SecondField,
}

/// The shape of a widget.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// `value` × `second` ranges.
    Rect { value: [f32; 2], second: [f32; 2] },
    /// Apex at (`center`, `second[0]`), `width` wide at `second[1]`.
    Tri {
        center: f32,
        second: [f32; 2],
        width: f32,
    },
}

/// One widget: a shape and its straight colour and opacity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Widget {
    pub shape: Shape,
    pub rgba: [f32; 4],
}

impl Widget {
    /// The widget's opacity at (v, s) (0 outside it).
    pub fn opacity(&self, v: f32, s: f32) -> f32 {
        match self.shape {
            Shape::Rect { value, second } => {
                let inside =
                    (value[0]..=value[1]).contains(&v) && (second[0]..=second[1]).contains(&s);
                if inside { self.rgba[3] } else { 0.0 }
            }
            Shape::Tri {
                center,
                second,
                width,
            } => {
                if !(second[0]..=second[1]).contains(&s) || second[1] <= second[0] {
                    return 0.0;
                }
                let half = 0.5 * width * (s - second[0]) / (second[1] - second[0]);
                let d = (v - center).abs();
                if half > 0.0 && d <= half {
                    self.rgba[3] * (1.0 - d / half)
                } else {
                    0.0
                }
            }
        }
    }
}

fn range(text: &str, what: &str) -> Result<[f32; 2], String> {
    let (a, b) = text
        .split_once("..")
        .ok_or_else(|| format!("{what} `{text}` is not a range A..B"))?;
    let a = number(a, what)?;
    let b = number(b, what)?;
    if b < a {
        return Err(format!("{what} `{text}` runs backwards"));
    }
    Ok([a, b])
}

fn number(text: &str, what: &str) -> Result<f32, String> {
    let x: f32 = text
        .trim()
        .parse()
        .map_err(|_| format!("{what}: `{}` is not a number", text.trim()))?;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("{what}: `{x}` is not finite"))
    }
}

fn parse_widget(entry: &str) -> Result<Widget, String> {
    let (shape, colour) = entry
        .split_once(':')
        .ok_or("no `:` before the colour `r g b a`")?;
    let rgba: Vec<f32> = colour
        .split(|c: char| c.is_whitespace() || c == ',')
        .filter(|s| !s.is_empty())
        .map(|s| number(s, "colour"))
        .collect::<Result<_, _>>()?;
    let rgba: [f32; 4] = rgba
        .try_into()
        .map_err(|v: Vec<f32>| format!("colour has {} numbers, not 4 (r g b a)", v.len()))?;
    if rgba.iter().any(|c| !(0.0..=1.0).contains(c)) {
        return Err("colour channels must lie in [0, 1]".into());
    }
    let words: Vec<&str> = shape.split_whitespace().collect();
    let shape = match words.as_slice() {
        ["rect", v, "x", s] => Shape::Rect {
            value: range(v, "value range")?,
            second: range(s, "second range")?,
        },
        ["tri", c, "x", s, "width", w] => {
            let width = number(w, "width")?;
            if width <= 0.0 {
                return Err("width must be positive".into());
            }
            Shape::Tri {
                center: number(c, "centre")?,
                second: range(s, "second range")?,
                width,
            }
        }
        _ => {
            return Err("expected `rect V0..V1 x S0..S1: r g b a` or \
                        `tri C x S0..S1 width W: r g b a`"
                .into());
        }
    };
    Ok(Widget { shape, rgba })
}

/// Parses widgets text (see the module documentation); an error names the widget (its number,
/// from 1, and its text).
pub fn parse_widgets(text: &str) -> Result<Vec<Widget>, DataError> {
    let entries = text
        .split([';', '\n'])
        .map(str::trim)
        .filter(|e| !e.is_empty());
    let mut widgets = Vec::new();
    for (n, entry) in entries.enumerate() {
        let w = parse_widget(entry)
            .map_err(|e| DataError::Invalid(format!("widget {} (`{entry}`): {e}", n + 1)))?;
        widgets.push(w);
    }
    if widgets.is_empty() {
        return Err(DataError::Invalid("no widgets given".into()));
    }
    Ok(widgets)
}

/// A baked 2-D transfer function.
#[derive(Debug, Clone, PartialEq)]
pub struct TransferFunction2D {
    pub axis: SecondAxis,
    /// Data values of the first and last columns.
    pub domain: [f32; 2],
    /// Second coordinates of the first and last rows.
    pub second_domain: [f32; 2],
    /// [`LUT_SIZE`] × [`ROWS`] entries, row-major: entry `j·LUT_SIZE + i` at value
    /// `domain[0] + i/(LUT_SIZE−1)·span` and second coordinate `second_domain[0] + j/(ROWS−1)·span`.
    pub table: Vec<[f32; 4]>,
}

impl TransferFunction2D {
    /// Bakes `widgets` over the domains (each must have `hi > lo`).
    pub fn new(
        axis: SecondAxis,
        domain: [f32; 2],
        second_domain: [f32; 2],
        widgets: &[Widget],
    ) -> Result<Self, DataError> {
        for (what, d) in [("value domain", domain), ("second domain", second_domain)] {
            if !(d[0].is_finite() && d[1].is_finite() && d[1] > d[0]) {
                return Err(DataError::Invalid(format!(
                    "{what} {}..{} is empty: it needs max > min",
                    d[0], d[1]
                )));
            }
        }
        let at = |d: [f32; 2], k: usize, n: usize| d[0] + k as f32 / (n - 1) as f32 * (d[1] - d[0]);
        let mut table = Vec::with_capacity(LUT_SIZE * ROWS);
        for j in 0..ROWS {
            let s = at(second_domain, j, ROWS);
            for i in 0..LUT_SIZE {
                let v = at(domain, i, LUT_SIZE);
                let (mut alpha, mut weight, mut rgb) = (0.0f32, 0.0f32, [0.0f32; 3]);
                for w in widgets {
                    let a = w.opacity(v, s);
                    if a > 0.0 {
                        alpha = alpha.max(a);
                        weight += a;
                        for (sum, c) in rgb.iter_mut().zip(w.rgba) {
                            *sum += a * c;
                        }
                    }
                }
                table.push(if weight > 0.0 {
                    [rgb[0] / weight, rgb[1] / weight, rgb[2] / weight, alpha]
                } else {
                    [0.0; 4]
                });
            }
        }
        Ok(Self {
            axis,
            domain,
            second_domain,
            table,
        })
    }

    /// The table's entry at (v, s): bilinear between entries, each coordinate by the rule of
    /// [`crate::transfer_function::TransferFunction1D::lookup`] (clamped to its domain). The
    /// ray caster's `table2d_lookup` does the same.
    pub fn lookup(&self, v: f32, s: f32) -> [f32; 4] {
        let (i, fi) = lut_position(self.domain, v);
        // ROWS = LUT_SIZE: the rows follow the same rule.
        let (j, fj) = lut_position(self.second_domain, s);
        let e = |i: usize, j: usize| self.table[j * LUT_SIZE + i];
        let lerp = |a: [f32; 4], b: [f32; 4], f: f32| -> [f32; 4] {
            std::array::from_fn(|c| a[c] + (b[c] - a[c]) * f)
        };
        lerp(
            lerp(e(i, j), e(i + 1, j), fi),
            lerp(e(i, j + 1), e(i + 1, j + 1), fi),
            fj,
        )
    }

    /// The largest opacity of each column over all rows: a 1-D opacity row for empty-space
    /// skipping (a value is visible when any second coordinate makes it so; exact, since the
    /// lookup interpolates between columns as a 1-D table does).
    pub fn max_opacity_per_value(&self) -> Vec<f32> {
        (0..LUT_SIZE)
            .map(|i| {
                (0..ROWS)
                    .map(|j| self.table[j * LUT_SIZE + i][3])
                    .fold(0.0, f32::max)
            })
            .collect()
    }
}

/// ∇²f at a voxel-space position by second differences of trilinear samples one voxel either
/// side along each axis, in data units per voxel² (no spacing): Σ f(q+e) − 2f(q) + f(q−e). At
/// the grid's border the missing neighbour is the (clamped) sample itself; an axis with "no
/// data" on either side adds 0. The ray caster's `laplacian_at` does the same.
pub fn laplacian(volume: &VolumeData, voxel: Vec3) -> f32 {
    let max = volume.max_voxel();
    let p = voxel.clamp(Vec3::ZERO, max);
    let centre = volume.sample_trilinear(p);
    if !centre.is_finite() {
        return 0.0;
    }
    let mut sum = 0.0;
    for axis in 0..3 {
        let mut lo = p;
        let mut hi = p;
        lo[axis] = (p[axis] - 1.0).max(0.0);
        hi[axis] = (p[axis] + 1.0).min(max[axis]);
        let (a, b) = (volume.sample_trilinear(lo), volume.sample_trilinear(hi));
        if a.is_finite() && b.is_finite() {
            sum += b - 2.0 * centre + a;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_rects_and_triangles_and_names_the_bad_widget() {
        let w = parse_widgets(
            "rect 80..140 x 0.1..1: 0.9 0.8 0.7 0.6; tri 110 x 0..1 width 30: 1 0.5 0.2 0.9",
        )
        .unwrap();
        assert_eq!(w.len(), 2);
        assert_eq!(
            w[0].shape,
            Shape::Rect {
                value: [80.0, 140.0],
                second: [0.1, 1.0]
            }
        );
        assert_eq!(
            w[1].shape,
            Shape::Tri {
                center: 110.0,
                second: [0.0, 1.0],
                width: 30.0
            }
        );
        let e = parse_widgets("rect 1..2 x 0..1: 1 1 1 1; tri 5 x 0..1 width: 1 1 1 1")
            .unwrap_err()
            .to_string();
        assert!(e.contains("widget 2") && e.contains("tri 5"), "{e}");
        let e = parse_widgets("rect 2..1 x 0..1: 1 1 1 1")
            .unwrap_err()
            .to_string();
        assert!(e.contains("widget 1") && e.contains("backwards"), "{e}");
        let e = parse_widgets("rect 1..2 x 0..1: 1 1 1")
            .unwrap_err()
            .to_string();
        assert!(e.contains("not 4"), "{e}");
        assert!(parse_widgets(" ; ").is_err());
    }

    #[test]
    fn triangle_opens_with_the_second_axis_and_overlaps_take_the_max() {
        let w =
            parse_widgets("tri 100 x 0..1 width 40: 1 0 0 0.8; rect 0..255 x 0.5..1: 0 0 1 0.4")
                .unwrap();
        assert_eq!(w[0].opacity(100.0, 0.0), 0.0);
        assert!((w[0].opacity(100.0, 1.0) - 0.8).abs() < 1e-6);
        assert!((w[0].opacity(110.0, 1.0) - 0.4).abs() < 1e-6);
        assert_eq!(w[0].opacity(121.0, 1.0), 0.0);
        assert!((w[0].opacity(105.0, 0.5) - 0.4).abs() < 1e-6);
        let t =
            TransferFunction2D::new(SecondAxis::GradientMagnitude, [0.0, 255.0], [0.0, 1.0], &w)
                .unwrap();
        // Column 100 (value 100), last row (s = 1): red 0.8 and blue 0.4 overlap.
        let e = t.table[(ROWS - 1) * LUT_SIZE + 100];
        assert!((e[3] - 0.8).abs() < 1e-6);
        assert!((e[0] - 0.8 / 1.2).abs() < 1e-5 && (e[2] - 0.4 / 1.2).abs() < 1e-5);
        assert_eq!(t.lookup(100.0, 1.0), e);
        let m = t.max_opacity_per_value();
        assert!((m[100] - 0.8).abs() < 1e-6 && m[10] > 0.0);
    }
}

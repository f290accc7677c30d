//! One-dimensional colour/opacity transfer functions: control points in data units, a
//! [`LUT_SIZE`]-entry lookup table over the points' value range, presets and a text syntax.
//!
//! The lookup rule of [`TransferFunction1D::lookup`] is the one the GPU ray caster implements;
//! the style transfer function and the lighting transfer function use the same rule.

use crate::DataError;

/// Entries in a transfer function lookup table.
pub const LUT_SIZE: usize = 256;

/// Names accepted by [`TransferFunction1D::preset`].
pub const PRESETS: &[&str] = &["grey_ramp", "bone", "skin_bone", "brain_mri", "rainbow"];

/// A transfer function node: at data value `value` the colour and opacity `rgba`.
///
/// `rgba` is straight (not premultiplied); alpha is the opacity per voxel of path, so the ray
/// caster corrects it for its step length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ControlPoint {
    pub value: f32,
    pub rgba: [f32; 4],
}

/// A piecewise-linear transfer function sampled into a lookup table.
#[derive(Debug, Clone, PartialEq)]
pub struct TransferFunction1D {
    /// Data values of the first and last table entries (`domain[0] < domain[1]`).
    pub domain: [f32; 2],
    /// [`LUT_SIZE`] entries; entry `k` holds the function at
    /// `domain[0] + k / (LUT_SIZE - 1) * (domain[1] - domain[0])`.
    pub lut: Vec<[f32; 4]>,
}

impl TransferFunction1D {
    /// Samples the piecewise-linear function through `points` into the table.
    ///
    /// Needs at least two points with finite, strictly increasing values and every channel in
    /// [0, 1]. The domain is `[first.value, last.value]`.
    pub fn from_points(points: &[ControlPoint]) -> Result<Self, DataError> {
        if points.len() < 2 {
            return Err(format!(
                "a transfer function needs at least 2 control points, got {}",
                points.len()
            )
            .into());
        }
        for (n, p) in points.iter().enumerate() {
            if !p.value.is_finite() {
                return Err(
                    format!("control point {} has a non-finite value {}", n + 1, p.value).into(),
                );
            }
            if let Some(c) = p
                .rgba
                .iter()
                .find(|c| !c.is_finite() || !(0.0..=1.0).contains(*c))
            {
                return Err(format!(
                    "control point {} (value {}) has channel {c} outside [0, 1]: {:?}",
                    n + 1,
                    p.value,
                    p.rgba
                )
                .into());
            }
            if n > 0 && p.value <= points[n - 1].value {
                return Err(format!(
                    "control point values must increase strictly: point {} has value {} after {}",
                    n + 1,
                    p.value,
                    points[n - 1].value
                )
                .into());
            }
        }
        let first = points[0].value;
        let last = points[points.len() - 1].value;
        let values: Vec<f32> = points.iter().map(|p| p.value).collect();
        let lut = (0..LUT_SIZE)
            .map(|k| {
                let v = table_position(first, last, k);
                let (seg, f) = segment(&values, v);
                lerp4(points[seg].rgba, points[seg + 1].rgba, f)
            })
            .collect();
        Ok(Self {
            domain: [first, last],
            lut,
        })
    }

    /// The function at data value `v`: linear interpolation between table entries, clamped
    /// to the domain.
    ///
    /// `u = clamp((v - d0) / (d1 - d0), 0, 1)`, `x = u (LUT_SIZE - 1)`,
    /// `k = min(floor(x), LUT_SIZE - 2)`, `f = x - k`, result `lut[k] (1 - f) + lut[k + 1] f`.
    /// A NaN `v` (or a domain with `d1 <= d0`) gives `u = 0`.
    pub fn lookup(&self, v: f32) -> [f32; 4] {
        let (k, f) = lut_position(self.domain, v);
        lerp4(self.lut[k], self.lut[k + 1], f)
    }

    /// Control points of a named preset (see [`PRESETS`]) spread over `value_range`, or `None`
    /// for an unknown name. A degenerate or non-finite range is replaced by a usable one
    /// (`[lo, lo + 1]`, or `[0, 1]`).
    pub fn preset(name: &str, value_range: [f32; 2]) -> Option<Vec<ControlPoint>> {
        let [lo, hi] = usable_range(value_range);
        let at = |fraction: f32| lo + fraction * (hi - lo);
        let p = |fraction: f32, rgba: [f32; 4]| ControlPoint {
            value: at(fraction),
            rgba,
        };
        const IVORY: [f32; 3] = [1.0, 0.96, 0.86];
        const SKIN: [f32; 3] = [0.93, 0.68, 0.55];
        const GREY_MATTER: [f32; 3] = [0.92, 0.62, 0.62];
        let with = |rgb: [f32; 3], a: f32| [rgb[0], rgb[1], rgb[2], a];
        let points = match name {
            // Value -> grey level, opacity ramping linearly over the whole range.
            "grey_ramp" => vec![p(0.0, [0.0; 4]), p(1.0, [1.0; 4])],
            // Transparent below 40 %, a short ramp to opaque ivory.
            "bone" => vec![
                p(0.0, with(IVORY, 0.0)),
                p(0.40, with(IVORY, 0.0)),
                p(0.45, with(IVORY, 1.0)),
                p(1.0, with(IVORY, 1.0)),
            ],
            // CT-like: faint skin around 25-35 %, nothing in between, opaque bone above 60 %.
            "skin_bone" => vec![
                p(0.0, with(SKIN, 0.0)),
                p(0.20, with(SKIN, 0.0)),
                p(0.27, with(SKIN, 0.08)),
                p(0.35, with(SKIN, 0.08)),
                p(0.42, with(SKIN, 0.0)),
                p(0.55, with(IVORY, 0.0)),
                p(0.62, with(IVORY, 1.0)),
                p(1.0, with(IVORY, 1.0)),
            ],
            // T1 MRI (0..255): background below 15 % transparent, grey matter warm pink and
            // faint, white matter ivory and more opaque.
            "brain_mri" => vec![
                p(0.0, with(GREY_MATTER, 0.0)),
                p(0.15, with(GREY_MATTER, 0.0)),
                p(0.25, with(GREY_MATTER, 0.03)),
                p(0.45, with(GREY_MATTER, 0.06)),
                p(0.60, with(IVORY, 0.35)),
                p(1.0, with(IVORY, 0.6)),
            ],
            // Hue from blue to red over the range, opacity ramping up.
            "rainbow" => vec![
                p(0.0, [0.0, 0.0, 1.0, 0.0]),
                p(0.25, [0.0, 1.0, 1.0, 0.25]),
                p(0.5, [0.0, 1.0, 0.0, 0.5]),
                p(0.75, [1.0, 1.0, 0.0, 0.75]),
                p(1.0, [1.0, 0.0, 0.0, 1.0]),
            ],
            _ => return None,
        };
        Some(points)
    }

    /// Parses `"value: r g b a; value: r g b a; ..."` (numbers separated by spaces and/or
    /// commas; entries by `;` or newlines; empty entries are skipped). Only the syntax is
    /// checked here; [`TransferFunction1D::from_points`] checks the values.
    pub fn parse_points(text: &str) -> Result<Vec<ControlPoint>, DataError> {
        let mut points = Vec::new();
        for (n, entry) in entries(text).enumerate() {
            let (value, numbers) = parse_entry(entry, n, 4, "r g b a")?;
            points.push(ControlPoint {
                value,
                rgba: [numbers[0], numbers[1], numbers[2], numbers[3]],
            });
        }
        if points.is_empty() {
            return Err("no transfer function control points given".into());
        }
        Ok(points)
    }
}

/// Writes points in the syntax [`TransferFunction1D::parse_points`] reads, each number in its
/// shortest form that reads back to the same `f32` (so editing a curve round-trips exactly).
pub fn format_points(points: &[ControlPoint]) -> String {
    points
        .iter()
        .map(|p| {
            let [r, g, b, a] = p.rgba;
            format!("{}: {} {} {} {}", p.value, r, g, b, a)
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// Data value of table entry `k` over `[first, last]`.
pub(crate) fn table_position(first: f32, last: f32, k: usize) -> f32 {
    if k == LUT_SIZE - 1 {
        // Exactly the last point, free of rounding.
        last
    } else {
        first + k as f32 / (LUT_SIZE - 1) as f32 * (last - first)
    }
}

/// The segment `s` of the increasing `values` containing `v` (clamped) and the fraction in it.
pub(crate) fn segment(values: &[f32], v: f32) -> (usize, f32) {
    debug_assert!(values.len() >= 2);
    let last_segment = values.len() - 2;
    let s = values[1..]
        .iter()
        .position(|&x| v <= x)
        .unwrap_or(last_segment)
        .min(last_segment);
    let (a, b) = (values[s], values[s + 1]);
    let f = ((v - a) / (b - a)).clamp(0.0, 1.0);
    (s, f)
}

/// The shared lookup rule: table index `k` (0..=LUT_SIZE-2) and fraction `f` for value `v`.
pub(crate) fn lut_position(domain: [f32; 2], v: f32) -> (usize, f32) {
    let span = domain[1] - domain[0];
    // NaN values and empty domains (never built here) -> 0.
    let u = (v - domain[0]) / span;
    let u = if span > 0.0 && !u.is_nan() {
        u.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = u * (LUT_SIZE - 1) as f32;
    let k = (x.floor() as usize).min(LUT_SIZE - 2);
    (k, x - k as f32)
}

pub(crate) fn lerp4(a: [f32; 4], b: [f32; 4], f: f32) -> [f32; 4] {
    std::array::from_fn(|c| a[c] + (b[c] - a[c]) * f)
}

fn usable_range([lo, hi]: [f32; 2]) -> [f32; 2] {
    if !lo.is_finite() || !hi.is_finite() {
        [0.0, 1.0]
    } else if hi > lo {
        [lo, hi]
    } else {
        [lo, lo + 1.0]
    }
}

/// Non-empty entries of a `;`/newline separated list.
pub(crate) fn entries(text: &str) -> impl Iterator<Item = &str> {
    text.split([';', '\n'])
        .map(str::trim)
        .filter(|e| !e.is_empty())
}

/// Parses `"value: n1 n2 ..."` with exactly `count` numbers after the colon; `n` is the
/// 0-based entry number for messages, `shape` describes the numbers (e.g. `"r g b a"`).
pub(crate) fn parse_entry(
    entry: &str,
    n: usize,
    count: usize,
    shape: &str,
) -> Result<(f32, Vec<f32>), String> {
    let bad = |why: String| {
        format!(
            "entry {} \"{entry}\": {why} (expected \"value: {shape}\")",
            n + 1
        )
    };
    let (value, rest) = entry
        .split_once(':')
        .ok_or_else(|| bad("missing ':' after the value".into()))?;
    let value = parse_number(value.trim()).map_err(|e| bad(format!("value {e}")))?;
    let numbers = rest
        .split([' ', ',', '\t', '\r'])
        .filter(|s| !s.is_empty())
        .map(parse_number)
        .collect::<Result<Vec<f32>, String>>()
        .map_err(bad)?;
    if numbers.len() != count {
        return Err(bad(format!(
            "{} numbers after ':', need {count}",
            numbers.len()
        )));
    }
    Ok((value, numbers))
}

fn parse_number(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(x) => Err(format!("{x} is not finite")),
        Err(_) => Err(format!("\"{s}\" is not a number")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formatted_points_parse_back_to_the_same_points() {
        let points = vec![
            ControlPoint {
                value: -12.5,
                rgba: [0.0, 0.1, 0.2, 0.0],
            },
            ControlPoint {
                value: 1.0 / 3.0,
                rgba: [0.7, 0.123_456_79, 1.0, 0.05],
            },
            ControlPoint {
                value: 255.0,
                rgba: [1.0; 4],
            },
        ];
        let text = format_points(&points);
        assert_eq!(text.split(';').count(), 3, "{text}");
        assert_eq!(TransferFunction1D::parse_points(&text).unwrap(), points);
    }

    fn close(a: [f32; 4], b: [f32; 4], tol: f32) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    fn pt(value: f32, rgba: [f32; 4]) -> ControlPoint {
        ControlPoint { value, rgba }
    }

    #[test]
    fn lookup_at_nodes_and_midpoints() {
        let points = [
            pt(0.0, [0.0, 0.0, 0.0, 0.0]),
            pt(51.0, [1.0, 0.5, 0.0, 0.2]),
            pt(255.0, [0.0, 1.0, 1.0, 1.0]),
        ];
        let tf = TransferFunction1D::from_points(&points).unwrap();
        assert_eq!(tf.domain, [0.0, 255.0]);
        assert_eq!(tf.lut.len(), LUT_SIZE);
        // Domain 0..255 puts one table entry on every integer, so nodes are exact.
        for p in &points {
            assert!(close(tf.lookup(p.value), p.rgba, 1e-6), "{p:?}");
        }
        // Midpoints of the segments.
        assert!(close(tf.lookup(25.5), [0.5, 0.25, 0.0, 0.1], 1e-6));
        assert!(close(tf.lookup(153.0), [0.5, 0.75, 0.5, 0.6], 1e-6));
        // Clamped outside, NaN -> first entry.
        assert_eq!(tf.lookup(-10.0), points[0].rgba);
        assert_eq!(tf.lookup(1e9), points[2].rgba);
        assert_eq!(tf.lookup(f32::NAN), points[0].rgba);
    }

    #[test]
    fn lookup_rule_interpolates_between_entries() {
        // A hand-made table alternating 0 and 1: between entries the lookup is linear in the
        // table, whatever the points were.
        let tf = TransferFunction1D {
            domain: [10.0, 20.0],
            lut: (0..LUT_SIZE).map(|k| [(k % 2) as f32; 4]).collect(),
        };
        for (k, f) in [(0usize, 0.25f32), (100, 0.5), (253, 0.75), (254, 0.5)] {
            let v = 10.0 + (k as f32 + f) / (LUT_SIZE - 1) as f32 * 10.0;
            let want = if k % 2 == 0 { f } else { 1.0 - f };
            assert!((tf.lookup(v)[0] - want).abs() < 1e-4, "k {k} f {f}");
        }
        // The last entry: k is clamped to LUT_SIZE - 2 with f = 1.
        assert_eq!(tf.lookup(20.0)[0], 1.0);
        // Non-uniform control points: the value of entry k.
        let tf = TransferFunction1D::from_points(&[
            pt(-2.0, [0.0; 4]),
            pt(-1.0, [1.0, 1.0, 1.0, 1.0]),
            pt(6.0, [0.0; 4]),
        ])
        .unwrap();
        for k in [0, 7, 36, 37, 100, 255] {
            let v = -2.0 + k as f32 / 255.0 * 8.0;
            let want = if v <= -1.0 { v + 2.0 } else { (6.0 - v) / 7.0 };
            assert!((tf.lut[k][0] - want).abs() < 1e-5, "entry {k}");
            assert!((tf.lookup(v)[0] - want).abs() < 1e-5, "entry {k}");
        }
    }

    #[test]
    fn from_points_validates() {
        let ok = pt(0.0, [0.0; 4]);
        assert!(TransferFunction1D::from_points(&[ok]).is_err());
        let e = TransferFunction1D::from_points(&[ok, pt(0.0, [1.0; 4])])
            .unwrap_err()
            .to_string();
        assert!(e.contains("increase strictly"), "{e}");
        let e = TransferFunction1D::from_points(&[ok, pt(1.0, [1.0, 1.5, 0.0, 0.0])])
            .unwrap_err()
            .to_string();
        assert!(e.contains("point 2") && e.contains("outside [0, 1]"), "{e}");
        assert!(TransferFunction1D::from_points(&[ok, pt(f32::NAN, [1.0; 4])]).is_err());
        assert!(TransferFunction1D::from_points(&[ok, pt(1.0, [f32::NAN; 4])]).is_err());
    }

    #[test]
    fn presets_are_valid() {
        for range in [[0.0, 255.0], [-1000.0, 3000.0], [-0.9, 0.6], [5.0, 5.0]] {
            for name in PRESETS {
                let points = TransferFunction1D::preset(name, range).unwrap();
                let tf = TransferFunction1D::from_points(&points)
                    .unwrap_or_else(|e| panic!("{name} over {range:?}: {e}"));
                assert!(tf.lut.iter().flatten().all(|c| (0.0..=1.0).contains(c)));
            }
        }
        assert!(TransferFunction1D::preset("nope", [0.0, 1.0]).is_none());
        // grey_ramp: value -> grey, alpha linear over the range.
        let tf = TransferFunction1D::from_points(
            &TransferFunction1D::preset("grey_ramp", [0.0, 2.0]).unwrap(),
        )
        .unwrap();
        assert!(close(tf.lookup(0.5), [0.25; 4], 1e-6));
        // bone: transparent below 40 %, opaque above the ramp.
        let tf = TransferFunction1D::from_points(
            &TransferFunction1D::preset("bone", [0.0, 100.0]).unwrap(),
        )
        .unwrap();
        assert_eq!(tf.lookup(39.0)[3], 0.0);
        assert_eq!(tf.lookup(60.0)[3], 1.0);
        // brain_mri: background transparent, white matter more opaque than grey matter.
        let tf = TransferFunction1D::from_points(
            &TransferFunction1D::preset("brain_mri", [0.0, 255.0]).unwrap(),
        )
        .unwrap();
        assert_eq!(tf.lookup(30.0)[3], 0.0);
        let grey = tf.lookup(100.0);
        let white = tf.lookup(200.0);
        assert!(grey[3] > 0.0 && white[3] > grey[3]);
        assert!(grey[0] > grey[2], "grey matter is warm: {grey:?}");
    }

    #[test]
    fn parse_points_syntax_and_errors() {
        let p =
            TransferFunction1D::parse_points("0: 0 0 0 0; 10.5: 1, 0.5, 0.25, 1;\n 20:1,1,1,1;")
                .unwrap();
        assert_eq!(p.len(), 3);
        assert_eq!(p[1], pt(10.5, [1.0, 0.5, 0.25, 1.0]));
        assert_eq!(p[2].rgba, [1.0; 4]);
        let e = TransferFunction1D::parse_points("0: 0 0 0 0; 5 1 1 1 1")
            .unwrap_err()
            .to_string();
        assert!(e.contains("entry 2") && e.contains("missing ':'"), "{e}");
        let e = TransferFunction1D::parse_points("0: 0 0 0 0; 5: 1 1 x 1")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("entry 2") && e.contains("\"x\" is not a number"),
            "{e}"
        );
        let e = TransferFunction1D::parse_points("0: 0 0 0")
            .unwrap_err()
            .to_string();
        assert!(e.contains("entry 1") && e.contains("3 numbers"), "{e}");
        let e = TransferFunction1D::parse_points("abc: 0 0 0 0")
            .unwrap_err()
            .to_string();
        assert!(e.contains("entry 1") && e.contains("value"), "{e}");
        assert!(TransferFunction1D::parse_points(" ; ").is_err());
        assert!(TransferFunction1D::parse_points("0: inf 0 0 0").is_err());
    }
}

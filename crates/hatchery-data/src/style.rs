//! Style transfer functions (Bruckner & Gröller 2007): transfer function nodes that carry a
//! lit-sphere style instead of a colour (§3.2, lookup as in §4.1), curvature-controlled style
//! contours (§3.3) and illustrative transparency (§3.4, eq. 2).

use crate::DataError;
use crate::lit_sphere::LitSphere;
use crate::transfer_function::{
    LUT_SIZE, entries, lut_position, parse_entry, segment, table_position,
};

/// A style transfer function node: at data value `value` use style number `style` (an index
/// into the list of M distinct lit-sphere maps) with uniform opacity α_u = `opacity`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StyleNode {
    pub value: f32,
    pub style: usize,
    pub opacity: f32,
}

/// The three tables of §4.1 minus the style maps themselves (`sft`, held by the caller).
#[derive(Debug, Clone, PartialEq)]
pub struct StyleTransferFunction {
    /// Data values of the first and last `tft` entries. For a single node `[v, v + 1]` (the
    /// table is constant, so any non-empty domain gives the same lookups).
    pub domain: [f32; 2],
    /// [`LUT_SIZE`] entries `(i, α_u)`: `i` is the fractional node index in `0..=N-1`; entry
    /// `k` sits at `domain[0] + k / (LUT_SIZE - 1) * (domain[1] - domain[0])`.
    pub tft: Vec<[f32; 2]>,
    /// N entries: node index -> style index `j` in `0..M`.
    pub ift: Vec<u32>,
}

impl StyleTransferFunction {
    /// Builds the tables from at least one node with finite, strictly increasing values,
    /// `style < style_count` and opacity in [0, 1]. Between nodes `k` and `k + 1` the index goes
    /// linearly from `k` to `k + 1` and α_u linearly between the nodes' opacities; outside the
    /// nodes both are clamped. A single node gives a constant function.
    pub fn from_nodes(nodes: &[StyleNode], style_count: usize) -> Result<Self, DataError> {
        if nodes.is_empty() {
            return Err("a style transfer function needs at least one node".into());
        }
        for (n, node) in nodes.iter().enumerate() {
            if !node.value.is_finite() {
                return Err(
                    format!("style node {} has a non-finite value {}", n + 1, node.value).into(),
                );
            }
            if node.style >= style_count {
                return Err(format!(
                    "style node {} (value {}) uses style {} but only {style_count} style(s) are given",
                    n + 1,
                    node.value,
                    node.style
                ).into());
            }
            if !(0.0..=1.0).contains(&node.opacity) {
                return Err(format!(
                    "style node {} (value {}) has opacity {} outside [0, 1]",
                    n + 1,
                    node.value,
                    node.opacity
                )
                .into());
            }
            if n > 0 && node.value <= nodes[n - 1].value {
                return Err(format!(
                    "style node values must increase strictly: node {} has value {} after {}",
                    n + 1,
                    node.value,
                    nodes[n - 1].value
                )
                .into());
            }
        }
        let ift = nodes.iter().map(|n| n.style as u32).collect();
        if nodes.len() == 1 {
            let v = nodes[0].value;
            return Ok(Self {
                domain: [v, v + 1.0],
                tft: vec![[0.0, nodes[0].opacity]; LUT_SIZE],
                ift,
            });
        }
        let first = nodes[0].value;
        let last = nodes[nodes.len() - 1].value;
        let values: Vec<f32> = nodes.iter().map(|n| n.value).collect();
        let tft = (0..LUT_SIZE)
            .map(|k| {
                let v = table_position(first, last, k);
                let (seg, f) = segment(&values, v);
                let (a, b) = (nodes[seg].opacity, nodes[seg + 1].opacity);
                [seg as f32 + f, a + (b - a) * f]
            })
            .collect();
        Ok(Self {
            domain: [first, last],
            tft,
            ift,
        })
    }

    /// Parses `"value: style opacity; ..."`, e.g. `"40: 0 0.05; 90: 1 0.6; 150: 2 1.0"`
    /// (numbers separated by spaces and/or commas; entries by `;` or newlines). The style must
    /// be a non-negative integer. [`StyleTransferFunction::from_nodes`] checks the rest.
    pub fn parse(text: &str) -> Result<Vec<StyleNode>, DataError> {
        let mut nodes = Vec::new();
        for (n, entry) in entries(text).enumerate() {
            let (value, numbers) = parse_entry(entry, n, 2, "style opacity")?;
            let style = numbers[0];
            if style < 0.0 || style.fract() != 0.0 || style > u32::MAX as f32 {
                return Err(format!(
                    "entry {} \"{entry}\": style {style} is not a style number (0, 1, 2, ...)",
                    n + 1
                )
                .into());
            }
            nodes.push(StyleNode {
                value,
                style: style as usize,
                opacity: numbers[1],
            });
        }
        if nodes.is_empty() {
            return Err("no style transfer function nodes given".into());
        }
        Ok(nodes)
    }

    /// Writes nodes the way [`StyleTransferFunction::parse`] reads them (shortest round-tripping
    /// numbers).
    pub fn format(nodes: &[StyleNode]) -> String {
        nodes
            .iter()
            .map(|n| format!("{}: {} {}", n.value, n.style, n.opacity))
            .collect::<Vec<_>>()
            .join("; ")
    }

    /// `(i, α_u)` at data value `v`, by exactly the rule of
    /// [`crate::transfer_function::TransferFunction1D::lookup`].
    pub fn lookup_tft(&self, v: f32) -> (f32, f32) {
        let (k, f) = lut_position(self.domain, v);
        let (a, b) = (self.tft[k], self.tft[k + 1]);
        (a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f)
    }

    /// §4.1 steps 1–4: `(i, α_u) = tft(v)`; `i0 = floor(i)`, `i1 = min(i0 + 1, N - 1)`,
    /// `w = i - i0`; `j0 = ift[i0]`, `j1 = ift[i1]`;
    /// `(r, g, b, α_d) = sft(j0)(nx, ny) (1 - w) + sft(j1)(nx, ny) w` — whole styles mixed with
    /// the same weight for every normal. Returns that straight-alpha RGBA (alpha = α_d) and α_u.
    ///
    /// `styles` are the M maps `ift` indexes (the caller picks the mip level).
    pub fn lookup(&self, v: f32, nx: f32, ny: f32, styles: &[LitSphere]) -> ([f32; 4], f32) {
        let (i, alpha_u) = self.lookup_tft(v);
        let last = self.ift.len() - 1;
        let i0 = (i.floor().max(0.0) as usize).min(last);
        let i1 = (i0 + 1).min(last);
        let w = (i - i0 as f32).clamp(0.0, 1.0);
        let a = styles[self.ift[i0] as usize].lookup(nx, ny);
        let b = styles[self.ift[i1] as usize].lookup(nx, ny);
        (
            std::array::from_fn(|c| a[c] * (1.0 - w) + b[c] * w),
            alpha_u,
        )
    }
}

/// Right-hand side of eq. 1: `sqrt(Tκv (2 − Tκv))` with `Tκv` clamped to [0, 1] (NaN -> 0),
/// so 0 at `Tκv = 0` and 1 from `Tκv = 1` on.
pub fn contour_limit(t: f32, kappa_v: f32) -> f32 {
    let x = t * kappa_v;
    let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
    (x * (2.0 - x)).sqrt()
}

/// The scale factor `r'/r` of §3.3 for the lit-sphere coordinates `(nx, ny)`: with
/// `limit = contour_limit(t, κv)`, on a contour (`limit > 0` and `|n·v| <= limit`)
/// `δ = 1 − min(1, (limit − |n·v|) / limit)`, `r' = min(1, r / δ)` (`r' = 1` when `δ = 0`);
/// 1 off the contour or when `r = 0`.
pub fn contour_push_scale(nx: f32, ny: f32, n_dot_v: f32, t: f32, kappa_v: f32) -> f32 {
    let limit = contour_limit(t, kappa_v);
    let nv = n_dot_v.abs();
    let r = (nx * nx + ny * ny).sqrt();
    let on_contour = limit > 0.0 && nv <= limit;
    if !on_contour || r == 0.0 {
        return 1.0;
    }
    let delta = 1.0 - ((limit - nv) / limit).min(1.0);
    let r_new = if delta == 0.0 {
        1.0
    } else {
        (r / delta).min(1.0)
    };
    r_new / r
}

/// §3.3 push of the lit-sphere coordinates outwards along the radius on a contour: returns the
/// pushed `(nx, ny)`, i.e. `(nx, ny)` times [`contour_push_scale`].
pub fn contour_push(nx: f32, ny: f32, n_dot_v: f32, t: f32, kappa_v: f32) -> (f32, f32) {
    let s = contour_push_scale(nx, ny, n_dot_v, t, kappa_v);
    (nx * s, ny * s)
}

/// Eq. 2: `α = α_d · α_u^(0.5 + max(0, |n·v| − limit) · (1 − |g|))`, `|g|` the gradient
/// magnitude normalised to [0, 1] (clamped). `α_u` is clamped to [0, 1]; `α_u = 0` gives 0 (the
/// exponent is always >= 0.5), `α_u = 1` gives `α_d`.
pub fn illustrative_alpha(
    alpha_d: f32,
    alpha_u: f32,
    n_dot_v: f32,
    limit: f32,
    gradient_norm: f32,
) -> f32 {
    let g = gradient_norm.clamp(0.0, 1.0);
    let exponent = 0.5 + (n_dot_v.abs() - limit).max(0.0) * (1.0 - g);
    alpha_d * alpha_u.clamp(0.0, 1.0).powf(exponent)
}

/// The κv estimate of §3.3: the angle between the current and the previous unit normal
/// (`acos` of their dot product clamped to [-1, 1]) divided by the step length in world units.
/// 0 if either normal is (near) zero or the step is not positive.
pub fn curvature_estimate(n: [f32; 3], previous: [f32; 3], step_world: f32) -> f32 {
    let len2 = |v: [f32; 3]| v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if step_world.is_nan() || step_world <= 0.0 || len2(n) < 1e-12 || len2(previous) < 1e-12 {
        return 0.0;
    }
    let dot = n[0] * previous[0] + n[1] * previous[1] + n[2] * previous[2];
    dot.clamp(-1.0, 1.0).acos() / step_world
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formatted_nodes_parse_back_to_the_same_nodes() {
        let nodes = vec![
            StyleNode {
                value: 40.0,
                style: 0,
                opacity: 0.02,
            },
            StyleNode {
                value: 1.0 / 3.0,
                style: 2,
                opacity: 0.123_456_79,
            },
        ];
        let text = StyleTransferFunction::format(&nodes);
        assert_eq!(StyleTransferFunction::parse(&text).unwrap(), nodes);
    }
    use crate::lit_sphere::procedural;

    fn node(value: f32, style: usize, opacity: f32) -> StyleNode {
        StyleNode {
            value,
            style,
            opacity,
        }
    }

    fn styles() -> Vec<LitSphere> {
        vec![
            procedural("shaded", 32, [0.9, 0.3, 0.2]).unwrap(),
            procedural("gooch", 32, [0.2, 0.6, 0.9]).unwrap(),
        ]
    }

    #[test]
    fn tables_and_repeated_styles() {
        // Styles [0, 1, 0]: three nodes, two distinct maps.
        let stf = StyleTransferFunction::from_nodes(
            &[node(0.0, 0, 0.0), node(127.5, 1, 0.5), node(255.0, 0, 1.0)],
            2,
        )
        .unwrap();
        assert_eq!(stf.ift, [0, 1, 0]);
        assert_eq!(stf.domain, [0.0, 255.0]);
        assert_eq!(stf.tft.len(), LUT_SIZE);
        assert_eq!(stf.lookup_tft(0.0), (0.0, 0.0));
        assert_eq!(stf.lookup_tft(255.0), (2.0, 1.0));
        let (i, a) = stf.lookup_tft(127.5);
        assert!((i - 1.0).abs() < 1e-5 && (a - 0.5).abs() < 1e-5);
        let (i, a) = stf.lookup_tft(191.25);
        assert!((i - 1.5).abs() < 1e-5 && (a - 0.75).abs() < 1e-5);
        // Clamped outside.
        assert_eq!(stf.lookup_tft(-5.0), (0.0, 0.0));
        assert_eq!(stf.lookup_tft(500.0), (2.0, 1.0));

        let maps = styles();
        for (nx, ny) in [(0.0, 0.0), (0.5, -0.3), (-0.7, 0.6), (0.95, 0.0)] {
            let s0 = maps[0].lookup(nx, ny);
            let s1 = maps[1].lookup(nx, ny);
            // At the nodes: the node's style.
            let (rgba, a) = stf.lookup(0.0, nx, ny, &maps);
            assert_eq!((rgba, a), (s0, 0.0));
            let (rgba, _) = stf.lookup(255.0, nx, ny, &maps);
            assert_eq!(rgba, s0);
            // i = 0.25: 0.75 style 0 + 0.25 style 1, for every normal.
            let v = 127.5 * 0.25;
            let (i, _) = stf.lookup_tft(v);
            assert!((i - 0.25).abs() < 1e-5);
            let (rgba, _) = stf.lookup(v, nx, ny, &maps);
            for c in 0..4 {
                let want = 0.75 * s0[c] + 0.25 * s1[c];
                assert!((rgba[c] - want).abs() < 1e-5, "{nx},{ny}: {rgba:?}");
            }
            // i = 1.5 between the repeated style 0 and style 1: mixes maps 1 and 0 (ift).
            let (rgba, _) = stf.lookup(191.25, nx, ny, &maps);
            for c in 0..4 {
                let want = 0.5 * s1[c] + 0.5 * s0[c];
                assert!((rgba[c] - want).abs() < 1e-5);
            }
        }
    }

    #[test]
    fn single_node_is_constant() {
        let stf = StyleTransferFunction::from_nodes(&[node(3.0, 1, 0.4)], 2).unwrap();
        let maps = styles();
        for v in [-100.0, 3.0, 3.5, 1e6, f32::NAN] {
            assert_eq!(stf.lookup_tft(v), (0.0, 0.4));
            let (rgba, a) = stf.lookup(v, 0.2, 0.3, &maps);
            assert_eq!(rgba, maps[1].lookup(0.2, 0.3));
            assert_eq!(a, 0.4);
        }
    }

    #[test]
    fn from_nodes_and_parse_errors() {
        assert!(StyleTransferFunction::from_nodes(&[], 1).is_err());
        let e = StyleTransferFunction::from_nodes(&[node(0.0, 2, 1.0)], 2)
            .unwrap_err()
            .to_string();
        assert!(e.contains("style 2") && e.contains("2 style"), "{e}");
        let e = StyleTransferFunction::from_nodes(&[node(1.0, 0, 1.0), node(1.0, 0, 1.0)], 1)
            .unwrap_err()
            .to_string();
        assert!(e.contains("increase strictly"), "{e}");
        assert!(StyleTransferFunction::from_nodes(&[node(1.0, 0, 1.5)], 1).is_err());
        assert!(StyleTransferFunction::from_nodes(&[node(f32::NAN, 0, 1.0)], 1).is_err());

        let nodes = StyleTransferFunction::parse("40: 0 0.05; 90: 1 0.6; 150: 2 1.0").unwrap();
        assert_eq!(
            nodes,
            [node(40.0, 0, 0.05), node(90.0, 1, 0.6), node(150.0, 2, 1.0)]
        );
        assert_eq!(
            StyleTransferFunction::parse("1:0,1;").unwrap(),
            [node(1.0, 0, 1.0)]
        );
        let e = StyleTransferFunction::parse("40: 0 0.05; 90: 1.5 0.6")
            .unwrap_err()
            .to_string();
        assert!(e.contains("entry 2") && e.contains("style 1.5"), "{e}");
        let e = StyleTransferFunction::parse("40: 0 0.05; 90: -1 0.6")
            .unwrap_err()
            .to_string();
        assert!(e.contains("entry 2"), "{e}");
        let e = StyleTransferFunction::parse("40: 0")
            .unwrap_err()
            .to_string();
        assert!(e.contains("entry 1") && e.contains("1 numbers"), "{e}");
        let e = StyleTransferFunction::parse("40 0 1")
            .unwrap_err()
            .to_string();
        assert!(e.contains("missing ':'"), "{e}");
        assert!(StyleTransferFunction::parse("").is_err());
    }

    #[test]
    fn contour_limit_values() {
        assert_eq!(contour_limit(1.0, 0.0), 0.0);
        assert!((contour_limit(1.0, 0.5) - 0.75f32.sqrt()).abs() < 1e-7);
        assert!((contour_limit(0.25, 2.0) - 0.75f32.sqrt()).abs() < 1e-7);
        assert_eq!(contour_limit(1.0, 1.0), 1.0);
        assert_eq!(contour_limit(2.0, 3.0), 1.0);
        assert_eq!(contour_limit(-1.0, 3.0), 0.0);
        assert_eq!(contour_limit(f32::NAN, 3.0), 0.0);
    }

    #[test]
    fn contour_push_values() {
        // Tκv = 0.5 -> limit sqrt(0.75) ~ 0.866.
        let limit = contour_limit(1.0, 0.5);
        // Off the contour: unchanged.
        assert_eq!(contour_push(0.3, 0.1, 0.95, 1.0, 0.5), (0.3, 0.1));
        // No curvature: never a contour.
        assert_eq!(contour_push(0.3, 0.1, 0.0, 1.0, 0.0), (0.3, 0.1));
        // On the contour: δ = |n·v| / limit, r' = min(1, r / δ).
        let nv = 0.5 * limit;
        let (x, y) = contour_push(0.3, 0.4, nv, 1.0, 0.5);
        assert!((x - 0.6).abs() < 1e-5 && (y - 0.8).abs() < 1e-5, "{x} {y}");
        let (x, y) = contour_push(0.1, 0.2, -0.8 * limit, 1.0, 0.5);
        let s = 1.0 / 0.8;
        assert!((x - 0.1 * s).abs() < 1e-5 && (y - 0.2 * s).abs() < 1e-5);
        // |n·v| = 0: δ = 0 -> pushed to the rim.
        let (x, y) = contour_push(0.6, 0.0, 0.0, 1.0, 0.5);
        assert!((x - 1.0).abs() < 1e-6 && y == 0.0);
        assert_eq!(contour_push_scale(0.0, 0.0, 0.0, 1.0, 0.5), 1.0);
    }

    #[test]
    fn illustrative_alpha_constraints() {
        for (alpha_d, nv, limit, g) in [
            (0.7, 0.9, 0.3, 0.2),
            (1.0, 0.1, 0.5, 0.0),
            (0.3, 1.0, 0.0, 1.0),
        ] {
            assert_eq!(illustrative_alpha(alpha_d, 1.0, nv, limit, g), alpha_d);
            assert_eq!(illustrative_alpha(alpha_d, 0.0, nv, limit, g), 0.0);
        }
        // On the contour the exponent is 0.5.
        let a = illustrative_alpha(0.8, 0.25, 0.2, 0.5, 0.1);
        assert!((a - 0.8 * 0.5).abs() < 1e-6, "{a}");
        // Full gradient magnitude: exponent 0.5 too.
        let a = illustrative_alpha(1.0, 0.25, 0.9, 0.1, 1.0);
        assert!((a - 0.5).abs() < 1e-6);
        // Off the contour in a homogeneous region: exponent 0.5 + (|n·v| - limit).
        let a = illustrative_alpha(1.0, 0.25, -0.9, 0.1, 0.0);
        assert!((a - 0.25f32.powf(1.3)).abs() < 1e-6);
    }

    #[test]
    fn curvature_estimate_values() {
        let a = [1.0, 0.0, 0.0];
        let b = [0.0, 1.0, 0.0];
        assert!((curvature_estimate(a, b, 0.5) - std::f32::consts::PI).abs() < 1e-6);
        assert_eq!(curvature_estimate(a, a, 0.5), 0.0);
        assert!((curvature_estimate(a, [-1.0, 0.0, 0.0], 1.0) - std::f32::consts::PI).abs() < 1e-6);
        assert_eq!(curvature_estimate(a, [0.0; 3], 1.0), 0.0);
        assert_eq!(curvature_estimate(a, b, 0.0), 0.0);
        // Slightly-off-unit dot products are clamped.
        assert_eq!(curvature_estimate([1.0000001, 0.0, 0.0], a, 1.0), 0.0);
    }
}

//! Lit-sphere (MatCap) shading styles (Bruckner & Gröller 2007, §3.1): the colour of a shaded
//! sphere under orthographic projection as a function of the eye-space normal's x and y.

use crate::DataError;
use glam::Vec3;

/// Names accepted by [`procedural`].
pub const STYLES: &[&str] = &[
    "shaded",
    "toon2",
    "toon3",
    "gooch",
    "metal",
    "ink_rim",
    "flat",
    "nagy_toon",
];

/// A square lit-sphere map of straight-alpha RGBA texels, row 0 at the top (`ny = +1`).
///
/// Texel `(x, y)`'s centre stands for the eye-space normal with
/// `nx = (x + 0.5) / size * 2 - 1`, `ny = 1 - (y + 0.5) / size * 2` (see [`texel_normal`]).
/// Texels whose centre lies outside the unit disk hold a copy of the nearest rim value, so
/// bilinear filtering and mip-mapping near the rim never pull in unrelated colours.
#[derive(Debug, Clone, PartialEq)]
pub struct LitSphere {
    pub size: u32,
    /// `size * size` texels, row-major from the top row.
    pub texels: Vec<[f32; 4]>,
}

/// The eye-space normal `(nx, ny)` at the centre of texel `(x, y)` of a `size`-wide map.
pub fn texel_normal(size: u32, x: u32, y: u32) -> (f32, f32) {
    let s = size as f32;
    (
        (x as f32 + 0.5) / s * 2.0 - 1.0,
        1.0 - (y as f32 + 0.5) / s * 2.0,
    )
}

/// The light direction of the procedural styles: upper left, towards the viewer.
pub fn style_light() -> Vec3 {
    Vec3::new(-0.4, 0.6, 1.0).normalize()
}

/// A procedural style (one of [`STYLES`]) tinted with `color` (clamped to [0, 1]), or `None`
/// for an unknown style, a size that is not a power of two, or a non-finite colour.
///
/// Normal `n = (nx, ny, sqrt(1 - nx² - ny²))`, view `v = (0, 0, 1)`, light `l` =
/// [`style_light`], `h = normalize(l + v)`. Alpha (the directional opacity α_d) is 1
/// everywhere; every channel is clamped to [0, 1].
pub fn procedural(style: &str, size: u32, color: [f32; 3]) -> Option<LitSphere> {
    if !size.is_power_of_two() || color.iter().any(|c| !c.is_finite()) {
        return None;
    }
    let color = Vec3::from_array(color).clamp(Vec3::ZERO, Vec3::ONE);
    // Checks the name before filling the map.
    shade(style, Vec3::Z, color)?;
    let texels = (0..size * size)
        .map(|i| {
            let (nx, ny) = texel_normal(size, i % size, i / size);
            let r2 = nx * nx + ny * ny;
            let n = if r2 <= 1.0 {
                Vec3::new(nx, ny, (1.0 - r2).max(0.0).sqrt())
            } else {
                // Outside the disk: the value at the nearest rim point.
                let r = r2.sqrt();
                Vec3::new(nx / r, ny / r, 0.0)
            };
            shade(style, n, color).expect("style checked above")
        })
        .collect();
    Some(LitSphere { size, texels })
}

/// The shaded colour of `style` at unit normal `n`, or `None` for an unknown style.
fn shade(style: &str, n: Vec3, color: Vec3) -> Option<[f32; 4]> {
    let l = style_light();
    let v = Vec3::Z;
    let h = (l + v).normalize();
    let nl = n.dot(l);
    let nh = n.dot(h);
    let nv = n.dot(v);
    let rgb = match style {
        "shaded" => {
            color * (0.15 + 0.85 * nl.max(0.0)) + Vec3::splat(0.35 * nh.max(0.0).powf(40.0))
        }
        "toon2" => {
            if nl > 0.4 {
                color
            } else {
                color * 0.45
            }
        }
        "toon3" => {
            if nh > 0.97 {
                Vec3::ONE
            } else if nl > 0.7 {
                color
            } else if nl > 0.2 {
                color * 0.7
            } else {
                color * 0.35
            }
        }
        "gooch" => {
            let k = (1.0 + nl) / 2.0;
            let cool = Vec3::new(0.1, 0.1, 0.55) + 0.25 * color;
            let warm = Vec3::new(0.6, 0.55, 0.1) + 0.5 * color;
            cool.lerp(warm, k)
        }
        "metal" => {
            let band = (3.0 * n.y).sin().abs().powi(2);
            color * (0.3 + 0.7 * band) + Vec3::splat(0.4 * nh.max(0.0).powf(30.0))
        }
        "ink_rim" => {
            let interior = Vec3::ONE.lerp(color, 0.3);
            interior * smoothstep(0.25, 0.45, nv)
        }
        "flat" => color,
        // Nagy et al. 2002, §4.4: two tones switched at N·L = 0.5, black silhouettes where
        // (N·V)² is small.
        "nagy_toon" => {
            if nv * nv < 0.1 {
                Vec3::ZERO
            } else if nl > 0.5 {
                color
            } else {
                color * 0.5
            }
        }
        _ => return None,
    };
    let rgb = rgb.clamp(Vec3::ZERO, Vec3::ONE);
    Some([rgb.x, rgb.y, rgb.z, 1.0])
}

fn smoothstep(e0: f32, e1: f32, x: f32) -> f32 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// A lit-sphere map from a painted RGBA8 image (row 0 at the top). The image must be square
/// with a power-of-two side. Texels whose centre lies outside the unit disk are replaced by the
/// nearest texel inside the disk along the same radius (whatever was painted there is never
/// meant to be read).
pub fn from_rgba8(width: u32, height: u32, rgba: &[u8]) -> Result<LitSphere, DataError> {
    if width != height {
        return Err(format!("a lit-sphere image must be square, got {width}x{height}").into());
    }
    if !width.is_power_of_two() {
        return Err(format!(
            "a lit-sphere image side must be a power of two (for mip-mapping), got {width}"
        )
        .into());
    }
    let size = width;
    let n = size as usize * size as usize;
    if rgba.len() != n * 4 {
        return Err(format!(
            "a {size}x{size} RGBA8 image needs {} bytes, got {}",
            n * 4,
            rgba.len()
        )
        .into());
    }
    let mut texels: Vec<[f32; 4]> = rgba
        .chunks_exact(4)
        .map(|p| std::array::from_fn(|c| p[c] as f32 / 255.0))
        .collect();
    let inside = |x: u32, y: u32| {
        let (nx, ny) = texel_normal(size, x, y);
        nx * nx + ny * ny <= 1.0
    };
    let texel_at = |nx: f32, ny: f32| {
        let s = size as f32;
        let x = (((nx * 0.5 + 0.5) * s).floor() as i64).clamp(0, size as i64 - 1) as u32;
        let y = (((0.5 - ny * 0.5) * s).floor() as i64).clamp(0, size as i64 - 1) as u32;
        (x, y)
    };
    for y in 0..size {
        for x in 0..size {
            if inside(x, y) {
                continue;
            }
            let (nx, ny) = texel_normal(size, x, y);
            let r = (nx * nx + ny * ny).sqrt();
            let (dx, dy) = (nx / r, ny / r);
            // Walk inwards from the rim in half-texel steps until a texel inside the disk.
            let half_texel = 1.0 / size as f32;
            let mut rho = 1.0f32;
            let source = loop {
                let (sx, sy) = texel_at(dx * rho, dy * rho);
                if inside(sx, sy) {
                    break (sx, sy);
                }
                rho -= half_texel;
                if rho <= 0.0 {
                    break texel_at(0.0, 0.0);
                }
            };
            texels[(y * size + x) as usize] = texels[(source.1 * size + source.0) as usize];
        }
    }
    Ok(LitSphere { size, texels })
}

impl LitSphere {
    /// Level 0 (a copy of `self`) and each following level the 2×2 box average of the previous
    /// one, down to 1×1. Every level is built from this map alone. A map whose size is not a
    /// power of two (only possible when built by hand) gives just level 0.
    pub fn mip_chain(&self) -> Vec<LitSphere> {
        let mut chain = vec![self.clone()];
        if !self.size.is_power_of_two() {
            return chain;
        }
        while chain.last().expect("non-empty").size > 1 {
            let prev = chain.last().expect("non-empty");
            let s = prev.size as usize;
            let half = s / 2;
            let texels = (0..half * half)
                .map(|i| {
                    let (x, y) = (2 * (i % half), 2 * (i / half));
                    let t = |dx: usize, dy: usize| prev.texels[(y + dy) * s + x + dx];
                    let (a, b, c, d) = (t(0, 0), t(1, 0), t(0, 1), t(1, 1));
                    std::array::from_fn(|k| (a[k] + b[k] + c[k] + d[k]) * 0.25)
                })
                .collect();
            chain.push(LitSphere {
                size: half as u32,
                texels,
            });
        }
        chain
    }

    /// Bilinear lookup at eye-space normal `(nx, ny)`: texel coordinates
    /// `x = (nx * 0.5 + 0.5) * size - 0.5`, `y = (0.5 - ny * 0.5) * size - 0.5`, the two
    /// texels either side of each (`floor` and `floor + 1`) clamped to the edge, as a GPU sampler
    /// with clamp-to-edge addressing and linear filtering does. NaN coordinates count as 0.
    pub fn lookup(&self, nx: f32, ny: f32) -> [f32; 4] {
        let s = self.size as f32;
        let nx = if nx.is_nan() { 0.0 } else { nx };
        let ny = if ny.is_nan() { 0.0 } else { ny };
        let x = (nx * 0.5 + 0.5) * s - 0.5;
        let y = (0.5 - ny * 0.5) * s - 0.5;
        let (x0, fx) = (x.floor(), x - x.floor());
        let (y0, fy) = (y.floor(), y - y.floor());
        let last = self.size as i64 - 1;
        let idx = |v: f32| (v as i64).clamp(0, last) as usize;
        let (xa, xb) = (idx(x0), idx(x0 + 1.0));
        let (ya, yb) = (idx(y0), idx(y0 + 1.0));
        let n = self.size as usize;
        let t = |x: usize, y: usize| self.texels[y * n + x];
        let lerp = |a: [f32; 4], b: [f32; 4], f: f32| -> [f32; 4] {
            std::array::from_fn(|c| a[c] + (b[c] - a[c]) * f)
        };
        lerp(
            lerp(t(xa, ya), t(xb, ya), fx),
            lerp(t(xa, yb), t(xb, yb), fx),
            fy,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ORANGE: [f32; 3] = [0.9, 0.5, 0.2];

    fn inside_disk(size: u32) -> impl Iterator<Item = (u32, u32)> {
        (0..size * size)
            .map(move |i| (i % size, i / size))
            .filter(move |&(x, y)| {
                let (nx, ny) = texel_normal(size, x, y);
                nx * nx + ny * ny <= 1.0
            })
    }

    #[test]
    fn styles_are_in_range_and_sizes_checked() {
        for style in STYLES {
            for size in [1, 2, 64] {
                let m = procedural(style, size, ORANGE).unwrap();
                assert_eq!(m.texels.len(), (size * size) as usize);
                assert!(
                    m.texels.iter().flatten().all(|c| (0.0..=1.0).contains(c)),
                    "{style}"
                );
                assert!(m.texels.iter().all(|t| t[3] == 1.0), "{style}");
            }
            assert!(procedural(style, 48, ORANGE).is_none());
            assert!(procedural(style, 0, ORANGE).is_none());
        }
        assert!(procedural("nope", 64, ORANGE).is_none());
        assert!(procedural("flat", 64, [f32::NAN, 0.0, 0.0]).is_none());
        assert!(procedural("flat", 4, [2.0, -1.0, 0.5]).unwrap().texels[0] == [1.0, 0.0, 0.5, 1.0]);
    }

    #[test]
    fn disk_mapping() {
        // The centre of the map is n = (0, 0, 1); row 0 is the top.
        assert_eq!(texel_normal(1, 0, 0), (0.0, 0.0));
        assert_eq!(texel_normal(64, 31, 31), (-1.0 / 64.0, 1.0 / 64.0));
        assert_eq!(texel_normal(64, 0, 0), (-63.0 / 64.0, 63.0 / 64.0));
        let m = procedural("shaded", 64, ORANGE).unwrap();
        // Texel nearest to the light's normal is the brightest one (the highlight is towards the
        // upper left).
        let l = style_light();
        let h = (l + Vec3::Z).normalize();
        let brightest = (0..64 * 64)
            .max_by(|&a, &b| {
                let s = |i: usize| m.texels[i][0] + m.texels[i][1] + m.texels[i][2];
                s(a).total_cmp(&s(b))
            })
            .unwrap() as u32;
        let (nx, ny) = texel_normal(64, brightest % 64, brightest / 64);
        assert!(
            (nx - h.x).abs() < 0.05 && (ny - h.y).abs() < 0.05,
            "{nx} {ny} vs {h}"
        );
        // The lookup at the centre equals the analytic shading at n = (0, 0, 1).
        let want = shade("shaded", Vec3::Z, Vec3::from_array(ORANGE)).unwrap();
        let got = m.lookup(0.0, 0.0);
        assert!(
            got.iter().zip(want).all(|(a, b)| (a - b).abs() < 0.01),
            "{got:?} vs {want:?}"
        );
        // The lookup at a texel centre returns that texel exactly.
        let (nx, ny) = texel_normal(64, 10, 40);
        assert_eq!(m.lookup(nx, ny), m.texels[40 * 64 + 10]);
        // Outside the disk: the rim value along the same direction.
        let (nx, ny) = texel_normal(64, 0, 0);
        let r = (nx * nx + ny * ny).sqrt();
        let rim = shade(
            "shaded",
            Vec3::new(nx / r, ny / r, 0.0),
            Vec3::from_array(ORANGE),
        )
        .unwrap();
        assert_eq!(m.texels[0], rim);
        // Lookups clamp to the edge.
        assert_eq!(m.lookup(5.0, 5.0), m.texels[63]);
        assert_eq!(m.lookup(-5.0, -5.0), m.texels[63 * 64]);
    }

    #[test]
    fn toon2_has_two_colours() {
        let m = procedural("toon2", 64, ORANGE).unwrap();
        let mut colours: Vec<[f32; 4]> = Vec::new();
        for (x, y) in inside_disk(64) {
            let t = m.texels[(y * 64 + x) as usize];
            if !colours.contains(&t) {
                colours.push(t);
            }
        }
        assert_eq!(colours.len(), 2, "{colours:?}");
        // Rim copies add no third colour either.
        assert!(m.texels.iter().all(|t| colours.contains(t)));
        let m = procedural("toon3", 64, ORANGE).unwrap();
        let mut colours: Vec<[f32; 4]> = Vec::new();
        for t in &m.texels {
            if !colours.contains(t) {
                colours.push(*t);
            }
        }
        assert_eq!(
            colours.len(),
            4,
            "three tones and the highlight: {colours:?}"
        );
    }

    #[test]
    fn ink_rim_is_dark_at_the_rim_and_light_inside() {
        let m = procedural("ink_rim", 64, ORANGE).unwrap();
        assert!(m.lookup(0.0, 0.0)[..3].iter().all(|&c| c > 0.7));
        let rim = m.lookup(0.99, 0.0);
        assert!(rim[..3].iter().all(|&c| c < 0.05), "{rim:?}");
    }

    #[test]
    fn mip_chain_levels() {
        let a = procedural("gooch", 64, ORANGE).unwrap();
        let b = procedural("toon2", 64, [0.1, 0.8, 0.3]).unwrap();
        let chain = a.mip_chain();
        assert_eq!(
            chain.iter().map(|m| m.size).collect::<Vec<_>>(),
            [64, 32, 16, 8, 4, 2, 1]
        );
        assert_eq!(chain[0], a);
        for level in &chain {
            assert_eq!(level.texels.len(), (level.size * level.size) as usize);
        }
        // Each level is the box average of the previous level of the same map.
        let l1 = &chain[1];
        let want: [f32; 4] = std::array::from_fn(|c| {
            (a.texels[0][c] + a.texels[1][c] + a.texels[64][c] + a.texels[65][c]) / 4.0
        });
        assert_eq!(l1.texels[0], want);
        // The 1x1 level is the mean of this map only (another map's chain is independent).
        let mean = |m: &LitSphere| -> [f32; 4] {
            let n = m.texels.len() as f64;
            std::array::from_fn(|c| (m.texels.iter().map(|t| t[c] as f64).sum::<f64>() / n) as f32)
        };
        let top_a = chain[6].texels[0];
        let top_b = b.mip_chain()[6].texels[0];
        for c in 0..4 {
            assert!((top_a[c] - mean(&a)[c]).abs() < 1e-5);
            assert!((top_b[c] - mean(&b)[c]).abs() < 1e-5);
        }
        assert_ne!(top_a, top_b);
        // Building B's chain leaves A's untouched (no shared state).
        assert_eq!(a.mip_chain(), chain);
        assert_eq!(procedural("flat", 1, ORANGE).unwrap().mip_chain().len(), 1);
        let odd = LitSphere {
            size: 3,
            texels: vec![[0.0; 4]; 9],
        };
        assert_eq!(odd.mip_chain().len(), 1);
    }

    #[test]
    fn from_rgba8_converts_and_cleans_the_corners() {
        assert!(
            from_rgba8(4, 2, &[0; 32])
                .unwrap_err()
                .to_string()
                .contains("square")
        );
        assert!(
            from_rgba8(6, 6, &[0; 144])
                .unwrap_err()
                .to_string()
                .contains("power of two")
        );
        assert!(
            from_rgba8(4, 4, &[0; 10])
                .unwrap_err()
                .to_string()
                .contains("bytes")
        );
        // Red inside the disk, green garbage outside.
        let size = 16u32;
        let mut bytes = Vec::new();
        for y in 0..size {
            for x in 0..size {
                let (nx, ny) = texel_normal(size, x, y);
                if nx * nx + ny * ny <= 1.0 {
                    bytes.extend([255, 0, (x * 16) as u8, 255]);
                } else {
                    bytes.extend([0, 255, 0, 0]);
                }
            }
        }
        let m = from_rgba8(size, size, &bytes).unwrap();
        assert_eq!(m.texels[8 * 16 + 8], [1.0, 0.0, 128.0 / 255.0, 1.0]);
        assert!(
            m.texels
                .iter()
                .all(|t| t[0] == 1.0 && t[1] == 0.0 && t[3] == 1.0)
        );
        // A corner copies a rim texel in its own direction (left edge -> small blue).
        assert!(m.texels[0][2] < 0.3 && m.texels[15][2] > 0.7);
    }
}

//! Shading for illustrative volume rendering: the VolumeShop lighting transfer function
//! (Bruckner & Gröller 2005, eq. 8 of the tutorial's VolumeShop chapter), two-sided
//! Blinn–Phong (tutorial eq. 3) and context-preserving opacity (tutorial eq. 5).

/// Entries along each axis of a lighting transfer function table.
pub const LIGHTING_SIZE: usize = 64;

/// Names accepted by [`lighting_tf`].
pub const LIGHTING_MODELS: &[&str] = &["phong", "phong_contour", "cartoon", "metal"];

/// Width (standard deviation, in units of `N·V`) of the Gaussian contour falloff of the
/// contour models.
pub const CONTOUR_WIDTH: f32 = 0.15;

/// A 2D lighting transfer function over `(N·L, N·H)`, each in [-1, 1].
///
/// Entry `(a, b)` sits at `N·L = -1 + 2a / (LIGHTING_SIZE - 1)`,
/// `N·H = -1 + 2b / (LIGHTING_SIZE - 1)` and is stored at `table[b * LIGHTING_SIZE + a]`
/// (row-major, `b` the row). Each entry is `(s_a, s_d, s_s, s_alpha)`.
#[derive(Debug, Clone, PartialEq)]
pub struct LightingTf {
    pub table: Vec<[f32; 4]>,
}

/// The table position of grid entry `k`.
fn grid(k: usize) -> f32 {
    -1.0 + 2.0 * k as f32 / (LIGHTING_SIZE - 1) as f32
}

/// Gaussian contour weight at `N·V` (1 on the contour, falling off with [`CONTOUR_WIDTH`]).
fn contour_weight(n_dot_v: f32) -> f32 {
    (-0.5 * (n_dot_v / CONTOUR_WIDTH).powi(2)).exp()
}

/// The table of a named model (see [`LIGHTING_MODELS`]), or `None`.
///
/// - `phong`: `s_a = 0.15`, `s_d = 0.85 max(N·L, 0)`, `s_s = 0.4 max(N·H, 0)^32`, `s_alpha = 1`.
/// - `phong_contour`: as `phong` with `s_a, s_d, s_s` times `1 − w` and `s_alpha = 1 − 0.5 w`,
///   `w = exp(−½ (N·V / 0.15)²)` the contour weight at `N·V = 2 N·H − N·L` (the tutorial's
///   relation, exact for a headlight `L = V`). So `s_alpha = 0.5` on the contour (opacity
///   enhancement), → 1 away from it.
/// - `cartoon`: `s_a = 0.1`, `s_d = 0.9` where `N·L > 0.3` else `0.35` (two levels), a hard
///   highlight `s_s = 0.5` where `N·H > 0.95`, and the contour of `phong_contour`.
/// - `metal`: `s_a = 0.1`, banded diffuse `s_d = 0.25 + 0.6 sin²(3 N·L)`,
///   `s_s = 0.8 max(N·H, 0)^64`, and the contour of `phong_contour`.
pub fn lighting_tf(model: &str) -> Option<LightingTf> {
    let entry: fn(f32, f32) -> [f32; 4] = match model {
        "phong" => phong_entry,
        "phong_contour" => |nl, nh| with_contour(phong_entry(nl, nh), nl, nh),
        "cartoon" => |nl, nh| {
            let d = if nl > 0.3 { 0.9 } else { 0.35 };
            let s = if nh > 0.95 { 0.5 } else { 0.0 };
            with_contour([0.1, d, s, 1.0], nl, nh)
        },
        "metal" => |nl, nh| {
            let d = 0.25 + 0.6 * (3.0 * nl).sin().powi(2);
            let s = 0.8 * nh.max(0.0).powi(64);
            with_contour([0.1, d, s, 1.0], nl, nh)
        },
        _ => return None,
    };
    let table = (0..LIGHTING_SIZE * LIGHTING_SIZE)
        .map(|i| entry(grid(i % LIGHTING_SIZE), grid(i / LIGHTING_SIZE)))
        .collect();
    Some(LightingTf { table })
}

fn phong_entry(nl: f32, nh: f32) -> [f32; 4] {
    [0.15, 0.85 * nl.max(0.0), 0.4 * nh.max(0.0).powi(32), 1.0]
}

fn with_contour(s: [f32; 4], nl: f32, nh: f32) -> [f32; 4] {
    let w = contour_weight(2.0 * nh - nl);
    [
        s[0] * (1.0 - w),
        s[1] * (1.0 - w),
        s[2] * (1.0 - w),
        1.0 - 0.5 * w,
    ]
}

impl LightingTf {
    /// Bilinear lookup with the arguments clamped to [-1, 1] (NaN -> -1): per axis
    /// `x = (d + 1) / 2 · (LIGHTING_SIZE − 1)`, `k = min(floor(x), LIGHTING_SIZE − 2)`, `f = x − k`
    /// — the transfer function rule on a grid whose entries sit exactly on the end points. A
    /// GPU texture of `LIGHTING_SIZE` texels reproduces it with the texture coordinate
    /// `(x + 0.5) / LIGHTING_SIZE`.
    pub fn lookup(&self, n_dot_l: f32, n_dot_h: f32) -> [f32; 4] {
        let pos = |d: f32| {
            let d = if d.is_nan() { -1.0 } else { d.clamp(-1.0, 1.0) };
            let x = (d + 1.0) * 0.5 * (LIGHTING_SIZE - 1) as f32;
            let k = (x.floor() as usize).min(LIGHTING_SIZE - 2);
            (k, x - k as f32)
        };
        let (a, fa) = pos(n_dot_l);
        let (b, fb) = pos(n_dot_h);
        let t = |a: usize, b: usize| self.table[b * LIGHTING_SIZE + a];
        let lerp = |p: [f32; 4], q: [f32; 4], f: f32| -> [f32; 4] {
            std::array::from_fn(|c| p[c] + (q[c] - p[c]) * f)
        };
        lerp(
            lerp(t(a, b), t(a + 1, b), fa),
            lerp(t(a, b + 1), t(a + 1, b + 1), fa),
            fb,
        )
    }
}

/// Eq. 8: `c_s = (s_a + s_d) · c_u + s_s` (not clamped) and
/// `α_s = min(1, α_u / max(1e-6, min(1, s_alpha + (1 − |N|))))`, `|N|` the gradient magnitude
/// normalised to [0, 1] (clamped). Where the gradient is strong and `s_alpha < 1` the opacity
/// is enhanced; in homogeneous regions (`|N| → 0`) it is unchanged.
pub fn apply_lighting_tf(
    s: [f32; 4],
    color: [f32; 3],
    alpha_u: f32,
    gradient_norm: f32,
) -> ([f32; 3], f32) {
    let [s_a, s_d, s_s, s_alpha] = s;
    let c = color.map(|c| (s_a + s_d) * c + s_s);
    let g = gradient_norm.clamp(0.0, 1.0);
    let denominator = (s_alpha + (1.0 - g)).clamp(1e-6, 1.0);
    (c, (alpha_u / denominator).min(1.0))
}

/// Tutorial eq. 3, two-sided Blinn–Phong: `s = c_d |L·n| + c_s |H·n|^c_e + c_a`.
pub fn phong_intensity(
    n: [f32; 3],
    l: [f32; 3],
    h: [f32; 3],
    c_a: f32,
    c_d: f32,
    c_s: f32,
    c_e: f32,
) -> f32 {
    let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    c_d * dot(l, n).abs() + c_s * dot(h, n).abs().powf(c_e) + c_a
}

/// Tutorial eq. 5, context-preserving opacity:
/// `α = α_tf · |g|^((κt · s · (1 − dist) · (1 − α_prev))^κs)`.
///
/// `|g|`, `dist` and `α_prev` are clamped to [0, 1]. Conventions for the powers (which a GPU
/// `pow` leaves undefined at 0):
/// - base `b = κt · s · (1 − dist) · (1 − α_prev)`; when `b <= 0` (or NaN) the exponent is 0,
///   otherwise `b^κs` (so `κs = 0` gives exponent 1, plain gradient-magnitude modulation,
///   wherever `b > 0`);
/// - an exponent of exactly 0 gives the factor 1 (so `κt = 0` is plain DVR even where
///   `|g| = 0`); otherwise the factor is `|g|^exponent` (0 where `|g| = 0`).
pub fn context_preserving_alpha(
    alpha_tf: f32,
    gradient_norm: f32,
    kappa_t: f32,
    kappa_s: f32,
    shading: f32,
    distance_norm: f32,
    alpha_prev: f32,
) -> f32 {
    let g = gradient_norm.clamp(0.0, 1.0);
    let base = eq5_base(kappa_t, shading, distance_norm, alpha_prev);
    let exponent = if base > 0.0 { base.powf(kappa_s) } else { 0.0 };
    if exponent == 0.0 {
        alpha_tf
    } else {
        alpha_tf * g.powf(exponent)
    }
}

/// The base of eq. 5's inner exponent: κt · s · (1 − ‖P − E‖) · (1 − α_{i−1}).
fn eq5_base(kappa_t: f32, shading: f32, distance_norm: f32, alpha_prev: f32) -> f32 {
    kappa_t * shading * (1.0 - distance_norm.clamp(0.0, 1.0)) * (1.0 - alpha_prev.clamp(0.0, 1.0))
}

/// [`context_preserving_alpha`] with the paper's fast exponentiation (§6, eq. 6–7): Schlick's
/// x^n ≈ x / (n − n·x + x) for both powers — the inner (κt·s·(1 − d)·(1 − α))^κs where its base
/// is in [0, 1] (a base above 1 keeps `powf`), and the outer g^e. A different curve than the
/// exact one with the same ends (g = 0 → 0, g = 1 → 1, e = 0 → the TF's opacity), monotone in g
/// and in e; the ray caster uses it with `fast_exponent`.
pub fn context_preserving_alpha_fast(
    alpha_tf: f32,
    gradient_norm: f32,
    kappa_t: f32,
    kappa_s: f32,
    shading: f32,
    distance_norm: f32,
    alpha_prev: f32,
) -> f32 {
    let schlick = |x: f32, n: f32| x / (n - n * x + x).max(1e-30);
    let base = eq5_base(kappa_t, shading, distance_norm, alpha_prev);
    if base <= 0.0 {
        return alpha_tf;
    }
    let exponent = if base <= 1.0 {
        schlick(base, kappa_s)
    } else {
        base.powf(kappa_s)
    };
    alpha_tf * schlick(gradient_norm.clamp(0.0, 1.0), exponent)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn normalize(v: [f32; 3]) -> [f32; 3] {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|c| c / l)
    }

    #[test]
    fn tables_have_the_right_shape() {
        for model in LIGHTING_MODELS {
            let tf = lighting_tf(model).unwrap();
            assert_eq!(tf.table.len(), LIGHTING_SIZE * LIGHTING_SIZE);
            assert!(
                tf.table
                    .iter()
                    .flatten()
                    .all(|c| c.is_finite() && *c >= 0.0)
            );
            assert!(tf.table.iter().all(|e| e[3] > 0.0 && e[3] <= 1.0));
        }
        assert!(lighting_tf("nope").is_none());
        // Grid entries sit on the end points; b is the row.
        let tf = lighting_tf("phong").unwrap();
        assert_eq!(tf.table[0], [0.15, 0.0, 0.0, 1.0]);
        assert_eq!(tf.table[LIGHTING_SIZE - 1], [0.15, 0.85, 0.0, 1.0]);
        assert_eq!(
            tf.table[LIGHTING_SIZE * (LIGHTING_SIZE - 1)],
            [0.15, 0.0, 0.4, 1.0]
        );
        assert_eq!(tf.lookup(1.0, 1.0), [0.15, 0.85, 0.4, 1.0]);
        assert_eq!(tf.lookup(5.0, -5.0), [0.15, 0.85, 0.0, 1.0]);
    }

    #[test]
    fn phong_table_matches_phong_intensity() {
        let tf = lighting_tf("phong").unwrap();
        let l = normalize([0.3, 0.5, 1.0]);
        let v = [0.0, 0.0, 1.0];
        let h = normalize([l[0] + v[0], l[1] + v[1], l[2] + v[2]]);
        for n in [
            [0.0, 0.0, 1.0],
            normalize([0.2, 0.4, 0.9]),
            normalize([0.9, -0.3, 0.3]),
            l,
            h,
        ] {
            let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let (nl, nh) = (dot(n, l), dot(n, h));
            let s = tf.lookup(nl, nh);
            // For a front-facing normal (N·L, N·H >= 0) the table's ambient + diffuse +
            // specular is eq. 3 with the same coefficients, up to the table's linear
            // interpolation (the specular power curve is steep near N·H = 1).
            let want = phong_intensity(n, l, h, 0.15, 0.85, 0.4, 32.0);
            let got = s[0] + s[1] + s[2];
            // Ambient + diffuse are piecewise linear (one kink at N·L = 0, between grid
            // points); the specular x^32 bends by up to ~0.03 between grid points near 1.
            let diffuse = phong_intensity(n, l, h, 0.15, 0.85, 0.0, 32.0);
            assert!(
                (s[0] + s[1] - diffuse).abs() < 0.01,
                "n {n:?}: {s:?} vs {diffuse}"
            );
            assert!(
                (got - want).abs() < 0.035,
                "n {n:?}: table {got} vs eq. 3 {want}"
            );
        }
        // At grid points the table is exact.
        for (a, b) in [(10usize, 40usize), (63, 63), (50, 60)] {
            let (nl, nh) = (grid(a), grid(b));
            let s = tf.lookup(nl, nh);
            let want = 0.15 + 0.85 * nl.max(0.0) + 0.4 * nh.max(0.0).powi(32);
            assert!((s[0] + s[1] + s[2] - want).abs() < 1e-5);
        }
    }

    #[test]
    fn contour_models_darken_and_enhance_at_the_contour() {
        let tf = lighting_tf("phong_contour").unwrap();
        // N·V = 2 N·H − N·L = 0 at (N·L, N·H) = (0.5, 0.25): dark and s_alpha ~ 0.5.
        let s = tf.lookup(0.5, 0.25);
        assert!(
            s[0] + s[1] + s[2] < 0.05 && (s[3] - 0.5).abs() < 0.02,
            "{s:?}"
        );
        // Facing the viewer (N·V = 1 at N·L = 1, N·H = 1): like phong.
        let s = tf.lookup(1.0, 1.0);
        assert!(
            (s[1] - 0.85).abs() < 1e-3 && (s[3] - 1.0).abs() < 1e-3,
            "{s:?}"
        );
        for model in ["cartoon", "metal"] {
            let tf = lighting_tf(model).unwrap();
            let s = tf.lookup(0.5, 0.25);
            assert!(s[0] + s[1] + s[2] < 0.05, "{model}: {s:?}");
        }
        // Cartoon: two diffuse levels away from the contour.
        let tf = lighting_tf("cartoon").unwrap();
        let mut levels: Vec<f32> = Vec::new();
        for b in 0..LIGHTING_SIZE {
            for a in 0..LIGHTING_SIZE {
                let (nl, nh) = (grid(a), grid(b));
                if (2.0 * nh - nl).abs() > 1.0 {
                    let d = (tf.table[b * LIGHTING_SIZE + a][1] * 1000.0).round();
                    if !levels.contains(&d) {
                        levels.push(d);
                    }
                }
            }
        }
        assert_eq!(levels.len(), 2, "{levels:?}");
    }

    #[test]
    fn eq8_colour_and_opacity() {
        let (c, a) = apply_lighting_tf([0.1, 0.5, 0.2, 1.0], [1.0, 0.5, 0.0], 0.4, 0.7);
        assert_eq!(c, [0.8, 0.5, 0.2]);
        assert!((a - 0.4).abs() < 1e-7);
        // Enhancement only with a strong gradient: s_alpha 0.5, |N| = 1 -> doubled.
        let (_, a) = apply_lighting_tf([0.0, 0.0, 0.0, 0.5], [1.0; 3], 0.3, 1.0);
        assert!((a - 0.6).abs() < 1e-6);
        // Homogeneous: unchanged.
        let (_, a) = apply_lighting_tf([0.0, 0.0, 0.0, 0.5], [1.0; 3], 0.3, 0.0);
        assert!((a - 0.3).abs() < 1e-7);
        // Partly: denominator 0.5 + 0.25.
        let (_, a) = apply_lighting_tf([0.0, 0.0, 0.0, 0.5], [1.0; 3], 0.3, 0.75);
        assert!((a - 0.4).abs() < 1e-6);
        // Clamped to 1; s_alpha = 0 with |N| = 1 does not divide by zero.
        let (_, a) = apply_lighting_tf([0.0, 0.0, 0.0, 0.0], [1.0; 3], 0.3, 1.0);
        assert_eq!(a, 1.0);
        let (_, a) = apply_lighting_tf([0.0, 0.0, 0.0, 0.0], [1.0; 3], 0.0, 1.0);
        assert_eq!(a, 0.0);
    }

    #[test]
    fn phong_intensity_is_two_sided() {
        let l = [0.0, 0.0, 1.0];
        let h = [0.0, 0.0, 1.0];
        let s = phong_intensity([0.0, 0.0, 1.0], l, h, 0.1, 0.6, 0.3, 20.0);
        assert!((s - 1.0).abs() < 1e-6);
        assert_eq!(
            phong_intensity([0.0, 0.0, -1.0], l, h, 0.1, 0.6, 0.3, 20.0),
            s
        );
        let n = normalize([1.0, 0.0, 1.0]);
        let s = phong_intensity(n, l, h, 0.1, 0.6, 0.3, 2.0);
        assert!((s - (0.1 + 0.6 * 0.5f32.sqrt() + 0.3 * 0.5)).abs() < 1e-6);
        // Zero normal: ambient only.
        assert_eq!(phong_intensity([0.0; 3], l, h, 0.1, 0.6, 0.3, 2.0), 0.1);
    }

    #[test]
    fn context_preserving_alpha_properties() {
        // κt = 0: plain DVR whatever the rest.
        for (g, ks, s, d, prev) in [
            (0.0, 0.0, 1.0, 0.0, 0.0),
            (0.0, 1.0, 2.0, 0.5, 0.3),
            (0.5, 3.0, 0.7, 1.0, 0.9),
            (1.0, 0.5, 0.0, 0.2, 0.0),
        ] {
            assert_eq!(context_preserving_alpha(0.37, g, 0.0, ks, s, d, prev), 0.37);
        }
        // κs = 0 (with κt > 0): gradient-magnitude modulation.
        let a = context_preserving_alpha(0.8, 0.25, 2.0, 0.0, 0.9, 0.3, 0.1);
        assert!((a - 0.2).abs() < 1e-6);
        // The formula.
        let a = context_preserving_alpha(0.8, 0.25, 2.0, 0.5, 0.9, 0.3, 0.1);
        let e = (2.0f32 * 0.9 * 0.7 * 0.9).powf(0.5);
        assert!((a - 0.8 * 0.25f32.powf(e)).abs() < 1e-6);
        // |g| = 1 is never attenuated, |g| = 0 fully once the exponent is positive.
        assert_eq!(
            context_preserving_alpha(0.8, 1.0, 5.0, 1.0, 0.9, 0.3, 0.1),
            0.8
        );
        assert_eq!(
            context_preserving_alpha(0.8, 0.0, 5.0, 1.0, 0.9, 0.3, 0.1),
            0.0
        );
        // No effect at the far end or behind an opaque front.
        assert_eq!(
            context_preserving_alpha(0.8, 0.3, 5.0, 1.0, 0.9, 1.0, 0.1),
            0.8
        );
        assert_eq!(
            context_preserving_alpha(0.8, 0.3, 5.0, 1.0, 0.9, 0.2, 1.0),
            0.8
        );
        // Monotonically non-increasing in κt for |g| < 1.
        for g in [0.0, 0.1, 0.5, 0.99] {
            for ks in [0.0, 0.3, 1.0, 4.0] {
                let mut prev = f32::INFINITY;
                for i in 0..200 {
                    let kt = i as f32 * 0.05;
                    let a = context_preserving_alpha(0.9, g, kt, ks, 0.8, 0.3, 0.2);
                    assert!(a <= prev, "g {g} ks {ks} kt {kt}: {a} > {prev}");
                    prev = a;
                }
            }
        }
    }

    #[test]
    fn fast_context_preserving_alpha_keeps_the_ends_and_the_order() {
        // Schlick's curve differs from pow in the middle, not at the ends, and keeps eq. 5's
        // monotonicity: more gradient → more opacity, more exponent → less.
        let (kt, ks, d, prev) = (1.5, 0.5, 0.2, 0.1);
        let mut largest = 0.0f32;
        for s in [0.2f32, 0.6, 1.0] {
            let at = |g: f32| context_preserving_alpha_fast(0.8, g, kt, ks, s, d, prev);
            assert_eq!(at(0.0), 0.0);
            assert!((at(1.0) - 0.8).abs() < 1e-6);
            let mut last = 0.0;
            for k in 1..=100 {
                let g = k as f32 / 100.0;
                let v = at(g);
                assert!(v >= last, "not monotone in g at {g}");
                last = v;
                largest =
                    largest.max((v - context_preserving_alpha(0.8, g, kt, ks, s, d, prev)).abs());
            }
        }
        // κt = 0: plain DVR.
        assert_eq!(
            context_preserving_alpha_fast(0.7, 0.3, 0.0, ks, 1.0, d, prev),
            0.7
        );
        // An approximation, not the same function.
        assert!(
            largest > 0.01 && largest < 0.3,
            "largest difference {largest}"
        );
    }
}

//! CPU reference ray caster: the sampling rule the GPU ray caster implements, written out
//! plainly (no acceleration, no jitter) so GPU images can be checked against it.
//!
//! Per pixel `(x, y)`: `ndc = ((x + 0.5) / W * 2 − 1, 1 − (y + 0.5) / H * 2)`; `P0`, `P1` =
//! `inverse(view_proj)` applied to `(ndc, 0)` and `(ndc, 1)` (divided by w); `dir =
//! normalize(P1 − P0)`. The ray, taken to voxel space (`world_to_voxel`, with `t` still in world
//! units), is clipped against the box of voxel centres `[0, dims − 1]` (slab test, `t_in`
//! clamped to >= 0). Samples at `t = t_in + k h`,
//! `k = 0, 1, …` while `t <= t_out`, `h = step_voxels · min(spacing)`; each `t` is computed from
//! `k` (not accumulated).
//!
//! Interpretations where the specification leaves room (the GPU must match these):
//! - Unit normal: `n̂ = SHADING_NORMAL_SIGN · g / |g|` with the sign −1 (towards lower values, outward
//!   for bright objects, the GPU's convention) (0 if `|g| < 1e-12`), moved to view
//!   space with `view.transform_vector3` and renormalised (a no-op for a rigid view matrix).
//!   The sign only matters for the lighting transfer function (signed `N·L`, `N·H`); see
//!   [`SHADING_NORMAL_SIGN`].
//! - `L = normalize(light_dir_view)`, `H = normalize(L + V)` (0 if `L = −V`).
//! - Gradient magnitude normalised as `|g| / gmax` clamped to [0, 1], 0 if `gmax = 0`, with
//!   `gmax = max_gradient_magnitude(volume)`.
//! - Context-preserving distance: perspective `d = |P − E|`, `E` = `inverse(view)` origin,
//!   normalised by the min/max of `|corner − E|` over the 8 box corners; orthographic: the eye
//!   is at infinity, `d` = depth along the ray from the near plane, `d = t` (measured from the
//!   ray's own `P0`), normalised by the min/max over the 8 corners of `(corner − P0) · dir`
//!   (the same for every ray, since all `P0` lie on the near plane). In both cases
//!   `dist = clamp((d − d_min) / (d_max − d_min), 0, 1)` (0 if `d_max <= d_min`).
//! - Iso colour with `Lighting` shading: the colour part of eq. 8 (alpha stays 1);
//!   with `ContextPreserving`: as `Phong`.
//! - Svakhine et al. 2005's Table 1 enhancements ([`Enhancement`], [`render_enhanced`]; DVR):
//!   samples whose transfer-function opacity `o_o` is 0 stay transparent; else the banding widget
//!   `o ← ((1 + sin(o·π·m)) / 2)^n` maps `o_o` first, and boundary `|∇P|^n` (`|∇P| = |g| / gmax`,
//!   as above) and silhouette `(1 − |n̂·V|)^n` enhancement (`n̂` the view-space unit normal, 0
//!   where `|g| < 1e-12`; `V` the view-space direction to the viewer, `+z` for orthographic
//!   cameras) multiply the opacity after shading (after eq. 8's enhancement) and before the step
//!   correction (and before eq. 5).
//! - 2-D transfer functions ([`render_2d`]; DVR): each sample is classified by
//!   `TransferFunction2D::lookup(v, s)`, `s` the normalised gradient magnitude `|g| / gmax` or
//!   the Laplacian of `hatchery_data::transfer_function_2d::laplacian`.

#![allow(dead_code)]

use glam::{Mat4, Vec3, Vec4};
use hatchery_data::VolumeData;
use hatchery_data::gradient::max_gradient_magnitude;
use hatchery_data::lighting::{
    LightingTf, apply_lighting_tf, context_preserving_alpha, phong_intensity,
};
use hatchery_data::transfer_function::TransferFunction1D;

/// Sign of the shading normal: `+1` is the specification's `n̂ = g / |g|` (towards higher
/// values, i.e. inwards for a bright object on a dark background). Phong and context-preserving
/// shading use absolute values and do not care; the lighting transfer function is looked up
/// with signed `N·L`, `N·H`, so with `+1` the lit side of a bright object gets `N·L < 0`.
/// `-1` (outward for bright objects, the gbuffer's convention) is the other choice.
pub const SHADING_NORMAL_SIGN: f32 = -1.0;

/// What a ray computes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Mode {
    /// Front-to-back direct volume rendering.
    Dvr,
    /// Maximum intensity projection.
    Mip,
    /// First crossing of the iso value (linearly refined between samples).
    Iso(f32),
}

/// How a DVR (or iso) sample is shaded.
#[derive(Debug, Clone, PartialEq)]
pub enum Shading {
    None,
    /// Two-sided Blinn–Phong (tutorial eq. 3); the colour is `clamp(c · s, 0, 1)`.
    Phong {
        ambient: f32,
        diffuse: f32,
        specular: f32,
        exponent: f32,
    },
    /// VolumeShop lighting transfer function (tutorial eq. 8), looked up with signed `N·L`,
    /// `N·H`.
    Lighting(LightingTf),
    /// Colour as `Phong`, opacity by the context-preserving model (tutorial eq. 5).
    ContextPreserving {
        kappa_t: f32,
        kappa_s: f32,
        /// Schlick's approximation of the exponentiations (`fast_exponent`).
        fast_exponent: bool,
        ambient: f32,
        diffuse: f32,
        specular: f32,
        exponent: f32,
    },
}

#[derive(Debug, Clone, PartialEq)]
pub struct RayParams {
    pub view_proj: Mat4,
    pub view: Mat4,
    pub width: u32,
    pub height: u32,
    pub orthographic: bool,
    /// Sample distance in voxels; the world step is `step_voxels · min(spacing)`.
    pub step_voxels: f32,
    pub mode: Mode,
    pub shading: Shading,
    /// Unit vector towards the light, in view space.
    pub light_dir_view: Vec3,
    /// Stop after the sample at which the accumulated alpha reaches this (1.0 disables).
    pub early_termination: f32,
}

/// `P0` (on the near plane) and the unit direction of the ray through pixel `(x, y)`.
pub fn pixel_ray(p: &RayParams, x: u32, y: u32) -> (Vec3, Vec3) {
    let inverse = p.view_proj.inverse();
    let ndc_x = (x as f32 + 0.5) / p.width as f32 * 2.0 - 1.0;
    let ndc_y = 1.0 - (y as f32 + 0.5) / p.height as f32 * 2.0;
    let unproject = |z: f32| {
        let h = inverse * Vec4::new(ndc_x, ndc_y, z, 1.0);
        h.truncate() / h.w
    };
    let p0 = unproject(0.0);
    let p1 = unproject(1.0);
    (p0, (p1 - p0).normalize())
}

/// Slab intersection of `origin + t dir` with the box `[lo, hi]`: `(t_in, t_out)` with `t_in`
/// clamped to >= 0, or `None` if the ray misses (or the box is behind it). A zero direction
/// component constrains nothing if the origin lies within that slab (bounds inclusive) and
/// misses otherwise.
pub fn intersect_box(lo: Vec3, hi: Vec3, origin: Vec3, dir: Vec3) -> Option<(f32, f32)> {
    let mut t_in = f32::NEG_INFINITY;
    let mut t_out = f32::INFINITY;
    for axis in 0..3 {
        let (o, d) = (origin[axis], dir[axis]);
        if d == 0.0 {
            if o < lo[axis] || o > hi[axis] {
                return None;
            }
            continue;
        }
        let t1 = (lo[axis] - o) / d;
        let t2 = (hi[axis] - o) / d;
        t_in = t_in.max(t1.min(t2));
        t_out = t_out.min(t1.max(t2));
    }
    let t_in = t_in.max(0.0);
    (t_in <= t_out).then_some((t_in, t_out))
}

/// The world step `h` of the parameters for this volume.
pub fn world_step(volume: &VolumeData, p: &RayParams) -> f32 {
    let min_spacing = volume
        .spacing()
        .iter()
        .copied()
        .fold(f32::INFINITY, f32::min);
    p.step_voxels * min_spacing
}

/// How values and gradients are reconstructed between voxels (the nodes' `reconstruction`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Filter {
    /// Trilinear values, central differences of trilinear values for gradients.
    Trilinear,
    /// The tricubic B-spline's values and gradients ([`super::bspline_reference`]).
    Bspline,
}

/// Svakhine et al. 2005, Table 1: the exponents of boundary and silhouette enhancement and the
/// banding widget's period `m` and power `n` (0 = off, as the `Raycast` node's parameters).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Enhancement {
    pub boundary: f32,
    pub silhouette: f32,
    pub banding_period: f32,
    pub banding_power: f32,
}

impl Default for Enhancement {
    fn default() -> Self {
        Self {
            boundary: 0.0,
            silhouette: 0.0,
            banding_period: 0.0,
            banding_power: 1.0,
        }
    }
}

/// Fields besides the rendered one (Svakhine et al. 2005 §3.2–3.3), on its grid: a second
/// scalar field S (a 2-D transfer function's second_field axis; `Measure::Second`) and a vector
/// field U (`Measure::Vector`).
#[derive(Clone, Copy, Default)]
pub struct Fields<'a> {
    pub second: Option<&'a VolumeData>,
    pub vector: Option<&'a hatchery_data::vector_field::VectorFieldData>,
    pub measure: Measure,
}

/// What boundary and silhouette enhancement measure (the node's `enhancement_field`).
#[derive(Clone, Copy, Default, PartialEq, Eq, Debug)]
pub enum Measure {
    /// ∇P / max |∇P| of the rendered field.
    #[default]
    Rendered,
    /// ∇S / max |∇S| of the second field.
    Second,
    /// U / max |U|.
    Vector,
}

/// [`render`] (DVR) with a 1-D (`tf2d` None) or 2-D transfer function, Table 1's enhancements
/// and the `fields` they read.
pub fn render_fields(
    volume: &VolumeData,
    tf: &TransferFunction1D,
    tf2d: Option<&hatchery_data::transfer_function_2d::TransferFunction2D>,
    p: &RayParams,
    enhancement: Enhancement,
    fields: Fields,
) -> Vec<[f32; 4]> {
    let mut caster = Caster::new(volume, p, Filter::Trilinear);
    caster.enhancement = enhancement;
    caster.tf2d = tf2d;
    caster.gmax = max_gradient_magnitude(volume);
    caster.second = fields.second.map(|s| (s, max_gradient_magnitude(s)));
    caster.vector = fields.vector.map(|u| {
        let component = |c: usize| {
            let values = u.vectors.iter().map(|v| v[c]).collect();
            VolumeData::with_geometry(u.dims, u.geometry, values).unwrap()
        };
        ([0, 1, 2].map(component), u.max_magnitude())
    });
    caster.measure = fields.measure;
    per_pixel(p.width, p.height, |x, y| caster.pixel(tf, x, y))
}

/// `x^n` for `x` in [0, 1] (0 for `x <= 0`), as the shader's `power`.
fn power(x: f32, n: f32) -> f32 {
    if x <= 0.0 { 0.0 } else { x.min(1.0).powf(n) }
}

impl Enhancement {
    /// The banding widget: `((1 + sin(o·π·m)) / 2)^n` (`o` unchanged when off).
    pub fn band(&self, o: f32) -> f32 {
        if self.banding_period > 0.0 {
            let s = (o * std::f32::consts::PI * self.banding_period).sin();
            power(0.5 * (1.0 + s), self.banding_power)
        } else {
            o
        }
    }

    /// Boundary × silhouette factor for normalised gradient magnitude `g_norm`, unit normal `n`
    /// and direction to the viewer `v` (1 when both are off).
    pub fn factor(&self, g_norm: f32, n: Vec3, v: Vec3) -> f32 {
        let mut f = 1.0;
        if self.boundary > 0.0 {
            f *= power(g_norm, self.boundary);
        }
        if self.silhouette > 0.0 {
            f *= power(1.0 - n.dot(v).abs(), self.silhouette);
        }
        f
    }
}

/// [`render`] (DVR) with Svakhine et al.'s Table 1 enhancements.
pub fn render_enhanced(
    volume: &VolumeData,
    tf: &TransferFunction1D,
    p: &RayParams,
    enhancement: Enhancement,
) -> Vec<[f32; 4]> {
    let mut caster = Caster::new(volume, p, Filter::Trilinear);
    caster.enhancement = enhancement;
    if enhancement.boundary > 0.0 {
        caster.gmax = max_gradient_magnitude(volume);
    }
    per_pixel(p.width, p.height, |x, y| caster.pixel(tf, x, y))
}

/// [`render`] (DVR) classified by a 2-D transfer function (value × normalised gradient
/// magnitude or Laplacian, `hatchery_data::transfer_function_2d`), with Table 1's enhancements.
pub fn render_2d(
    volume: &VolumeData,
    tf: &hatchery_data::transfer_function_2d::TransferFunction2D,
    p: &RayParams,
    enhancement: Enhancement,
) -> Vec<[f32; 4]> {
    let mut caster = Caster::new(volume, p, Filter::Trilinear);
    caster.enhancement = enhancement;
    caster.tf2d = Some(tf);
    caster.gmax = max_gradient_magnitude(volume);
    // The 1-D table is not read.
    let unused = TransferFunction1D::from_points(&[
        hatchery_data::transfer_function::ControlPoint {
            value: 0.0,
            rgba: [0.0; 4],
        },
        hatchery_data::transfer_function::ControlPoint {
            value: 1.0,
            rgba: [0.0; 4],
        },
    ])
    .unwrap();
    per_pixel(p.width, p.height, |x, y| caster.pixel(&unused, x, y))
}

/// Premultiplied RGBA per pixel, row 0 at the top.
pub fn render(volume: &VolumeData, tf: &TransferFunction1D, p: &RayParams) -> Vec<[f32; 4]> {
    render_with(volume, tf, p, Filter::Trilinear)
}

/// [`render`] with the given reconstruction filter.
pub fn render_with(
    volume: &VolumeData,
    tf: &TransferFunction1D,
    p: &RayParams,
    filter: Filter,
) -> Vec<[f32; 4]> {
    let caster = Caster::new(volume, p, filter);
    per_pixel(p.width, p.height, |x, y| caster.pixel(tf, x, y))
}

/// [`render`] (DVR, shading none or Phong) with a pre-integrated transfer function: each sample
/// composites the segment from the previous sample's value to its own, integrated by
/// `hatchery_data::preintegration::segment` at the exact (not tabulated) positions; the first
/// sample of a ray is a constant segment.
pub fn render_preintegrated(
    volume: &VolumeData,
    tf: &TransferFunction1D,
    p: &RayParams,
) -> Vec<[f32; 4]> {
    let mut caster = Caster::new(volume, p, Filter::Trilinear);
    caster.preintegrated = true;
    per_pixel(p.width, p.height, |x, y| caster.pixel(tf, x, y))
}

/// Per pixel: the window depth `(view_proj · P).z / w` of the first crossing `P` of `iso` (as
/// [`Mode::Iso`] finds it; 1 if none) and the view-space unit normal `−g / |g|` there (towards
/// lower values; zero if no hit or `|g| < 1e-12`). `p.mode` and `p.shading` are ignored.
pub fn gbuffer_iso(volume: &VolumeData, p: &RayParams, iso: f32) -> Vec<(f32, Vec3)> {
    gbuffer_iso_with(volume, p, iso, Filter::Trilinear)
}

/// [`gbuffer_iso`] with the given reconstruction filter.
pub fn gbuffer_iso_with(
    volume: &VolumeData,
    p: &RayParams,
    iso: f32,
    filter: Filter,
) -> Vec<(f32, Vec3)> {
    let caster = Caster::new(volume, p, filter);
    per_pixel(p.width, p.height, |x, y| {
        let Some(ray) = caster.ray(x, y) else {
            return (1.0, Vec3::ZERO);
        };
        let Some(t) = caster.iso_hit(&ray, iso) else {
            return (1.0, Vec3::ZERO);
        };
        let pos = ray.at(t);
        let clip = p.view_proj * pos.extend(1.0);
        let g = caster.gradient(pos);
        let normal = if g.length() < 1e-12 {
            Vec3::ZERO
        } else {
            p.view
                .transform_vector3(-g / g.length())
                .normalize_or_zero()
        };
        (clip.z / clip.w, normal)
    })
}

/// Runs `f` for every pixel on all cores; row-major from the top row.
fn per_pixel<T: Send + Clone + Default>(
    width: u32,
    height: u32,
    f: impl Fn(u32, u32) -> T + Sync,
) -> Vec<T> {
    let mut out = vec![T::default(); width as usize * height as usize];
    if out.is_empty() {
        return out;
    }
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let rows_per_chunk = (height as usize).div_ceil(threads).max(1);
    std::thread::scope(|scope| {
        for (chunk, rows) in out.chunks_mut(rows_per_chunk * width as usize).enumerate() {
            let f = &f;
            scope.spawn(move || {
                for (i, px) in rows.iter_mut().enumerate() {
                    let i = chunk * rows_per_chunk * width as usize + i;
                    *px = f((i % width as usize) as u32, (i / width as usize) as u32);
                }
            });
        }
    });
    out
}

struct Ray {
    origin: Vec3,
    dir: Vec3,
    t_in: f32,
    t_out: f32,
}

impl Ray {
    fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.dir
    }
}

struct Caster<'a> {
    volume: &'a VolumeData,
    p: &'a RayParams,
    filter: Filter,
    preintegrated: bool,
    enhancement: Enhancement,
    /// A 2-D transfer function classifies instead of the 1-D one (DVR).
    tf2d: Option<&'a hatchery_data::transfer_function_2d::TransferFunction2D>,
    /// The second field with its largest gradient magnitude.
    second: Option<(&'a VolumeData, f32)>,
    /// The vector field's components with its largest magnitude.
    vector: Option<([VolumeData; 3], f32)>,
    measure: Measure,
    h: f32,
    /// Gradient magnitude normaliser (0 for a constant volume).
    gmax: f32,
    lo: Vec3,
    hi: Vec3,
    /// Perspective eye position (world).
    eye: Vec3,
    light: Vec3,
}

impl<'a> Caster<'a> {
    fn new(volume: &'a VolumeData, p: &'a RayParams, filter: Filter) -> Self {
        let h = world_step(volume, p);
        assert!(
            h > 0.0 && h.is_finite(),
            "step_voxels must be positive, got {}",
            p.step_voxels
        );
        let needs_gmax = matches!(
            p.shading,
            Shading::Lighting(_) | Shading::ContextPreserving { .. }
        );
        Self {
            volume,
            p,
            filter,
            preintegrated: false,
            enhancement: Enhancement::default(),
            tf2d: None,
            second: None,
            vector: None,
            measure: Measure::Rendered,
            h,
            gmax: if needs_gmax {
                max_gradient_magnitude(volume)
            } else {
                0.0
            },
            lo: -box_margin(volume),
            hi: last_voxel(volume) + box_margin(volume),
            eye: p.view.inverse().transform_point3(Vec3::ZERO),
            light: p.light_dir_view.normalize_or_zero(),
        }
    }

    fn ray(&self, x: u32, y: u32) -> Option<Ray> {
        let (origin, dir) = pixel_ray(self.p, x, y);
        // March in voxel space (t stays in world units), as the shader does.
        let q0 = self.volume.world_to_voxel(origin);
        let dq = self.volume.world_to_voxel(origin + dir) - q0;
        let (t_in, t_out) = intersect_box(self.lo, self.hi, q0, dq)?;
        Some(Ray {
            origin,
            dir,
            t_in,
            t_out,
        })
    }

    /// The sample positions' parameters `t_in + k h` for `k < floor((t_out − t_in) / h) + 1`
    /// (the count is computed once, exactly as the shader does).
    fn samples(&self, ray: &Ray) -> impl Iterator<Item = f32> + use<> {
        let (t_in, h) = (ray.t_in, self.h);
        let count = ((ray.t_out - t_in) / h).floor().max(-1.0) as i64 + 1;
        (0..count.max(0)).map(move |k| t_in + k as f32 * h)
    }

    fn voxel(&self, pos: Vec3) -> Vec3 {
        self.volume.world_to_voxel(pos)
    }

    fn value(&self, pos: Vec3) -> f32 {
        match self.filter {
            Filter::Trilinear => self.volume.sample_trilinear(self.voxel(pos)),
            Filter::Bspline => super::bspline_reference::value(self.volume, self.voxel(pos)),
        }
    }

    fn gradient(&self, pos: Vec3) -> Vec3 {
        match self.filter {
            Filter::Trilinear => self.volume.gradient(self.voxel(pos)),
            Filter::Bspline => super::bspline_reference::gradient(self.volume, self.voxel(pos)),
        }
    }

    fn gradient_norm(&self, g: Vec3) -> f32 {
        if self.gmax > 0.0 {
            (g.length() / self.gmax).min(1.0)
        } else {
            0.0
        }
    }

    /// View-space unit normal `n̂`, light `L` and half vector `H` at world position `pos` with
    /// gradient `g`.
    fn frame(&self, pos: Vec3, g: Vec3) -> (Vec3, Vec3, Vec3) {
        let len = g.length();
        let n = if len < 1e-12 {
            Vec3::ZERO
        } else {
            self.p
                .view
                .transform_vector3(SHADING_NORMAL_SIGN * g / len)
                .normalize_or_zero()
        };
        let v = if self.p.orthographic {
            Vec3::Z
        } else {
            -self.p.view.transform_point3(pos).normalize_or_zero()
        };
        let l = self.light;
        (n, l, (l + v).normalize_or_zero())
    }

    fn pixel(&self, tf: &TransferFunction1D, x: u32, y: u32) -> [f32; 4] {
        let Some(ray) = self.ray(x, y) else {
            return [0.0; 4];
        };
        match self.p.mode {
            Mode::Dvr => self.dvr(tf, &ray),
            Mode::Mip => {
                let m = self
                    .samples(&ray)
                    .map(|t| self.value(ray.at(t)))
                    .fold(None, |m: Option<f32>, v| Some(m.map_or(v, |m| m.max(v))));
                match m {
                    Some(m) => {
                        let [r, g, b, a] = tf.lookup(m);
                        [r * a, g * a, b * a, a]
                    }
                    None => [0.0; 4],
                }
            }
            Mode::Iso(iso) => match self.iso_hit(&ray, iso) {
                Some(t) => {
                    let pos = ray.at(t);
                    let [r, g, b, _] = tf.lookup(iso);
                    let c = self.shade_iso(Vec3::new(r, g, b), pos);
                    [c.x, c.y, c.z, 1.0]
                }
                None => [0.0; 4],
            },
        }
    }

    /// `t*` of the first sample with `v >= iso` (`t_in` if the first one is), refined linearly
    /// from the previous sample.
    fn iso_hit(&self, ray: &Ray, iso: f32) -> Option<f32> {
        let mut previous: Option<(f32, f32)> = None;
        for t in self.samples(ray) {
            let v = self.value(ray.at(t));
            if v >= iso {
                return Some(match previous {
                    None => t,
                    Some((t0, v0)) => t0 + self.h * (iso - v0) / (v - v0),
                });
            }
            previous = Some((t, v));
        }
        None
    }

    fn shade_iso(&self, c: Vec3, pos: Vec3) -> Vec3 {
        match &self.p.shading {
            Shading::None => c,
            Shading::Phong {
                ambient,
                diffuse,
                specular,
                exponent,
            }
            | Shading::ContextPreserving {
                ambient,
                diffuse,
                specular,
                exponent,
                ..
            } => {
                let (n, l, h) = self.frame(pos, self.gradient(pos));
                let s = phong_intensity(
                    n.to_array(),
                    l.to_array(),
                    h.to_array(),
                    *ambient,
                    *diffuse,
                    *specular,
                    *exponent,
                );
                (c * s).clamp(Vec3::ZERO, Vec3::ONE)
            }
            Shading::Lighting(table) => {
                let g = self.gradient(pos);
                let (n, l, h) = self.frame(pos, g);
                let s = table.lookup(n.dot(l), n.dot(h));
                let (c, _) = apply_lighting_tf(s, c.to_array(), 1.0, self.gradient_norm(g));
                Vec3::from_array(c).clamp(Vec3::ZERO, Vec3::ONE)
            }
        }
    }

    /// Normalised context-preserving distance of the sample at `t` on `ray`.
    fn distance_norm(&self, ray: &Ray, t: f32) -> f32 {
        let last = last_voxel(self.volume);
        let corners = (0..8).map(|i| {
            self.volume.voxel_to_world(Vec3::new(
                if i & 1 == 0 { 0.0 } else { last.x },
                if i & 2 == 0 { 0.0 } else { last.y },
                if i & 4 == 0 { 0.0 } else { last.z },
            ))
        });
        let (d, measure): (f32, Box<dyn Fn(Vec3) -> f32>) = if self.p.orthographic {
            let (o, dir) = (ray.origin, ray.dir);
            (t, Box::new(move |c: Vec3| (c - o).dot(dir)))
        } else {
            let eye = self.eye;
            (
                (ray.at(t) - eye).length(),
                Box::new(move |c: Vec3| (c - eye).length()),
            )
        };
        let (d_min, d_max) = corners
            .map(measure)
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), d| {
                (a.min(d), b.max(d))
            });
        if d_max > d_min {
            ((d - d_min) / (d_max - d_min)).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// The boundary × silhouette factor of Table 1 at `pos` (1 when both are off).
    fn enhancement_factor(&self, pos: Vec3) -> f32 {
        let e = &self.enhancement;
        if e.boundary <= 0.0 && e.silhouette <= 0.0 {
            return 1.0;
        }
        let v = if self.p.orthographic {
            Vec3::Z
        } else {
            -self.p.view.transform_point3(pos).normalize_or_zero()
        };
        // The measured field, divided by its largest magnitude.
        let scaled = |f: Vec3, max: f32| if max > 0.0 { f / max } else { Vec3::ZERO };
        let f = match self.measure {
            Measure::Rendered => {
                let g = self.gradient(pos);
                let (n, _, _) = self.frame(pos, g);
                return e.factor(self.gradient_norm(g), n, v);
            }
            Measure::Second => {
                let (s, max) = self.second.expect("Measure::Second needs a second field");
                scaled(s.gradient(self.voxel(pos)), max)
            }
            Measure::Vector => {
                let (u, max) = self.vector.as_ref().expect("Measure::Vector needs U");
                let q = self.voxel(pos);
                scaled(
                    Vec3::from(u.each_ref().map(|c| c.sample_trilinear(q))),
                    *max,
                )
            }
        };
        let (n, _, _) = self.frame(pos, f);
        e.factor(f.length().min(1.0), n, v)
    }

    fn dvr(&self, tf: &TransferFunction1D, ray: &Ray) -> [f32; 4] {
        let mut acc_c = Vec3::ZERO;
        let mut acc_a = 0.0f32;
        let mut front: Option<f32> = None;
        let enhanced = self.enhancement != Enhancement::default();
        for t in self.samples(ray) {
            let pos = ray.at(t);
            let v = self.value(pos);
            let [r, g, b, mut a] = match self.tf2d {
                Some(t) => {
                    use hatchery_data::transfer_function_2d::{SecondAxis, laplacian};
                    let s = match t.axis {
                        SecondAxis::GradientMagnitude => self.gradient_norm(self.gradient(pos)),
                        SecondAxis::Laplacian => laplacian(self.volume, self.voxel(pos)),
                        SecondAxis::SecondField => {
                            let (s, _) = self.second.expect("second_field needs a second field");
                            s.sample_trilinear(self.voxel(pos))
                        }
                    };
                    t.lookup(v, s)
                }
                None => tf.lookup(v),
            };
            if enhanced {
                if a <= 0.0 {
                    continue;
                }
                a = self.enhancement.band(a);
            }
            // Boundary and silhouette enhancement (1 when off): after shading, before the step
            // correction.
            let e = self.enhancement_factor(pos);
            let mut c = Vec3::new(r, g, b);
            let mut alpha = 1.0 - (1.0 - (a * e).min(1.0)).powf(self.p.step_voxels);
            if self.preintegrated {
                let position = |v: f32| {
                    let u = ((v - tf.domain[0]) / (tf.domain[1] - tf.domain[0])).clamp(0.0, 1.0);
                    u * (hatchery_data::transfer_function::LUT_SIZE - 1) as f32
                };
                let [r, g, b, a] = hatchery_data::preintegration::segment(
                    tf,
                    position(front.unwrap_or(v)),
                    position(v),
                    self.p.step_voxels,
                    1.0,
                );
                front = Some(v);
                alpha = a;
                c = if a > 0.0 {
                    Vec3::new(r, g, b) / a
                } else {
                    Vec3::ZERO
                };
            }
            match &self.p.shading {
                Shading::None => {}
                Shading::Phong {
                    ambient,
                    diffuse,
                    specular,
                    exponent,
                } => {
                    let (n, l, h) = self.frame(pos, self.gradient(pos));
                    let s = phong_intensity(
                        n.to_array(),
                        l.to_array(),
                        h.to_array(),
                        *ambient,
                        *diffuse,
                        *specular,
                        *exponent,
                    );
                    c = (c * s).clamp(Vec3::ZERO, Vec3::ONE);
                }
                Shading::Lighting(table) => {
                    let grad = self.gradient(pos);
                    let (n, l, h) = self.frame(pos, grad);
                    let s = table.lookup(n.dot(l), n.dot(h));
                    // Eq. 8 enhances the TF's α_u, then the step correction applies.
                    let (shaded, a_u) =
                        apply_lighting_tf(s, c.to_array(), a, self.gradient_norm(grad));
                    c = Vec3::from_array(shaded).clamp(Vec3::ZERO, Vec3::ONE);
                    alpha = 1.0 - (1.0 - (a_u * e).min(1.0)).powf(self.p.step_voxels);
                }
                Shading::ContextPreserving {
                    kappa_t,
                    kappa_s,
                    fast_exponent,
                    ambient,
                    diffuse,
                    specular,
                    exponent,
                } => {
                    let grad = self.gradient(pos);
                    let (n, l, h) = self.frame(pos, grad);
                    let s = phong_intensity(
                        n.to_array(),
                        l.to_array(),
                        h.to_array(),
                        *ambient,
                        *diffuse,
                        *specular,
                        *exponent,
                    );
                    c = (c * s).clamp(Vec3::ZERO, Vec3::ONE);
                    let eq5 = if *fast_exponent {
                        hatchery_data::lighting::context_preserving_alpha_fast
                    } else {
                        context_preserving_alpha
                    };
                    alpha = eq5(
                        alpha,
                        self.gradient_norm(grad),
                        *kappa_t,
                        *kappa_s,
                        s,
                        self.distance_norm(ray, t),
                        acc_a,
                    );
                }
            }
            acc_c += (1.0 - acc_a) * alpha * c;
            acc_a += (1.0 - acc_a) * alpha;
            if acc_a >= self.p.early_termination {
                break;
            }
        }
        [acc_c.x, acc_c.y, acc_c.z, acc_a]
    }
}

/// The box of voxel centres (in voxel space) is widened by this much on every side, so that rays
/// running exactly along a face (axis-aligned orthographic views) hit it despite rounding; the
/// shader does the same.
pub fn box_margin(_volume: &VolumeData) -> Vec3 {
    Vec3::splat(1e-4)
}

/// Voxel-space position of the last voxel centre.
pub fn last_voxel(volume: &VolumeData) -> Vec3 {
    Vec3::new(
        (volume.dims[0] - 1) as f32,
        (volume.dims[1] - 1) as f32,
        (volume.dims[2] - 1) as f32,
    )
}

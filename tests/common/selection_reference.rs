//! CPU reference of SelectionRender (VolumeShop: the tutorial's VolumeShop chapter eq. 1–5,
//! cutaways and ghosting §6.2), unshaded, written out plainly:
//!
//! - Rays as in [`super::raycast_reference`] (no jitter), marched over the union of the
//!   volume's box and the displaced selection's box (the source box seen through T⁻¹), on a
//!   lattice anchored at the near plane: `t = k h` for the k with `t_in ≤ t ≤ t_out`.
//! - f_S: the trilinear interpolation of the selected ids' indicator, 0 outside the box of
//!   voxel centres (`[0, n − 1]` per axis, widened by the ray casters' 1e-4); f_V likewise,
//!   "none" outside — the domain Raycast samples.
//! - Cutaway region: samples before the last one where f_S (ghost) or f_S∘T⁻¹ (selection) > ½.
//! - Per sample: S = min(f_S(T⁻¹p), α_S(f_V(T⁻¹p))), G = min(f_S(p), α_G(f_V(p))),
//!   B = min(1 − f_S(p), α_B(f_V(p))), B × (1 − g) in the cutaway region; colour = Σ cμ / Σ μ,
//!   α = max μ, corrected for the step, composited front to back with early termination.

#![allow(dead_code)]

use super::raycast_reference::{RayParams, box_margin, intersect_box, pixel_ray, world_step};
use glam::{Mat4, Vec3, Vec4};
use hatchery_data::VolumeData;
use hatchery_data::segmentation::LabelData;
use hatchery_data::transfer_function::TransferFunction1D;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cutaway {
    None,
    Ghost,
    Selection,
    Both,
}

pub struct Setup<'a> {
    pub ids: &'a [u16],
    pub background: &'a TransferFunction1D,
    pub ghost: &'a TransferFunction1D,
    pub selection: &'a TransferFunction1D,
    /// T: world → world, where the selection is shown.
    pub transform: Mat4,
    pub cutaway: Cutaway,
    pub ghosting: f32,
}

/// Whether voxel-space q lies in the box of voxel centres of a grid of `dims`.
fn in_box(dims: [u32; 3], q: Vec3) -> bool {
    (0..3).all(|a| q[a] >= -1e-4 && q[a] <= dims[a] as f32 - 1.0 + 1e-4)
}

fn inside(volume: &VolumeData, q: Vec3) -> bool {
    in_box(volume.dims, q)
}

/// The filtered indicator of `ids` at voxel-space q (0 outside the box of voxel centres).
pub fn selected(labels: &LabelData, ids: &[u16], q: Vec3) -> f32 {
    let dims = labels.dims;
    if !in_box(dims, q) {
        return 0.0;
    }
    let top = Vec3::new(
        (dims[0] - 1) as f32,
        (dims[1] - 1) as f32,
        (dims[2] - 1) as f32,
    );
    let p = q.clamp(Vec3::ZERO, top);
    let base = p.floor();
    let f = p - base;
    let mut sum = 0.0;
    for c in 0..8 {
        let o = [c & 1, (c >> 1) & 1, (c >> 2) & 1];
        let at = |a: usize| (base[a] as u32 + o[a] as u32).min(dims[a] - 1);
        let w: f32 = (0..3)
            .map(|a| if o[a] == 1 { f[a] } else { 1.0 - f[a] })
            .product();
        if ids.contains(&labels.id(at(0), at(1), at(2))) {
            sum += w;
        }
    }
    sum
}

/// Premultiplied RGBA per pixel, row 0 at the top.
pub fn render(volume: &VolumeData, labels: &LabelData, s: &Setup, p: &RayParams) -> Vec<[f32; 4]> {
    let h = world_step(volume, p);
    let margin = box_margin(volume);
    let last = Vec3::new(
        (volume.dims[0] - 1) as f32,
        (volume.dims[1] - 1) as f32,
        (volume.dims[2] - 1) as f32,
    );
    let back_to_source = s.transform.inverse();
    let member = |v: Option<f32>, degree: f32, tf: &TransferFunction1D| -> (f32, Vec3) {
        match v {
            Some(v) if degree > 0.0 => {
                let c = tf.lookup(v);
                (degree.min(c[3]), Vec3::new(c[0], c[1], c[2]))
            }
            _ => (0.0, Vec3::ZERO),
        }
    };
    let mut out = Vec::with_capacity((p.width * p.height) as usize);
    for y in 0..p.height {
        for x in 0..p.width {
            let (origin, dir) = pixel_ray(p, x, y);
            let q0 = volume.world_to_voxel(origin);
            let dq = volume.world_to_voxel(origin + dir) - q0;
            let source = |w: Vec3| volume.world_to_voxel(back_to_source.transform_point3(w));
            let s0 = source(origin);
            let ds = source(origin + dir) - s0;
            let a = intersect_box(-margin, last + margin, q0, dq);
            let b = intersect_box(-margin, last + margin, s0, ds);
            let (t_in, t_out) = match (a, b) {
                (Some(a), Some(b)) => (a.0.min(b.0), a.1.max(b.1)),
                (Some(a), None) | (None, Some(a)) => a,
                (None, None) => {
                    out.push([0.0; 4]);
                    continue;
                }
            };
            // The sample lattice is anchored at the near plane: t = k h from t = 0.
            let start = (t_in / h).ceil() * h;
            let count = ((t_out - start) / h).floor().max(-1.0) as i64 + 1;
            let sample_t = |k: i64| start + k as f32 * h;
            let mut t_cut = f32::NEG_INFINITY;
            if s.cutaway != Cutaway::None && s.ghosting > 0.0 {
                for k in 0..count.max(0) {
                    let t = sample_t(k);
                    let ghost = matches!(s.cutaway, Cutaway::Ghost | Cutaway::Both)
                        && selected(labels, s.ids, q0 + dq * t) > 0.5;
                    let moved = matches!(s.cutaway, Cutaway::Selection | Cutaway::Both)
                        && selected(labels, s.ids, s0 + ds * t) > 0.5;
                    if ghost || moved {
                        t_cut = t;
                    }
                }
            }
            let mut total = Vec4::ZERO;
            for k in 0..count.max(0) {
                let t = sample_t(k);
                let (q, qs) = (q0 + dq * t, s0 + ds * t);
                let v = inside(volume, q).then(|| volume.sample_trilinear(q));
                let vs = inside(volume, qs).then(|| volume.sample_trilinear(qs));
                let f = selected(labels, s.ids, q);
                let (sel, c_sel) = member(vs, selected(labels, s.ids, qs), s.selection);
                let (ghost, c_ghost) = member(v, f, s.ghost);
                let (mut back, c_back) = member(v, 1.0 - f, s.background);
                if t < t_cut {
                    back *= 1.0 - s.ghosting;
                }
                let alpha = sel.max(ghost).max(back);
                if alpha <= 0.0 {
                    continue;
                }
                let c = (c_sel * sel + c_ghost * ghost + c_back * back) / (sel + ghost + back);
                let a = 1.0 - (1.0 - alpha.clamp(0.0, 1.0)).powf(p.step_voxels);
                total += (1.0 - total.w) * Vec4::new(c.x * a, c.y * a, c.z * a, a);
                if total.w >= p.early_termination {
                    break;
                }
            }
            out.push([total.x, total.y, total.z, total.w]);
        }
    }
    out
}

//! CPU reference of two-level volume rendering (Hadwiger §2.2–2.4), the rules
//! shaders/two_level_raycast.wgsl implements, written out plainly for unshaded rendering modes
//! (dvr, mip, and iso compositing with an unshaded surface colour):
//!
//! - Rays and samples as in [`super::raycast_reference`] (no jitter): `t = t_in + k h`.
//! - Object of a sample (boundary filtering, §2.3): for each of the 8 voxels around the sample,
//!   the sum of the trilinear weights of the corners holding the same id; the first corner
//!   whose sum exceeds 0.5 gives the object, else none. Point sampling: the nearest voxel's id.
//!   Id 0, ids not in the table and disabled objects are "none".
//! - Segments: maximal runs of samples of one object. Local compositing: over (front to back,
//!   opacity corrected for the step: `1 − (1 − a)^step`; the segment ends its compositing once
//!   its alpha reaches the early-termination opacity), sum (corrected colours added), mip
//!   (the sample of largest value, uncorrected: `(c·a, a)`), iso (the first sample at or above
//!   the iso value: the TF colour at the iso value, alpha 1; no refinement needed for colour).
//! - Global: over (`total += (1 − total.a) · segment`, a ray stops once `total.a` reaches the
//!   early-termination opacity at a segment end), mip (per-channel maximum), sum; the result is
//!   clamped to 1.

#![allow(dead_code)]

use super::raycast_reference::{RayParams, box_margin, intersect_box, pixel_ray, world_step};
use glam::{Vec3, Vec4};
use hatchery_data::VolumeData;
use hatchery_data::segmentation::LabelData;
use hatchery_data::transfer_function::TransferFunction1D;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Local {
    Over,
    Mip,
    Iso(f32),
    Sum,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Global {
    Over,
    Mip,
    Sum,
}

#[derive(Clone)]
pub struct Object {
    pub id: u16,
    pub tf: TransferFunction1D,
    pub local: Local,
}

/// The object at voxel-space `q` (see the module docs).
pub fn object_at(labels: &LabelData, q: Vec3, filtered: bool) -> u16 {
    let top = Vec3::new(
        (labels.dims[0] - 1) as f32,
        (labels.dims[1] - 1) as f32,
        (labels.dims[2] - 1) as f32,
    );
    let p = q.clamp(Vec3::ZERO, top);
    let id_at = |x: i32, y: i32, z: i32| {
        let c = |v: i32, n: u32| v.clamp(0, n as i32 - 1) as u32;
        labels.id(
            c(x, labels.dims[0]),
            c(y, labels.dims[1]),
            c(z, labels.dims[2]),
        )
    };
    if !filtered {
        let r = p.round();
        return id_at(r.x as i32, r.y as i32, r.z as i32);
    }
    let base = p.floor();
    let f = p - base;
    let mut corners = [(0u16, 0.0f32); 8];
    for (c, corner) in corners.iter_mut().enumerate() {
        let o = [c & 1, (c >> 1) & 1, (c >> 2) & 1];
        let w = |axis: usize| if o[axis] == 1 { f[axis] } else { 1.0 - f[axis] };
        *corner = (
            id_at(
                base.x as i32 + o[0] as i32,
                base.y as i32 + o[1] as i32,
                base.z as i32 + o[2] as i32,
            ),
            w(0) * w(1) * w(2),
        );
    }
    for (id, _) in corners {
        let mask: f32 = corners
            .iter()
            .filter(|(d, _)| *d == id)
            .map(|(_, w)| w)
            .sum();
        if mask > 0.5 {
            return id;
        }
    }
    0
}

/// Premultiplied RGBA per pixel, row 0 at the top.
pub fn render(
    volume: &VolumeData,
    labels: &LabelData,
    objects: &[Object],
    global: Global,
    filtered: bool,
    p: &RayParams,
) -> Vec<[f32; 4]> {
    let h = world_step(volume, p);
    let margin = box_margin(volume);
    let last = Vec3::new(
        (volume.dims[0] - 1) as f32,
        (volume.dims[1] - 1) as f32,
        (volume.dims[2] - 1) as f32,
    );
    let mut out = Vec::with_capacity((p.width * p.height) as usize);
    for y in 0..p.height {
        for x in 0..p.width {
            let (origin, dir) = pixel_ray(p, x, y);
            let q0 = volume.world_to_voxel(origin);
            let dq = volume.world_to_voxel(origin + dir) - q0;
            let Some((t_in, t_out)) = intersect_box(-margin, last + margin, q0, dq) else {
                out.push([0.0; 4]);
                continue;
            };
            let count = ((t_out - t_in) / h).floor().max(-1.0) as i64 + 1;
            let mut total = Vec4::ZERO;
            let mut segment: Option<(usize, Vec4, f32, bool)> = None; // object, colour, best, done
            let close = |total: &mut Vec4, seg: Vec4| {
                if seg.w <= 0.0 {
                    return;
                }
                let s = Vec4::new(seg.x, seg.y, seg.z, seg.w.min(1.0));
                *total = match global {
                    Global::Over => *total + (1.0 - total.w) * s,
                    Global::Mip => total.max(s),
                    Global::Sum => *total + s,
                };
            };
            for k in 0..=count.max(0) {
                let t = t_in + k as f32 * h;
                let q = q0 + dq * t;
                let object = if k < count {
                    let id = object_at(labels, q, filtered);
                    objects.iter().position(|o| o.id == id && id != 0)
                } else {
                    None
                };
                if object != segment.map(|s| s.0) {
                    if let Some((_, seg, _, _)) = segment {
                        close(&mut total, seg);
                    }
                    if global == Global::Over && total.w >= p.early_termination {
                        break;
                    }
                    segment = object.map(|o| (o, Vec4::ZERO, f32::NEG_INFINITY, false));
                }
                let Some((o, seg, best, done)) = segment.as_mut() else {
                    continue;
                };
                if *done {
                    continue;
                }
                let object = &objects[*o];
                let v = volume.sample_trilinear(q);
                match object.local {
                    Local::Iso(iso) => {
                        if v >= iso {
                            let c = object.tf.lookup(iso);
                            *seg = Vec4::new(c[0], c[1], c[2], 1.0);
                            *done = true;
                        }
                    }
                    Local::Mip => {
                        let c = object.tf.lookup(v);
                        if v > *best && c[3] > 0.0 {
                            *best = v;
                            *seg = Vec4::new(c[0] * c[3], c[1] * c[3], c[2] * c[3], c[3]);
                        }
                    }
                    Local::Over | Local::Sum => {
                        let c = object.tf.lookup(v);
                        if c[3] <= 0.0 {
                            continue;
                        }
                        let a = 1.0 - (1.0 - c[3].clamp(0.0, 1.0)).powf(p.step_voxels);
                        let sample = Vec4::new(c[0] * a, c[1] * a, c[2] * a, a);
                        if object.local == Local::Over {
                            *seg += (1.0 - seg.w) * sample;
                            // Early termination inside the segment.
                            *done = seg.w >= p.early_termination;
                        } else {
                            *seg += sample;
                        }
                    }
                }
            }
            let t = total.min(Vec4::ONE);
            out.push([t.x, t.y, t.z, t.w]);
        }
    }
    out
}

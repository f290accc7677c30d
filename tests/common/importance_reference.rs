//! CPU reference of importance-driven volume rendering (Viola et al.; the tutorial's importance
//! compositing, eq. 1–3), the rules shaders/importance.wgsl and the importance part of
//! shaders/two_level_raycast.wgsl implement, written out plainly:
//!
//! - Footprint: the same samples as two-level rendering (no jitter); per pixel the focus
//!   object's first and last sample's view depth `z = −(V p).z`, and Σ I over the distinct drawn
//!   objects the ray meets (no transition smoothing here).
//! - Countersink (eq. 1): e_max = the largest last-hit depth of the footprint; outside it
//!   `E = e_max − d · s_c · w_px` with d the exact Euclidean distance (pixels, between pixel
//!   indices) to the nearest footprint pixel and w_px the world size of a pixel (orthographic),
//!   or that at depth e_max (perspective); inside, E = the focus's first hit. Cylindrical
//!   (s_c = 0): nothing outside the footprint is cut.
//! - MImP's per-ray rule (§IV.A): the buffer's second channel is, outside the footprint, the
//!   highest importance among the drawn objects the ray meets at depths z ≥ E (in the footprint
//!   and for a cutaway: 0).
//! - Final synthesis, per sample of drawn object o at depth z:
//!   MImP — in the footprint only the focus is drawn; outside, samples with z < E are dropped,
//!   and so are those of objects less important than the ray's highest (the cutaway keeps them);
//!   AImC image space — opacity × S_o (S_o = I_o / Σ I, eq. 2) for every sample;
//!   AImC object space — the same, for non-focus samples with z < E only; outside the footprint
//!   (in the countersink) the focus's importance is added to the sum;
//!   VPImC — non-focus samples with z < E in the footprint form their own segments ("occluding") whose
//!   accumulated colour and opacity are scaled by S_o / α_avg (eq. 3), α_avg the mean opacity
//!   of a first pass drawing only those segments, over its non-empty pixels.
//! - Volume thinning (§V.C) as the level of sparseness ([`render_thinned`]): a non-focus sample
//!   with s < 1 is kept, unchanged, where the fraction of its object's voxels whose key lies in a
//!   lower of 256 bins over [0, 1] (its rank, [`thinning_ranks`], every voxel keyed) is at least
//!   1 − s, else dropped. The key is (L + κ̂) / B: L =
//!   min(⌊B · |g| / g_max⌋, B − 1), g the trilinear central-difference gradient (world) and g_max
//!   the volume's largest; κ̂ = min(w · √(a² + 2b² + c²), 1), (a, b; b, c) the shape operator
//!   −t_i·H t_j / |g| in the tangent basis of n = −g/|g|, H the central differences of g at
//!   ±w along the world axes (symmetrised), w the smallest spacing; key 0 where |g| < 1e-12.

#![allow(dead_code)]

use super::raycast_reference::{
    RayParams, box_margin, intersect_box, last_voxel, pixel_ray, world_step,
};
use super::two_level_reference::{Local, Object, object_at};
use glam::{Vec3, Vec4};
use hatchery_data::VolumeData;
use hatchery_data::segmentation::LabelData;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    Mimp,
    Cutaway,
    AimcImage,
    AimcObject,
    Vpimc,
}

pub struct Setup {
    pub method: Method,
    pub focus: u16,
    /// Importance by object id.
    pub importance: Vec<(u16, f32)>,
    /// s_c; 0 for a cylindrical countersink.
    pub slope: f32,
}

/// Per pixel: (E, Σ I, 1 in the footprint, focus last-hit depth or −1), like the GPU buffer,
/// and d (pixels to the footprint; 0 inside).
pub struct Buffers {
    pub pixels: Vec<[f32; 4]>,
    pub distance: Vec<f32>,
    pub e_max: f32,
}

fn view_depth(p: &RayParams, point: Vec3) -> f32 {
    -(p.view * point.extend(1.0)).z
}

/// The importance buffers of `setup` for the drawn `objects` (see the module docs).
pub fn buffers(
    volume: &VolumeData,
    labels: &LabelData,
    objects: &[Object],
    setup: &Setup,
    p: &RayParams,
    pixel_world: f32,
) -> Buffers {
    let h = world_step(volume, p);
    let margin = box_margin(volume);
    let last = last_voxel(volume);
    let importance = |id: u16| {
        setup
            .importance
            .iter()
            .find(|(i, _)| *i == id)
            .map_or(0.0, |(_, v)| *v)
    };
    let mut hits = Vec::new(); // (first, last, sum)
    for y in 0..p.height {
        for x in 0..p.width {
            let (origin, dir) = pixel_ray(p, x, y);
            let q0 = volume.world_to_voxel(origin);
            let dq = volume.world_to_voxel(origin + dir) - q0;
            let mut first = -1.0f32;
            let mut last_hit = -1.0f32;
            let mut met: Vec<u16> = Vec::new();
            if let Some((t_in, t_out)) = intersect_box(-margin, last + margin, q0, dq) {
                let count = ((t_out - t_in) / h).floor().max(-1.0) as i64 + 1;
                for k in 0..count.max(0) {
                    let t = t_in + k as f32 * h;
                    let id = object_at(labels, q0 + dq * t, true);
                    if id == 0 || !objects.iter().any(|o| o.id == id) {
                        continue;
                    }
                    if !met.contains(&id) {
                        met.push(id);
                    }
                    if id == setup.focus {
                        let z = view_depth(p, origin + dir * t);
                        if first < 0.0 {
                            first = z;
                        }
                        last_hit = z;
                    }
                }
            }
            let sum: f32 = met.iter().map(|&id| importance(id)).sum();
            hits.push((first, last_hit, sum));
        }
    }
    let footprint: Vec<(f32, f32)> = hits
        .iter()
        .enumerate()
        .filter(|(_, h)| h.1 >= 0.0)
        .map(|(i, _)| ((i as u32 % p.width) as f32, (i as u32 / p.width) as f32))
        .collect();
    let e_max = hits.iter().map(|h| h.1).fold(-1.0f32, f32::max);
    let mut pixels = Vec::new();
    let mut distance = Vec::new();
    for (i, &(first, last_hit, sum)) in hits.iter().enumerate() {
        let (x, y) = ((i as u32 % p.width) as f32, (i as u32 / p.width) as f32);
        if last_hit >= 0.0 {
            pixels.push([first, sum, 1.0, last_hit]);
            distance.push(0.0);
            continue;
        }
        let d = footprint
            .iter()
            .map(|&(fx, fy)| ((fx - x).powi(2) + (fy - y).powi(2)).sqrt())
            .fold(f32::INFINITY, f32::min);
        let mut e = -1.0e30;
        if setup.slope > 0.0 && d.is_finite() {
            let w = if p.orthographic {
                pixel_world
            } else {
                pixel_world * e_max
            };
            e = e_max - d * w * setup.slope;
        }
        pixels.push([e, sum, 0.0, -1.0]);
        distance.push(if d.is_finite() { d } else { 0.0 });
    }
    for (i, pixel) in pixels.iter_mut().enumerate() {
        match setup.method {
            // (In the footprint only the focus is drawn: 0 there.)
            Method::Mimp if pixel[2] > 0.5 => pixel[1] = 0.0,
            Method::Mimp => {
                let (x, y) = (i as u32 % p.width, i as u32 / p.width);
                let met = objects_behind(volume, labels, objects, p, x, y, pixel[0]);
                pixel[1] = met
                    .iter()
                    .map(|&id| importance(id).max(0.0))
                    .fold(0.0, f32::max);
            }
            Method::Cutaway => pixel[1] = 0.0,
            _ => {}
        }
    }
    Buffers {
        pixels,
        distance,
        e_max,
    }
}

/// The drawn objects whose samples on the ray of pixel (x, y) lie at view depths ≥ `e`.
fn objects_behind(
    volume: &VolumeData,
    labels: &LabelData,
    objects: &[Object],
    p: &RayParams,
    x: u32,
    y: u32,
    e: f32,
) -> Vec<u16> {
    let h = world_step(volume, p);
    let margin = box_margin(volume);
    let last = last_voxel(volume);
    let (origin, dir) = pixel_ray(p, x, y);
    let q0 = volume.world_to_voxel(origin);
    let dq = volume.world_to_voxel(origin + dir) - q0;
    let mut met = Vec::new();
    if let Some((t_in, t_out)) = intersect_box(-margin, last + margin, q0, dq) {
        let count = ((t_out - t_in) / h).floor().max(-1.0) as i64 + 1;
        for k in 0..count.max(0) {
            let t = t_in + k as f32 * h;
            let id = object_at(labels, q0 + dq * t, true);
            if id != 0
                && objects.iter().any(|o| o.id == id)
                && view_depth(p, origin + dir * t) >= e
                && !met.contains(&id)
            {
                met.push(id);
            }
        }
    }
    met
}

/// Importance-driven two-level rendering with global over, opacity as the level of
/// sparseness; premultiplied RGBA per pixel. `objects` use local over, sum or mip.
pub fn render(
    volume: &VolumeData,
    labels: &LabelData,
    objects: &[Object],
    setup: &Setup,
    buffers: &Buffers,
    p: &RayParams,
) -> Vec<[f32; 4]> {
    let alpha_avg = if setup.method == Method::Vpimc {
        let first = render_pass(volume, labels, objects, setup, buffers, p, true, 1.0, None);
        let (sum, n) = first
            .iter()
            .filter(|c| c[3] > 0.0)
            .fold((0.0f32, 0u32), |(s, n), c| (s + c[3], n + 1));
        sum / n.max(1) as f32
    } else {
        1.0
    };
    render_pass(
        volume, labels, objects, setup, buffers, p, false, alpha_avg, None,
    )
}

/// Volume thinning's parameters: the levels B of gradient magnitude, the volume's largest
/// gradient magnitude and the smallest spacing w.
pub struct Thinning {
    pub levels: f32,
    pub max_gradient: f32,
    pub spacing: f32,
}

/// Volume thinning's key of the sample at world point `p` (see the module docs).
pub fn thinning_key(volume: &VolumeData, th: &Thinning, p: Vec3) -> f32 {
    let gradient = |p: Vec3| volume.gradient(volume.world_to_voxel(p));
    let g = gradient(p);
    let g_length = g.length();
    if g_length < 1e-12 {
        return 0.0;
    }
    let b = th.levels.max(1.0);
    let level = (b * (g_length * (1.0 / th.max_gradient)).min(1.0))
        .floor()
        .min(b - 1.0);
    let w = th.spacing;
    let columns: Vec<Vec3> = (0..3)
        .map(|axis| {
            let e = Vec3::AXES[axis] * w;
            (gradient(p + e) - gradient(p - e)) / (2.0 * w)
        })
        .collect();
    let h = glam::Mat3::from_cols(columns[0], columns[1], columns[2]);
    let h = 0.5 * (h + h.transpose());
    let n = -g / g_length;
    let helper = if n.x.abs() > 0.9 { Vec3::Y } else { Vec3::X };
    let t1 = n.cross(helper).normalize();
    let t2 = n.cross(t1);
    let a = -t1.dot(h * t1) / g_length;
    let bb = -t1.dot(h * t2) / g_length;
    let c = -t2.dot(h * t2) / g_length;
    let kappa = ((a * a + 2.0 * bb * bb + c * c).sqrt() * w).min(1.0);
    (level + kappa) / b
}

/// Per object id, per key bin (256 over [0, 1]), the fraction of the object's voxels whose key
/// lies in a lower bin, every voxel keyed at its centre.
pub fn thinning_ranks(volume: &VolumeData, labels: &LabelData, th: &Thinning) -> Vec<Vec<f32>> {
    const BINS: usize = 256;
    let bin = |key: f32| ((key * BINS as f32) as usize).min(BINS - 1);
    let rows = labels.ids.iter().copied().max().unwrap_or(0) as usize + 1;
    let mut counts = vec![vec![0u64; BINS]; rows];
    let [nx, ny, nz] = volume.dims;
    for z in 0..nz {
        for y in 0..ny {
            for x in 0..nx {
                let q = Vec3::new(x as f32, y as f32, z as f32);
                let id = labels.ids[volume.index(x, y, z)] as usize;
                counts[id][bin(thinning_key(volume, th, volume.voxel_to_world(q)))] += 1;
            }
        }
    }
    counts
        .iter()
        .map(|c| {
            let total = c.iter().sum::<u64>().max(1) as f32;
            let mut below = 0u64;
            c.iter()
                .map(|&n| {
                    let r = below as f32 / total;
                    below += n;
                    r
                })
                .collect()
        })
        .collect()
}

/// [`render`] (not VPImC) with volume thinning as the level of sparseness.
pub fn render_thinned(
    volume: &VolumeData,
    labels: &LabelData,
    objects: &[Object],
    setup: &Setup,
    buffers: &Buffers,
    p: &RayParams,
    thinning: &Thinning,
) -> Vec<[f32; 4]> {
    assert!(
        setup.method != Method::Vpimc,
        "VPImC has no level of sparseness"
    );
    render_pass(
        volume,
        labels,
        objects,
        setup,
        buffers,
        p,
        false,
        1.0,
        Some(thinning),
    )
}

#[allow(clippy::too_many_arguments)]
fn render_pass(
    volume: &VolumeData,
    labels: &LabelData,
    objects: &[Object],
    setup: &Setup,
    buffers: &Buffers,
    p: &RayParams,
    first_pass: bool,
    alpha_avg: f32,
    thinning: Option<&Thinning>,
) -> Vec<[f32; 4]> {
    let h = world_step(volume, p);
    let margin = box_margin(volume);
    let last = last_voxel(volume);
    let ranks = thinning.map(|th| thinning_ranks(volume, labels, th));
    let importance = |id: u16| {
        setup
            .importance
            .iter()
            .find(|(i, _)| *i == id)
            .map_or(0.0, |(_, v)| *v)
    };
    let mut out = Vec::with_capacity((p.width * p.height) as usize);
    for y in 0..p.height {
        for x in 0..p.width {
            let [e, sum, inside, _] = buffers.pixels[(y * p.width + x) as usize];
            let inside = inside > 0.5;
            let (origin, dir) = pixel_ray(p, x, y);
            let q0 = volume.world_to_voxel(origin);
            let dq = volume.world_to_voxel(origin + dir) - q0;
            let Some((t_in, t_out)) = intersect_box(-margin, last + margin, q0, dq) else {
                out.push([0.0; 4]);
                continue;
            };
            let count = ((t_out - t_in) / h).floor().max(-1.0) as i64 + 1;
            let mut total = Vec4::ZERO;
            // (key, object index, colour, best, done, scale)
            let mut segment: Option<(u32, usize, Vec4, f32, bool, f32)> = None;
            let close = |total: &mut Vec4, seg: Vec4, scale: f32| {
                if seg.w <= 0.0 {
                    return;
                }
                let seg = if scale != 1.0 {
                    seg * scale.min(1.0 / seg.w)
                } else {
                    seg
                };
                let s = Vec4::new(seg.x, seg.y, seg.z, seg.w.min(1.0));
                *total += (1.0 - total.w) * s;
            };
            for k in 0..=count.max(0) {
                let t = t_in + k as f32 * h;
                let q = q0 + dq * t;
                let mut id = if k < count {
                    object_at(labels, q, true)
                } else {
                    0
                };
                if !objects.iter().any(|o| o.id == id) {
                    id = 0;
                }
                let mut flag = 0u32;
                let mut s = 1.0f32;
                if id != 0 {
                    let z = view_depth(p, origin + dir * t);
                    let in_front = z < e;
                    let s_o = (importance(id) / sum.max(1e-6)).clamp(0.0, 1.0);
                    match setup.method {
                        Method::Mimp | Method::Cutaway => {
                            // (The second channel: for MImP the ray's highest importance.)
                            let weaker = importance(id).max(0.0) < sum;
                            if (inside && id != setup.focus) || (!inside && (in_front || weaker)) {
                                id = 0;
                            }
                        }
                        Method::Vpimc => {
                            if id != setup.focus && in_front && inside {
                                flag = 1;
                                s = s_o;
                            } else if first_pass {
                                id = 0;
                            }
                        }
                        Method::AimcImage => s = s_o,
                        Method::AimcObject => {
                            if id != setup.focus && in_front {
                                s = s_o;
                                if !inside {
                                    // The countersink: the focus counts in the sum.
                                    let with_focus = sum + importance(setup.focus);
                                    s = (importance(id) / with_focus.max(1e-6)).clamp(0.0, 1.0);
                                }
                            }
                        }
                    }
                }
                let key = u32::from(id) * 2 + flag;
                if Some(key) != segment.map(|s| s.0) {
                    if let Some((_, _, seg, _, _, scale)) = segment {
                        close(&mut total, seg, scale);
                    }
                    if total.w >= p.early_termination {
                        break;
                    }
                    segment = (id != 0).then(|| {
                        let o = objects.iter().position(|o| o.id == id).unwrap();
                        let scale = if flag == 1 && !first_pass {
                            s / alpha_avg
                        } else {
                            1.0
                        };
                        (key, o, Vec4::ZERO, f32::NEG_INFINITY, false, scale)
                    });
                }
                let Some((_, o, seg, best, done, _)) = segment.as_mut() else {
                    continue;
                };
                if *done {
                    continue;
                }
                if flag == 1 {
                    s = 1.0;
                }
                if let Some(th) = thinning
                    && s < 1.0
                    && id != setup.focus
                {
                    let key = thinning_key(volume, th, origin + dir * t);
                    let bin = ((key * 256.0) as usize).min(255);
                    let ranks = ranks.as_ref().expect("ranks are made with thinning");
                    if ranks[id as usize].get(bin).copied().unwrap_or(0.0) < 1.0 - s {
                        continue;
                    }
                    s = 1.0;
                }
                let object = &objects[*o];
                let v = volume.sample_trilinear(q);
                let c = object.tf.lookup(v);
                let a = c[3] * s;
                match object.local {
                    Local::Mip => {
                        if v > *best && a > 0.0 {
                            *best = v;
                            *seg = Vec4::new(c[0] * a, c[1] * a, c[2] * a, a);
                        }
                    }
                    Local::Over | Local::Sum => {
                        if a <= 0.0 {
                            continue;
                        }
                        let a = 1.0 - (1.0 - a.clamp(0.0, 1.0)).powf(p.step_voxels);
                        let sample = Vec4::new(c[0] * a, c[1] * a, c[2] * a, a);
                        if object.local == Local::Over {
                            *seg += (1.0 - seg.w) * sample;
                            *done = seg.w >= p.early_termination;
                        } else {
                            *seg += sample;
                        }
                    }
                    Local::Iso(_) => unimplemented!("the importance reference has no iso"),
                }
            }
            let t = total.min(Vec4::ONE);
            out.push([t.x, t.y, t.z, t.w]);
        }
    }
    out
}

//! Volume thinning, the fourth level of sparseness of importance-driven rendering (Viola et al.
//! §V.C; TwoLevelRaycast `sparseness = thinning`): an object's voxels are sorted by the key
//! (L + κ̂) / B — L the level of gradient magnitude (of B), κ̂ the curvature magnitude in voxel
//! units — and a context sample of level of sparseness S is kept, unchanged, only where the
//! fraction of its object's voxels sorted before it (its rank) is at least 1 − S: the last S of
//! the order remain (see hatchery_data::thinning, shaders/two_level_raycast.wgsl and the CPU
//! reference tests/common/importance_reference.rs).
//!
//! The scene: a context slab of three layers of known, constant gradient (planar iso-surfaces,
//! no curvature) in front of a focus block, seen orthographically along the layers' normal;
//! object-space AImC gives the slab S = I_c / (I_c + I_f) in the focus's footprint. Each layer
//! has its own colour and the slab is summed (local sum), so each colour channel counts the
//! samples kept of one layer.

mod common;

use common::importance_reference::{self as reference, Method, Setup, Thinning};
use common::importance_scene::{
    N, SIZE, Scene, camera, flat, pixel_world, ray_params, render_gpu, session,
};
use common::two_level_reference::{Local, Object};
use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;
use hatchery_data::segmentation::LabelData;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
use hatchery_graph::ParamValue;

/// Slopes (value per voxel along z) of the layers back to front: red, green, blue; and of the
/// rest of the volume. The largest, 7, is the volume's largest gradient.
const SLOPES: [f32; 3] = [7.0, 1.0, 5.0];
const REST_SLOPE: f32 = 1.0;
/// The slab's layers start at these z indices; it ends at the last slice (the front: the eye is
/// on +z).
const LAYERS: [u32; 3] = [13, 22, 31];
/// Levels of gradient magnitude: the layers' |∇f| / 7 = 1, 1/7, 5/7 lie in levels 3, 0, 2, so
/// their keys are 3/4, 0 and 1/2.
const LEVELS: u32 = 4;
const KEYS: [f32; 3] = [0.75, 0.0, 0.5];
/// Their ranks within the slab (27 slices, z 13 … 39; keys at the voxel centres): the red layer
/// has 8 slices of key 3/4 (its first slice mixes slopes 1 and 7: key 1/2), the green 8 of key 0,
/// the blue 8 of key 1/2 after one of key 1/4. Sorted before the red: 19 slices; before the
/// blue: 9; before the green: none.
const RANKS: [f32; 3] = [19.0 / 27.0, 0.0, 9.0 / 27.0];
const OPACITY: f32 = 0.02;

/// The value at z index k: piecewise linear with the slopes above (continuous).
fn value(k: u32) -> f32 {
    let mut v = 0.0;
    for j in 0..k {
        let layer = LAYERS.iter().rposition(|&start| j >= start);
        v += layer.map_or(REST_SLOPE, |l| SLOPES[l]);
    }
    v
}

/// The focus (id 2): a block of 16 × 16 × 8 voxels at the back; the context slab (id 1): every
/// voxel from z index 13 on.
fn layered() -> Scene {
    let mut ids = Vec::new();
    let mut values = Vec::new();
    for z in 0..N {
        for y in 0..N {
            for x in 0..N {
                let centre = (12..28).contains(&x) && (12..28).contains(&y);
                ids.push(if z >= LAYERS[0] {
                    1
                } else if centre && (3..11).contains(&z) {
                    2
                } else {
                    0
                });
                values.push(value(z));
            }
        }
    }
    let half = (N - 1) as f64 / 2.0;
    let geometry = Geometry::axis_aligned([1.0; 3], [-half; 3]);
    let volume = VolumeData::with_geometry([N; 3], geometry, values).unwrap();
    let labels = LabelData::new([N; 3], geometry, ids);
    // The slab's colour by layer (pure red, green, blue: premultiplied sums count samples).
    let bounds: Vec<f32> = LAYERS.iter().map(|&k| value(k)).collect();
    let colour = |c: usize| {
        let mut rgba = [0.0, 0.0, 0.0, OPACITY];
        rgba[c] = 1.0;
        rgba
    };
    let mut points = Vec::new();
    for (c, &lo) in bounds.iter().enumerate() {
        let hi = bounds.get(c + 1).map_or(value(N), |&b| b - 1e-3);
        points.push(ControlPoint {
            value: lo,
            rgba: colour(c),
        });
        points.push(ControlPoint {
            value: hi,
            rgba: colour(c),
        });
    }
    let slab = TransferFunction1D::from_points(&points).unwrap();
    Scene {
        volume,
        labels,
        objects: vec![
            Object {
                id: 1,
                tf: slab,
                local: Local::Sum,
            },
            Object {
                id: 2,
                tf: flat([0.0, 0.0, 0.0, 0.5]),
                local: Local::Over,
            },
        ],
    }
}

fn setup(s: f32) -> Setup {
    Setup {
        method: Method::AimcObject,
        focus: 2,
        importance: vec![(1, s), (2, 1.0 - s)],
        slope: 0.0,
    }
}

fn thinning() -> [(&'static str, ParamValue); 2] {
    [
        ("sparseness", ParamValue::Choice("thinning".into())),
        ("thinning_levels", ParamValue::Int(i64::from(LEVELS))),
    ]
}

/// Pixels well inside the focus footprint (the central 10 × 10).
fn centre() -> Vec<usize> {
    let c = SIZE / 2;
    (c - 5..c + 5)
        .flat_map(|y| (c - 5..c + 5).map(move |x| (y * SIZE + x) as usize))
        .collect()
}

/// Mean over `pixels` of each layer's summed opacity (the red, green and blue channels), of the
/// slab's (their sum) and of the focus's, recovered from the picture's alpha (the slab in front
/// composited over the black focus: a = slab + (1 − slab) · focus).
fn measure(picture: &[[f32; 4]], pixels: &[usize]) -> ([f32; 3], f32) {
    let (mut layers, mut focus) = ([0.0f32; 3], 0.0f32);
    for &i in pixels {
        let p = picture[i];
        let slab = p[0] + p[1] + p[2];
        for c in 0..3 {
            layers[c] += p[c];
        }
        focus += (p[3] - slab) / (1.0 - slab);
    }
    let n = pixels.len() as f32;
    (layers.map(|l| l / n), focus / n)
}

#[test]
fn volume_thinning_drops_the_weakest_gradient_layers_first_and_never_the_focus() {
    let mut session = session();
    let cam = camera(&mut session);
    let scene = layered();
    let p = ray_params(&cam);
    let th = Thinning {
        levels: LEVELS as f32,
        max_gradient: hatchery_data::gradient::max_gradient_magnitude(&scene.volume),
        spacing: 1.0,
    };
    assert!((th.max_gradient - 7.0).abs() < 1e-4, "{}", th.max_gradient);
    // The slab's ranks of the layers' keys, the reference's (every voxel keyed) and the
    // library's (the table the node uploads) against the count in RANKS' comment.
    let reference_ranks = reference::thinning_ranks(&scene.volume, &scene.labels, &th);
    let key = hatchery_data::thinning::KeyParams {
        bands: LEVELS as f32,
        inv_max_gradient: 1.0 / th.max_gradient,
        step: 1.0,
    };
    let library = hatchery_data::thinning::thinning_ranks(
        &scene.volume,
        &scene.labels.ids,
        3,
        &key,
        usize::MAX,
    );
    for c in 0..3 {
        let bin = hatchery_data::thinning::key_bin(KEYS[c]);
        let (r, l) = (
            reference_ranks[1][bin],
            library[hatchery_data::thinning::RANK_BINS + bin],
        );
        assert!((r - RANKS[c]).abs() < 1e-6, "layer {c}: reference rank {r}");
        assert!((l - RANKS[c]).abs() < 1e-6, "layer {c}: library rank {l}");
    }
    let (_, plain) = render_gpu(&mut session, &cam, &scene, None, &[]);
    let centre = centre();
    let (dense, dense_focus) = measure(&plain, &centre);
    // The dense slab: 9 voxels per layer at 0.37 voxels a step, each sample 1 − 0.98^0.37.
    let per_sample = 1.0 - (1.0 - OPACITY).powf(0.37);
    for (c, &d) in dense.iter().enumerate() {
        let samples = d / per_sample;
        assert!(
            (22.0..27.0).contains(&samples),
            "layer {c}: {samples} samples"
        );
    }
    // S = 1 (the focus's importance 0): the dense rendering, within 1/255.
    let (_, one) = render_gpu(&mut session, &cam, &scene, Some(&setup(1.0)), &thinning());
    common::assert_images_close(
        "thinning at S = 1 vs dense",
        &one,
        &plain,
        SIZE,
        1.0 / 255.0,
    );

    let mut previous = [f32::INFINITY; 3];
    for s in [0.9f32, 0.6, 0.4, 0.2] {
        let setup = setup(s);
        let (buffer, gpu) = render_gpu(&mut session, &cam, &scene, Some(&setup), &thinning());
        assert!(
            centre.iter().all(|&i| buffer[i][2] > 0.5),
            "centre in the footprint"
        );
        let (kept, focus) = measure(&gpu, &centre);
        let fraction: Vec<f32> = kept.iter().zip(&dense).map(|(k, d)| k / d).collect();
        // The rule: a layer stays where its rank is at least 1 − S; only the samples within a
        // voxel of a layer boundary (whose central differences mix two slopes, so their level
        // differs; up to 0.6 voxel at each of a layer's two boundaries) go against it: a kept layer
        // keeps ≥ 80 %, a dropped one ≤ 20 %.
        for c in 0..3 {
            let expected = RANKS[c] >= 1.0 - s;
            let f = fraction[c];
            assert!(
                if expected { f >= 0.8 } else { f <= 0.2 },
                "S = {s}: layer {c} (key {}) keeps {f:.3}",
                KEYS[c]
            );
            // Thinning only removes: no layer grows as S falls.
            assert!(kept[c] <= previous[c] + 1e-4, "S = {s}: layer {c} grew");
        }
        previous = kept;
        // The slab's kept fraction: the layers whose rank is at least 1 − S, each a third of
        // it, within 0.07 — never more than S, as the paper's sort keeps.
        let whole = kept.iter().sum::<f32>() / dense.iter().sum::<f32>();
        let rule = RANKS.iter().filter(|&&r| r >= 1.0 - s).count() as f32 / 3.0;
        assert!(rule <= s, "S = {s}: the rule keeps {rule}");
        assert!(
            (whole - rule).abs() < 0.07,
            "S = {s}: kept {whole:.3}, rule {rule:.3}"
        );
        // The focus is never thinned: its own opacity is the dense one.
        assert!(
            (focus - dense_focus).abs() < 2e-3,
            "S = {s}: focus {focus} vs {dense_focus}"
        );
        // Outside the footprint (S = 1) nothing changes; everywhere the CPU reference agrees.
        common::assert_images_close_where(
            "outside the footprint vs dense",
            &gpu,
            &plain,
            SIZE,
            1.0 / 255.0,
            |i| buffer[i][2] < 0.5,
        );
        let buffers = reference::buffers(
            &scene.volume,
            &scene.labels,
            &scene.objects,
            &setup,
            &p,
            pixel_world(&cam),
        );
        let cpu = reference::render_thinned(
            &scene.volume,
            &scene.labels,
            &scene.objects,
            &setup,
            &buffers,
            &p,
            &th,
        );
        common::assert_images_close(
            &format!("thinning S = {s} vs CPU"),
            &gpu,
            &cpu,
            SIZE,
            2.0 / 255.0,
        );
    }
}

/// Curved iso-surfaces (spheres about a point far in front) keyed by curvature: a copy of the
/// scene stored with its x axis flipped (LAS: direction −1, the same world) thins as the
/// original does — the key's gradient and Hessian are taken in world space.
#[test]
fn a_flipped_grid_thins_as_the_original() {
    use glam::{DMat3, DVec3};
    let half = (N - 1) as f64 / 2.0;
    let ras = curved(DMat3::IDENTITY, DVec3::splat(-half));
    let las = curved(
        DMat3::from_diagonal(DVec3::new(-1.0, 1.0, 1.0)),
        DVec3::new(half, -half, -half),
    );
    let mut session = session();
    let cam = camera(&mut session);
    let (_, want) = render_gpu(&mut session, &cam, &ras, Some(&setup(0.5)), &thinning());
    let (_, got) = render_gpu(&mut session, &cam, &las, Some(&setup(0.5)), &thinning());
    let (_, dense) = render_gpu(&mut session, &cam, &ras, None, &[]);
    assert!(
        thinned_pixels(&want, &dense) > 100,
        "the test shows no thinning"
    );
    common::assert_images_close("LAS vs RAS thinning", &got, &want, SIZE, 2.0 / 255.0);
}

/// On CPU adapters the key's gradients come from a texture of the voxel gradients (one filtered
/// fetch each; value/gradient_texture.rs) instead of central differences of the volume (six):
/// the same thinning as with the texture switched off (`quads_bytes` 0), within 2/255.
#[test]
fn the_gradient_texture_thins_as_central_differences_do() {
    let half = (N - 1) as f64 / 2.0;
    let scene = curved(glam::DMat3::IDENTITY, glam::DVec3::splat(-half));
    let mut pictures = Vec::new();
    for texture in [true, false] {
        let mut session = session();
        if !texture {
            session
                .ctx
                .gpu
                .set_volume_limits(hatchery_gpu::VolumeLimits {
                    quads_bytes: 0,
                    ..hatchery_gpu::VolumeLimits::default()
                });
        }
        let volume = hatchery_nodes::value::Volume::new(scene.volume.clone());
        let made = volume.gradient_texture(&session.ctx.gpu).unwrap().is_some();
        let cpu = session.ctx.gpu.adapter_info.device_type == wgpu::DeviceType::Cpu;
        assert_eq!(
            made,
            texture && cpu,
            "gradient texture made (allowed: {texture})"
        );
        let cam = camera(&mut session);
        let (_, picture) = render_gpu(&mut session, &cam, &scene, Some(&setup(0.5)), &thinning());
        pictures.push(picture);
    }
    common::assert_images_close(
        "gradient texture vs differences",
        &pictures[0],
        &pictures[1],
        SIZE,
        2.0 / 255.0,
    );
}

/// Pixels where thinning changed the context's colour (red) by more than 8/255.
fn thinned_pixels(thinned: &[[f32; 4]], dense: &[[f32; 4]]) -> usize {
    (0..thinned.len())
        .filter(|&i| (thinned[i][0] - dense[i][0]).abs() > 8.0 / 255.0)
        .count()
}

/// Spheres about a point far in front (curved iso-surfaces, |∇f| = 1), stored with `direction`
/// and `origin`: the context (id 1, orange) from z = −6.5 on, the focus (id 2, blue) a block
/// behind it.
fn curved(direction: glam::DMat3, origin: glam::DVec3) -> Scene {
    let geometry = Geometry {
        spacing: glam::DVec3::ONE,
        direction,
        origin,
    };
    let (mut ids, mut values) = (Vec::new(), Vec::new());
    for z in 0..N {
        for y in 0..N {
            for x in 0..N {
                let p = geometry.voxel_to_world(glam::Vec3::new(x as f32, y as f32, z as f32));
                values.push(p.distance(glam::Vec3::new(3.0, -2.0, 40.0)));
                let centre = p.x.abs() < 8.0 && p.y.abs() < 8.0;
                ids.push(if p.z >= -6.5 {
                    1
                } else if centre && (-16.5..-8.5).contains(&p.z) {
                    2
                } else {
                    0
                });
            }
        }
    }
    let volume = VolumeData::with_geometry([N; 3], geometry, values).unwrap();
    Scene {
        volume,
        labels: LabelData::new([N; 3], geometry, ids),
        objects: vec![
            Object {
                id: 1,
                tf: flat([0.9, 0.5, 0.2, 0.05]),
                local: Local::Over,
            },
            Object {
                id: 2,
                tf: flat([0.1, 0.3, 0.9, 0.5]),
                local: Local::Over,
            },
        ],
    }
}

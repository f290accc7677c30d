//! Importance-driven volume rendering (Viola et al., eq. 1–3): ImportanceCompositing's buffers
//! and TwoLevelRaycast's final synthesis against the CPU reference
//! (tests/common/importance_reference.rs) and against plain and focus-only renderings, on
//! synthetic nested objects seen orthographically along an axis.
//!
//! Over 600 lines: one test file per capability; each case builds its scene and its CPU reference
//! of the paper's equations.

mod common;

use common::importance_reference::{self as reference, Method, Setup};
use common::importance_scene::{
    N, SIZE, Scene, camera, flat, pixel_world, ray_params, render_gpu, session,
};
use common::two_level_reference::{Local, Object};
use glam::Vec3;
use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;
use hatchery_data::segmentation::LabelData;
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;

/// An N³ grid centred at the origin whose ids come from `id(x, y, z)`; value = 100 · id.
fn grid(id: impl Fn(u32, u32, u32) -> u16) -> (VolumeData, LabelData) {
    let mut ids = Vec::new();
    for z in 0..N {
        for y in 0..N {
            for x in 0..N {
                ids.push(id(x, y, z));
            }
        }
    }
    let half = (N - 1) as f64 / 2.0;
    let geometry = Geometry::axis_aligned([1.0; 3], [-half; 3]);
    let values = ids.iter().map(|&id| 100.0 * f32::from(id)).collect();
    let volume = VolumeData::with_geometry([N; 3], geometry, values).unwrap();
    (volume, LabelData::new([N; 3], geometry, ids))
}

/// Nested spheres: id 3 for r < 0.3, 2 for r < 0.6, 1 for r < 0.85 (r relative to the
/// half-size), or only ids 2 (r < 0.45) and 1 (r < 0.85) with `three = false`.
fn nested(three: bool) -> (VolumeData, LabelData) {
    let half = (N - 1) as f32 / 2.0;
    grid(|x, y, z| {
        let r = Vec3::new(x as f32 - half, y as f32 - half, z as f32 - half).length() / half;
        match (three, r) {
            (true, r) if r < 0.3 => 3,
            (true, r) if r < 0.6 => 2,
            (false, r) if r < 0.45 => 2,
            (_, r) if r < 0.85 => 1,
            _ => 0,
        }
    })
}

/// The CPU reference's importance buffers and picture of `scene` with `setup` (no jitter).
fn cpu_reference(
    scene: &Scene,
    setup: &Setup,
    cam: &Camera,
) -> (reference::Buffers, Vec<[f32; 4]>) {
    let p = ray_params(cam);
    let (volume, labels, objects) = (&scene.volume, &scene.labels, &scene.objects);
    let buffers = reference::buffers(volume, labels, objects, setup, &p, pixel_world(cam));
    let picture = reference::render(volume, labels, objects, setup, &buffers, &p);
    (buffers, picture)
}

const SHELL: [f32; 4] = [1.0, 0.2, 0.1, 0.25];
const CORE: [f32; 4] = [0.1, 0.9, 0.2, 0.6];
const INNER: [f32; 4] = [0.2, 0.3, 1.0, 0.5];

fn two_objects() -> Scene {
    let (volume, labels) = nested(false);
    Scene {
        volume,
        labels,
        objects: vec![
            Object {
                id: 1,
                tf: flat(SHELL),
                local: Local::Over,
            },
            Object {
                id: 2,
                tf: flat(CORE),
                local: Local::Over,
            },
        ],
    }
}

#[test]
fn cylindrical_mimp_shows_only_the_focus_in_its_footprint_and_the_plain_rendering_elsewhere() {
    let mut session = session();
    let cam = camera(&mut session);
    let scene = two_objects();
    let setup = Setup {
        method: Method::Mimp,
        focus: 2,
        importance: vec![(1, 0.2), (2, 0.8)],
        slope: 0.0,
    };
    let (buffer, mimp) = render_gpu(&mut session, &cam, &scene, Some(&setup), &[]);
    let (_, plain) = render_gpu(&mut session, &cam, &scene, None, &[]);
    let focus_only = Scene {
        objects: scene.objects.iter().skip(1).cloned().collect(),
        volume: scene.volume.clone(),
        labels: scene.labels.clone(),
    };
    let (_, focus) = render_gpu(&mut session, &cam, &focus_only, None, &[]);
    let inside = |i: usize| buffer[i][2] > 0.5;
    let footprint = (0..buffer.len()).filter(|&i| inside(i)).count();
    // The core (r < 0.45 of the half-size 19.5 voxels) covers about π·(8.8 / 0.917)² pixels.
    assert!(
        (200..400).contains(&footprint),
        "footprint of {footprint} pixels"
    );
    common::assert_images_close_where(
        "footprint vs focus only",
        &mimp,
        &focus,
        SIZE,
        1.0 / 255.0,
        inside,
    );
    common::assert_images_close_where("outside vs plain", &mimp, &plain, SIZE, 1.0 / 255.0, |i| {
        !inside(i)
    });
    // Not trivially equal: in the footprint the plain rendering shows the shell in front.
    let changed = common::diff_images(&plain, &focus, SIZE, inside, 0.05)
        .over
        .len();
    assert!(changed > footprint / 2, "only {changed} pixels changed");
    // And the CPU reference agrees everywhere.
    let (_, cpu) = cpu_reference(&scene, &setup, &cam);
    common::assert_images_close("MImP vs CPU", &mimp, &cpu, SIZE, 1.0 / 255.0);
}

#[test]
fn conical_mimp_starts_rays_on_the_countersink_of_eq_1() {
    let mut session = session();
    let cam = camera(&mut session);
    let scene = two_objects();
    let setup = Setup {
        method: Method::Mimp,
        focus: 2,
        importance: vec![(1, 0.2), (2, 0.8)],
        slope: 0.7,
    };
    let (buffer, gpu) = render_gpu(&mut session, &cam, &scene, Some(&setup), &[]);
    let p = ray_params(&cam);
    let w = pixel_world(&cam);
    let cpu_buffers =
        reference::buffers(&scene.volume, &scene.labels, &scene.objects, &setup, &p, w);
    // Eq. 1 at every pixel outside the footprint: E = e_max − d·s_c (world units). Jump
    // flooding's distance may exceed the exact one by a fraction of a pixel at rare pixels:
    // allow 0.5 pixel of distance, and count how many differ at all.
    let mut inexact = 0;
    let mut checked = 0;
    for (i, (g, c)) in buffer.iter().zip(&cpu_buffers.pixels).enumerate() {
        assert_eq!(g[2], c[2], "footprint flag at pixel {i}");
        if c[2] > 0.5 {
            assert!(
                (g[0] - c[0]).abs() < 1e-3,
                "first hit at {i}: {g:?} vs {c:?}"
            );
            continue;
        }
        checked += 1;
        let error = (g[0] - c[0]).abs();
        assert!(
            error <= 0.5 * w * setup.slope + 1e-3,
            "E at pixel {i} (d = {}): GPU {} vs eq. 1 {}",
            cpu_buffers.distance[i],
            g[0],
            c[0]
        );
        if error > 1e-3 {
            inexact += 1;
        }
    }
    assert!(checked > 1000);
    assert!(inexact * 100 <= checked, "{inexact} of {checked} inexact");
    // The countersink cuts the shell around the core: some pixels outside the footprint
    // lose shell in front (brighter core-free, less shell) compared with cylindrical MImP.
    let cylindrical = Setup {
        slope: 0.0,
        ..setup
    };
    let (_, cyl) = render_gpu(&mut session, &cam, &scene, Some(&cylindrical), &[]);
    let cut = common::diff_images(&gpu, &cyl, SIZE, |i| buffer[i][2] < 0.5, 0.02)
        .over
        .len();
    assert!(cut > 50, "the countersink changed only {cut} pixels");
    // The whole picture against the CPU reference (pixels where jump flooding is inexact
    // excluded: there the cut may move by a sample).
    let setup = Setup {
        slope: 0.7,
        ..cylindrical
    };
    let cpu = reference::render(
        &scene.volume,
        &scene.labels,
        &scene.objects,
        &setup,
        &cpu_buffers,
        &p,
    );
    common::assert_images_close_where("conical MImP vs CPU", &gpu, &cpu, SIZE, 2.0 / 255.0, |i| {
        (buffer[i][0] - cpu_buffers.pixels[i][0]).abs() <= 1e-3
    });
}

/// Three context slabs stacked along the view axis, each covering part of the frame, and a small
/// focus cube in a corner where no slab is: rays meet all three slabs, two of them, or one.
fn stacked_slabs() -> Scene {
    let (volume, labels) = grid(|x, y, z| {
        let inside = |x0, x1, y0, y1, z0, z1| {
            (x0..x1).contains(&x) && (y0..y1).contains(&y) && (z0..z1).contains(&z)
        };
        if inside(3, 10, 3, 10, 15, 25) {
            4
        } else if inside(14, 37, 14, 37, 28, 32) {
            1 // front (nearest the eye on +z), everywhere
        } else if inside(14, 26, 14, 37, 18, 22) {
            2 // middle, half of x
        } else if inside(14, 37, 14, 26, 6, 10) {
            3 // back, half of y
        } else {
            0
        }
    });
    let object = |id, rgba| Object {
        id,
        tf: flat(rgba),
        local: Local::Over,
    };
    Scene {
        volume,
        labels,
        objects: vec![
            object(1, SHELL),
            object(2, CORE),
            object(3, INNER),
            object(4, [0.9, 0.9, 0.1, 0.7]),
        ],
    }
}

/// Issue 31: MImP's per-ray rule (§IV.A, "for each ray the object with highest importance along
/// the ray is determined … all the remaining objects along the ray are … fully transparent"),
/// with three context objects along one ray; the cutaway keeps today's compositing.
#[test]
fn mimp_draws_only_the_most_important_object_along_each_ray() {
    let mut session = session();
    let cam = camera(&mut session);
    let scene = stacked_slabs();
    let importance = vec![(1, 0.2), (2, 0.6), (3, 0.4), (4, 1.0)];
    let setup = Setup {
        method: Method::Mimp,
        focus: 4,
        importance: importance.clone(),
        slope: 0.0,
    };
    let (buffer, mimp) = render_gpu(&mut session, &cam, &scene, Some(&setup), &[]);
    let (cpu_buffers, cpu) = cpu_reference(&scene, &setup, &cam);
    // Which slabs each ray meets, from the importance sums (distinct for every combination).
    let sums = reference::buffers(
        &scene.volume,
        &scene.labels,
        &scene.objects,
        &Setup {
            method: Method::AimcImage,
            ..Setup {
                importance: importance.clone(),
                ..setup
            }
        },
        &ray_params(&cam),
        pixel_world(&cam),
    );
    let region = |i: usize, sum: f32| (sums.pixels[i][1] - sum).abs() < 1e-4;
    // (front, middle, back) → the middle (0.6); (front, back) → the back (0.4); (front, middle)
    // → the middle; the front alone → the front (0.2).
    let cases = [
        (1.2, 0.6, 2u16),
        (0.6, 0.4, 3),
        (0.8, 0.6, 2),
        (0.2, 0.2, 1),
    ];
    for (sum, strongest, id) in cases {
        let pixels: Vec<usize> = (0..buffer.len()).filter(|&i| region(i, sum)).collect();
        assert!(
            pixels.len() > 40,
            "{} pixels meet Σ I = {sum}",
            pixels.len()
        );
        for &i in &pixels {
            assert_eq!(
                buffer[i][1], strongest,
                "the ray's highest importance at pixel {i}"
            );
        }
        // The picture there is that object's alone.
        let alone = Scene {
            objects: scene
                .objects
                .iter()
                .filter(|o| o.id == id)
                .cloned()
                .collect(),
            volume: scene.volume.clone(),
            labels: scene.labels.clone(),
        };
        let (_, only) = render_gpu(&mut session, &cam, &alone, None, &[]);
        common::assert_images_close_where(
            &format!("rays meeting Σ I = {sum} vs object {id} alone"),
            &mimp,
            &only,
            SIZE,
            1.0 / 255.0,
            |i| region(i, sum),
        );
    }
    for (i, (g, c)) in buffer.iter().zip(&cpu_buffers.pixels).enumerate() {
        assert_eq!(g[1], c[1], "highest importance at pixel {i}: GPU vs CPU");
    }
    common::assert_images_close("per-ray MImP vs CPU", &mimp, &cpu, SIZE, 1.0 / 255.0);

    // The cutaway composites every slab a ray meets, as the plain rendering does outside the
    // focus footprint.
    let cutaway = Setup {
        method: Method::Cutaway,
        ..setup
    };
    let (buffer, cut) = render_gpu(&mut session, &cam, &scene, Some(&cutaway), &[]);
    let (_, plain) = render_gpu(&mut session, &cam, &scene, None, &[]);
    common::assert_images_close_where("cutaway vs plain", &cut, &plain, SIZE, 1.0 / 255.0, |i| {
        buffer[i][2] < 0.5
    });
    let (_, cpu) = cpu_reference(&scene, &cutaway, &cam);
    common::assert_images_close("cutaway vs CPU", &cut, &cpu, SIZE, 1.0 / 255.0);
    let differ = common::diff_images(&cut, &mimp, SIZE, |i| region(i, 1.2), 0.05)
        .over
        .len();
    assert!(differ > 40, "the per-ray rule changed only {differ} pixels");
}

fn three_objects() -> Scene {
    let (volume, labels) = nested(true);
    Scene {
        volume,
        labels,
        objects: vec![
            Object {
                id: 1,
                tf: flat(SHELL),
                local: Local::Over,
            },
            Object {
                id: 2,
                tf: flat(CORE),
                local: Local::Over,
            },
            Object {
                id: 3,
                tf: flat(INNER),
                local: Local::Over,
            },
        ],
    }
}

#[test]
fn aimc_levels_of_sparseness_are_importance_over_the_sum_of_eq_2() {
    let mut session = session();
    let cam = camera(&mut session);
    let scene = three_objects();
    // Importances summing to 2, so that S_o = I_o / Σ is not I_o itself.
    let importance = vec![(1, 0.2), (2, 0.5), (3, 1.3)];
    for method in [Method::AimcImage, Method::AimcObject] {
        let setup = Setup {
            method,
            focus: 3,
            importance: importance.clone(),
            slope: 1.0,
        };
        let (buffer, gpu) = render_gpu(&mut session, &cam, &scene, Some(&setup), &[]);
        // The centre column meets all three objects: S_o = I_o / (0.2 + 0.5 + 1.3).
        let centre = buffer[(SIZE / 2 * SIZE + SIZE / 2) as usize];
        for (id, i) in &importance {
            let s = i / centre[1];
            assert!(
                (s - i / 2.0).abs() < 1e-3,
                "{method:?}: S_{id} = {s}, eq. 2 gives {}",
                i / 2.0
            );
        }
        // A column through the shell only: Σ = I_1, S_1 = 1 (no suppression).
        let edge = buffer[(SIZE / 2 * SIZE + SIZE / 2 - 15) as usize];
        assert!((0.2 / edge[1] - 1.0).abs() < 1e-3, "shell only: {edge:?}");
        if method == Method::AimcObject {
            // The countersink around the footprint suppresses the context there too: pixels
            // outside the footprint differ from the cylindrical (no countersink) rendering.
            let cylindrical = Setup {
                slope: 0.0,
                importance: importance.clone(),
                ..setup
            };
            let (_, cyl) = render_gpu(&mut session, &cam, &scene, Some(&cylindrical), &[]);
            let outside = |i: usize| buffer[i][2] < 0.5;
            let cut = common::diff_images(&gpu, &cyl, SIZE, outside, 0.02)
                .over
                .len();
            assert!(
                cut > 30,
                "the countersink changed {cut} pixels outside the footprint"
            );
        }
        let (cpu_buffers, cpu) = cpu_reference(&scene, &setup, &cam);
        let name = format!("{method:?} vs CPU");
        common::assert_images_close_where(&name, &gpu, &cpu, SIZE, 2.0 / 255.0, |i| {
            (buffer[i][0] - cpu_buffers.pixels[i][0]).abs() <= 1e-3
        });
        let (_, plain) = render_gpu(&mut session, &cam, &scene, None, &[]);
        let centre = (SIZE / 2 * SIZE + SIZE / 2) as usize;
        assert!(
            common::channel_difference(&gpu[centre], &plain[centre]) > 0.05,
            "{method:?}: the centre is not sparser than the plain rendering"
        );
    }
}

/// A context slab (id 1, voxels z 26..=33) in front of a focus cube (id 2, z 10..=20), both
/// seen along −z: every ray through the focus crosses the same slab thickness.
fn slab_and_cube(focus_alpha: f32) -> Scene {
    let (volume, labels) = grid(|x, y, z| {
        let within = |v: u32, lo: u32, hi: u32| (lo..=hi).contains(&v);
        if within(x, 8, 31) && within(y, 8, 31) && within(z, 26, 33) {
            1
        } else if within(x, 14, 25) && within(y, 14, 25) && within(z, 10, 20) {
            2
        } else {
            0
        }
    });
    Scene {
        volume,
        labels,
        objects: vec![
            Object {
                id: 1,
                tf: flat([0.9, 0.3, 0.2, 0.12]),
                local: Local::Over,
            },
            Object {
                id: 2,
                tf: flat([0.2, 0.8, 0.3, focus_alpha]),
                local: Local::Over,
            },
        ],
    }
}

#[test]
fn vpimc_scales_the_occluding_context_to_the_opacity_s_o_of_eq_3() {
    let mut session = session();
    let cam = camera(&mut session);
    // An invisible focus: the picture's opacity in the footprint is the occluding part's.
    let scene = slab_and_cube(0.0);
    for (i_context, i_focus) in [(0.2f32, 0.8f32), (0.5, 0.5), (0.7, 0.3)] {
        let setup = Setup {
            method: Method::Vpimc,
            focus: 2,
            importance: vec![(1, i_context), (2, i_focus)],
            slope: 0.0,
        };
        let (buffer, gpu) = render_gpu(&mut session, &cam, &scene, Some(&setup), &[]);
        let (_, plain) = render_gpu(&mut session, &cam, &scene, None, &[]);
        let s_o = i_context / (i_context + i_focus);
        let mut sampled = 0;
        for i in (0..buffer.len()).filter(|&i| buffer[i][2] > 0.5) {
            sampled += 1;
            assert!(
                (gpu[i][3] - s_o).abs() < 1e-3,
                "I = ({i_context}, {i_focus}): opacity {} at pixel {i}, S_o = {s_o} (plain {})",
                gpu[i][3],
                plain[i][3]
            );
        }
        assert!(sampled > 100, "footprint of {sampled} pixels");
        // Outside the footprint the slab keeps its plain opacity (VPImC suppresses only the
        // occluding part).
        let outside = (SIZE / 2 * SIZE + 12) as usize;
        assert!(buffer[outside][2] < 0.5);
        assert!(common::channel_difference(&gpu[outside], &plain[outside]) < 1.0 / 255.0);
        // Also with a conical countersink: the slab around the footprint stays as it is.
        let conical = Setup {
            slope: 1.0,
            importance: setup.importance.clone(),
            ..setup
        };
        let (cone_buffer, cone) = render_gpu(&mut session, &cam, &scene, Some(&conical), &[]);
        // Every difference below 1/255: none beyond the largest float under it.
        common::assert_images_close_where(
            "conical VPImC outside the footprint vs plain",
            &cone,
            &plain,
            SIZE,
            (1.0f32 / 255.0).next_down(),
            |i| cone_buffer[i][2] < 0.5,
        );
        let (_, cpu) = cpu_reference(&scene, &setup, &cam);
        common::assert_images_close("VPImC vs CPU", &gpu, &cpu, SIZE, 1.0 / 255.0);
    }
}

#[test]
fn levels_of_sparseness_change_the_context_as_named() {
    let mut session = session();
    let cam = camera(&mut session);
    let scene = slab_and_cube(0.8);
    let setup = Setup {
        method: Method::AimcObject,
        focus: 2,
        importance: vec![(1, 0.25), (2, 0.75)],
        slope: 0.0,
    };
    let centre = (SIZE / 2 * SIZE + SIZE / 2) as usize;
    let level = |name: &str| ("sparseness", ParamValue::Choice(name.into()));
    let (_, opacity) = render_gpu(
        &mut session,
        &cam,
        &scene,
        Some(&setup),
        &[level("opacity")],
    );
    let (_, saturation) = render_gpu(
        &mut session,
        &cam,
        &scene,
        Some(&setup),
        &[level("saturation")],
    );
    let (_, door) = render_gpu(
        &mut session,
        &cam,
        &scene,
        Some(&setup),
        &[level("screen_door")],
    );
    let (_, style) = render_gpu(
        &mut session,
        &cam,
        &scene,
        Some(&setup),
        &[
            level("style"),
            ("sparse_mode", ParamValue::Choice("mip".into())),
        ],
    );
    let (_, plain) = render_gpu(&mut session, &cam, &scene, None, &[]);
    // A sparse style: the slab in front of the focus as a MIP segment (one sample's colour
    // and opacity, 0.12, instead of the slab's accumulated opacity), so more focus shows.
    assert!(style[centre][1] > plain[centre][1] + 0.05);
    assert!(common::channel_difference(&style[centre], &opacity[centre]) > 0.01);
    // Opacity and saturation: the same opacity; saturation greys the slab's red (0.9, 0.3,
    // 0.2) towards its luminance 0.47, so the slab adds less red and more green.
    assert!((opacity[centre][3] - saturation[centre][3]).abs() < 1e-3);
    assert!(saturation[centre][0] < opacity[centre][0] - 0.01);
    assert!(saturation[centre][1] > opacity[centre][1] + 0.01);
    // Both show more of the focus (green) than the plain rendering.
    assert!(opacity[centre][1] > plain[centre][1] + 0.05);
    // The screen door keeps about S = 1/4 of the slab's voxels: its colour lies between the
    // plain rendering and the slab removed, not equal to either.
    assert!(door[centre][1] > plain[centre][1] + 0.05);
    let focus_only = Scene {
        objects: scene.objects.iter().skip(1).cloned().collect(),
        volume: scene.volume.clone(),
        labels: scene.labels.clone(),
    };
    let (_, removed) = render_gpu(&mut session, &cam, &focus_only, None, &[]);
    assert!(
        door[centre][1] < removed[centre][1] - 0.02,
        "the screen door removed the whole slab: {:?} vs {:?}",
        door[centre],
        removed[centre]
    );
    // Outside the focus footprint nothing changes.
    let outside = (SIZE / 2 * SIZE + 12) as usize;
    for (name, picture) in [
        ("opacity", &opacity),
        ("saturation", &saturation),
        ("door", &door),
    ] {
        assert!(
            common::channel_difference(&picture[outside], &plain[outside]) < 1.0 / 255.0,
            "{name}"
        );
    }
}

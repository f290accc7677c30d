//! Marching cubes against analytic surfaces, and on the real MRI.

use std::collections::HashMap;
use std::f64::consts::PI;
use std::path::Path;
use std::time::Instant;

use glam::Vec3;
use hatchery_data::marching_cubes::{marching_cubes, marching_cubes_with_progress};
use hatchery_data::procedural::{self, SHELL_HALF_THICKNESS, SHELL_RADII};
use hatchery_data::{MeshData, nifti_file};

fn data(rel: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data")
        .join(rel)
}

/// Asserts that every directed edge is used by exactly one triangle and its reverse by exactly
/// one other: the mesh is closed, manifold along edges and consistently oriented.
fn assert_closed(mesh: &MeshData) {
    let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
    for t in mesh.indices.chunks_exact(3) {
        for k in 0..3 {
            *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    let mut bad = 0;
    for (&(a, b), &n) in &directed {
        if n != 1 || directed.get(&(b, a)) != Some(&1) {
            bad += 1;
        }
    }
    assert_eq!(
        bad,
        0,
        "{bad} of {} directed edges are not matched exactly once",
        directed.len()
    );
}

/// Fraction of triangles whose geometric (winding) normal agrees with their vertex normals.
fn winding_agreement(mesh: &MeshData) -> f64 {
    let p = |i: u32| Vec3::from_array(mesh.positions[i as usize]);
    let n = |i: u32| Vec3::from_array(mesh.normals[i as usize]);
    let agree = mesh
        .indices
        .chunks_exact(3)
        .filter(|t| {
            let face = (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0]));
            face.dot(n(t[0]) + n(t[1]) + n(t[2])) > 0.0
        })
        .count();
    agree as f64 / mesh.triangle_count() as f64
}

fn assert_unit_normals(mesh: &MeshData) {
    assert_eq!(mesh.normals.len(), mesh.positions.len());
    for n in &mesh.normals {
        let len = Vec3::from_array(*n).length();
        assert!((len - 1.0).abs() < 1e-4, "normal length {len}");
    }
}

fn assert_relative(what: &str, got: f64, want: f64, tolerance: f64) {
    let err = (got - want).abs() / want;
    eprintln!(
        "{what}: got {got:.5}, want {want:.5}, relative error {:.3}%",
        err * 100.0
    );
    assert!(
        err < tolerance,
        "{what}: got {got}, want {want} (relative error {err})"
    );
}

#[test]
fn sphere_is_accurate_closed_and_outward() {
    let r = 0.7f32;
    let volume = procedural::sphere(96, r).unwrap();
    let voxel = volume.spacing()[0];
    let mesh = marching_cubes(&volume, 0.0);
    eprintln!(
        "sphere: {} vertices, {} triangles",
        mesh.positions.len(),
        mesh.triangle_count()
    );

    assert_relative(
        "sphere area",
        mesh.surface_area(),
        4.0 * PI * (r as f64).powi(2),
        0.02,
    );

    let mut worst_angle = 0.0f32;
    let mut worst_radius = 0.0f32;
    for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
        let p = Vec3::from_array(*p);
        worst_angle = worst_angle.max(
            Vec3::from_array(*n)
                .angle_between(p.normalize())
                .to_degrees(),
        );
        worst_radius = worst_radius.max((p.length() - r).abs());
    }
    eprintln!(
        "sphere: worst normal angle {worst_angle:.3} deg, worst radius error {worst_radius:.5}"
    );
    assert!(
        worst_angle < 2.0,
        "worst normal is {worst_angle} degrees off radial"
    );
    assert!(
        worst_radius < 0.5 * voxel,
        "a vertex is {worst_radius} off the radius (voxel {voxel})"
    );

    assert_unit_normals(&mesh);
    let agreement = winding_agreement(&mesh);
    assert!(
        agreement == 1.0,
        "only {:.4}% of triangles wind with their normals",
        agreement * 100.0
    );
    assert_closed(&mesh);

    // The mesh is welded: a closed genus-0 triangle mesh has V - E + F = 2.
    let (v, f) = (mesh.positions.len() as i64, mesh.triangle_count() as i64);
    assert_eq!(v - 3 * f / 2 + f, 2, "Euler characteristic");
}

#[test]
fn torus_area() {
    let (major, minor) = (0.6f32, 0.25f32);
    let volume = procedural::torus(96, major, minor).unwrap();
    let mesh = marching_cubes(&volume, 0.0);
    let want = 4.0 * PI * PI * major as f64 * minor as f64;
    assert_relative("torus area", mesh.surface_area(), want, 0.02);
    assert_closed(&mesh);
    assert!(winding_agreement(&mesh) > 0.999);
    // Genus 1: V - E + F = 0.
    let (v, f) = (mesh.positions.len() as i64, mesh.triangle_count() as i64);
    assert_eq!(v - 3 * f / 2 + f, 0, "Euler characteristic");
}

#[test]
fn shells_give_six_spheres() {
    let volume = procedural::shells(128).unwrap();
    let mesh = marching_cubes(&volume, 0.0);
    let t = SHELL_HALF_THICKNESS as f64;
    let want: f64 = SHELL_RADII
        .iter()
        .map(|&rk| 4.0 * PI * ((rk as f64 - t).powi(2) + (rk as f64 + t).powi(2)))
        .sum();
    assert_relative("shells area", mesh.surface_area(), want, 0.02);
    assert_closed(&mesh);
    assert!(winding_agreement(&mesh) > 0.999);
    // Six disjoint spheres: V - E + F = 12.
    let (v, f) = (mesh.positions.len() as i64, mesh.triangle_count() as i64);
    assert_eq!(v - 3 * f / 2 + f, 12, "Euler characteristic");
}

#[test]
fn progress_is_reported_up_to_one() {
    let volume = procedural::sphere(40, 0.5).unwrap();
    let seen = std::sync::Mutex::new(Vec::new());
    let mesh = marching_cubes_with_progress(&volume, 0.0, &|f| seen.lock().unwrap().push(f));
    let mut seen = seen.into_inner().unwrap();
    assert!(!seen.is_empty());
    seen.sort_by(f32::total_cmp);
    assert!(seen.iter().all(|f| (0.0..=1.0).contains(f)));
    assert_eq!(*seen.last().unwrap(), 1.0);
    // Same result as without progress.
    assert_eq!(mesh, marching_cubes(&volume, 0.0));
}

#[test]
fn anisotropic_spacing_and_origin_are_respected() {
    // The same ball sampled on a stretched grid: world-space results must not change.
    let (dims, spacing, origin) = (
        [40u32, 20, 80],
        [0.05f32, 0.1, 0.025],
        [-1.0f32, -0.95, -1.0],
    );
    let mut values = Vec::new();
    for z in 0..dims[2] {
        for y in 0..dims[1] {
            for x in 0..dims[0] {
                let p = Vec3::from_array(origin)
                    + Vec3::new(x as f32, y as f32, z as f32) * Vec3::from_array(spacing);
                values.push(0.6 - p.length());
            }
        }
    }
    let volume = hatchery_data::VolumeData::new(dims, spacing, origin, values).unwrap();
    let mesh = marching_cubes(&volume, 0.0);
    assert_relative(
        "anisotropic sphere area",
        mesh.surface_area(),
        4.0 * PI * 0.36,
        0.02,
    );
    let worst = mesh
        .positions
        .iter()
        .zip(&mesh.normals)
        .map(|(p, n)| {
            Vec3::from_array(*n)
                .angle_between(Vec3::from_array(*p))
                .to_degrees()
        })
        .fold(0.0f32, f32::max);
    assert!(worst < 3.0, "worst normal {worst} degrees off radial");
    assert_closed(&mesh);
}

#[test]
fn mri_surface() {
    let volume = nifti_file::load_nifti(&data("volumes/mni152_t1.nii.gz")).unwrap();
    let iso = 80.0;
    let start = Instant::now();
    let mesh = marching_cubes(&volume, iso);
    let elapsed = start.elapsed();
    eprintln!(
        "MRI marching cubes at iso {iso}: {} vertices, {} triangles in {:.2?}",
        mesh.positions.len(),
        mesh.triangle_count(),
        elapsed
    );
    assert!(
        mesh.triangle_count() > 300_000,
        "{} triangles",
        mesh.triangle_count()
    );
    assert_unit_normals(&mesh);
    let agreement = winding_agreement(&mesh);
    eprintln!("MRI winding agreement {:.3}%", agreement * 100.0);
    // Noisy data has sub-voxel features where the smoothed gradient and the facet disagree.
    assert!(agreement > 0.99);
    // Integer data at an integer iso: the zero-area triangles at voxels equal to iso are gone.
    let p = |i: u32| glam::DVec3::from_array(mesh.positions[i as usize].map(f64::from));
    let zero_area = mesh
        .indices
        .chunks_exact(3)
        .filter(|t| (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0])).length() == 0.0)
        .count();
    assert_eq!(zero_area, 0);
    // The surface lies within the volume's world bounds.
    let (lo, hi) = mesh.bounds().unwrap();
    assert!(lo.cmpge(volume.world_min() - 1e-3).all() && hi.cmple(volume.world_max() + 1e-3).all());
}

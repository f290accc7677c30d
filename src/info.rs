//! `hatchery info FILE`: what a volume or mesh file holds and where it lies in the world.

use anyhow::Result;
use hatchery_data::mesh_file::{MESH_ENDINGS, load_mesh};
use hatchery_data::volume_file::{VOLUME_ENDINGS, load_volume};
use std::path::Path;

/// A multi-line description of a volume (dims, spacing, voxel → world affine in RAS+ mm, value
/// range, stored type, the header rule that placed it) or a mesh (counts, world bounds).
pub fn describe(path: &Path) -> Result<String> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let path = hatchery_data::ome_zarr::group_of(path);
    let is_volume = VOLUME_ENDINGS.iter().any(|e| name.ends_with(e)) || path.is_dir();
    if !is_volume && !MESH_ENDINGS.iter().any(|e| name.ends_with(e)) {
        anyhow::bail!(
            "{}: unknown file ending; volumes: {}, or a DICOM folder; meshes: {}",
            path.display(),
            VOLUME_ENDINGS.join(", "),
            MESH_ENDINGS.join(", ")
        );
    }
    if !is_volume {
        let mesh = load_mesh(path)?;
        let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for p in &mesh.positions {
            for a in 0..3 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        return Ok(format!(
            "{}\n  mesh: {} vertices, {} triangles\n  bounds: {:?} .. {:?}\n",
            path.display(),
            mesh.positions.len(),
            mesh.triangle_count(),
            lo,
            hi
        ));
    }
    let v = load_volume(path)?;
    let g = &v.geometry;
    let no_data = v
        .voxels
        .as_f32()
        .map_or(0, |f| f.iter().filter(|x| !x.is_finite()).count());
    let [lo, hi] = g.world_bounds(v.dims);
    let mut out = format!("{}\n", path.display());
    out += &format!("  dims: {} x {} x {}\n", v.dims[0], v.dims[1], v.dims[2]);
    out += &format!(
        "  spacing: {:.6} {:.6} {:.6}\n",
        g.spacing.x, g.spacing.y, g.spacing.z
    );
    out += &format!("  voxel -> world (RAS+ mm): {}\n", g.describe());
    out += &format!(
        "  world bounds of voxel centres: [{:.3}, {:.3}, {:.3}] .. [{:.3}, {:.3}, {:.3}]\n",
        lo.x, lo.y, lo.z, hi.x, hi.y, hi.z
    );
    out += &format!(
        "  placed by: {}\n",
        if v.placement.is_empty() {
            "-"
        } else {
            &v.placement
        }
    );
    for warning in &v.warnings {
        out += &format!("  warning: {warning}\n");
    }
    out += &format!(
        "  stored type: {} (kept as {})\n",
        v.stored_type,
        v.voxels.type_name()
    );
    out += &if v.has_finite_values() {
        format!(
            "  value range: {} .. {}{}\n",
            v.value_range[0],
            v.value_range[1],
            if no_data > 0 {
                format!(" ({no_data} voxels are no data: NaN/inf)")
            } else {
                String::new()
            }
        )
    } else {
        format!("  value range: none (all {no_data} voxels are no data: NaN/inf)\n")
    };
    if hatchery_data::ome_zarr::is_zarr(path) {
        out += &ome_zarr_levels(path)?;
    }
    Ok(out)
}

/// An OME-Zarr image's pyramid and label images, one line each.
fn ome_zarr_levels(path: &Path) -> Result<String> {
    use hatchery_data::ome_zarr::{Multiscale, label_images};
    let image = Multiscale::open(path)?;
    let mut out = String::new();
    for (k, l) in image.levels.iter().enumerate() {
        let [x, y, z] = l.dims;
        let s = l.geometry.spacing;
        out += &format!(
            "  level {k} ({}): {x} x {y} x {z}, spacing {:.6} {:.6} {:.6}\n",
            l.path, s.x, s.y, s.z
        );
    }
    for name in label_images(path) {
        let label = Multiscale::open(&path.join("labels").join(&name))?;
        let names = label.label_names();
        out += &format!(
            "  label image labels/{name}: {} named objects{}\n",
            names.len(),
            if names.is_empty() {
                String::new()
            } else {
                format!(
                    " ({})",
                    names
                        .iter()
                        .map(|(id, n)| format!("{id} {n}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            }
        );
    }
    Ok(out)
}

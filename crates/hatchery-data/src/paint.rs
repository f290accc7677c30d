//! Volume painting (the tutorial's VolumeShop §6.1, "direct volume manipulation … 3D painting"):
//! a selection painted onto the data with a spherical brush, stored as brush dabs and applied to
//! a label map. A dab fills, with its id, every voxel whose centre lies within its radius (world
//! units) of its centre; id 0 erases. Dabs apply in order, so a later one overwrites.

use crate::error::DataError;
use crate::segmentation::LabelData;
use glam::Vec3;

/// One brush dab: a ball in world coordinates (millimetres) and the id it paints (0 erases).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dab {
    pub center: Vec3,
    pub radius: f32,
    pub id: u16,
}

/// Parses dabs written "x y z r id; …" (world units; `id` 0 erases). Errors name the dab.
pub fn parse_dabs(text: &str) -> Result<Vec<Dab>, DataError> {
    parse_dab_list(text).map_err(DataError::Invalid)
}

fn parse_dab_list(text: &str) -> Result<Vec<Dab>, String> {
    let mut dabs = Vec::new();
    for (n, part) in text.split(';').map(str::trim).enumerate() {
        if part.is_empty() {
            continue;
        }
        let numbers: Vec<f32> = part
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()
            .map_err(|_| format!("dab {} `{part}`: expected five numbers `x y z r id`", n + 1))?;
        let [x, y, z, r, id] = numbers[..] else {
            return Err(format!(
                "dab {} `{part}`: expected five numbers `x y z r id`, found {}",
                n + 1,
                numbers.len()
            ));
        };
        if !(x.is_finite() && y.is_finite() && z.is_finite() && r > 0.0 && r.is_finite()) {
            return Err(format!(
                "dab {} `{part}`: the centre must be finite and the radius positive",
                n + 1
            ));
        }
        if id < 0.0 || id > f32::from(u16::MAX) || id.fract() != 0.0 {
            return Err(format!(
                "dab {} `{part}`: the id must be a whole number from 0 to 65535",
                n + 1
            ));
        }
        dabs.push(Dab {
            center: Vec3::new(x, y, z),
            radius: r,
            id: id as u16,
        });
    }
    Ok(dabs)
}

/// Writes dabs as [`parse_dabs`] reads them (millimetres to 0.01).
pub fn format_dabs(dabs: &[Dab]) -> String {
    dabs.iter()
        .map(|d| {
            format!(
                "{:.2} {:.2} {:.2} {:.2} {}",
                d.center.x, d.center.y, d.center.z, d.radius, d.id
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// Applies `dabs` to `labels` in order; a painted id without a name (or named only by its
/// number, "object 7") is called `name`.
/// Errors: a dab wider than the whole grid's diagonal times 4 (a typo, not a brush).
pub fn paint(labels: &mut LabelData, dabs: &[Dab], name: &str) -> Result<(), DataError> {
    let [nx, ny, nz] = labels.dims;
    let g = labels.geometry;
    let to_voxel = g.to_voxel().as_mat4();
    let [lo, hi] = g.world_bounds(labels.dims);
    let diagonal = (hi - lo).length();
    for dab in dabs {
        if dab.radius > 4.0 * diagonal.max(1e-6) {
            return Err(DataError::Invalid(format!(
                "a dab of radius {} is far larger than the volume ({diagonal:.1} across)",
                dab.radius
            )));
        }
        // The dab's box in voxel space: the voxel images of its world box's corners.
        let (mut vlo, mut vhi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for corner in 0..8 {
            let sign = |bit: u32| if corner & (1 << bit) == 0 { -1.0 } else { 1.0 };
            let p = dab.center + dab.radius * Vec3::new(sign(0), sign(1), sign(2));
            let v = to_voxel.transform_point3(p);
            vlo = vlo.min(v);
            vhi = vhi.max(v);
        }
        let range = |lo: f32, hi: f32, n: u32| {
            let a = lo.ceil().max(0.0) as u32;
            let b = (hi.floor().min(n as f32 - 1.0)).max(-1.0) as i64;
            a..(b + 1).max(a as i64) as u32
        };
        for z in range(vlo.z, vhi.z, nz) {
            for y in range(vlo.y, vhi.y, ny) {
                for x in range(vlo.x, vhi.x, nx) {
                    let p = g.voxel_to_world(Vec3::new(x as f32, y as f32, z as f32));
                    if p.distance(dab.center) <= dab.radius {
                        let i = (z as usize * ny as usize + y as usize) * nx as usize + x as usize;
                        labels.ids[i] = dab.id;
                    }
                }
            }
        }
        if dab.id != 0 {
            // A new id, or one the labels only call by its number, takes the painting's name.
            let entry = labels.objects.entry(dab.id).or_default();
            if entry.is_empty() || *entry == format!("object {}", dab.id) {
                *entry = name.to_owned();
            }
        }
    }
    // Ids painted over entirely leave the table.
    let present: std::collections::BTreeSet<u16> = labels.ids.iter().copied().collect();
    labels.objects.retain(|id, _| present.contains(id));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Geometry;

    #[test]
    fn a_dab_fills_the_voxels_within_its_radius_in_world_units() {
        // Anisotropic and rotated: the ball is round in millimetres, not in voxels.
        let rotation = glam::DMat3::from_rotation_z(0.5);
        let g = Geometry::from_lps([0.5, 1.0, 2.0], rotation, [3.0, -4.0, 1.0]);
        let mut labels = LabelData::new([40, 30, 20], g, vec![0; 40 * 30 * 20]);
        let center = g.voxel_to_world(Vec3::new(20.0, 15.0, 10.0));
        let dabs = parse_dabs(&format!(
            "{} {} {} 6 3; {} {} {} 2 0",
            center.x, center.y, center.z, center.x, center.y, center.z
        ))
        .unwrap();
        paint(&mut labels, &dabs, "selection").unwrap();
        let mut painted = 0;
        for (i, &id) in labels.ids.iter().enumerate() {
            let v = Vec3::new((i % 40) as f32, ((i / 40) % 30) as f32, (i / 1200) as f32);
            let d = g.voxel_to_world(v).distance(center);
            let want = if d <= 2.0 {
                0
            } else if d <= 6.0 {
                3
            } else {
                0
            };
            assert_eq!(id, want, "voxel {v} at {d} mm");
            painted += usize::from(id == 3);
        }
        // The shell's volume, 4/3 π (6³ − 2³) mm³, in voxels of 1 mm³: about 871.
        assert!((800..950).contains(&painted), "{painted} voxels painted");
        assert_eq!(
            labels.objects.get(&3).map(String::as_str),
            Some("selection")
        );
    }

    #[test]
    fn dabs_round_trip_and_bad_ones_are_named() {
        let dabs = parse_dabs("1 2 3 4 5; -1.5 0 2.25 0.5 0").unwrap();
        assert_eq!(parse_dabs(&format_dabs(&dabs)).unwrap(), dabs);
        for (text, says) in [
            ("1 2 3 4", "dab 1"),
            ("1 2 3 4 5; 1 2 x 4 5", "dab 2"),
            ("1 2 3 -4 5", "radius positive"),
            ("1 2 3 4 70000", "0 to 65535"),
        ] {
            let e = parse_dabs(text).unwrap_err().to_string();
            assert!(e.contains(says), "{text}: {e}");
        }
    }
}

//! Annotations (VolumeShop §6.4 in the tutorial): labelled 3-D anchors, written in the graph
//! (`AnnotationList`, annotation_list.rs) or one per object of a segmentation
//! (`AnnotationsFromLabels`, annotations_from_labels.rs). Laid out by `AnnotationLayout`, drawn
//! by `AnnotationOverlay`, written by `SaveSvg`.

use crate::value::Labels;
use glam::Vec3;
use hatchery_annotation::Anchor;

pub use crate::value::annotations::{Annotations, Placed};

/// Parses "x y z: text; …" (or one row per line) into anchors; earlier rows get higher
/// priority. Errors name the row.
pub(crate) fn parse_anchor_list(text: &str) -> Result<Vec<Anchor>, String> {
    let rows: Vec<&str> = text
        .split([';', '\n'])
        .map(str::trim)
        .filter(|r| !r.is_empty())
        .collect();
    let n = rows.len();
    rows.iter()
        .enumerate()
        .map(|(i, row)| {
            let (position, label) = row
                .split_once(':')
                .ok_or_else(|| format!("row {} `{row}`: expected `x y z: text`", i + 1))?;
            let numbers: Result<Vec<f32>, _> = position
                .split(|c: char| c == ',' || c.is_whitespace())
                .filter(|s| !s.is_empty())
                .map(str::parse::<f32>)
                .collect();
            match numbers {
                Ok(v) if v.len() == 3 && v.iter().all(|x| x.is_finite()) => Ok(Anchor {
                    position: Vec3::new(v[0], v[1], v[2]),
                    text: label.trim().to_owned(),
                    object: 0,
                    priority: (n - i) as f32,
                }),
                Ok(v) if v.len() == 3 => Err(format!(
                    "row {} `{row}`: `{}` has a number too large for 32-bit floats (x y z, \
                     world units, below about 3.4e38)",
                    i + 1,
                    position.trim()
                )),
                _ => Err(format!(
                    "row {} `{row}`: `{}` is not three numbers (x y z, world units)",
                    i + 1,
                    position.trim()
                )),
            }
        })
        .collect()
}

/// Per object id: voxel count, sum of voxel indices, and index bounds.
pub(crate) struct ObjectVoxels {
    count: u64,
    sum: glam::DVec3,
    lo: glam::UVec3,
    hi: glam::UVec3,
}

/// One anchor per object in `ids` that has voxels: at the object's voxel nearest its centroid
/// (so on the object even where it is concave), with the object's world box as bounds.
pub(crate) fn anchors_for(labels: &Labels, ids: &[u16]) -> (Vec<Anchor>, Vec<Option<[Vec3; 2]>>) {
    let l = &labels.data;
    let [nx, ny, _] = l.dims.map(|d| d as usize);
    let mut stats: Vec<Option<ObjectVoxels>> = (0..ids.len()).map(|_| None).collect();
    let mut slot = vec![usize::MAX; u16::MAX as usize + 1];
    for (i, &id) in ids.iter().enumerate() {
        slot[id as usize] = i;
    }
    let voxel = |i: usize| {
        glam::UVec3::new(
            (i % nx) as u32,
            (i / nx % ny) as u32,
            (i / (nx * ny)) as u32,
        )
    };
    for (i, &id) in l.ids.iter().enumerate() {
        let s = slot[id as usize];
        if s == usize::MAX {
            continue;
        }
        let v = voxel(i);
        let entry = stats[s].get_or_insert(ObjectVoxels {
            count: 0,
            sum: glam::DVec3::ZERO,
            lo: v,
            hi: v,
        });
        entry.count += 1;
        entry.sum += v.as_dvec3();
        entry.lo = entry.lo.min(v);
        entry.hi = entry.hi.max(v);
    }
    let total: u64 = stats.iter().flatten().map(|s| s.count).sum();
    let mut anchors = Vec::new();
    let mut bounds = Vec::new();
    for (s, &id) in stats.iter().zip(ids) {
        let Some(s) = s else {
            continue;
        };
        let centroid = (s.sum / s.count as f64).as_vec3();
        // The object's voxel nearest the centroid (searched within its box).
        let mut best = (f32::INFINITY, s.lo);
        for z in s.lo.z..=s.hi.z {
            for y in s.lo.y..=s.hi.y {
                for x in s.lo.x..=s.hi.x {
                    if l.id(x, y, z) != id {
                        continue;
                    }
                    let d =
                        glam::Vec3::new(x as f32, y as f32, z as f32).distance_squared(centroid);
                    if d < best.0 {
                        best = (d, glam::UVec3::new(x, y, z));
                    }
                }
            }
        }
        let world = |v: Vec3| l.geometry.voxel_to_world(v);
        let corners = hatchery_annotation::box_corners(s.lo.as_vec3(), s.hi.as_vec3()).map(world);
        let lo = corners.iter().copied().fold(Vec3::INFINITY, Vec3::min);
        let hi = corners.iter().copied().fold(Vec3::NEG_INFINITY, Vec3::max);
        anchors.push(Anchor {
            position: world(best.1.as_vec3()),
            text: l
                .objects
                .get(&id)
                .cloned()
                .unwrap_or_else(|| format!("object {id}")),
            object: id,
            priority: s.count as f32 / total.max(1) as f32,
        });
        bounds.push(Some([lo, hi]));
    }
    (anchors, bounds)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn anchor_lists_parse_and_name_the_bad_row() {
        let a = parse_anchor_list("1 2 3: piston; 4, 5, 6: cylinder bore\n0 0 -1.5: oil").unwrap();
        assert_eq!(a.len(), 3);
        assert_eq!(a[1].text, "cylinder bore");
        assert_eq!(a[2].position, Vec3::new(0.0, 0.0, -1.5));
        assert!(a[0].priority > a[1].priority && a[1].priority > a[2].priority);
        let e = parse_anchor_list("1 2 3: ok; 1 2: short").unwrap_err();
        assert!(e.contains("row 2") && e.contains("three numbers"), "{e}");
        let e = parse_anchor_list("0 0 0: a; 1e40 0 0: b").unwrap_err();
        assert!(e.contains("row 2") && e.contains("too large"), "{e}");
        assert!(parse_anchor_list("no colon").unwrap_err().contains("row 1"));
    }
}

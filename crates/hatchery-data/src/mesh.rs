//! Indexed triangle meshes.

use glam::Vec3;

use crate::DataError;

/// An indexed triangle mesh with one unit normal per vertex.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshData {
    pub positions: Vec<[f32; 3]>,
    /// Same length as `positions`, unit length.
    pub normals: Vec<[f32; 3]>,
    /// Three indices per triangle, counter-clockwise seen from the front.
    pub indices: Vec<u32>,
}

impl MeshData {
    /// Validates the mesh (finite positions, whole triangles, indices in range). Given normals
    /// are normalized; where they are missing, of the wrong count, or degenerate (zero length or
    /// not finite), area-weighted normals computed from the triangles are used instead.
    pub fn new(
        positions: Vec<[f32; 3]>,
        normals: Option<Vec<[f32; 3]>>,
        indices: Vec<u32>,
    ) -> Result<Self, DataError> {
        if u32::try_from(positions.len()).is_err() {
            return Err(DataError::Invalid(format!(
                "mesh has {} vertices, more than a u32 index can address",
                positions.len()
            )));
        }
        if let Some(i) = positions
            .iter()
            .position(|p| p.iter().any(|c| !c.is_finite()))
        {
            return Err(DataError::Invalid(format!(
                "vertex {i} has a non-finite position {:?}",
                positions[i]
            )));
        }
        if !indices.len().is_multiple_of(3) {
            return Err(DataError::Invalid(format!(
                "index count {} is not a multiple of 3",
                indices.len()
            )));
        }
        if let Some(&bad) = indices.iter().find(|&&i| i as usize >= positions.len()) {
            return Err(DataError::Invalid(format!(
                "triangle index {bad} is out of range for {} vertices",
                positions.len()
            )));
        }

        let mut mesh = MeshData {
            positions,
            normals: Vec::new(),
            indices,
        };
        match normals {
            Some(given) if given.len() == mesh.positions.len() => {
                let computed = mesh.area_weighted_normals();
                mesh.normals = given
                    .iter()
                    .zip(computed)
                    .map(|(n, fallback)| {
                        let n = Vec3::from_array(*n);
                        let len = n.length();
                        if len.is_finite() && len > 1e-20 {
                            (n / len).to_array()
                        } else {
                            fallback
                        }
                    })
                    .collect();
            }
            _ => mesh.compute_vertex_normals(),
        }
        Ok(mesh)
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Axis-aligned bounds of the positions, `None` for a mesh without vertices.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let first = Vec3::from_array(*self.positions.first()?);
        Some(self.positions.iter().fold((first, first), |(lo, hi), p| {
            let p = Vec3::from_array(*p);
            (lo.min(p), hi.max(p))
        }))
    }

    /// Total triangle area, accumulated in f64.
    pub fn surface_area(&self) -> f64 {
        self.indices
            .chunks_exact(3)
            .map(|t| {
                let [a, b, c] =
                    [0, 1, 2].map(|k| Vec3::from_array(self.positions[t[k] as usize]).as_dvec3());
                0.5 * (b - a).cross(c - a).length()
            })
            .sum()
    }

    /// Replaces the normals with area-weighted averages of the adjacent triangle normals.
    /// Vertices without a non-degenerate triangle get +Z so every normal stays unit length.
    pub fn compute_vertex_normals(&mut self) {
        self.normals = self.area_weighted_normals();
    }

    fn area_weighted_normals(&self) -> Vec<[f32; 3]> {
        let mut sums = vec![Vec3::ZERO; self.positions.len()];
        for t in self.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| Vec3::from_array(self.positions[t[k] as usize]));
            // The cross product's length is twice the area: that is the weighting.
            let n = (b - a).cross(c - a);
            for &i in t {
                sums[i as usize] += n;
            }
        }
        sums.into_iter()
            .map(|n| n.try_normalize().unwrap_or(Vec3::Z).to_array())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube with outward-facing counter-clockwise triangles.
    pub(crate) fn cube() -> MeshData {
        let positions = (0..8)
            .map(|i| [(i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32])
            .collect();
        let quads = [
            [0, 2, 3, 1], // z = 0, facing -z
            [4, 5, 7, 6], // z = 1
            [0, 1, 5, 4], // y = 0
            [2, 6, 7, 3], // y = 1
            [0, 4, 6, 2], // x = 0
            [1, 3, 7, 5], // x = 1
        ];
        let indices = quads
            .iter()
            .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
            .collect();
        MeshData::new(positions, None, indices).unwrap()
    }

    #[test]
    fn cube_area_bounds_normals() {
        let m = cube();
        assert_eq!(m.triangle_count(), 12);
        assert!((m.surface_area() - 6.0).abs() < 1e-9);
        assert_eq!(m.bounds(), Some((Vec3::ZERO, Vec3::ONE)));
        // Corner normals point diagonally outward.
        let n = Vec3::from_array(m.normals[7]);
        assert!((n - Vec3::ONE.normalize()).length() < 1e-5, "{n}");
        let n = Vec3::from_array(m.normals[0]);
        assert!((n + Vec3::ONE.normalize()).length() < 1e-5, "{n}");
    }

    #[test]
    fn new_validates() {
        let p = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert!(MeshData::new(p.clone(), None, vec![0, 1]).is_err());
        assert!(MeshData::new(p.clone(), None, vec![0, 1, 3]).is_err());
        let mut bad = p.clone();
        bad[1][2] = f32::INFINITY;
        assert!(MeshData::new(bad, None, vec![0, 1, 2]).is_err());
        let empty = MeshData::new(vec![], None, vec![]).unwrap();
        assert_eq!(empty.bounds(), None);
        assert_eq!(empty.surface_area(), 0.0);
    }

    #[test]
    fn given_normals_are_normalized_and_repaired() {
        let p = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let n = vec![[0.0, 0.0, 5.0], [0.0, 0.0, 0.0], [f32::NAN, 0.0, 0.0]];
        let m = MeshData::new(p.clone(), Some(n), vec![0, 1, 2]).unwrap();
        assert_eq!(m.normals, vec![[0.0, 0.0, 1.0]; 3]);
        // Wrong count: ignored, computed instead.
        let m = MeshData::new(p, Some(vec![[1.0, 0.0, 0.0]]), vec![0, 2, 1]).unwrap();
        assert_eq!(m.normals, vec![[0.0, 0.0, -1.0]; 3]);
    }
}

//! `MeshTransform`: scales, rotates and moves a mesh (to place secondary geometry, align scans).

use crate::value::Mesh;
use crate::{Ctx, Value};
use glam::{EulerRot, Mat3, Quat, Vec3};
use hatchery_data::MeshData;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::node_params! {
    /// The parameters of `MeshTransform`.
    pub struct MeshTransformParams {
        /// scale per axis (non-zero)
        pub scale: [f32; 3] = [1.0, 1.0, 1.0];
        /// Euler angles about x, y, z in degrees
        pub rotate: [f32; 3] = [0.0, 0.0, 0.0];
        /// offset, world units
        pub translate: [f32; 3] = [0.0, 0.0, 0.0];
        /// point normals the other way
        pub flip_normals: bool = false;
    }
}

pub struct MeshTransformNode;

impl Node<Value, Ctx> for MeshTransformNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "MeshTransform",
            category: "Geometry",
            doc: "Applies p' = R·(s ⊙ p) + t to every vertex (rotation R from Euler angles x, then y, \
                  then z, in degrees) and transforms normals accordingly; `flip_normals` reverses \
                  normals and winding.",
            inputs: vec![PortSpec::input(
                "mesh",
                PortType::Mesh,
                "the mesh to transform",
            )],
            outputs: vec![PortSpec::output(
                "mesh",
                PortType::Mesh,
                "the transformed mesh",
            )],
            params: MeshTransformParams::specs(),
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        _ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let mesh = inputs.require("mesh")?.mesh("mesh")?;
        let p = MeshTransformParams::read(p)?;
        let scale = Vec3::from(p.scale);
        if scale.abs().min_element() < 1e-12 {
            return Err(NodeError::new(
                "parameter `scale` must be non-zero on every axis",
            ));
        }
        let [rx, ry, rz] = p.rotate.map(f32::to_radians);
        let rotation = Quat::from_euler(EulerRot::ZYX, rz, ry, rx);
        let translate = Vec3::from(p.translate);
        // Normals transform with the inverse transpose: rotation · (1/scale).
        let normal_matrix = Mat3::from_quat(rotation) * Mat3::from_diagonal(scale.recip());
        let flip = if p.flip_normals { -1.0 } else { 1.0 };
        // A mirroring scale reverses the winding; flipping normals reverses it again.
        let mirrored = (scale.x * scale.y * scale.z < 0.0) != (flip < 0.0);

        let src = &mesh.data;
        let positions = src
            .positions
            .iter()
            .map(|&q| (rotation * (Vec3::from(q) * scale) + translate).to_array())
            .collect();
        let normals = src
            .normals
            .iter()
            .map(|&n| {
                (normal_matrix * Vec3::from(n) * flip)
                    .normalize_or_zero()
                    .to_array()
            })
            .collect();
        let mut indices = src.indices.clone();
        if mirrored {
            indices.chunks_exact_mut(3).for_each(|t| t.swap(1, 2));
        }
        let data = MeshData::new(positions, Some(normals), indices)
            .map_err(|e| NodeError::new(e.to_string()))?;
        Ok(vec![Value::Mesh(Arc::new(Mesh::new(data)))])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(MeshTransformNode);
}

//! `MarchingCubes`: extracts an iso-surface mesh from a volume on the CPU (in parallel).

use crate::value::Mesh;
use crate::{Ctx, Value};
use hatchery_graph::{
    DataValue, NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::node_params! {
    /// Parameters of `MarchingCubes`.
    pub struct MarchingCubesParams {
        /// iso value, in the volume's units, or relative to its values: "percentile(60)",
        /// "range(0.3)", "otsu"
        pub iso: DataValue = 0.0, range(-1e12, 1e12);
    }
}

pub struct MarchingCubesNode;

impl Node<Value, Ctx> for MarchingCubesNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "MarchingCubes",
            category: "Geometry",
            doc: "Lorensen–Cline marching cubes on the CPU, parallel over slabs. Vertices are shared \
                  between cells; normals are the negated, normalised volume gradient (pointing towards \
                  lower values).",
            inputs: vec![PortSpec::input(
                "volume",
                PortType::Volume,
                "the scalar field",
            )],
            outputs: vec![PortSpec::output(
                "mesh",
                PortType::Mesh,
                "the iso-surface in world units",
            )],
            params: MarchingCubesParams::specs(),
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let volume = inputs.require("volume")?.volume("volume")?;
        let params = MarchingCubesParams::read(p)?;
        let iso = crate::relative::data_value(ctx, "iso", params.iso, &volume.data)?;
        let range = volume.data.value_range;
        // No surface is a warning, not an error (issue 9 item 4): the picture renders without it
        // and the node says why, as for an iso value that crosses no cell.
        let in_range = (range[0]..=range[1]).contains(&iso);
        let mesh = if in_range {
            hatchery_data::marching_cubes::marching_cubes(&volume.data, iso)
        } else {
            hatchery_data::mesh::MeshData::default()
        };
        tracing::info!(iso, triangles = mesh.triangle_count(), "marching cubes");
        if mesh.triangle_count() == 0 {
            ctx.warn(if !volume.data.has_finite_values() {
                "the volume holds no finite value (all voxels are no data): no surface".into()
            } else if !in_range {
                format!(
                    "iso value {iso} is outside the volume's value range [{}, {}]: no surface",
                    range[0], range[1]
                )
            } else if range[0] == range[1] {
                format!("the volume is constant ({}): no surface", range[0])
            } else {
                format!("iso value {iso} gives no surface")
            });
        }
        Ok(vec![Value::Mesh(Arc::new(Mesh::new(mesh)))])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(MarchingCubesNode);
}

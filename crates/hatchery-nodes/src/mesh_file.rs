//! `MeshFile`: a triangle mesh read from OBJ, PLY (ASCII or binary) or STL.

use crate::value::Mesh;
use crate::{Ctx, Value};
use hatchery_graph::{
    FilePath, NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::node_params! {
    /// Parameters of `MeshFile`.
    pub struct MeshFileParams {
        /// the mesh file
        pub path: FilePath = "", reads(hatchery_graph::InputKind::Mesh);
    }
}

pub struct MeshFileNode;

impl Node<Value, Ctx> for MeshFileNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "MeshFile",
            category: "Data",
            doc: "Reads a triangle mesh from .obj, .ply (ASCII or binary) or .stl; polygons are \
                  triangulated, missing normals are computed. Relative paths are relative to the graph \
                  file's folder.",
            inputs: vec![],
            outputs: vec![PortSpec::output("mesh", PortType::Mesh, "the mesh")],
            params: MeshFileParams::specs(),
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        _inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let params = MeshFileParams::read(p)?;
        let key = params.path.written.as_str();
        if crate::memory_inputs::is_memory_key(key) {
            return match ctx.memory(key) {
                Some(crate::memory_inputs::InputData::Mesh(m)) => {
                    Ok(vec![Value::Mesh(Arc::new(Mesh::shared(m.clone())))])
                }
                Some(other) => Err(crate::memory_inputs::wrong_kind(key, "mesh", other)),
                None => Err(crate::memory_inputs::missing(key)),
            };
        }
        let path = params.path.resolved.clone();
        if path.as_os_str().is_empty() {
            return Err(NodeError::new(
                "parameter `path` is empty: name an .obj, .ply or .stl file",
            ));
        }
        let data = hatchery_data::mesh_file::load_mesh(&path)
            .map_err(|e| NodeError::new(e.to_string()))?;
        tracing::info!(path = %path.display(), triangles = data.triangle_count(), "mesh loaded");
        Ok(vec![Value::Mesh(Arc::new(Mesh::new(data)))])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(MeshFileNode);
}

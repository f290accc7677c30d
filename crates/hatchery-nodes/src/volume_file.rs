//! `VolumeFile`: a scalar volume read from a NIfTI file.

use crate::value::Volume;
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

pub struct VolumeFileNode;

impl Node<Value, Ctx> for VolumeFileNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "VolumeFile",
            category: "Data",
            doc: "Reads a volume: NIfTI-1 (.nii, .nii.gz) of any integer or float type with \
                  scl_slope/scl_inter applied, or VTK XML image data (.vti, e.g. label volumes). Voxel \
                  spacing and origin are kept. Relative paths are relative to the graph file's folder.",
            inputs: vec![],
            outputs: vec![PortSpec::output(
                "volume",
                PortType::Volume,
                "the volume, in world units (mm)",
            )],
            params: vec![ParamSpec::path(
                "path",
                "",
                "the .nii, .nii.gz or .vti file",
            )],
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        _ctx: &mut Ctx,
        _inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let path = p.path("path");
        if path.as_os_str().is_empty() {
            return Err(NodeError::new(
                "parameter `path` is empty: name a .nii, .nii.gz or .vti file",
            ));
        }
        let data = hatchery_data::load_volume(&path).map_err(|e| NodeError::new(e.to_string()))?;
        tracing::info!(
            path = %path.display(),
            dims = ?data.dims,
            spacing = ?data.spacing(),
            range = ?data.value_range,
            world_min = ?data.world_min(),
            world_max = ?data.world_max(),
            "volume loaded"
        );
        Ok(vec![Value::Volume(Arc::new(Volume::new(data)))])
    }
}

//! `LabelFile`: a label map from a file (any volume format), with object names.

use crate::label_sources::finish;
use crate::label_sources::finish_shared;
use crate::label_sources::given_names;
use crate::label_sources::labels_output;
use crate::label_sources::names_table;
use crate::memory_inputs::{self, InputData};
use crate::{Ctx, Value};
use hatchery_data::segmentation::LabelData;
use hatchery_graph::{
    FilePath, NodeError, NodeInputs, NodeSchema, Params,
    executor::Node,
};
use std::sync::Arc;

hatchery_graph::node_params! {
    /// Parameters of `LabelFile`.
    pub struct LabelFileParams {
        /// the label map file, or a DICOM folder
        pub path: FilePath = "", reads(hatchery_graph::InputKind::Labels);
        /// the named data array to read (VTK; OME-Zarr: a label image of labels/); empty: the
        /// active scalars (OME-Zarr: the first label image)
        pub array: String = "";
        /// object names: CSV `id,name` or ITK-SNAP label file (optional)
        pub names: FilePath = "", reads(hatchery_graph::InputKind::Names);
    }
}

pub struct LabelFileNode;

impl Node<Value, Ctx> for LabelFileNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "LabelFile",
            category: "Data",
            doc: "Reads a label map (object id per voxel, whole numbers 0–65535, 0 = background) \
                  from any volume format VolumeFile reads, placed in the world the same way. \
                  Object names come from `names` (a CSV/TSV table `id,name` or an ITK-SNAP label \
                  description file) or from the file itself (3D Slicer's segment names in a \
                  .seg.nrrd header, an OME-Zarr label image's properties); objects without a name are called \"object N\".",
            inputs: vec![],
            outputs: vec![labels_output()],
            params: LabelFileParams::specs(),
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
        let params = LabelFileParams::read(p)?;
        let key = params.path.written.as_str();
        if memory_inputs::is_memory_key(key) {
            let mut data = match ctx.memory(key) {
                Some(InputData::Labels(l)) => l.clone(),
                Some(other) => return Err(memory_inputs::wrong_kind(key, "label map", other)),
                None => return Err(memory_inputs::missing(key)),
            };
            // Names given with the array win over a names table (which names the rest).
            let table = names_table(ctx, &params.names)?;
            if !table.is_empty() {
                let given = data.objects.clone();
                let labels = Arc::make_mut(&mut data);
                labels.name_objects(&table);
                labels.name_objects(&given_names(&given));
            }
            return finish_shared(ctx, "labels in memory", data);
        }
        let path = params.path.resolved.clone();
        if path.as_os_str().is_empty() {
            return Err(NodeError::new(
                "parameter `path` is empty: name a label map (.nii.gz, .vti, .nrrd, ...)",
            ));
        }
        let array = params.array.trim();
        let options = hatchery_data::volume_file::LoadOptions {
            array: (!array.is_empty()).then(|| array.to_owned()),
        };
        // Names the file carries (an OME-Zarr label image's, a .seg.nrrd's) come with it.
        let (volume, file_names) =
            hatchery_data::volume_file::load_label_volume(&path, &options)
                .map_err(|e| NodeError::new(e.to_string()))?;
        if !volume.warnings.is_empty() {
            ctx.warn(format!(
                "{}: {}",
                path.display(),
                volume.warnings.join("; ")
            ));
        }
        let mut data = LabelData::from_volume(&volume)
            .map_err(|e| NodeError::new(format!("{}: {e}", path.display())))?;
        data.name_objects(&file_names);
        data.name_objects(&names_table(ctx, &params.names)?);
        finish(ctx, &path.display().to_string(), data)
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(LabelFileNode);
}

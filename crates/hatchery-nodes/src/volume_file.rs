//! `VolumeFile`: a scalar volume read from a file, placed in the world (RAS+ mm).

use crate::value::Volume;
use crate::{Ctx, Value};
use hatchery_graph::{
    FilePath, NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::path::Path;
use std::sync::Arc;

hatchery_graph::node_params! {
    /// Parameters of `VolumeFile`.
    pub struct VolumeFileParams {
        /// the volume file, or a folder holding a DICOM series
        pub path: FilePath = "", reads(hatchery_graph::InputKind::Volume);
        /// the named data array to read from a file with several (VTK; OME-Zarr: a label image
        /// of labels/); empty: the file's active scalars, else the first array (OME-Zarr: the
        /// image)
        pub array: String = "";
    }
}

pub struct VolumeFileNode;

impl Node<Value, Ctx> for VolumeFileNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "VolumeFile",
            category: "Data",
            doc: "Reads a volume: NIfTI-1 or NIfTI-2 (.nii, .nii.gz, scl_slope/scl_inter \
                  applied), FreeSurfer MGH/MGZ (.mgh, .mgz), VTK \
                  XML image data (.vti), NRRD (.nrrd, .nhdr), MetaImage (.mha, .mhd), a \
                  multi-page TIFF stack (.tif) or a DICOM series (a folder, or one .dcm of it). \
                  The file's voxel → world transform (origin, spacing, direction; NIfTI \
                  sform/qform) places the voxels in hatchery's RAS+ world in mm (LPS formats \
                  are converted; see docs/data.md). NaN voxels are \"no data\". Relative paths \
                  are relative to the graph file's folder.",
            inputs: vec![],
            outputs: vec![PortSpec::output(
                "volume",
                PortType::Volume,
                "the volume, in world units (mm)",
            )],
            params: VolumeFileParams::specs(),
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
        let params = VolumeFileParams::read(p)?;
        if let Some(volume) = memory_volume(ctx, params.path.written.as_str())? {
            return Ok(vec![Value::Volume(Arc::new(volume))]);
        }
        let path = params.path.resolved.clone();
        if path.as_os_str().is_empty() {
            return Err(NodeError::new(
                "parameter `path` is empty: name a volume file (.nii, .nii.gz, .mgz, .vti, .nrrd, \
                 .mha, .tif, ...) or a DICOM folder",
            ));
        }
        let array = params.array.as_str().trim();
        let options = hatchery_data::volume_file::LoadOptions {
            array: (!array.is_empty()).then(|| array.to_owned()),
        };
        if let Some(volume) = streamed(ctx, &path, options.array.as_deref())? {
            return Ok(vec![Value::Volume(Arc::new(volume))]);
        }
        let data = hatchery_data::volume_file::load_volume_with(&path, &options)
            .map_err(|e| NodeError::new(e.to_string()))?;
        // What the loader worked around (a resampled slice gap, skipped files) and what the
        // values are like: one warning line for the node.
        let mut warnings: Vec<String> = data.warnings.clone();
        if !data.has_finite_values() {
            warnings.push("no voxel holds a finite value (all are no data: NaN/inf)".into());
        } else if data.value_range[0] == data.value_range[1] {
            warnings.push(format!(
                "the volume is constant ({}): nothing to tell apart",
                data.value_range[0]
            ));
        }
        if !warnings.is_empty() {
            ctx.warn(format!("{}: {}", path.display(), warnings.join("; ")));
        }
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

/// The volume streamed from `path` when it is beyond the host budget (see
/// [`crate::value::stream`]); `None`: load it whole.
fn streamed(ctx: &mut Ctx, path: &Path, array: Option<&str>) -> Result<Option<Volume>, NodeError> {
    use hatchery_data::stream_file::{host_budget, open_beyond_budget};
    let budget = host_budget().map_err(|e| NodeError::new(e.to_string()))?;
    let Some(s) = open_beyond_budget(path, array, budget, false)
        .map_err(|e| NodeError::new(e.to_string()))?
    else {
        return Ok(None);
    };
    let levels = s.source.levels();
    let [x, y, z] = levels[0].dims;
    let [px, py, pz] = s.preview.dims;
    let message = format!(
        "{}: {x}×{y}×{z} voxels exceed the host budget ({} MiB, HATCHERY_HOST_BUDGET_MB): \
         streamed, {} levels; ray casters read the region and level each view needs, other \
         nodes the preview level {} ({px}×{py}×{pz}); values span its range {:?}",
        path.display(),
        budget >> 20,
        levels.len(),
        s.preview_level,
        s.preview.value_range
    );
    ctx.warn(message);
    let stream = crate::value::stream::Stream::new(
        s.source,
        path.to_path_buf(),
        s.preview.value_range,
        s.preview_level,
        budget / 8,
    );
    Ok(Some(Volume::streamed(s.preview, Arc::new(stream))))
}

/// The volume a `memory:` key names (see [`crate::memory_inputs`]): a volume as it is, a label
/// map's ids as u16 voxels. `None` when `text` is not a key.
fn memory_volume(ctx: &Ctx, text: &str) -> Result<Option<Volume>, NodeError> {
    use crate::memory_inputs::{self, InputData};
    if !memory_inputs::is_memory_key(text) {
        return Ok(None);
    }
    match ctx.memory(text) {
        Some(InputData::Volume(v)) => Ok(Some(Volume::shared(v.clone()))),
        Some(InputData::Labels(l)) => memory_inputs::labels_as_volume(l)
            .map(|v| Some(Volume::new(v)))
            .map_err(|e| NodeError::new(e.to_string())),
        Some(other) => Err(memory_inputs::wrong_kind(text, "volume", other)),
        None => Err(memory_inputs::missing(text)),
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(VolumeFileNode);
}

//! Graph inputs given as data in memory instead of files (issue 26: numpy arrays from Python).
//!
//! A graph input binds file parameters (`VolumeFile.path`, `LabelFile.path`, …). Data held in
//! memory is given to those parameters as a key, `memory:NAME#N` (the input's name and a
//! counter, so each new array changes the parameter and the executor's cache re-runs what reads
//! it), and the data itself is kept in the [`crate::RenderContext`]. The file nodes look the key
//! up before they read a file. Keys never reach a saved graph: the session remembers what the
//! parameters held before and writes that back (see [`crate::Session::document`]).

use hatchery_data::mesh::MeshData;
use hatchery_data::segmentation::LabelData;
use hatchery_data::{DataError, VolumeData};
use hatchery_graph::{InputKind, NodeError};
use std::collections::BTreeMap;
use std::sync::Arc;

/// What marks a parameter's text as a key of in-memory data.
pub const MEMORY_PREFIX: &str = "memory:";

/// Data given to a graph input in memory.
#[derive(Clone, Debug)]
pub enum InputData {
    /// A scalar volume placed in the world (for `volume` inputs).
    Volume(Arc<VolumeData>),
    /// An object-id map with names (for `labels` inputs).
    Labels(Arc<LabelData>),
    /// A triangle mesh (for `mesh` inputs).
    Mesh(Arc<MeshData>),
    /// An object-name table id → name (for `names` inputs).
    Names(Arc<BTreeMap<u16, String>>),
}

impl InputData {
    /// The input kind this data is for.
    pub fn kind(&self) -> InputKind {
        match self {
            InputData::Volume(_) => InputKind::Volume,
            InputData::Labels(_) => InputKind::Labels,
            InputData::Mesh(_) => InputKind::Mesh,
            InputData::Names(_) => InputKind::Names,
        }
    }
}

/// Whether a parameter's text is a key of in-memory data.
pub fn is_memory_key(text: &str) -> bool {
    text.starts_with(MEMORY_PREFIX)
}

/// The error of a key this session holds no data for (a graph saved with one by hand, or a
/// key copied from another session).
pub fn missing(key: &str) -> NodeError {
    NodeError::new(format!(
        "`{key}` names data held in memory by another session (or one that has ended): give the \
         graph input its data again, or a file"
    ))
}

/// The error of data of the wrong kind under a key (a key written by hand).
pub fn wrong_kind(key: &str, wanted: &str, data: &InputData) -> NodeError {
    NodeError::new(format!(
        "`{key}` holds a {} in memory, not a {wanted}",
        data.kind()
    ))
}

/// The object ids of a label map as a volume (a labels input bound to `VolumeFile.path`):
/// u16 voxels on the same grid.
pub fn labels_as_volume(labels: &LabelData) -> Result<VolumeData, DataError> {
    let mut volume = VolumeData::from_voxels(
        labels.dims,
        labels.geometry,
        hatchery_data::voxels::Voxels::U16(labels.ids.clone()),
    )?;
    volume.placement = "in memory".into();
    Ok(volume)
}

//! The kinds of data a graph input holds and a path parameter reads.

use std::fmt;

/// What an input holds; a path parameter says which kind of file it reads
/// ([`crate::ParamSpec::reads`]), and an input may only be bound to parameters of its kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum InputKind {
    /// A scalar volume (NIfTI, NRRD, MetaImage, VTK, TIFF, DICOM).
    Volume,
    /// A label map: object ids per voxel (the same formats).
    Labels,
    /// A triangle mesh (.obj, .ply, .stl).
    Mesh,
    /// An object-name table (CSV/TSV `id,name`, ITK-SNAP label description).
    Names,
}

impl InputKind {
    pub const ALL: [InputKind; 4] = [
        InputKind::Volume,
        InputKind::Labels,
        InputKind::Mesh,
        InputKind::Names,
    ];

    /// The name written in graph files and shown by `hatchery inputs`.
    pub fn name(self) -> &'static str {
        match self {
            InputKind::Volume => "volume",
            InputKind::Labels => "labels",
            InputKind::Mesh => "mesh",
            InputKind::Names => "names",
        }
    }

    pub fn parse(text: &str) -> Option<InputKind> {
        InputKind::ALL.into_iter().find(|k| k.name() == text)
    }
}

impl fmt::Display for InputKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

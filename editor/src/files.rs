//! Files from outside the editor: the file dialog (egui-file-dialog, drawn by egui itself so it
//! works the same on every platform and in the headless tests) for path parameters, Open and
//! Save as; and what a data file dropped on the window becomes.

use egui_file_dialog::{DialogState, FileDialog};
use std::path::{Path, PathBuf};

/// Extensions of the volumes `VolumeFile` reads (`.nii.gz` ends in `gz`); see
/// `hatchery_data::volume_file::VOLUME_ENDINGS`.
pub const VOLUME_EXTENSIONS: &[&str] = &[
    "nii", "gz", "mgz", "mgh", "vti", "nrrd", "nhdr", "mha", "mhd", "tif", "tiff", "dcm", "zarr",
    // An OME-Zarr folder is chosen by its zarr.json (the dialog picks files).
    "json",
];
/// Extensions of the meshes `MeshFile` reads.
pub const MESH_EXTENSIONS: &[&str] = &["obj", "ply", "stl"];

/// What a dropped or picked file is, by its name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    Graph,
    Volume,
    Mesh,
    /// A WGSL fragment shader (read by a CustomShader node).
    Shader,
}

impl FileKind {
    pub fn of(path: &Path) -> Option<FileKind> {
        let name = path.file_name()?.to_string_lossy().to_ascii_lowercase();
        let ext = name.rsplit('.').next()?;
        if name.ends_with(".ron") {
            Some(FileKind::Graph)
        } else if name == "zarr.json" || name == ".zattrs" {
            // An OME-Zarr group's metadata file stands for the group (a file dialog picks files).
            Some(FileKind::Volume)
        } else if hatchery_data::volume_file::VOLUME_ENDINGS
            .iter()
            .any(|e| name.ends_with(e))
        {
            Some(FileKind::Volume)
        } else if MESH_EXTENSIONS.contains(&ext) {
            Some(FileKind::Mesh)
        } else if ext == "wgsl" {
            Some(FileKind::Shader)
        } else {
            None
        }
    }

    /// The source node kind that reads such a file.
    pub fn node_kind(self) -> Option<&'static str> {
        match self {
            FileKind::Graph => None,
            FileKind::Volume => Some("VolumeFile"),
            FileKind::Mesh => Some("MeshFile"),
            FileKind::Shader => Some("CustomShader"),
        }
    }

    /// The parameter of that node kind that names the file.
    pub fn path_param(self) -> &'static str {
        match self {
            FileKind::Shader => "shader",
            _ => "path",
        }
    }
}

/// `path` as a graph file stores it: relative to the graph's folder `base` when there is one
/// (so the graph and its data can move together), else as given.
pub fn path_for_graph(base: Option<&Path>, path: &Path) -> String {
    let absolute = |p: &Path| {
        if p.is_absolute() {
            Some(p.to_path_buf())
        } else {
            std::env::current_dir().ok().map(|cwd| cwd.join(p))
        }
    };
    let relative = base.and_then(|base| pathdiff::diff_paths(absolute(path)?, absolute(base)?));
    relative
        .unwrap_or_else(|| path.to_path_buf())
        .to_string_lossy()
        .replace('\\', "/")
}

/// What the open file dialog was opened for.
#[derive(Clone, Debug, PartialEq)]
pub enum Purpose {
    /// A path parameter of a node.
    Param {
        node: String,
        param: String,
    },
    OpenGraph,
    SaveGraphAs,
    /// A graph input (the Data panel).
    Input {
        name: String,
    },
}

/// The one file dialog of the editor.
#[derive(Default)]
pub struct FilePicker {
    dialog: Option<(Purpose, FileDialog)>,
}

impl FilePicker {
    /// Opens the dialog in `folder` for `purpose`, offering files of `kind` first.
    pub fn open(&mut self, purpose: Purpose, kind: Option<FileKind>, folder: Option<PathBuf>) {
        let saving = purpose == Purpose::SaveGraphAs;
        let mut dialog = FileDialog::new().title(
            match &purpose {
                Purpose::Param { node, param } => format!("Choose {node}.{param}"),
                Purpose::OpenGraph => "Open a graph".into(),
                Purpose::SaveGraphAs => "Save the graph as".into(),
                Purpose::Input { name } => format!("Choose the file for input `{name}`"),
            }
            .as_str(),
        );
        if let Some(folder) = folder.filter(|f| f.is_dir()) {
            dialog = dialog.initial_directory(folder);
        }
        let filter = match kind {
            Some(FileKind::Graph) => Some(("Graphs (.ron)", vec!["ron"])),
            Some(FileKind::Volume) => Some((
                "Volumes (.nii, .nii.gz, .mgz, .mgh, .vti, .nrrd, .nhdr, .mha, .mhd, .tif, .dcm; \
                 OME-Zarr: its zarr.json)",
                VOLUME_EXTENSIONS.to_vec(),
            )),
            Some(FileKind::Mesh) => Some(("Meshes (.obj, .ply, .stl)", MESH_EXTENSIONS.to_vec())),
            Some(FileKind::Shader) => Some(("WGSL shaders (.wgsl)", vec!["wgsl"])),
            None => None,
        };
        if let Some((name, extensions)) = filter {
            dialog = dialog
                .add_file_filter_extensions(name, extensions)
                .default_file_filter(name);
        }
        if saving {
            dialog.save_file();
        } else {
            dialog.pick_file();
        }
        self.dialog = Some((purpose, dialog));
    }

    /// What the dialog is open for, if it is open.
    pub fn purpose(&self) -> Option<&Purpose> {
        self.dialog.as_ref().map(|(p, _)| p)
    }

    /// Draws the dialog; returns the purpose and the chosen path once the user picked one.
    pub fn update(&mut self, ctx: &egui::Context) -> Option<(Purpose, PathBuf)> {
        let (_, dialog) = self.dialog.as_mut()?;
        dialog.update(ctx);
        let picked = dialog.take_picked();
        let closed = matches!(dialog.state(), DialogState::Closed | DialogState::Cancelled);
        match picked {
            Some(path) => self.dialog.take().map(|(purpose, _)| (purpose, path)),
            None => {
                if closed {
                    self.dialog = None;
                }
                None
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_by_file_name() {
        assert_eq!(
            FileKind::of(Path::new("a/brain.nii.gz")),
            Some(FileKind::Volume)
        );
        assert_eq!(FileKind::of(Path::new("FROG.VTI")), Some(FileKind::Volume));
        assert_eq!(FileKind::of(Path::new("bunny.obj")), Some(FileKind::Mesh));
        assert_eq!(FileKind::of(Path::new("x.ron")), Some(FileKind::Graph));
        assert_eq!(FileKind::of(Path::new("archive.tar.gz")), None);
        assert_eq!(FileKind::of(Path::new("notes.txt")), None);
        assert_eq!(
            FileKind::of(Path::new("cells.zarr/zarr.json")),
            Some(FileKind::Volume)
        );
        assert_eq!(
            FileKind::of(Path::new("cells.zarr")),
            Some(FileKind::Volume)
        );
    }

    #[test]
    fn paths_are_stored_relative_to_the_graph_folder() {
        assert_eq!(
            path_for_graph(
                Some(Path::new("/w/main/graphs")),
                Path::new("/w/shared/data/b.obj")
            ),
            "../../shared/data/b.obj"
        );
        assert_eq!(path_for_graph(None, Path::new("/w/b.obj")), "/w/b.obj");
    }
}

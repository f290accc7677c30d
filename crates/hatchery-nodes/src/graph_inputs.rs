//! Giving a graph's inputs (issue 25) files of the user's: the checks that make a wrong or
//! unreadable file a one-line error naming the input, before anything runs.

use hatchery_data::mesh_file::MESH_ENDINGS;
use hatchery_data::volume_file::VOLUME_ENDINGS;
use hatchery_graph::InputKind;
use hatchery_graph::inputs::GraphInput;
use std::path::Path;

/// Endings of object-name tables (`LabelFile.names`).
pub const NAMES_ENDINGS: [&str; 4] = [".csv", ".tsv", ".txt", ".label"];

fn ends_with_any(name: &str, endings: &[&str]) -> bool {
    endings.iter().any(|e| name.ends_with(e))
}

/// What kind of data file `path` is by its name: a volume or label map (the same formats), a
/// mesh, a names table, or unknown.
fn kind_of_name(path: &Path) -> Option<&'static str> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if path.is_dir()
        || ends_with_any(&name, &VOLUME_ENDINGS)
        || hatchery_data::dicom_series::is_dicom_file(path)
    {
        Some("volume")
    } else if ends_with_any(&name, &MESH_ENDINGS) {
        Some("mesh")
    } else if ends_with_any(&name, &NAMES_ENDINGS) {
        Some("names table")
    } else {
        None
    }
}

/// Why a file cannot be given to a graph input ([`check_input_file`]); one line naming the input.
#[derive(Debug, thiserror::Error)]
pub enum InputFileError {
    /// The file does not exist or cannot be opened.
    #[error("{0}")]
    Unreadable(String),
    /// The file's name says it is another kind of file than the input reads.
    #[error("{0}")]
    WrongKind(String),
}

/// Checks that `path` can be given to an input of `kind`: it exists and can be read, and its
/// name says it is that kind of file (a folder is a DICOM series, for volumes and labels).
/// Errors are one line naming the input: "input `volume`: brain.obj is a mesh file, not a
/// volume (NIfTI .nii/.nii.gz, …)".
pub fn check_input_file(input: &str, kind: InputKind, path: &Path) -> Result<(), InputFileError> {
    let shown = path.display();
    let unreadable = |e: std::io::Error| {
        InputFileError::Unreadable(format!("input `{input}`: cannot read {shown}: {e}"))
    };
    let folder = match std::fs::metadata(path) {
        Ok(metadata) => {
            if metadata.is_file() {
                std::fs::File::open(path).map_err(unreadable)?;
            }
            metadata.is_dir()
        }
        // The browser has no file system: a file the page mounted is readable.
        Err(_) if hatchery_data::files::is_file(path) => false,
        Err(e) => return Err(unreadable(e)),
    };
    let (wanted, mut endings): (&str, Vec<&str>) = match kind {
        InputKind::Volume => ("volume", VOLUME_ENDINGS.to_vec()),
        InputKind::Labels => ("volume", VOLUME_ENDINGS.to_vec()),
        InputKind::Mesh => ("mesh", MESH_ENDINGS.to_vec()),
        InputKind::Names => ("names table", NAMES_ENDINGS.to_vec()),
    };
    // The browser reads single files: a DICOM series and OME-Zarr are folders.
    if cfg!(target_arch = "wasm32") {
        endings.retain(|e| ![".dcm", ".zarr"].contains(e));
    }
    if folder && kind != InputKind::Volume && kind != InputKind::Labels {
        return Err(InputFileError::WrongKind(format!(
            "input `{input}`: {shown} is a folder, not a {kind} file ({})",
            endings.join(", ")
        )));
    }
    match kind_of_name(path) {
        Some(found) if found == wanted => Ok(()),
        Some(found) => Err(InputFileError::WrongKind(format!(
            "input `{input}` takes a {} file ({}), but {shown} is a {found} file",
            kind_word(kind),
            endings.join(", ")
        ))),
        None => Err(InputFileError::WrongKind(format!(
            "input `{input}` takes a {} file ({}); {shown} has none of these endings",
            kind_word(kind),
            endings.join(", ")
        ))),
    }
}

fn kind_word(kind: InputKind) -> &'static str {
    match kind {
        InputKind::Volume => "volume",
        InputKind::Labels => "label map",
        InputKind::Mesh => "mesh",
        InputKind::Names => "names table",
    }
}

/// The input a file named `path` goes to when a reader drops it on a figure (the browser
/// page): the graph's first input of its kind — a volume file to a volume input, else to a
/// label-map input; a mesh to a mesh input; a names table to a names input. `None`: the file is
/// of no kind the graph's inputs take.
pub fn input_for<'a>(inputs: &'a [GraphInput], path: &Path) -> Option<&'a str> {
    let first = |kind: InputKind| {
        inputs
            .iter()
            .find(|i| i.kind == kind)
            .map(|i| i.name.as_str())
    };
    match kind_of_name(path)? {
        "volume" => first(InputKind::Volume).or_else(|| first(InputKind::Labels)),
        "mesh" => first(InputKind::Mesh),
        _ => first(InputKind::Names),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_dropped_file_goes_to_the_input_of_its_kind() {
        let input = |name: &str, kind| GraphInput {
            name: name.into(),
            kind,
            doc: String::new(),
            to: Vec::new(),
            default: String::new(),
        };
        // As the frog presets declare them: a label map and its names, no volume.
        let frog = [
            input("labels", InputKind::Labels),
            input("names", InputKind::Names),
        ];
        let to = |inputs: &[GraphInput], name: &str| {
            input_for(inputs, Path::new(name)).map(str::to_owned)
        };
        assert_eq!(to(&frog, "my_labels.nii.gz").as_deref(), Some("labels"));
        assert_eq!(to(&frog, "organs.CSV").as_deref(), Some("names"));
        assert_eq!(to(&frog, "bunny.obj"), None);
        assert_eq!(to(&frog, "notes.pdf"), None);
        let both = [
            input("mri", InputKind::Volume),
            input("seg", InputKind::Labels),
        ];
        assert_eq!(to(&both, "t1.mhd").as_deref(), Some("mri"));
        let mesh = [input("surface", InputKind::Mesh)];
        assert_eq!(to(&mesh, "part.STL").as_deref(), Some("surface"));
    }

    #[test]
    fn wrong_kinds_and_missing_files_name_the_input() {
        let dir = tempfile::tempdir().unwrap();
        let mesh = dir.path().join("bunny.OBJ");
        std::fs::write(&mesh, "v 0 0 0\n").unwrap();
        let table = dir.path().join("names.csv");
        std::fs::write(&table, "1,liver\n").unwrap();
        let e = check_input_file("volume", InputKind::Volume, &mesh)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("input `volume` takes a volume file") && e.contains("is a mesh file"),
            "{e}"
        );
        assert!(check_input_file("mesh", InputKind::Mesh, &mesh).is_ok());
        assert!(check_input_file("names", InputKind::Names, &table).is_ok());
        let e = check_input_file("labels", InputKind::Labels, &table)
            .unwrap_err()
            .to_string();
        assert!(e.contains("label map") && e.contains("names table"), "{e}");
        let e = check_input_file("volume", InputKind::Volume, &dir.path().join("no.nii"))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("input `volume`: cannot read") && e.contains("no.nii"),
            "{e}"
        );
        // A folder is a DICOM series; a file without an ending is one by its DICM marker.
        assert!(check_input_file("volume", InputKind::Volume, dir.path()).is_ok());
        let slice = dir.path().join("IM000001");
        let mut bytes = vec![0u8; 128];
        bytes.extend_from_slice(b"DICM");
        std::fs::write(&slice, &bytes).unwrap();
        assert!(check_input_file("volume", InputKind::Volume, &slice).is_ok());
        std::fs::write(dir.path().join("README"), "notes").unwrap();
        assert!(check_input_file("volume", InputKind::Volume, &dir.path().join("README")).is_err());
        assert!(check_input_file("mesh", InputKind::Mesh, dir.path()).is_err());
    }
}

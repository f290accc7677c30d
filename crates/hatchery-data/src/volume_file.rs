//! Volume files of any supported format, chosen by file name.

use std::path::Path;

use crate::dicom_series::load_dicom_series;
use crate::metaimage_file::load_metaimage;
use crate::nifti_file::load_nifti;
use crate::nrrd_file::load_nrrd;
use crate::tiff_stack::load_tiff_stack;
use crate::vti_file::load_vti;
use crate::{DataError, VolumeData};

/// File name endings [`load_volume`] reads (matched case-insensitively); folders are read as
/// DICOM series too.
pub const VOLUME_ENDINGS: [&str; 13] = [
    ".nii", ".nii.gz", ".mgz", ".mgh", ".vti", ".nrrd", ".nhdr", ".mha", ".mhd", ".tif", ".tiff",
    ".dcm", ".zarr",
];

/// Choices a user can make when loading a volume (the VolumeFile node's parameters).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LoadOptions {
    /// The named data array to read, for formats with several (VTK); `None`: the file's active
    /// scalars, else the first array.
    pub array: Option<String>,
}

/// Loads a volume with default options; see [`load_volume_with`].
pub fn load_volume(path: &Path) -> Result<VolumeData, DataError> {
    load_volume_with(path, &LoadOptions::default())
}

/// Loads a volume, choosing the format by the (case-insensitive) end of the file name:
/// `.nii` and `.nii.gz` with [`load_nifti`], `.vti` with [`load_vti`], `.nrrd` and `.nhdr` with
/// [`load_nrrd`], `.mha` and `.mhd` with [`load_metaimage`], `.tif` and `.tiff` with
/// [`load_tiff_stack`]; an OME-Zarr image (a Zarr group, usually `.zarr`) with
/// [`crate::ome_zarr::load_ome_zarr`] (`options.array` may name a label image); another folder, or a `.dcm` file meaning the series it belongs to, with
/// [`load_dicom_series`]. Every format's voxels
/// are placed in hatchery's RAS+ world (see [`crate::geometry`]).
pub fn load_volume_with(path: &Path, options: &LoadOptions) -> Result<VolumeData, DataError> {
    // The whole name, not `extension()`: `.nii.gz` has two parts.
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let zarr = crate::ome_zarr::group_of(path);
    if crate::ome_zarr::is_zarr(zarr) || name.ends_with(".zarr") {
        crate::ome_zarr::load_ome_zarr(path, options.array.as_deref())
    } else if path.is_dir() || name.ends_with(".dcm") {
        load_dicom_series(path)
    } else if name.ends_with(".nii") || name.ends_with(".nii.gz") {
        load_nifti(path)
    } else if name.ends_with(".mgz") || name.ends_with(".mgh") {
        crate::mgh_file::load_mgh(path)
    } else if name.ends_with(".vti") {
        load_vti(path, options.array.as_deref())
    } else if name.ends_with(".nrrd") || name.ends_with(".nhdr") {
        load_nrrd(path)
    } else if name.ends_with(".mha") || name.ends_with(".mhd") {
        load_metaimage(path)
    } else if name.ends_with(".tif") || name.ends_with(".tiff") {
        load_tiff_stack(path)
    } else if crate::dicom_series::is_dicom_file(path) {
        // A slice without an ending (IM000001 on export media): its series.
        load_dicom_series(path)
    } else {
        Err(DataError::unsupported(
            path,
            format!(
                "unknown volume file type, supported endings are {} (or a DICOM file, told by its \
                 content, or a folder of them)",
                VOLUME_ENDINGS.join(", ")
            ),
        ))
    }
}

/// A label map and the object names its file carries: an OME-Zarr label image's `image-label`
/// properties ([`crate::ome_zarr::load_label_image`]: `options.array` names the label image,
/// else the group's first), 3D Slicer's segment names in a `.seg.nrrd` header; none for other
/// formats. Errors: as [`load_volume_with`].
pub fn load_label_volume(
    path: &Path,
    options: &LoadOptions,
) -> Result<(VolumeData, std::collections::BTreeMap<u16, String>), DataError> {
    if crate::ome_zarr::is_zarr(crate::ome_zarr::group_of(path)) {
        return crate::ome_zarr::load_label_image(path, options.array.as_deref());
    }
    let volume = load_volume_with(path, options)?;
    let name = path.to_string_lossy().to_ascii_lowercase();
    let names = if name.ends_with(".nrrd") || name.ends_with(".nhdr") {
        crate::segmentation::nrrd_segment_names(path)?
    } else {
        Default::default()
    };
    Ok((volume, names))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn picks_the_loader_by_ending() {
        let dir = tempfile::tempdir().unwrap();
        let vti = dir.path().join("Small.VTI");
        std::fs::write(
            &vti,
            r#"<VTKFile type="ImageData" version="1.0">
<ImageData WholeExtent="0 1 0 1 0 1" Origin="0 0 0" Spacing="1 1 1"><Piece Extent="0 1 0 1 0 1">
<PointData><DataArray type="UInt8" Name="v" format="ascii">0 1 2 3 4 5 6 7</DataArray></PointData>
</Piece></ImageData></VTKFile>"#,
        )
        .unwrap();
        assert_eq!(load_volume(&vti).unwrap().value_range, [0.0, 7.0]);

        // The VTI bytes under NIfTI names go to the NIfTI loader, which refuses them.
        for name in ["a.nii", "a.NII.GZ", "a.Nii.gz"] {
            let path = dir.path().join(name);
            std::fs::copy(&vti, &path).unwrap();
            let e = load_volume(&path).unwrap_err().to_string();
            assert!(
                e.contains("NIfTI") || e.contains("gzip") || e.contains("truncated"),
                "{e}"
            );
        }

        for name in ["a.vti.gz", "nii", "a.gz", "a.nrrd.gz"] {
            let path = dir.path().join(name);
            let e = load_volume(&path).unwrap_err();
            assert!(matches!(e, DataError::Unsupported { .. }), "{name}: {e}");
            let e = e.to_string();
            assert!(e.starts_with(&path.display().to_string()), "{e}");
            assert!(e.contains(".nii, .nii.gz, .mgz, .mgh, .vti, .nrrd"), "{e}");
        }

        // A folder is a DICOM series (this one has none).
        let e = load_volume(dir.path()).unwrap_err().to_string();
        assert!(e.contains("no DICOM image files"), "{e}");
    }
}

//! FreeSurfer volumes: `.mgh`, and `.mgz` (the same, gzip-compressed). Read by hand: no Rust
//! crate reads them, and the format is a fixed big-endian header of a few fields.
//!
//! Layout (FreeSurfer's mghformat, as nibabel's `MGHHeader` reads it): version (int32, 1),
//! width, height, depth, frames, type, dof (int32), goodRASFlag (int16), then — valid when
//! goodRASFlag > 0 — the voxel sizes `delta[3]`, the direction cosines `Mdc` (x_r x_a x_s, y_r y_a
//! y_s, z_r z_a z_s: one row per voxel axis) and the world position `Pxyz_c` of the volume's centre
//! (float32); voxels start at byte 284, x fastest.

use std::io::{self, BufRead, BufReader, Read};
use std::path::Path;

use glam::{DMat3, DVec3};
use nifti::NiftiType;

use crate::geometry::Geometry;
use crate::nifti_file::{decode_voxels, stored_type_name, stream_error, truncated, voxel_count};
use crate::raw_voxels;
use crate::{DataError, VolumeData};

/// Where the voxels start.
const DATA_OFFSET: usize = 284;

/// Loads an MGH or MGZ volume (gzip detected from the content).
///
/// * Types: uint8, int16 and float32 kept; int32 becomes f32.
/// * The voxel → world transform is nibabel's `MGHImage.affine`: columns `Mdc[i] · delta[i]`, and
///   the centre `Pxyz_c` at voxel index `dims / 2` (FreeSurfer's convention, not `(dims − 1)/2`).
///   The world is FreeSurfer's scanner RAS, which is hatchery's RAS+. Without goodRASFlag the
///   header's geometry is not valid and FreeSurfer's default (1 mm coronal: x → −R, y → −S,
///   z → +A, centred at 0) is used, and `placement` says so.
/// * Of several frames only the first is read (noted in `placement`).
///
/// Errors: not an MGH file (version ≠ 1), dims under 2 or too many voxels, an unknown type,
/// truncated data.
pub fn load_mgh(path: &Path) -> Result<VolumeData, DataError> {
    let file = crate::files::open(path).map_err(|e| DataError::io(path, e))?;
    let file_len = crate::files::len_of(&file).map_err(|e| DataError::io(path, e))?;
    let mut buffered = BufReader::new(file);
    let gzip = buffered
        .fill_buf()
        .map_err(|e| DataError::io(path, e))?
        .starts_with(&[0x1f, 0x8b]);
    let mut source: Box<dyn Read> = if gzip {
        Box::new(flate2::bufread::MultiGzDecoder::new(buffered))
    } else {
        Box::new(buffered)
    };
    let mut head = [0u8; DATA_OFFSET];
    source
        .read_exact(&mut head)
        .map_err(|e| stream_error(path, gzip, e))?;
    let int = |o: usize| i32::from_be_bytes(head[o..o + 4].try_into().expect("4 bytes"));
    let float = |o: usize| f64::from(f32::from_be_bytes(head[o..o + 4].try_into().expect("4")));
    if int(0) != 1 {
        return Err(DataError::format(
            path,
            format!("not an MGH file (version {} where 1 is expected)", int(0)),
        ));
    }
    let dims_signed = [int(4), int(8), int(12)];
    let frames = int(16);
    if dims_signed.iter().any(|&d| d < 2) || frames < 1 {
        return Err(DataError::unsupported(
            path,
            format!(
                "only 3-D volumes with at least 2 voxels per axis are supported, dims are \
                 {dims_signed:?} with {frames} frame(s)"
            ),
        ));
    }
    let dims = dims_signed.map(|d| d as u32);
    let voxels = voxel_count(path, dims)?;
    let (datatype, size) = match int(20) {
        0 => (NiftiType::Uint8, 1),
        1 => (NiftiType::Int32, 4),
        3 => (NiftiType::Float32, 4),
        4 => (NiftiType::Int16, 2),
        other => {
            return Err(DataError::unsupported(
                path,
                format!(
                    "MGH voxel type {other} is not supported (0 uchar, 1 int, 3 float, 4 short are)"
                ),
            ));
        }
    };
    let good_ras = i16::from_be_bytes([head[28], head[29]]) > 0;
    let (geometry, mut placement) = if good_ras {
        let delta = [float(30), float(34), float(38)];
        let mdc: [DVec3; 3] = std::array::from_fn(|i| {
            DVec3::new(float(42 + 12 * i), float(46 + 12 * i), float(50 + 12 * i))
        });
        let centre = DVec3::new(float(78), float(82), float(86));
        (
            geometry_of(path, dims, delta, mdc, centre)?,
            "MGH vox2ras (Mdc, delta, c_ras)".to_string(),
        )
    } else {
        let mdc = [DVec3::NEG_X, DVec3::NEG_Z, DVec3::Y];
        (
            geometry_of(path, dims, [1.0; 3], mdc, DVec3::ZERO)?,
            "goodRASFlag 0: FreeSurfer's default 1 mm coronal orientation".to_string(),
        )
    };
    if frames > 1 {
        placement += &format!("; the first of {frames} frames");
    }

    let byte_count = voxels as usize * size;
    let available = if gzip {
        raw_voxels::decoded_bound(file_len, true)
    } else {
        file_len.saturating_sub(DATA_OFFSET as u64)
    };
    let room = usize::try_from(available).map_or(byte_count, |a| a.min(byte_count));
    let mut raw = Vec::new();
    raw.try_reserve_exact(room)
        .map_err(|_| DataError::format(path, format!("cannot allocate {room} bytes")))?;
    (&mut source)
        .take(byte_count as u64)
        .read_to_end(&mut raw)
        .map_err(|e: io::Error| stream_error(path, gzip, e))?;
    if raw.len() < byte_count {
        return Err(truncated(path, gzip));
    }
    let voxels = decode_voxels(datatype, raw, true, 0.0, 0.0);
    let mut volume =
        VolumeData::from_voxels(dims, geometry, voxels).map_err(|e| e.in_file(path))?;
    volume.stored_type = stored_type_name(datatype);
    volume.placement = placement;
    Ok(volume)
}

/// nibabel's MGH affine: `A = Mdcᵀ · diag(delta)` (column i is voxel axis i's direction times
/// its size) and the origin `Pxyz_c − A · dims / 2`.
fn geometry_of(
    path: &Path,
    dims: [u32; 3],
    delta: [f64; 3],
    mdc: [DVec3; 3],
    centre: DVec3,
) -> Result<Geometry, DataError> {
    let a = DMat3::from_cols(mdc[0] * delta[0], mdc[1] * delta[1], mdc[2] * delta[2]);
    let origin = centre - a * DVec3::from_array(dims.map(f64::from)) / 2.0;
    let rows: [[f64; 4]; 3] =
        std::array::from_fn(|r| [a.col(0)[r], a.col(1)[r], a.col(2)[r], origin[r]]);
    Geometry::from_affine(rows).map_err(|e| DataError::format(path, format!("bad vox2ras: {e}")))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An MGH file: `dims`, `kind`, goodRASFlag, then `data` bytes.
    fn mgh(dims: [i32; 3], kind: i32, good_ras: i16, version: i32, data: &[u8]) -> Vec<u8> {
        let mut b = Vec::new();
        for v in [version, dims[0], dims[1], dims[2], 1, kind, 0] {
            b.extend_from_slice(&v.to_be_bytes());
        }
        b.extend_from_slice(&good_ras.to_be_bytes());
        let floats = [
            2.0f32, 2.0, 2.0, 1., 0., 0., 0., 1., 0., 0., 0., 1., 5., 6., 7.,
        ];
        for f in floats {
            b.extend_from_slice(&f.to_be_bytes());
        }
        b.resize(DATA_OFFSET, 0);
        b.extend_from_slice(data);
        b
    }

    fn load(bytes: &[u8]) -> Result<VolumeData, String> {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("v.mgh");
        std::fs::write(&path, bytes).unwrap();
        load_mgh(&path).map_err(|e| e.to_string())
    }

    #[test]
    fn geometry_types_and_errors() {
        let shorts: Vec<u8> = (0..8i16).flat_map(|v| (v * 100).to_be_bytes()).collect();
        let v = load(&mgh([2, 2, 2], 4, 1, 1, &shorts)).unwrap();
        assert_eq!(v.stored_type, "int16");
        assert_eq!(v.value(1, 1, 1), 700.0);
        // Identity directions, 2 mm voxels, c_ras (5, 6, 7) at voxel dims / 2 = (1, 1, 1).
        assert_eq!(
            v.voxel_to_world(glam::Vec3::ONE),
            glam::Vec3::new(5.0, 6.0, 7.0)
        );
        let v = load(&mgh([2, 2, 2], 0, 0, 1, &[0; 8])).unwrap();
        assert!(v.placement.contains("goodRASFlag 0"), "{}", v.placement);
        let e = load(&mgh([2, 2, 2], 4, 1, 1, &shorts[..10])).unwrap_err();
        assert!(e.contains("truncated"), "{e}");
        let e = load(&mgh([2, 2, 2], 4, 1, 2, &shorts)).unwrap_err();
        assert!(e.contains("not an MGH file (version 2"), "{e}");
        let e = load(&mgh([2, 2, 2], 6, 1, 1, &shorts)).unwrap_err();
        assert!(e.contains("MGH voxel type 6 is not supported"), "{e}");
        let e = load(&mgh([2, 1, 2], 0, 1, 1, &[0; 4])).unwrap_err();
        assert!(e.contains("at least 2 voxels per axis"), "{e}");
    }
}

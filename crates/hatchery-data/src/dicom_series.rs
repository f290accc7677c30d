//! DICOM series: a folder of single-frame slices (CT, MR, PET, ...) read as one volume.
//!
//! The slices are ordered by where they are, never by file name or InstanceNumber: positions
//! (ImagePositionPatient) are projected on the slice normal (row cosines × column cosines of
//! ImageOrientationPatient) and sorted along it, as ITK/GDCM do. DICOM states positions in LPS+;
//! they are turned into hatchery's RAS+ world by [`Geometry::from_lps`].
//!
//! Native pixel data is decoded here from its bytes; compressed pixel data by the transfer
//! syntax's codec (8-bit JPEG baseline/extended, JPEG lossless, JPEG 2000, RLE Lossless; see
//! `compressed`) or, for JPEG-LS, by `jpeg_ls`; other compressed syntaxes (12-bit JPEG, MPEG video,
//! ...) are refused by name.
//!
//! Over 600 lines: reading a series is one procedure (grouping, ordering by position, spacing and
//! orientation checks, rescale, the refusals that name the slice) whose steps share the slice
//! records.

use std::collections::BTreeMap;
use std::error::Error;
use std::fs::File;
use std::io::Read;
use std::path::{Path, PathBuf};

use dicom_core::VR;
use dicom_core::dictionary::DataDictionary;
use dicom_core::value::PrimitiveValue;
use dicom_dictionary_std::{StandardDataDictionary, tags};
use dicom_object::file::ReadPreamble;
use dicom_object::{DefaultDicomObject, OpenFileOptions, Tag};
use glam::{DMat3, DVec3};

use self::pixels::{PixelFormat, append, pixel_format, read_pixels, with_capacity};

use crate::geometry::Geometry;
use crate::nifti_file::voxel_count;
use crate::voxels::Voxels;
use crate::{DataError, VolumeData};

mod compressed;
mod jpeg_ls;
mod lengths;
mod pixels;

/// Slices may deviate this much (as a fraction of the slice spacing) from a uniform stack along
/// the normal, both in their step and sideways. Scanners round positions to ~0.001 mm, far
/// below this; a missing slice (a 100 % step error) or a gantry tilt of a degree is far above.
const STACK_TOLERANCE: f64 = 0.02;
/// ... and at least this much, in mm, for very thin slices.
const STACK_TOLERANCE_MM: f64 = 0.02;
/// Orientation cosines and pixel spacings of the slices of one series must agree this closely.
const SAME_TOLERANCE: f64 = 1e-4;

/// Reads a DICOM series into one volume.
///
/// `path` is either a folder, or one DICOM file of the series (then the other slices of that
/// file's SeriesInstanceUID are read from its folder). Sub-folders are not searched.
///
/// * **Files**: every regular file with the `DICM` marker at byte 128 is read as DICOM (others,
///   e.g. `.txt`, are skipped); those without an image (no Rows, e.g. DICOMDIR, reports) and
///   those with the marker that do not parse (a truncated file of another series) are skipped,
///   with one warning line naming them ([`VolumeData::warnings`]). A slice of the series that is
///   missing shows as a gap in the positions (below), never silently.
/// * **Series**: files are grouped by SeriesInstanceUID. For a folder with several series the
///   one with the most slices is read and the others are named in `placement`; a tie is an
///   error listing the series (pass one of its files to choose).
/// * **Order and geometry**: slices are sorted by the projection of ImagePositionPatient on the
///   normal n = row × column cosines. Voxel (0, 0, 0) is the first pixel of the first slice; i
///   follows the row cosines (ImageOrientationPatient[0..3]) with spacing PixelSpacing[1], j the
///   column cosines ([3..6]) with spacing PixelSpacing[0], k follows n with the mean distance
///   between slices. Units: mm, world RAS+ (DICOM's LPS with x and y negated).
/// * **Uneven spacing** (a gap, missing slices): the slices are resampled to the median step
///   along the normal, each new slice interpolated linearly between the two around it (as
///   Slicer regularises an acquisition geometry; ITK would use one spacing for all), float32,
///   with a one-line warning naming the widest gap.
/// * **Voxels**: one sample per pixel (MONOCHROME1/2), BitsAllocated 8, 16 or 32, signed or
///   unsigned, BitsStored <= BitsAllocated (HighBit = BitsStored − 1). 8- and 16-bit values stay
///   in their type unless rescaled; 32-bit ones become float32. RescaleSlope/RescaleIntercept
///   are applied (float32 result); they may differ between slices.
///   MONOCHROME1 values are kept as stored (not inverted), as ITK does.
/// * **Transfer syntaxes**: implicit VR little endian, explicit VR little and big endian,
///   deflated explicit VR little endian; 8-bit JPEG baseline/extended, JPEG lossless (2–16
///   bits), RLE Lossless (each slice's stream checked against its Rows, Columns and
///   BitsAllocated before decoding).
///
/// Errors (a [`DataError`] naming the folder or the offending file): no DICOM image in the
/// folder; fewer than 2 slices, or fewer than 2 rows or columns; a missing or malformed
/// geometry attribute; slices that disagree in size, orientation, spacing or pixel format;
/// two slices at one position (several echoes or time points in one series: steps under 2 % of
/// the median step); slices not stacked along their normal (gantry tilt);
/// other compressed pixel data (named by its transfer syntax); colour or palette images; multi-frame
/// files; more than [`crate::nifti_file::MAX_VOXELS`] voxels; truncated pixel data.
pub fn load_dicom_series(path: &Path) -> Result<VolumeData, DataError> {
    let (folder, wanted) = if path.is_dir() {
        (path.to_path_buf(), None)
    } else {
        let folder = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let header = read_header(path)?
            .ok_or_else(|| DataError::format(path, "not a DICOM file (no DICM marker)"))?;
        if header.element_opt(tags::ROWS).ok().flatten().is_none() {
            return Err(DataError::unsupported(path, "DICOM file without an image"));
        }
        (folder, Some(text(&header, tags::SERIES_INSTANCE_UID)))
    };

    let (series, skipped) = find_series(&folder)?;
    let (uid, files, note) = choose_series(&folder, series, wanted)?;
    let stack = Stack::new(&folder, &files)?;
    let voxels = stack.read_voxels()?;
    let dims = [stack.columns, stack.rows, stack.output_slices() as u32];
    let mut volume =
        VolumeData::from_voxels(dims, stack.geometry, voxels).map_err(|e| e.in_file(&folder))?;
    volume.placement = format!(
        "DICOM ImagePositionPatient/ImageOrientationPatient (LPS), {} slices, series {uid}{}{}{note}",
        stack.slices.len(),
        stack.rescale_note(),
        if stack.resample.is_some() {
            ", resampled to uniform spacing"
        } else {
            ""
        }
    );
    volume.warnings.extend(stack.resample.clone());
    volume.warnings.extend(skipped.warning());
    Ok(volume)
}

/// The image files of each series in `folder`, by SeriesInstanceUID, in file-name order, and
/// what was skipped: files with the DICM marker that do not parse (a truncated file of another
/// series, say) by name with the reason, and how many DICOM objects hold no image (DICOMDIR,
/// reports).
fn find_series(folder: &Path) -> Result<(BTreeMap<String, Vec<Header>>, Skipped), DataError> {
    let entries = std::fs::read_dir(folder).map_err(|e| DataError::io(folder, e))?;
    let mut paths = Vec::new();
    for entry in entries {
        let path = entry.map_err(|e| DataError::io(folder, e))?.path();
        // Follows links; a dangling link or a sub-folder is not a slice.
        if path.is_file() {
            paths.push(path);
        }
    }
    paths.sort();
    let looked_at = paths.len();
    let mut series: BTreeMap<String, Vec<Header>> = BTreeMap::new();
    let mut skipped = Skipped::default();
    for path in paths {
        let object = match read_header(&path) {
            Ok(Some(object)) => object,
            Ok(None) => continue,
            Err(e) => {
                skipped.unreadable.push((file_name(&path), e.to_string()));
                continue;
            }
        };
        if object.element_opt(tags::ROWS).ok().flatten().is_none() {
            skipped.without_image += 1;
            continue;
        }
        let uid = text(&object, tags::SERIES_INSTANCE_UID);
        series.entry(uid).or_default().push(Header { path, object });
    }
    if series.is_empty() {
        let why = match skipped.unreadable.first() {
            Some((_, reason)) => format!(
                "; {} DICOM file(s) could not be read, e.g. {reason}",
                skipped.unreadable.len()
            ),
            None => String::new(),
        };
        return Err(DataError::format(
            folder,
            format!("no DICOM image files in this folder (files looked at: {looked_at}){why}"),
        ));
    }
    Ok((series, skipped))
}

/// Files of a folder that are not read as slices.
#[derive(Default)]
struct Skipped {
    /// (file name, why) of files with the DICM marker that do not parse.
    unreadable: Vec<(String, String)>,
    /// DICOM objects without an image.
    without_image: usize,
}

impl Skipped {
    /// One warning line, or None when nothing but non-DICOM files was skipped.
    fn warning(&self) -> Option<String> {
        if self.unreadable.is_empty() && self.without_image == 0 {
            return None;
        }
        let mut parts = Vec::new();
        if !self.unreadable.is_empty() {
            let names: Vec<&str> = self.unreadable.iter().map(|(n, _)| n.as_str()).collect();
            let why = &self.unreadable[0].1;
            parts.push(format!(
                "{} unreadable ({}; {})",
                self.unreadable.len(),
                names.join(", "),
                why.rsplit(": ").next().unwrap_or(why)
            ));
        }
        if self.without_image > 0 {
            parts.push(format!(
                "{} without an image (DICOMDIR, reports, …)",
                self.without_image
            ));
        }
        Some(format!(
            "skipped {} DICOM file(s) that are not slices of this series: {}",
            self.unreadable.len() + self.without_image,
            parts.join(", ")
        ))
    }
}

/// The series to read: `wanted`, else the one with the most slices. Also returns a note for
/// `placement` naming the series left out.
fn choose_series(
    folder: &Path,
    mut series: BTreeMap<String, Vec<Header>>,
    wanted: Option<String>,
) -> Result<(String, Vec<Header>, String), DataError> {
    let listing = |series: &BTreeMap<String, Vec<Header>>, skip: &str| {
        let others: Vec<String> = series
            .iter()
            .filter(|(uid, _)| uid.as_str() != skip)
            .map(|(uid, files)| format!("{uid} ({} files)", files.len()))
            .collect();
        others.join(", ")
    };
    let uid = match wanted {
        Some(uid) => uid,
        None => {
            let most = series.values().map(Vec::len).max().unwrap_or(0);
            let biggest: Vec<&String> = series
                .iter()
                .filter(|(_, f)| f.len() == most)
                .map(|(u, _)| u)
                .collect();
            if biggest.len() > 1 {
                return Err(DataError::format(
                    folder,
                    format!(
                        "{} series with {most} files each, load one of their files to choose: {}",
                        biggest.len(),
                        listing(&series, "")
                    ),
                ));
            }
            biggest[0].clone()
        }
    };
    let note = if series.len() > 1 {
        format!(" (the folder also holds {})", listing(&series, &uid))
    } else {
        String::new()
    };
    match series.remove(&uid) {
        Some(files) if !files.is_empty() => Ok((uid, files, note)),
        // The file named by the caller vanished from the folder in between.
        _ => Err(DataError::format(
            folder,
            format!("no image files of series {uid} in this folder"),
        )),
    }
}

/// A DICOM file's attributes before the pixel data.
struct Header {
    path: PathBuf,
    object: DefaultDicomObject,
}

/// Whether `path` is a DICOM file by its content: the `DICM` marker at byte 128 (files on
/// export media often have no ending: `IM000001`).
pub fn is_dicom_file(path: &Path) -> bool {
    let mut head = [0u8; 132];
    File::open(path)
        .and_then(|mut f| f.read_exact(&mut head))
        .is_ok()
        && &head[128..] == b"DICM"
}

/// Reads the attributes of a DICOM file up to its pixel data; `None` for files without the
/// `DICM` marker (not DICOM files).
fn read_header(path: &Path) -> Result<Option<DefaultDicomObject>, DataError> {
    let mut head = [0u8; 132];
    let mut file = File::open(path).map_err(|e| DataError::io(path, e))?;
    let mut filled = 0;
    while filled < head.len() {
        match file.read(&mut head[filled..]) {
            Ok(0) => break,
            Ok(n) => filled += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(DataError::io(path, e)),
        }
    }
    if filled < head.len() || &head[128..] != b"DICM" {
        return Ok(None);
    }
    parse(path, true).map(Some)
}

/// Reads a whole DICOM file, pixel data included (after [`read_header`] checked it).
fn open_whole(path: &Path) -> Result<DefaultDicomObject, DataError> {
    parse(path, false)
}

/// Parses a DICOM file (up to its pixel data if `header_only`) after checking its lengths;
/// undefined-length UN elements, which dicom-parser would read in the wrong VR encoding, are
/// left out of the bytes it parses (see `lengths`).
fn parse(path: &Path, header_only: bool) -> Result<DefaultDicomObject, DataError> {
    let cuts = lengths::check_lengths(path)?;
    let options = if header_only {
        OpenFileOptions::new().read_until(tags::PIXEL_DATA)
    } else {
        OpenFileOptions::new()
    };
    let parsed = if cuts.is_empty() {
        options.open_file(path)
    } else {
        let bytes = std::fs::read(path).map_err(|e| DataError::io(path, e))?;
        let mut kept = Vec::with_capacity(bytes.len());
        let mut from = 0;
        for cut in &cuts {
            // The walk's positions lie in the file, in ascending order.
            kept.extend_from_slice(&bytes[from..cut.start as usize]);
            from = cut.end as usize;
        }
        kept.extend_from_slice(&bytes[from..]);
        options
            .read_preamble(ReadPreamble::Always)
            .from_reader(kept.as_slice())
    };
    parsed.map_err(|e| DataError::format(path, format!("unreadable DICOM file: {}", chain(&e))))
}

/// An error and its causes on one line (dicom-rs errors say the most in their sources).
fn chain(e: &dyn Error) -> String {
    let mut out = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        out.push_str(": ");
        out.push_str(&s.to_string());
        source = s.source();
    }
    out
}

/// An attribute's value. An element stored with VR UN (what some tools write for attributes
/// whose VR they lost, e.g. GDCM converting implicit-VR files) is read by its dictionary VR, as
/// pydicom and GDCM do: binary numbers little-endian, other VRs as text.
fn value(object: &DefaultDicomObject, tag: Tag) -> Option<PrimitiveValue> {
    let element = object.element_opt(tag).ok().flatten()?;
    let value = element.value().primitive()?;
    if element.vr() != VR::UN {
        return Some(value.clone());
    }
    let bytes = value.to_bytes();
    let vr = StandardDataDictionary.by_tag(tag)?.vr.relaxed();
    macro_rules! binary {
        ($variant:ident, $t:ty) => {{
            const N: usize = std::mem::size_of::<$t>();
            PrimitiveValue::$variant(
                bytes
                    .chunks_exact(N)
                    .map(|c| <$t>::from_le_bytes(c.try_into().expect("N bytes")))
                    .collect(),
            )
        }};
    }
    Some(match vr {
        VR::US => binary!(U16, u16),
        VR::SS => binary!(I16, i16),
        VR::UL => binary!(U32, u32),
        VR::SL => binary!(I32, i32),
        VR::FL => binary!(F32, f32),
        VR::FD => binary!(F64, f64),
        _ => PrimitiveValue::Strs(
            String::from_utf8_lossy(&bytes)
                .split('\\')
                .map(|part| {
                    part.trim_matches(|c: char| c == '\0' || c == ' ')
                        .to_string()
                })
                .collect(),
        ),
    })
}

/// A string attribute, trimmed of spaces and of the NUL that pads UIDs to an even length; empty
/// when absent or not text.
fn text(object: &DefaultDicomObject, tag: Tag) -> String {
    value(object, tag)
        .map(|v| {
            v.to_str()
                .trim_matches(|c: char| c.is_whitespace() || c == '\0')
                .to_string()
        })
        .unwrap_or_default()
}

/// Numeric attribute values (DS, IS, US, ...); `None` when absent.
fn numbers(header: &Header, tag: Tag, name: &str) -> Result<Option<Vec<f64>>, DataError> {
    let Some(value) = value(&header.object, tag) else {
        return Ok(None);
    };
    let values = value
        .to_multi_float64()
        .map_err(|e| DataError::format(&header.path, format!("bad {name}: {}", chain(&e))))?;
    if values.iter().any(|v| !v.is_finite()) {
        return Err(DataError::format(
            &header.path,
            format!("{name} is not finite: {values:?}"),
        ));
    }
    Ok(Some(values))
}

/// Exactly `N` numbers of a required attribute.
fn required<const N: usize>(header: &Header, tag: Tag, name: &str) -> Result<[f64; N], DataError> {
    let values = numbers(header, tag, name)?
        .ok_or_else(|| DataError::format(&header.path, format!("missing {name}")))?;
    values.try_into().map_err(|v: Vec<f64>| {
        DataError::format(
            &header.path,
            format!("{name} has {} values, expected {N}", v.len()),
        )
    })
}

/// One number of an optional attribute, or `default`.
fn optional(header: &Header, tag: Tag, name: &str, default: f64) -> Result<f64, DataError> {
    Ok(match numbers(header, tag, name)? {
        Some(v) if !v.is_empty() => v[0],
        _ => default,
    })
}

/// One slice of the stack, with what its header says.
struct Slice {
    path: PathBuf,
    position: DVec3,
    /// Projection of the position on the slice normal (mm).
    along_normal: f64,
    slope: f64,
    intercept: f64,
    transfer_syntax: String,
}

/// The slices of a series, checked to form a regular grid, in order along the normal.
struct Stack {
    slices: Vec<Slice>,
    rows: u32,
    columns: u32,
    format: PixelFormat,
    geometry: Geometry,
    /// The slice spacing of the volume (mm).
    spacing: f64,
    /// When the slices are not evenly spaced: the warning saying they were resampled.
    resample: Option<String>,
}

impl Stack {
    /// Reads and checks the geometry and pixel format of every slice, and orders them.
    fn new(folder: &Path, files: &[Header]) -> Result<Self, DataError> {
        let first = &files[0];
        // The pixel format first: it refuses multi-frame and colour files by name, which would
        // otherwise fail on a missing attribute below.
        let format = pixel_format(first)?;
        let rows = required::<1>(first, tags::ROWS, "Rows")?[0];
        let columns = required::<1>(first, tags::COLUMNS, "Columns")?[0];
        let iop = required::<6>(
            first,
            tags::IMAGE_ORIENTATION_PATIENT,
            "ImageOrientationPatient",
        )?;
        let pixel_spacing = required::<2>(first, tags::PIXEL_SPACING, "PixelSpacing")?;
        if pixel_spacing.iter().any(|&s| s <= 0.0) {
            return Err(DataError::format(
                &first.path,
                format!("PixelSpacing must be positive, got {pixel_spacing:?}"),
            ));
        }
        let (row_dir, col_dir) = (DVec3::from_slice(&iop[..3]), DVec3::from_slice(&iop[3..]));
        if row_dir.length() < 0.5 || col_dir.length() < 0.5 {
            return Err(DataError::format(
                &first.path,
                format!("ImageOrientationPatient has a zero direction: {iop:?}"),
            ));
        }
        let (row_dir, col_dir) = (row_dir.normalize(), col_dir.normalize());
        if row_dir.dot(col_dir).abs() > 0.01 {
            return Err(DataError::format(
                &first.path,
                format!("ImageOrientationPatient rows and columns are not perpendicular: {iop:?}"),
            ));
        }
        let normal = row_dir.cross(col_dir).normalize();

        voxel_count(folder, [columns as u32, rows as u32, files.len() as u32])?;

        let mut slices = Vec::with_capacity(files.len());
        for header in files {
            let same = |a: &[f64], b: &[f64]| {
                a.iter()
                    .zip(b)
                    .all(|(x, y)| (x - y).abs() <= SAME_TOLERANCE * y.abs().max(1.0))
            };
            let mismatch = |what: &str, here: String, there: String| {
                DataError::format(
                    &header.path,
                    format!(
                        "{what} {here} differs from {there} in {} of the same series",
                        file_name(&first.path)
                    ),
                )
            };
            let size = [
                required::<1>(header, tags::ROWS, "Rows")?[0],
                required::<1>(header, tags::COLUMNS, "Columns")?[0],
            ];
            if size != [rows, columns] {
                return Err(mismatch(
                    "image size",
                    format!("{size:?}"),
                    format!("{:?}", [rows, columns]),
                ));
            }
            let here = required::<6>(
                header,
                tags::IMAGE_ORIENTATION_PATIENT,
                "ImageOrientationPatient",
            )?;
            if !same(&here, &iop) {
                return Err(mismatch(
                    "ImageOrientationPatient",
                    format!("{here:?}"),
                    format!("{iop:?}"),
                ));
            }
            let here = required::<2>(header, tags::PIXEL_SPACING, "PixelSpacing")?;
            if !same(&here, &pixel_spacing) {
                return Err(mismatch(
                    "PixelSpacing",
                    format!("{here:?}"),
                    format!("{pixel_spacing:?}"),
                ));
            }
            let here = pixel_format(header)?;
            if here != format {
                return Err(mismatch("pixel format", here.describe(), format.describe()));
            }
            let position = DVec3::from_array(required::<3>(
                header,
                tags::IMAGE_POSITION_PATIENT,
                "ImagePositionPatient",
            )?);
            let slope = optional(header, tags::RESCALE_SLOPE, "RescaleSlope", 1.0)?;
            let intercept = optional(header, tags::RESCALE_INTERCEPT, "RescaleIntercept", 0.0)?;
            slices.push(Slice {
                path: header.path.clone(),
                position,
                along_normal: position.dot(normal),
                // A zero slope would erase the image; like NIfTI's scl_slope, it means "none".
                slope: if slope == 0.0 { 1.0 } else { slope },
                intercept,
                transfer_syntax: header.object.meta().transfer_syntax().to_string(),
            });
        }
        if slices.len() < 2 {
            return Err(DataError::unsupported(
                &slices[0].path,
                "the series has a single slice, a volume needs at least 2",
            ));
        }
        slices.sort_by(|a, b| a.along_normal.total_cmp(&b.along_normal));
        let (slice_spacing, resample) = check_stack(folder, &slices, normal)?;

        let geometry = Geometry::from_lps(
            // PixelSpacing is (between rows, between columns): j first, then i.
            [pixel_spacing[1], pixel_spacing[0], slice_spacing],
            DMat3::from_cols(row_dir, col_dir, normal),
            slices[0].position.to_array(),
        );
        let stack = Stack {
            slices,
            rows: rows as u32,
            columns: columns as u32,
            format,
            geometry,
            spacing: slice_spacing,
            resample,
        };
        // A wide gap resamples to many slices.
        voxel_count(
            folder,
            [stack.columns, stack.rows, stack.output_slices() as u32],
        )?;
        Ok(stack)
    }

    /// Slices of the volume: the files', or the resampled count (checked against MAX_VOXELS
    /// in [`Stack::new`]).
    fn output_slices(&self) -> usize {
        match self.resample {
            None => self.slices.len(),
            Some(_) => {
                let first = self.slices[0].along_normal;
                let last = self.slices[self.slices.len() - 1].along_normal;
                ((last - first) / self.spacing).round() as usize + 1
            }
        }
    }

    /// The voxels of all slices in order, rescaled; resampled along the normal when the slices
    /// are unevenly spaced.
    fn read_voxels(&self) -> Result<Voxels, DataError> {
        if self.resample.is_some() {
            return self.read_resampled();
        }
        let per_slice = self.rows as usize * self.columns as usize;
        let total = per_slice * self.slices.len();
        let uniform_rescale = self
            .slices
            .iter()
            .all(|s| s.slope == self.slices[0].slope && s.intercept == self.slices[0].intercept);
        let mut out: Option<Voxels> = None;
        for slice in &self.slices {
            let mut voxels = read_pixels(
                &slice.path,
                &slice.transfer_syntax,
                [self.rows, self.columns],
                self.format,
            )?;
            if !uniform_rescale {
                voxels = Voxels::F32(voxels.rescaled(slice.slope, slice.intercept).into_f32());
            }
            match &mut out {
                None => {
                    out = Some(
                        with_capacity(voxels, total)
                            .map_err(|m| DataError::format(&slice.path, m))?,
                    )
                }
                Some(all) => append(all, voxels),
            }
        }
        let out = out.unwrap_or(Voxels::F32(Vec::new()));
        let first = &self.slices[0];
        Ok(if uniform_rescale {
            out.rescaled(first.slope, first.intercept)
        } else {
            out
        })
    }

    /// Uneven slices resampled to `spacing` along the normal: each output slice is the linear
    /// interpolation of the two file slices around its position (what Slicer's regularisation
    /// of the acquisition geometry does), float32.
    fn read_resampled(&self) -> Result<Voxels, DataError> {
        let per_slice = self.rows as usize * self.columns as usize;
        let mut files = Vec::with_capacity(self.slices.len());
        for slice in &self.slices {
            let voxels = read_pixels(
                &slice.path,
                &slice.transfer_syntax,
                [self.rows, self.columns],
                self.format,
            )?;
            files.push(voxels.rescaled(slice.slope, slice.intercept).into_f32());
        }
        let first = self.slices[0].along_normal;
        let count = self.output_slices();
        let mut out = Vec::new();
        out.try_reserve_exact(per_slice * count).map_err(|_| {
            DataError::format(&self.slices[0].path, "cannot allocate the resampled volume")
        })?;
        let mut below = 0;
        for k in 0..count {
            let at = first + k as f64 * self.spacing;
            while below + 2 < self.slices.len() && self.slices[below + 1].along_normal <= at {
                below += 1;
            }
            let (a, b) = (&self.slices[below], &self.slices[below + 1]);
            let t = ((at - a.along_normal) / (b.along_normal - a.along_normal)).clamp(0.0, 1.0);
            let (va, vb) = (&files[below], &files[below + 1]);
            out.extend(
                va.iter()
                    .zip(vb)
                    .map(|(x, y)| (*x as f64 * (1.0 - t) + *y as f64 * t) as f32),
            );
        }
        Ok(Voxels::F32(out))
    }

    /// What `placement` says about rescaling.
    fn rescale_note(&self) -> String {
        let first = &self.slices[0];
        if self
            .slices
            .iter()
            .any(|s| s.slope != first.slope || s.intercept != first.intercept)
        {
            ", RescaleSlope/Intercept per slice".into()
        } else if first.slope != 1.0 || first.intercept != 0.0 {
            format!(", rescaled × {} + {}", first.slope, first.intercept)
        } else {
            String::new()
        }
    }
}

/// Checks the sorted slices along `normal`: no two at one position (measured against the median
/// spacing, which a gap does not inflate), all on the line through the first (no gantry tilt).
/// Returns the slice spacing in mm — the mean of even steps, else the median — and, when the
/// steps are uneven (a gap, missing slices), the warning that the volume is resampled.
fn check_stack(
    folder: &Path,
    slices: &[Slice],
    normal: DVec3,
) -> Result<(f64, Option<String>), DataError> {
    let n = slices.len();
    let steps: Vec<f64> = slices
        .windows(2)
        .map(|p| p[1].along_normal - p[0].along_normal)
        .collect();
    let mut sorted = steps.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    let tolerance = (median * STACK_TOLERANCE).max(STACK_TOLERANCE_MM);
    // Duplicates first: they also make the spacing look non-uniform, which would mislead.
    for (pair, step) in slices.windows(2).zip(&steps) {
        if *step < tolerance {
            return Err(DataError::unsupported(
                folder,
                format!(
                    "{} and {} lie at the same position ({step:.4} mm apart along the normal, \
                     the median step is {median:.4} mm); series with several echoes, phases or \
                     time points are not supported",
                    file_name(&pair[0].path),
                    file_name(&pair[1].path)
                ),
            ));
        }
    }
    for slice in &slices[1..] {
        let offset = slice.position - slices[0].position;
        let sideways = (offset - offset.dot(normal) * normal).length();
        if sideways > tolerance {
            return Err(DataError::unsupported(
                folder,
                format!(
                    "slices are not stacked along their normal ({} is {sideways:.4} mm off the \
                     line through {}): gantry tilt or sheared stacks are not supported",
                    file_name(&slice.path),
                    file_name(&slices[0].path)
                ),
            ));
        }
    }
    let uneven: Vec<usize> = (0..steps.len())
        .filter(|&i| (steps[i] - median).abs() > tolerance)
        .collect();
    let Some(&widest) = uneven
        .iter()
        .max_by(|&&a, &&b| steps[a].total_cmp(&steps[b]))
    else {
        let mean = (slices[n - 1].along_normal - slices[0].along_normal) / (n - 1) as f64;
        return Ok((mean, None));
    };
    let count =
        ((slices[n - 1].along_normal - slices[0].along_normal) / median).round() as usize + 1;
    let others = if uneven.len() > 1 {
        format!(" ({} uneven steps in all)", uneven.len())
    } else {
        String::new()
    };
    Ok((
        median,
        Some(format!(
            "slice spacing is not uniform: {} to {} is {:.4} mm where the median step is \
             {median:.4} mm{others}; resampled to {count} slices {median:.4} mm apart along the \
             normal (linear between neighbouring slices)",
            file_name(&slices[widest].path),
            file_name(&slices[widest + 1].path),
            steps[widest]
        )),
    ))
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

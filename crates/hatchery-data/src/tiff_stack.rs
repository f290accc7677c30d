//! Multi-page TIFF stacks (`.tif`, `.tiff`): one page per slice, as ImageJ/Fiji and tifffile
//! write them. Decoded with the `tiff` crate.

use std::io::BufReader;
use std::path::Path;

use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::Tag;
use tiff::{ColorType, TiffError};

use crate::geometry::Geometry;
use crate::raw_voxels;
use crate::voxels::Voxels;
use crate::{DataError, VolumeData};

/// Loads a multi-page grayscale TIFF as a volume: page `k` is slice `k`, its rows go along j
/// (top row first) and its columns along i.
///
/// * Every page must have the same size and sample type: 8- or 16-bit integers (unsigned or
///   signed) or 32-bit floats, one sample per pixel. Colour, palette, multi-sample and other
///   sample types are refused; so are ImageJ hyperstacks with several channels or frames.
/// * Spacing: x and y from `XResolution`/`YResolution` (pixels per unit), z from an ImageJ
///   description's `spacing=`, each 1 where missing. The ImageJ `unit=` (mm, cm, m, micron/µm,
///   nm, inch) converts them to mm; without a known unit they are taken as given. Without an
///   ImageJ description a centimetre `ResolutionUnit` is converted to mm, and an inch one (the
///   TIFF default, a print resolution such as 72 dpi, not a voxel size) is ignored.
/// * Geometry: axis-aligned with the origin at 0. A TIFF stack has no anatomical frame: i, j, k
///   are taken as hatchery's x, y, z as they are. [`VolumeData::placement`] says what was used.
///
/// Errors: [`DataError::Format`] for a corrupt file, pages of different sizes or pages larger
/// than the file could hold at the best compression ratio,
/// [`DataError::Unsupported`] for the refused kinds of image above, [`DataError::TooLarge`]
/// above [`crate::nifti_file::MAX_VOXELS`] voxels (checked on the page headers, before any
/// pixel is decoded), [`DataError::Io`] when the file cannot be read.
pub fn load_tiff_stack(path: &Path) -> Result<VolumeData, DataError> {
    let file = crate::files::open(path).map_err(|e| DataError::io(path, e))?;
    let file_len = crate::files::len_of(&file).map_err(|e| DataError::io(path, e))?;
    let terr = |e: TiffError| tiff_error(path, e);
    let mut decoder = Decoder::new(BufReader::new(file))
        .map_err(terr)?
        .with_limits(file_limits(file_len));

    let (width, height) = decoder.dimensions().map_err(terr)?;
    let colour = decoder.colortype().map_err(terr)?;
    if !matches!(colour, ColorType::Gray(8 | 16 | 32)) {
        return Err(DataError::unsupported(
            path,
            format!(
                "pages are {colour:?}; only one-sample grayscale pages (8-, 16-bit or 32-bit \
                 float) are read"
            ),
        ));
    }
    let description = match decoder.find_tag(Tag::ImageDescription).map_err(terr)? {
        Some(v) => v.into_string().unwrap_or_default(),
        None => String::new(),
    };
    let imagej = ImageJ::parse(&description);
    for (what, n) in [("channels", imagej.channels), ("frames", imagej.frames)] {
        if n > 1 {
            return Err(DataError::unsupported(
                path,
                format!("ImageJ hyperstack with {n} {what}; only single-channel z stacks are read"),
            ));
        }
    }
    let resolution = |decoder: &mut Decoder<_>, tag| -> Result<Option<f64>, DataError> {
        use tiff::decoder::ifd::Value;
        // RATIONAL by the standard; a few writers use other number types.
        let r = match decoder.find_tag(tag).map_err(terr)? {
            Some(Value::Rational(n, d)) => n as f64 / d as f64,
            Some(Value::Float(v)) => v as f64,
            Some(Value::Double(v)) => v,
            Some(v) => v.into_u64().map_or(f64::NAN, |v| v as f64),
            None => f64::NAN,
        };
        Ok(Some(r).filter(|r| r.is_finite() && *r > 0.0))
    };
    let x_res = resolution(&mut decoder, Tag::XResolution)?;
    let y_res = resolution(&mut decoder, Tag::YResolution)?;
    let res_unit: u16 = decoder
        .find_tag_unsigned(Tag::ResolutionUnit)
        .map_err(terr)?
        .unwrap_or(2);

    // Walk the page headers: same size and type on every page, and the voxel limit, before
    // any pixel is decoded.
    let mut pages = 1u64;
    raw_voxels::checked_count(path, &[width as u64, height as u64, pages])?;
    while decoder.more_images() {
        decoder.next_image().map_err(terr)?;
        let size = decoder.dimensions().map_err(terr)?;
        let page_colour = decoder.colortype().map_err(terr)?;
        if size != (width, height) || page_colour != colour {
            return Err(DataError::format(
                path,
                format!(
                    "page {pages} is {}x{} {page_colour:?}, page 0 is {width}x{height} {colour:?}; \
                     a stack needs equal pages",
                    size.0, size.1
                ),
            ));
        }
        pages += 1;
        raw_voxels::checked_count(path, &[width as u64, height as u64, pages])?;
    }
    if imagej.images > pages {
        return Err(DataError::unsupported(
            path,
            format!(
                "the ImageJ description promises {} images but the file has {pages} pages \
                 (ImageJ's contiguous layout for very large stacks is not supported)",
                imagej.images
            ),
        ));
    }

    // Every page decodes to width x height samples. Refuse pages the file cannot hold (at the
    // best compression ratio) before the crate allocates them; then let it decode a whole page.
    let sample_bytes = match colour {
        ColorType::Gray(bits) => u64::from(bits) / 8,
        _ => 1,
    };
    let page_bytes = u64::from(width) * u64::from(height) * sample_bytes;
    let total = page_bytes * pages;
    if total > file_len.saturating_mul(MAX_RATIO) {
        return Err(DataError::format(
            path,
            format!(
                "{width}x{height} pixels on {pages} pages need {total} bytes, more than a \
                 {file_len}-byte file can hold"
            ),
        ));
    }
    let mut limits = file_limits(file_len);
    limits.decoding_buffer_size = limits
        .decoding_buffer_size
        .max(usize::try_from(page_bytes).unwrap_or(usize::MAX));
    decoder = decoder.with_limits(limits);

    decoder.seek_to_image(0).map_err(terr)?;
    let mut voxels: Option<Voxels> = None;
    for page in 0..pages {
        if page > 0 {
            decoder.next_image().map_err(terr)?;
        }
        let slice = decoder.read_image().map_err(terr)?;
        voxels = Some(append(path, voxels, slice, page)?);
    }
    let voxels = voxels.unwrap_or(Voxels::U8(Vec::new()));

    let (spacing, placement) = spacing(&imagej, x_res, y_res, res_unit);
    let dims = [width, height, pages.min(u32::MAX as u64) as u32];
    let geometry = Geometry::axis_aligned(spacing, [0.0; 3]);
    let mut volume =
        VolumeData::from_voxels(dims, geometry, voxels).map_err(|e| e.in_file(path))?;
    volume.placement = placement;
    Ok(volume)
}

/// The most bytes one byte of a page's strips can decode to: TIFF LZW emits at most a
/// 4 kB-entry table's longest string (under 4096 bytes) per code of at least 9 bits, deflate
/// at most 1032 bytes per byte, PackBits 64; the other compressions are not decoded here.
const MAX_RATIO: u64 = 4096;

/// The crate's limits while it reads directories. It allocates a tag's values (and a chunk's
/// compressed bytes) before reading them, bounded only by these limits, and those must be in
/// the file: so no more than the file's length (in values) is allowed.
fn file_limits(file_len: u64) -> Limits {
    let len = usize::try_from(file_len).unwrap_or(usize::MAX);
    let mut limits = Limits::default();
    limits.decoding_buffer_size = len.saturating_mul(size_of::<tiff::decoder::ifd::Value>());
    limits.intermediate_buffer_size = len;
    limits
}

/// Adds one decoded page to the stack; pages must keep the first page's sample type.
fn append(
    path: &Path,
    stack: Option<Voxels>,
    slice: DecodingResult,
    page: u64,
) -> Result<Voxels, DataError> {
    let mismatch = || {
        DataError::format(
            path,
            format!("page {page} has another sample type than page 0"),
        )
    };
    Ok(match (stack, slice) {
        (None, DecodingResult::U8(s)) => Voxels::U8(s),
        (None, DecodingResult::I8(s)) => Voxels::I8(s),
        (None, DecodingResult::U16(s)) => Voxels::U16(s),
        (None, DecodingResult::I16(s)) => Voxels::I16(s),
        (None, DecodingResult::F32(s)) => Voxels::F32(s),
        (None, other) => {
            return Err(DataError::unsupported(
                path,
                format!(
                    "{} samples are not supported (8- and 16-bit integers and 32-bit floats are)",
                    sample_name(&other)
                ),
            ));
        }
        (Some(Voxels::U8(mut v)), DecodingResult::U8(s)) => {
            v.extend(s);
            Voxels::U8(v)
        }
        (Some(Voxels::I8(mut v)), DecodingResult::I8(s)) => {
            v.extend(s);
            Voxels::I8(v)
        }
        (Some(Voxels::U16(mut v)), DecodingResult::U16(s)) => {
            v.extend(s);
            Voxels::U16(v)
        }
        (Some(Voxels::I16(mut v)), DecodingResult::I16(s)) => {
            v.extend(s);
            Voxels::I16(v)
        }
        (Some(Voxels::F32(mut v)), DecodingResult::F32(s)) => {
            v.extend(s);
            Voxels::F32(v)
        }
        _ => return Err(mismatch()),
    })
}

fn sample_name(r: &DecodingResult) -> &'static str {
    match r {
        DecodingResult::U32(_) => "32-bit unsigned integer",
        DecodingResult::I32(_) => "32-bit signed integer",
        DecodingResult::U64(_) => "64-bit unsigned integer",
        DecodingResult::I64(_) => "64-bit signed integer",
        DecodingResult::F16(_) => "16-bit float",
        DecodingResult::F64(_) => "64-bit float",
        _ => "these",
    }
}

/// What an ImageJ description (`ImageJ=1.x` then `key=value` lines) says about the stack.
#[derive(Debug, Default, PartialEq)]
struct ImageJ {
    found: bool,
    images: u64,
    channels: u64,
    frames: u64,
    spacing: Option<f64>,
    unit: Option<String>,
}

impl ImageJ {
    fn parse(description: &str) -> ImageJ {
        let mut ij = ImageJ::default();
        if !description.starts_with("ImageJ=") {
            return ij;
        }
        ij.found = true;
        for line in description.lines() {
            let Some((key, value)) = line.split_once('=') else {
                continue;
            };
            let value = value.trim();
            match key.trim() {
                "images" => ij.images = value.parse().unwrap_or(0),
                "channels" => ij.channels = value.parse().unwrap_or(0),
                "frames" => ij.frames = value.parse().unwrap_or(0),
                "spacing" => {
                    ij.spacing = value
                        .parse()
                        .ok()
                        .filter(|s: &f64| s.is_finite() && *s > 0.0)
                }
                "unit" => ij.unit = Some(value.to_string()),
                _ => {}
            }
        }
        ij
    }
}

/// Millimetres per unit of an ImageJ unit name, `None` when unknown (or `pixel`).
fn millimetres_per(unit: &str) -> Option<f64> {
    // ImageJ escapes µ in the description as a literal `\u00B5`.
    Some(match unit.trim().to_ascii_lowercase().as_str() {
        "mm" | "millimeter" | "millimetre" | "millimeters" | "millimetres" => 1.0,
        "cm" | "centimeter" | "centimetre" => 10.0,
        "m" | "meter" | "metre" => 1000.0,
        "micron" | "microns" | "um" | "µm" | "\\u00b5m" | "micrometer" | "micrometre" => 1e-3,
        "nm" | "nanometer" | "nanometre" => 1e-6,
        "inch" | "in" => 25.4,
        _ => return None,
    })
}

/// Voxel spacing in mm (or the file's unit) and a note of where it came from.
fn spacing(
    ij: &ImageJ,
    x_res: Option<f64>,
    y_res: Option<f64>,
    res_unit: u16,
) -> ([f64; 3], String) {
    let per_pixel = |r: Option<f64>| r.map_or(1.0, |r| 1.0 / r);
    let (xy_scale, from) = if ij.found {
        let unit = ij.unit.as_deref().unwrap_or("");
        // Shown as written, but with ImageJ's `\u00B5` escape as the µ it stands for.
        let shown = unit.replace("\\u00B5", "µ").replace("\\u00b5", "µ");
        match millimetres_per(unit) {
            Some(mm) => (
                Some(mm),
                format!("ImageJ spacing and X/YResolution in {shown}, as mm"),
            ),
            None if unit.is_empty() => (
                Some(1.0),
                "ImageJ spacing and X/YResolution, no unit".into(),
            ),
            None => (
                Some(1.0),
                format!("ImageJ spacing and X/YResolution in `{shown}` (taken as given)"),
            ),
        }
    } else {
        match (res_unit, x_res.or(y_res)) {
            (_, None) => (None, "no spacing in the file; unit spacing".to_string()),
            (3, _) => (
                Some(10.0),
                "X/YResolution per cm, as mm; z spacing 1".into(),
            ),
            (1, _) => (Some(1.0), "X/YResolution without unit; z spacing 1".into()),
            _ => (
                None,
                "inch X/YResolution ignored (a print resolution); unit spacing".into(),
            ),
        }
    };
    let spacing = match xy_scale {
        Some(mm) => [
            per_pixel(x_res) * mm,
            per_pixel(y_res) * mm,
            // ImageJ's default depth is 1 in its unit; without ImageJ, z is simply 1.
            if ij.found {
                ij.spacing.unwrap_or(1.0) * mm
            } else {
                1.0
            },
        ],
        None => [1.0; 3],
    };
    (
        spacing,
        format!("TIFF stack: {from}; axis-aligned, no anatomical frame"),
    )
}

fn tiff_error(path: &Path, e: TiffError) -> DataError {
    match e {
        TiffError::IoError(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => {
            DataError::format(path, "truncated TIFF file")
        }
        TiffError::IoError(e) => DataError::io(path, e),
        // The limits are the file's length (see `file_limits`).
        TiffError::LimitsExceeded => DataError::format(
            path,
            "bad TIFF file: a tag or strip declares more data than the file holds",
        ),
        TiffError::UnsupportedError(e) => {
            DataError::unsupported(path, format!("TIFF feature not supported: {e}"))
        }
        other => DataError::format(path, format!("bad TIFF file: {other}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn imagej_description_and_spacing() {
        let ij = ImageJ::parse("ImageJ=1.54f\nimages=12\nslices=12\nunit=\\u00B5m\nspacing=2.5\n");
        assert_eq!(ij.images, 12);
        assert_eq!(ij.spacing, Some(2.5));
        let (s, note) = spacing(&ij, Some(4.0), Some(2.0), 1);
        assert_eq!(s, [0.25e-3, 0.5e-3, 2.5e-3]);
        assert!(note.contains("in µm, as mm"), "{note}");
        // Not ImageJ: a 72 dpi print resolution is no voxel size; centimetres are.
        let none = ImageJ::parse("{\"shape\": [3, 4, 5]}");
        assert!(!none.found);
        assert_eq!(spacing(&none, Some(72.0), Some(72.0), 2).0, [1.0; 3]);
        assert_eq!(spacing(&none, Some(20.0), Some(10.0), 3).0, [0.5, 1.0, 1.0]);
        let odd = ImageJ::parse("ImageJ=1.5\nunit=furlong\nspacing=3\n");
        assert_eq!(spacing(&odd, None, None, 1).0, [1.0, 1.0, 3.0]);
    }
}

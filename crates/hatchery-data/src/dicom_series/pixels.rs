//! The pixels of DICOM slices: the sample format a header states (refusing what is not
//! decoded here), one slice's pixel data — native bytes decoded here, compressed frames by
//! [`super::compressed`] — and the voxel array the slices are gathered in.

use std::path::Path;

use dicom_core::value::{PrimitiveValue, Value};
use dicom_dictionary_std::{tags, uids};

use super::{Header, open_whole, optional, required, text};
use crate::DataError;
use crate::voxels::Voxels;

/// Explicit VR Big Endian: retired from the standard (so deprecated in dicom-dictionary-std)
/// but still met in archives.
const EXPLICIT_VR_BIG_ENDIAN: &str = "1.2.840.10008.1.2.2";

/// How the samples of a slice are stored.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct PixelFormat {
    pub bits_allocated: u32,
    pub bits_stored: u32,
    pub signed: bool,
}

impl PixelFormat {
    pub fn describe(&self) -> String {
        format!(
            "{} {}-bit ({} bits stored)",
            if self.signed { "signed" } else { "unsigned" },
            self.bits_allocated,
            self.bits_stored
        )
    }
}

/// The pixel format of a slice; refuses what this reader cannot decode.
pub(super) fn pixel_format(header: &Header) -> Result<PixelFormat, DataError> {
    let path = &header.path;
    let samples = optional(header, tags::SAMPLES_PER_PIXEL, "SamplesPerPixel", 1.0)?;
    let photometric = text(&header.object, tags::PHOTOMETRIC_INTERPRETATION);
    if samples != 1.0 || !matches!(photometric.as_str(), "MONOCHROME1" | "MONOCHROME2" | "") {
        return Err(DataError::unsupported(
            path,
            format!(
                "colour images are not supported (SamplesPerPixel {samples}, \
                 PhotometricInterpretation {photometric}); only grey-scale (MONOCHROME) slices are"
            ),
        ));
    }
    let frames = optional(header, tags::NUMBER_OF_FRAMES, "NumberOfFrames", 1.0)?;
    if frames != 1.0 {
        return Err(DataError::unsupported(
            path,
            format!(
                "multi-frame files ({frames} frames) are not supported, only single-frame slices"
            ),
        ));
    }
    let bits_allocated = required::<1>(header, tags::BITS_ALLOCATED, "BitsAllocated")?[0];
    let bits_stored = optional(header, tags::BITS_STORED, "BitsStored", bits_allocated)?;
    let high_bit = optional(header, tags::HIGH_BIT, "HighBit", bits_stored - 1.0)?;
    let representation = optional(
        header,
        tags::PIXEL_REPRESENTATION,
        "PixelRepresentation",
        0.0,
    )?;
    if representation != 0.0 && representation != 1.0 {
        return Err(DataError::format(
            path,
            format!("PixelRepresentation must be 0 or 1, got {representation}"),
        ));
    }
    if ![8.0, 16.0, 32.0].contains(&bits_allocated) {
        return Err(DataError::unsupported(
            path,
            format!("BitsAllocated {bits_allocated} is not supported, only 8, 16 and 32"),
        ));
    }
    if !(1.0..=bits_allocated).contains(&bits_stored) || high_bit != bits_stored - 1.0 {
        return Err(DataError::unsupported(
            path,
            format!(
                "BitsStored {bits_stored} with HighBit {high_bit} in {bits_allocated} bits is not \
                 supported (HighBit must be BitsStored - 1)"
            ),
        ));
    }
    Ok(PixelFormat {
        bits_allocated: bits_allocated as u32,
        bits_stored: bits_stored as u32,
        signed: representation == 1.0,
    })
}

/// Reads one slice's pixel data: `rows` × `columns` samples in `format`, in the slice's own
/// type.
pub(super) fn read_pixels(
    path: &Path,
    syntax: &str,
    [rows, columns]: [u32; 2],
    format: PixelFormat,
) -> Result<Voxels, DataError> {
    let count = rows as usize * columns as usize;
    let big_endian = syntax == EXPLICIT_VR_BIG_ENDIAN;
    // Deflate compresses the whole data set, which dicom-object inflates; the pixel data inside
    // is native.
    let uncompressed = [
        uids::IMPLICIT_VR_LITTLE_ENDIAN,
        uids::EXPLICIT_VR_LITTLE_ENDIAN,
        uids::DEFLATED_EXPLICIT_VR_LITTLE_ENDIAN,
        EXPLICIT_VR_BIG_ENDIAN,
    ];
    if !uncompressed.contains(&syntax) {
        let le = super::compressed::decode_slice(path, syntax, [rows, columns], format)?;
        let needed = count * (format.bits_allocated as usize / 8);
        if le.len() < needed {
            return Err(DataError::format(
                path,
                format!("decoded pixel data has {} of {needed} bytes", le.len()),
            ));
        }
        return Ok(decode(&le[..needed], format));
    }
    let object = open_whole(path)?;
    let element = object
        .element_opt(tags::PIXEL_DATA)
        .ok()
        .flatten()
        .ok_or_else(|| DataError::format(path, "no PixelData"))?;
    // Put the samples into little-endian byte order whatever the VR: OW words are already
    // native numbers (the parser swapped big-endian ones), OB is bytes as stored.
    let bytes_per_sample = format.bits_allocated as usize / 8;
    let le: Vec<u8> = match element.value() {
        Value::Primitive(PrimitiveValue::U8(bytes)) if big_endian && bytes_per_sample > 1 => bytes
            .chunks_exact(bytes_per_sample)
            .flat_map(|c| c.iter().rev().copied())
            .collect(),
        Value::Primitive(PrimitiveValue::U8(bytes)) => bytes.to_vec(),
        // 32-bit samples as big-endian OW: the parser swapped each 16-bit word, so a sample's
        // two words are (high, low).
        Value::Primitive(PrimitiveValue::U16(words)) if big_endian && bytes_per_sample == 4 => {
            words
                .chunks_exact(2)
                .flat_map(|w| [w[1].to_le_bytes(), w[0].to_le_bytes()])
                .flatten()
                .collect()
        }
        Value::Primitive(PrimitiveValue::U16(words)) => {
            words.iter().flat_map(|w| w.to_le_bytes()).collect()
        }
        Value::PixelSequence(_) => {
            return Err(DataError::unsupported(
                path,
                "encapsulated (compressed) pixel data is not supported",
            ));
        }
        _ => return Err(DataError::format(path, "PixelData is neither OB nor OW")),
    };
    let needed = count * bytes_per_sample;
    if le.len() < needed {
        return Err(DataError::format(
            path,
            format!("truncated pixel data: {} of {needed} bytes", le.len()),
        ));
    }
    Ok(decode(&le[..needed], format))
}

/// Little-endian samples to voxels, keeping only the BitsStored low bits (sign-extended when
/// signed): the bits above may hold overlays in old files.
fn decode(le: &[u8], format: PixelFormat) -> Voxels {
    let unused = 32 - format.bits_stored;
    // Shift the stored bits to the top of 32, then back: an arithmetic shift extends the sign.
    let unsigned = |v: u32| (v << unused) >> unused;
    let signed = |v: u32| ((v << unused) as i32) >> unused;
    match (format.bits_allocated, format.signed) {
        (8, false) => Voxels::U8(le.iter().map(|&b| unsigned(b as u32) as u8).collect()),
        (8, true) => Voxels::I8(le.iter().map(|&b| signed(b as u32) as i8).collect()),
        (16, s) => {
            let words = le
                .chunks_exact(2)
                .map(|c| u16::from_le_bytes([c[0], c[1]]) as u32);
            if s {
                Voxels::I16(words.map(|v| signed(v) as i16).collect())
            } else {
                Voxels::U16(words.map(|v| unsigned(v) as u16).collect())
            }
        }
        (_, s) => {
            let words = le
                .chunks_exact(4)
                .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]));
            if s {
                Voxels::F32(words.map(|v| signed(v) as f32).collect())
            } else {
                Voxels::F32(words.map(|v| unsigned(v) as f32).collect())
            }
        }
    }
}

/// An empty array of `like`'s type with room for `total` values, holding `like`'s values.
pub(super) fn with_capacity(like: Voxels, total: usize) -> Result<Voxels, String> {
    fn grow<T>(mut v: Vec<T>, total: usize) -> Result<Vec<T>, String> {
        v.try_reserve_exact(total.saturating_sub(v.len()))
            .map_err(|_| format!("cannot allocate memory for {total} voxels"))?;
        Ok(v)
    }
    Ok(match like {
        Voxels::U8(v) => Voxels::U8(grow(v, total)?),
        Voxels::I8(v) => Voxels::I8(grow(v, total)?),
        Voxels::U16(v) => Voxels::U16(grow(v, total)?),
        Voxels::I16(v) => Voxels::I16(grow(v, total)?),
        Voxels::F32(v) => Voxels::F32(grow(v, total)?),
    })
}

/// Appends `more` to `all` (slices of one series share their type).
pub(super) fn append(all: &mut Voxels, more: Voxels) {
    match (all, more) {
        (Voxels::U8(a), Voxels::U8(b)) => a.extend(b),
        (Voxels::I8(a), Voxels::I8(b)) => a.extend(b),
        (Voxels::U16(a), Voxels::U16(b)) => a.extend(b),
        (Voxels::I16(a), Voxels::I16(b)) => a.extend(b),
        (Voxels::F32(a), Voxels::F32(b)) => a.extend(b),
        // Unreachable: every slice has the same pixel format and rescaling. Were it reached, the
        // array would come out short, which VolumeData::from_voxels refuses.
        _ => {}
    }
}

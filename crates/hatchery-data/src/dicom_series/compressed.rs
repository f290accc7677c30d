//! Compressed (encapsulated) pixel data of one slice, decoded by the transfer syntax's codec
//! from dicom-transfer-syntax-registry: JPEG (jpeg-decoder), JPEG 2000 (openjp2) and RLE
//! Lossless; JPEG-LS by [`super::jpeg_ls`].
//!
//! The codecs trust their input: a JPEG frame larger than the slice, or an RLE header with
//! segments outside its fragment, makes them index out of bounds (panic), and jpeg-decoder
//! allocates what a JPEG frame header says. So the stream's own header is checked against the
//! slice first (size, precision, segments), and a panic inside a codec still becomes an error
//! naming the file.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use dicom_dictionary_std::tags;
use dicom_encoding::Codec;
use dicom_object::DefaultDicomObject;
use dicom_transfer_syntax_registry::{TransferSyntaxIndex, TransferSyntaxRegistry};

use super::pixels::PixelFormat;
use super::{chain, jpeg_ls, open_whole};
use crate::DataError;

const RLE_LOSSLESS: &str = "1.2.840.10008.1.2.5";
/// The supported encodings, for messages.
const SUPPORTED: &str = "uncompressed, 8-bit JPEG baseline/extended, JPEG lossless (2–16 bits), \
                         JPEG-LS, JPEG 2000 and RLE Lossless (8, 16, 32 bits) are";

/// JPEG 2000 Image Compression (Lossless Only) and JPEG 2000 Image Compression: decoded by the
/// pure-Rust port of OpenJPEG (dicom-rs's `openjp2` feature).
const JPEG_2000: [&str; 2] = ["1.2.840.10008.1.2.4.90", "1.2.840.10008.1.2.4.91"];

/// Decodes the first frame of the slice at `path` (`rows` × `columns` samples of `format`) into
/// little-endian samples of `format.bits_allocated` bits.
pub(super) fn decode_slice(
    path: &Path,
    syntax: &str,
    [rows, columns]: [u32; 2],
    format: PixelFormat,
) -> Result<Vec<u8>, DataError> {
    let ts = TransferSyntaxRegistry.get(syntax);
    let name = ts.map_or("an unknown transfer syntax", |ts| ts.name());
    if jpeg_ls::JPEG_LS.contains(&syntax) {
        // A single-frame slice: its fragments together are the frame's stream (PS3.5 A.4).
        let object = open_whole(path)?;
        let stream: Vec<u8> = fragments(path, &object, name)?.concat();
        return jpeg_ls::decode(&stream, rows, columns, format)
            .map_err(|m| DataError::format(path, format!("{name}: {m}")));
    }
    let Some(Codec::EncapsulatedPixelData(Some(reader), _)) = ts.map(|ts| ts.codec()) else {
        return Err(DataError::unsupported(
            path,
            format!(
                "{name} ({syntax}) pixel data is not supported; {SUPPORTED} (convert with e.g. \
                 `gdcmconv --raw`)"
            ),
        ));
    };
    let object = open_whole(path)?;
    let first = fragments(path, &object, name)?[0].as_slice();
    if syntax == RLE_LOSSLESS {
        let samples = rows as usize * columns as usize;
        check_rle(first, samples, format)
            .map_err(|m| DataError::format(path, format!("{name}: {m}")))?;
        if format.bits_allocated == 32 {
            // dicom-rs's RLE decoder stops at 16 bits; the segments are checked above.
            return Ok(rle_decode(first, samples, 4));
        }
    } else if JPEG_2000.contains(&syntax) {
        check_j2k(first, rows, columns, format)
            .map_err(|m| DataError::format(path, format!("{name}: {m}")))?;
    } else {
        check_jpeg(first, rows, columns, format).map_err(|(unsupported, m)| {
            if unsupported {
                DataError::unsupported(path, format!("{m}; {SUPPORTED}"))
            } else {
                DataError::format(path, format!("{name}: {m}"))
            }
        })?;
    }
    let mut le = Vec::new();
    match catch_unwind(AssertUnwindSafe(|| {
        reader.decode_frame(&object, 0, &mut le)
    })) {
        Ok(Ok(())) => Ok(le),
        Ok(Err(e)) => Err(DataError::format(
            path,
            format!("cannot decode its {name} pixel data: {}", chain(&e)),
        )),
        Err(_) => Err(DataError::format(
            path,
            format!("corrupt {name} pixel data (its decoder failed)"),
        )),
    }
}

/// The non-empty list of fragments of the encapsulated PixelData of `object` (read from `path`,
/// in transfer syntax `name`).
fn fragments<'a>(
    path: &Path,
    object: &'a DefaultDicomObject,
    name: &str,
) -> Result<&'a [Vec<u8>], DataError> {
    object
        .element_opt(tags::PIXEL_DATA)
        .ok()
        .flatten()
        .and_then(|e| e.value().fragments())
        .filter(|f| !f.is_empty())
        .ok_or_else(|| DataError::format(path, format!("{name} pixel data without fragments")))
}

/// RLE Lossless (PS3.5 G.3): a 64-byte header of 15 segment offsets, one segment per byte of
/// a sample (single-sample pixels), each starting inside the fragment after the previous one
/// and holding PackBits runs for at least `samples` bytes (the codec indexes past a shorter
/// one).
fn check_rle(fragment: &[u8], samples: usize, format: PixelFormat) -> Result<(), String> {
    let word = |i: usize| {
        fragment
            .get(4 * i..4 * i + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    let segments = word(0).filter(|_| fragment.len() >= 64).ok_or_else(|| {
        format!(
            "the fragment has {} bytes, less than its 64-byte header",
            fragment.len()
        )
    })?;
    let wanted = format.bits_allocated as usize / 8;
    if segments != wanted {
        return Err(format!(
            "{segments} segments, a {}-bit grey image has {wanted}",
            format.bits_allocated
        ));
    }
    let mut previous = 63;
    for i in 1..=segments {
        let offset = word(i).unwrap_or(0);
        if offset <= previous || offset >= fragment.len() {
            return Err(format!(
                "segment {i} starts at byte {offset}, outside the {}-byte fragment or before \
                 the previous one",
                fragment.len()
            ));
        }
        previous = offset;
    }
    for i in 1..=segments {
        let end = if i == segments {
            fragment.len()
        } else {
            word(i + 1).unwrap_or(0)
        };
        let segment = &fragment[word(i).unwrap_or(0)..end];
        if !packbits_holds(segment, samples) {
            return Err(format!(
                "segment {i} decodes to fewer than the slice's {samples} bytes"
            ));
        }
    }
    Ok(())
}

/// A JPEG 2000 codestream's SIZ marker segment (ISO 15444-1 A.5.1) against the slice: the
/// image area `Xsiz − XOsiz` × `Ysiz − YOsiz` is the slice's columns × rows, one component,
/// whose precision fits `format.bits_allocated`; checked before the decoder sees the stream.
fn check_j2k(stream: &[u8], rows: u32, columns: u32, format: PixelFormat) -> Result<(), String> {
    let be32 = |o: usize| {
        stream
            .get(o..o + 4)
            .map(|b| u32::from_be_bytes([b[0], b[1], b[2], b[3]]))
    };
    let be16 = |o: usize| {
        stream
            .get(o..o + 2)
            .map(|b| u16::from_be_bytes([b[0], b[1]]))
    };
    if stream.get(..4) != Some(&[0xFF, 0x4F, 0xFF, 0x51]) {
        return Err("not a JPEG 2000 codestream (no SOC and SIZ markers at its start)".into());
    }
    // SIZ: Lsiz, Rsiz, then Xsiz, Ysiz, XOsiz, YOsiz, tile sizes and offsets, Csiz, Ssiz…
    let (Some(x), Some(y), Some(x0), Some(y0), Some(components), Some(&ssiz)) = (
        be32(8),
        be32(12),
        be32(16),
        be32(20),
        be16(40),
        stream.get(42),
    ) else {
        return Err("the JPEG 2000 SIZ marker segment is cut short".into());
    };
    let (width, height) = (x.saturating_sub(x0), y.saturating_sub(y0));
    if (width, height) != (columns, rows) {
        return Err(format!(
            "the codestream is {width}×{height}, the slice {columns}×{rows}"
        ));
    }
    if components != 1 {
        return Err(format!("{components} components, a grey image has 1"));
    }
    let precision = u32::from(ssiz & 0x7F) + 1;
    if precision > format.bits_allocated {
        return Err(format!(
            "{precision}-bit samples do not fit BitsAllocated {}",
            format.bits_allocated
        ));
    }
    Ok(())
}

/// Decodes an RLE Lossless fragment whose segments [`check_rle`] checked: segment i holds byte
/// i of every sample, most significant first (PS3.5 G.2); returns little-endian samples.
fn rle_decode(fragment: &[u8], samples: usize, bytes_per_sample: usize) -> Vec<u8> {
    let offset = |i: usize| {
        let b = &fragment[4 * i..4 * i + 4];
        u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize
    };
    let mut le = vec![0u8; samples * bytes_per_sample];
    for segment in 0..bytes_per_sample {
        let start = offset(segment + 1);
        let end = if segment + 1 == bytes_per_sample {
            fragment.len()
        } else {
            offset(segment + 2)
        };
        let plane = unpack_bits(&fragment[start..end], samples);
        let byte = bytes_per_sample - 1 - segment;
        for (s, value) in plane.into_iter().enumerate() {
            le[s * bytes_per_sample + byte] = value;
        }
    }
    le
}

/// PackBits: a header byte n < 128 copies the next n + 1 bytes, n > 128 repeats the next byte
/// 257 − n times, 128 is a no-op; stops after `needed` bytes.
fn unpack_bits(data: &[u8], needed: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(needed);
    let mut i = 0;
    while out.len() < needed && i < data.len() {
        let n = data[i] as usize;
        i += 1;
        if n < 128 {
            let end = (i + n + 1).min(data.len());
            out.extend_from_slice(&data[i..end]);
            i = end;
        } else if n > 128 {
            if let Some(&b) = data.get(i) {
                out.extend(std::iter::repeat_n(b, 257 - n));
            }
            i += 1;
        }
    }
    out.resize(needed, 0);
    out
}

/// Whether PackBits `data` decodes to at least `needed` bytes with every run complete.
fn packbits_holds(data: &[u8], needed: usize) -> bool {
    let (mut at, mut out) = (0usize, 0usize);
    while out < needed {
        let Some(&control) = data.get(at) else {
            return false;
        };
        match control as i8 {
            // A literal run of n + 1 bytes.
            n @ 0.. => {
                let count = n as usize + 1;
                if at + 1 + count > data.len() {
                    return false;
                }
                at += 1 + count;
                out += count;
            }
            // No operation.
            -128 => at += 1,
            // The next byte 1 − n times.
            n => {
                if at + 1 >= data.len() {
                    return false;
                }
                at += 2;
                out += (1 - n as isize) as usize;
            }
        }
    }
    true
}

/// The JPEG frame header (SOFn) against the slice: same size, one component, a precision the
/// decoder reads into `format.bits_allocated`. Errors: `(true, _)` for a valid stream the
/// decoder does not read, `(false, _)` for a stream that does not fit the slice.
fn check_jpeg(
    stream: &[u8],
    rows: u32,
    columns: u32,
    format: PixelFormat,
) -> Result<(), (bool, String)> {
    let bad = |m: String| Err((false, m));
    if !stream.starts_with(&[0xFF, 0xD8]) {
        return bad("the fragment does not start a JPEG stream (no SOI marker)".into());
    }
    let mut at = 2;
    loop {
        // Markers may be preceded by fill bytes 0xFF.
        while stream.get(at) == Some(&0xFF) && stream.get(at + 1) == Some(&0xFF) {
            at += 1;
        }
        let (Some(&0xFF), Some(&marker)) = (stream.get(at), stream.get(at + 1)) else {
            return bad("no JPEG frame header (SOF) before the image data".into());
        };
        let Some(length) = stream
            .get(at + 2..at + 4)
            .map(|b| u16::from_be_bytes([b[0], b[1]]) as usize)
        else {
            return bad("the JPEG stream ends inside a marker".into());
        };
        let segment = stream.get(at + 4..at + 2 + length);
        match marker {
            0xC0..=0xC3 | 0xC5..=0xC7 | 0xC9..=0xCB | 0xCD..=0xCF => {
                let Some(&[precision, y0, y1, x0, x1, components, ..]) = segment else {
                    return bad("a truncated JPEG frame header".into());
                };
                let (height, width) = (
                    u16::from_be_bytes([y0, y1]) as u32,
                    u16::from_be_bytes([x0, x1]) as u32,
                );
                if marker > 0xC3 {
                    return Err((
                        true,
                        format!(
                            "JPEG process SOF{} (hierarchical or arithmetic coding) is not \
                             decoded",
                            marker - 0xC0
                        ),
                    ));
                }
                if (width, height) != (columns, rows) || components != 1 {
                    return bad(format!(
                        "its JPEG frame is {width}×{height} with {components} components, the \
                         slice is {columns}×{rows} grey"
                    ));
                }
                let lossless = marker == 0xC3;
                if !lossless && precision != 8 {
                    return Err((
                        true,
                        format!("{precision}-bit JPEG (DCT) is not decoded, only 8-bit"),
                    ));
                }
                let allocated = if precision <= 8 { 8 } else { 16 };
                if !(2..=16).contains(&precision) || format.bits_allocated != allocated {
                    return bad(format!(
                        "{precision}-bit JPEG samples in a slice of BitsAllocated {}",
                        format.bits_allocated
                    ));
                }
                return Ok(());
            }
            // Start of scan or end of image before any frame header.
            0xDA | 0xD9 => return bad("no JPEG frame header (SOF) before the image data".into()),
            _ => at += 2 + length,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GREY8: PixelFormat = PixelFormat {
        bits_allocated: 8,
        bits_stored: 8,
        signed: false,
    };
    const GREY16: PixelFormat = PixelFormat {
        bits_allocated: 16,
        bits_stored: 12,
        signed: true,
    };

    fn sof(marker: u8, precision: u8, height: u16, width: u16, components: u8) -> Vec<u8> {
        let mut s = vec![
            0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x04, 0x00, 0x00, 0xFF, marker, 0, 11,
        ];
        s.push(precision);
        s.extend(height.to_be_bytes());
        s.extend(width.to_be_bytes());
        s.extend([components, 1, 0x11, 0]);
        s
    }

    #[test]
    fn jpeg_frames_must_fit_the_slice() {
        assert!(check_jpeg(&sof(0xC3, 16, 4, 6, 1), 4, 6, GREY16).is_ok());
        assert!(check_jpeg(&sof(0xC0, 8, 4, 6, 1), 4, 6, GREY8).is_ok());
        // JPEG 2000: SOC, SIZ with a 6×4 image area at offset (1, 2), one 12-bit component.
        let mut siz = vec![0xFF, 0x4F, 0xFF, 0x51, 0, 41, 0, 0];
        for v in [7u32, 6, 1, 2, 7, 6, 0, 0] {
            siz.extend_from_slice(&v.to_be_bytes());
        }
        siz.extend_from_slice(&[0, 1, 11, 1, 1]);
        assert_eq!(check_j2k(&siz, 4, 6, GREY16), Ok(()));
        assert!(check_j2k(&siz, 4, 7, GREY16).unwrap_err().contains("6×4"));
        assert!(check_j2k(&siz, 4, 6, GREY8).unwrap_err().contains("12-bit"));
        assert!(
            check_j2k(&siz[..30], 4, 6, GREY16)
                .unwrap_err()
                .contains("cut short")
        );
        assert!(check_j2k(&[0xFF, 0xD8], 4, 6, GREY16).is_err());
        let refused = |s: &[u8], f| check_jpeg(s, 4, 6, f).unwrap_err();
        // A frame larger than the slice (the codec would index past its buffer).
        assert!(!refused(&sof(0xC3, 16, 400, 6, 1), GREY16).0);
        assert!(!refused(&sof(0xC3, 16, 4, 6, 3), GREY16).0);
        // 8-bit samples in a 16-bit slice, 12-bit DCT, arithmetic coding.
        assert!(!refused(&sof(0xC3, 8, 4, 6, 1), GREY16).0);
        assert!(refused(&sof(0xC1, 12, 4, 6, 1), GREY16).0);
        assert!(refused(&sof(0xC9, 8, 4, 6, 1), GREY8).0);
        // Not JPEG, truncated, no frame header.
        assert!(!refused(&[0, 1, 2], GREY8).0);
        assert!(!refused(&sof(0xC3, 16, 4, 6, 1)[..14], GREY16).0);
        assert!(!refused(&[0xFF, 0xD8, 0xFF, 0xDA, 0, 2], GREY8).0);
        assert!(!refused(&[0xFF, 0xD8, 0xFF, 0xE0, 0xFF, 0xFF], GREY8).0);
    }

    #[test]
    fn rle_headers_must_fit_the_fragment() {
        let header = |segments: u32, offsets: &[u32], len: usize| {
            let mut f = vec![0u8; len];
            f[0..4].copy_from_slice(&segments.to_le_bytes());
            for (i, o) in offsets.iter().enumerate() {
                f[4 + 4 * i..8 + 4 * i].copy_from_slice(&o.to_le_bytes());
            }
            f
        };
        // Segments of 6 samples: a run of 6 (−5, value), or a literal of 6 (5, six bytes).
        let with = |mut f: Vec<u8>, at: usize, bytes: &[u8]| {
            f[at..at + bytes.len()].copy_from_slice(bytes);
            f
        };
        let two = with(
            header(2, &[64, 70], 80),
            64,
            &[0xFB, 7, 5, 1, 2, 3, 4, 5, 6],
        );
        assert!(check_rle(&two, 6, GREY16).is_ok());
        let one = with(header(1, &[64], 66), 64, &[0xFB, 7]);
        assert!(check_rle(&one, 6, GREY8).is_ok());
        // Decodes to fewer bytes than the slice (the codec would index past it).
        assert!(check_rle(&one, 7, GREY8).is_err());
        assert!(check_rle(&with(header(1, &[64], 70), 64, &[5, 1, 2]), 6, GREY8).is_err());
        assert!(check_rle(&[1, 0, 0], 6, GREY8).is_err());
        assert!(check_rle(&header(u32::MAX, &[64], 80), 6, GREY8).is_err());
        assert!(check_rle(&header(1, &[64], 80), 6, GREY16).is_err());
        assert!(check_rle(&header(2, &[64, 64], 80), 6, GREY16).is_err());
        assert!(check_rle(&header(2, &[64, 900], 80), 6, GREY16).is_err());
        assert!(check_rle(&header(1, &[10], 80), 6, GREY8).is_err());
    }
}

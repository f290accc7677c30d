//! JPEG-LS (ITU-T T.87) pixel data of one slice: JPEG-LS Lossless (1.2.840.10008.1.2.4.80) and
//! Near-Lossless (….81), decoded by pure_jpegls (pure Rust, no `unsafe`; dicom-rs reads
//! JPEG-LS only through CharLS, a C++ library).
//!
//! The stream's own headers (SOF55, SOS) are checked against the slice first, as for the other
//! codecs (see [`super::compressed`]): its size, one component, a precision that fits
//! BitsAllocated; the decoder then checks the coding parameters (LSE presets, NEAR) against
//! T.87's bounds, and a panic inside it still becomes an error naming the file.

use std::panic::{AssertUnwindSafe, catch_unwind};

use super::pixels::PixelFormat;

/// JPEG-LS Lossless Image Compression and JPEG-LS Lossy (Near-Lossless) Image Compression.
pub(super) const JPEG_LS: [&str; 2] = ["1.2.840.10008.1.2.4.80", "1.2.840.10008.1.2.4.81"];

/// Decodes one slice's JPEG-LS stream (`rows` × `columns` samples of `format`, the frame's
/// fragments joined) into little-endian samples of `format.bits_allocated` bits.
///
/// Errors (a message for the file's error): a stream that is not JPEG-LS, does not fit the slice,
/// holds several components or interleaved scans, or does not decode.
pub(super) fn decode(
    stream: &[u8],
    rows: u32,
    columns: u32,
    format: PixelFormat,
) -> Result<Vec<u8>, String> {
    check_frame(stream, rows, columns, format)?;
    let decoded = catch_unwind(AssertUnwindSafe(|| jpegls::decode(stream, columns, rows)))
        .map_err(|_| "corrupt JPEG-LS data (its decoder failed)".to_string())?
        .map_err(|e| format!("cannot decode its JPEG-LS data: {e}"))?;
    let samples = decoded.0;
    Ok(match format.bits_allocated {
        // check_frame allows at most 8-bit samples in an 8-bit slice.
        8 => samples.iter().map(|&s| s as u8).collect(),
        _ => samples.iter().flat_map(|s| s.to_le_bytes()).collect(),
    })
}

/// The frame header (SOF55, T.87 C.2.2) against the slice: same size, one component, a
/// precision of 2–16 bits that fits BitsAllocated (8 or 16: JPEG-LS codes at most 16).
fn check_frame(stream: &[u8], rows: u32, columns: u32, format: PixelFormat) -> Result<(), String> {
    if !stream.starts_with(&[0xFF, 0xD8]) {
        return Err("the fragment does not start a JPEG-LS stream (no SOI marker)".into());
    }
    let mut at = 2;
    loop {
        let (Some(&0xFF), Some(&marker)) = (stream.get(at), stream.get(at + 1)) else {
            return Err("no JPEG-LS frame header (SOF55) before the image data".into());
        };
        let Some(length) = stream
            .get(at + 2..at + 4)
            .map(|b| u16::from_be_bytes([b[0], b[1]]) as usize)
        else {
            return Err("the JPEG-LS stream ends inside a marker".into());
        };
        let segment = stream.get(at + 4..at + 2 + length.max(2));
        match marker {
            0xF7 => {
                let Some(&[precision, y0, y1, x0, x1, components, ..]) = segment else {
                    return Err("a truncated JPEG-LS frame header".into());
                };
                let (height, width) = (
                    u32::from(u16::from_be_bytes([y0, y1])),
                    u32::from(u16::from_be_bytes([x0, x1])),
                );
                if components != 1 {
                    return Err(format!(
                        "a JPEG-LS frame of {components} components, a grey image has 1"
                    ));
                }
                if (width, height) != (columns, rows) {
                    return Err(format!(
                        "its JPEG-LS frame is {width}×{height}, the slice is {columns}×{rows}"
                    ));
                }
                let fits = match format.bits_allocated {
                    8 => precision <= 8,
                    16 => precision <= 16,
                    _ => false,
                };
                if !(2..=16).contains(&precision) || !fits {
                    return Err(format!(
                        "{precision}-bit JPEG-LS samples in a slice of BitsAllocated {}",
                        format.bits_allocated
                    ));
                }
                return Ok(());
            }
            // Other SOF markers: a JPEG (T.81) stream under a JPEG-LS transfer syntax.
            0xC0..=0xCF if !matches!(marker, 0xC4 | 0xC8 | 0xCC) => {
                return Err(format!(
                    "a JPEG (SOF{}) stream where JPEG-LS (SOF55) belongs",
                    marker - 0xC0
                ));
            }
            0xDA | 0xD9 => {
                return Err("no JPEG-LS frame header (SOF55) before the image data".into());
            }
            _ => at += 2 + length,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unsigned grey samples of `bits` bits, all stored.
    const fn grey(bits: u32) -> PixelFormat {
        PixelFormat {
            bits_allocated: bits,
            bits_stored: bits,
            signed: false,
        }
    }
    const GREY16: PixelFormat = grey(16);
    const GREY8: PixelFormat = grey(8);

    /// A 6×4 ramp coded by pure_jpegls's encoder at `precision` bits.
    fn ramp(precision: u8) -> (Vec<u16>, Vec<u8>) {
        let max = (1u32 << precision) - 1;
        let pixels: Vec<u16> = (0..24u32).map(|i| (i * 37 % (max + 1)) as u16).collect();
        let mut stream = Vec::new();
        let mut options = jpegls::EncodeOptions::default();
        options.precision = Some(precision);
        jpegls::encode_with_options(&pixels, 6, 4, &options, &mut stream).unwrap();
        (pixels, stream)
    }

    #[test]
    fn a_lossless_stream_decodes_to_its_samples() {
        let (pixels, stream) = ramp(12);
        let le = decode(&stream, 4, 6, GREY16).unwrap();
        let back: Vec<u16> = le
            .chunks_exact(2)
            .map(|b| u16::from_le_bytes([b[0], b[1]]))
            .collect();
        assert_eq!(back, pixels);
        let (pixels, stream) = ramp(8);
        assert_eq!(
            decode(&stream, 4, 6, GREY8).unwrap(),
            pixels.iter().map(|&p| p as u8).collect::<Vec<_>>()
        );
    }

    #[test]
    fn frames_that_do_not_fit_the_slice_are_refused() {
        let (_, stream) = ramp(12);
        let refused = |s: &[u8], rows, columns, f| decode(s, rows, columns, f).unwrap_err();
        assert!(refused(&stream, 4, 7, GREY16).contains("6×4, the slice is 7×4"));
        assert!(refused(&stream, 4, 6, GREY8).contains("12-bit JPEG-LS samples"));
        let mut three = stream.clone();
        let sof = three.windows(2).position(|w| w == [0xFF, 0xF7]).unwrap();
        three[sof + 9] = 3;
        assert!(refused(&three, 4, 6, GREY16).contains("3 components"));
        assert!(refused(&stream[..sof + 5], 4, 6, GREY16).contains("truncated"));
        assert!(refused(&[0, 1, 2], 4, 6, GREY16).contains("no SOI"));
        assert!(refused(&[0xFF, 0xD8, 0xFF, 0xDA, 0, 2], 4, 6, GREY16).contains("SOF55"));
        assert!(refused(&[0xFF, 0xD8, 0xFF, 0xC3, 0, 11], 4, 6, GREY16).contains("SOF3"));
        // A stream cut inside its scan: the decoder's error, not a panic.
        assert!(refused(&stream[..stream.len() - 6], 4, 6, GREY16).contains("cannot decode"));
    }
}

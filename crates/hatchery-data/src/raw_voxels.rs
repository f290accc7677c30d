//! Voxel bytes as the header-plus-raw-data formats (NRRD, MetaImage) store them: element types,
//! byte order, ASCII values, zlib/gzip streams and the size checks shared by their readers.

use std::io::{self, BufRead, Read};
use std::path::Path;

use crate::DataError;
use crate::voxels::MAX_VOXELS;
use crate::voxels::Voxels;

/// An element type of a raw voxel file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Element {
    U8,
    I8,
    U16,
    I16,
    U32,
    I32,
    U64,
    I64,
    F32,
    F64,
}

impl Element {
    pub(crate) fn size(self) -> usize {
        match self {
            Element::U8 | Element::I8 => 1,
            Element::U16 | Element::I16 => 2,
            Element::U32 | Element::I32 | Element::F32 => 4,
            Element::U64 | Element::I64 | Element::F64 => 8,
        }
    }

    /// The name `VolumeData::stored_type` reports (the file's type, before any widening).
    pub(crate) fn name(self) -> &'static str {
        match self {
            Element::U8 => "uint8",
            Element::I8 => "int8",
            Element::U16 => "uint16",
            Element::I16 => "int16",
            Element::U32 => "uint32",
            Element::I32 => "int32",
            Element::U64 => "uint64",
            Element::I64 => "int64",
            Element::F32 => "float32",
            Element::F64 => "float64",
        }
    }
}

/// `dims` multiplied out, refused above [`MAX_VOXELS`] (before anything is allocated).
pub(crate) fn checked_count(path: &Path, dims: &[u64]) -> Result<u64, DataError> {
    checked_count_within(path, dims, MAX_VOXELS)
}

/// `dims` multiplied out, refused above `limit` voxels or where a side exceeds `u32::MAX`.
pub(crate) fn checked_count_within(
    path: &Path,
    dims: &[u64],
    limit: u64,
) -> Result<u64, DataError> {
    let count = dims
        .iter()
        .try_fold(1u64, |acc, &d| acc.checked_mul(d))
        .unwrap_or(u64::MAX);
    if count > limit || dims.iter().any(|&d| d > u32::MAX as u64) {
        return Err(DataError::TooLarge {
            path: path.to_path_buf(),
            voxels: count,
            limit,
        });
    }
    Ok(count)
}

/// Decodes `bytes` (whole elements) into voxels: u8, i8, u16, i16 and f32 stay native, the wider
/// types become f32 (integers above 2^24 and doubles lose precision).
pub(crate) fn decode(bytes: &[u8], element: Element, big_endian: bool) -> Voxels {
    macro_rules! read {
        ($t:ty) => {
            bytes.chunks_exact(size_of::<$t>()).map(|c| {
                let a = c.try_into().unwrap_or_default();
                if big_endian {
                    <$t>::from_be_bytes(a)
                } else {
                    <$t>::from_le_bytes(a)
                }
            })
        };
    }
    match element {
        Element::U8 => Voxels::U8(bytes.to_vec()),
        Element::I8 => Voxels::I8(bytes.iter().map(|&b| b as i8).collect()),
        Element::U16 => Voxels::U16(read!(u16).collect()),
        Element::I16 => Voxels::I16(read!(i16).collect()),
        Element::F32 => Voxels::F32(read!(f32).collect()),
        Element::U32 => Voxels::F32(read!(u32).map(|v| v as f32).collect()),
        Element::I32 => Voxels::F32(read!(i32).map(|v| v as f32).collect()),
        Element::U64 => Voxels::F32(read!(u64).map(|v| v as f32).collect()),
        Element::I64 => Voxels::F32(read!(i64).map(|v| v as f32).collect()),
        Element::F64 => Voxels::F32(read!(f64).map(|v| v as f32).collect()),
    }
}

/// Parses `count` whitespace-separated ASCII values (text encodings) into little-endian bytes
/// of `element`, so they go through [`decode`] like binary data. Integer types refuse values
/// that are not integers in their range.
pub(crate) fn parse_ascii(
    path: &Path,
    text: &str,
    element: Element,
    count: usize,
) -> Result<Vec<u8>, DataError> {
    // Each value takes a character and a separator, so a short text cannot fill a huge count:
    // reserve no more than the text can hold (a header may promise anything).
    let room = count.min(text.len() / 2 + 1) * element.size();
    let mut bytes = Vec::new();
    bytes
        .try_reserve_exact(room)
        .map_err(|_| cannot_allocate(path, room))?;
    let mut found = 0;
    // Some writers separate values with commas as well as whitespace.
    let tokens = text
        .split(|c: char| c.is_ascii_whitespace() || c == ',')
        .filter(|t| !t.is_empty());
    for token in tokens.take(count) {
        let bad = || {
            DataError::format(
                path,
                format!("bad {} value `{token}` in the data", element.name()),
            )
        };
        macro_rules! value {
            ($t:ty) => {
                bytes.extend(token.parse::<$t>().map_err(|_| bad())?.to_le_bytes())
            };
        }
        match element {
            Element::U8 => value!(u8),
            Element::I8 => value!(i8),
            Element::U16 => value!(u16),
            Element::I16 => value!(i16),
            Element::U32 => value!(u32),
            Element::I32 => value!(i32),
            Element::U64 => value!(u64),
            Element::I64 => value!(i64),
            Element::F32 => value!(f32),
            Element::F64 => value!(f64),
        }
        found += 1;
    }
    if found < count {
        return Err(DataError::format(
            path,
            format!("truncated data: found {found} of the {count} values the header promises"),
        ));
    }
    Ok(bytes)
}

/// A deflate stream (zlib or gzip data) decodes to at most 1032 times its length (the
/// format's best case: 258-byte matches coded in about two bits each; see zlib's technical
/// details, "Maximum compression factor").
pub(crate) const MAX_DEFLATE_RATIO: u64 = 1032;

/// The most bytes `n` bytes of a file can decode to: `n` for raw data, `n` times
/// [`MAX_DEFLATE_RATIO`] for deflate data.
pub(crate) fn decoded_bound(n: u64, deflate: bool) -> u64 {
    if deflate {
        n.saturating_mul(MAX_DEFLATE_RATIO)
    } else {
        n
    }
}

/// Opens a data file named by a header and returns it with its length. Anything but a regular
/// file is refused before it is opened: a header may name `/dev/zero` or `/dev/urandom` (which
/// never end), a pipe or a terminal (which block).
pub(crate) fn open_data_file(
    path: &Path,
    what: &str,
) -> Result<(crate::files::DataFile, u64), DataError> {
    let Some(len) = crate::files::regular_file_len(path).map_err(|e| DataError::io(path, e))?
    else {
        return Err(DataError::unsupported(
            path,
            format!("{what} is not a regular file"),
        ));
    };
    let file = crate::files::open(path).map_err(|e| DataError::io(path, e))?;
    Ok((file, len))
}

/// Reads exactly `len` bytes, or says how many there were (`what` names the data source).
/// `available` bounds what `source` can yield (see [`decoded_bound`]): no more than that is
/// allocated up front, so a header promising more data than the file holds costs nothing.
pub(crate) fn read_bytes(
    path: &Path,
    source: &mut dyn Read,
    len: usize,
    what: &str,
    available: u64,
) -> Result<Vec<u8>, DataError> {
    let room = usize::try_from(available).map_or(len, |a| a.min(len));
    let mut bytes = Vec::new();
    bytes
        .try_reserve_exact(room)
        .map_err(|_| cannot_allocate(path, room))?;
    source
        .take(len as u64)
        .read_to_end(&mut bytes)
        .map_err(|e| stream_error(path, what, e))?;
    if bytes.len() < len {
        return Err(DataError::format(
            path,
            format!(
                "truncated data: {what} has {} of the {len} bytes the header promises",
                bytes.len()
            ),
        ));
    }
    Ok(bytes)
}

/// Skips `n` bytes of `source`; running out is a truncated file.
pub(crate) fn skip_bytes(
    path: &Path,
    source: &mut dyn Read,
    n: u64,
    what: &str,
) -> Result<(), DataError> {
    let skipped =
        io::copy(&mut source.take(n), &mut io::sink()).map_err(|e| stream_error(path, what, e))?;
    if skipped < n {
        return Err(DataError::format(
            path,
            format!("truncated data: {what} ends inside the {n} bytes to skip"),
        ));
    }
    Ok(())
}

/// Skips `n` lines (up to and including their `\n`).
pub(crate) fn skip_lines(
    path: &Path,
    source: &mut dyn BufRead,
    n: u64,
    what: &str,
) -> Result<(), DataError> {
    let mut line = Vec::new();
    for i in 0..n {
        line.clear();
        // A line longer than this is binary data, not a line to skip.
        let read = source
            .take(1 << 20)
            .read_until(b'\n', &mut line)
            .map_err(|e| stream_error(path, what, e))?;
        if read == 0 || line.last() != Some(&b'\n') {
            return Err(DataError::format(
                path,
                format!("truncated data: {what} has {i} of the {n} lines to skip"),
            ));
        }
    }
    Ok(())
}

/// A decompressing reader: gzip when the stream starts with the gzip magic, else zlib (what
/// MetaIO's `inflateInit2(.., 47)` and teem accept).
pub(crate) fn inflate<'a>(mut source: Box<dyn BufRead + 'a>) -> io::Result<Box<dyn Read + 'a>> {
    let head = source.fill_buf()?;
    Ok(if head.starts_with(&[0x1f, 0x8b]) {
        Box::new(flate2::bufread::MultiGzDecoder::new(source))
    } else {
        Box::new(flate2::bufread::ZlibDecoder::new(source))
    })
}

/// Keeps index 0 along one axis of a multi-dimensional element array: `inner` elements vary
/// faster than that axis (contiguous runs), `size` is its length, the rest repeat outside it.
pub(crate) fn first_along_axis(
    bytes: Vec<u8>,
    element: Element,
    inner: usize,
    size: usize,
) -> Vec<u8> {
    if size <= 1 {
        return bytes;
    }
    let run = inner * element.size();
    bytes
        .chunks(run * size)
        .flat_map(|block| &block[..run.min(block.len())])
        .copied()
        .collect()
}

fn cannot_allocate(path: &Path, bytes: usize) -> DataError {
    DataError::format(
        path,
        format!("cannot allocate {bytes} bytes for the voxel data"),
    )
}

/// End-of-file and decoder errors are problems of the file, the rest are I/O errors.
fn stream_error(path: &Path, what: &str, e: io::Error) -> DataError {
    match e.kind() {
        io::ErrorKind::UnexpectedEof => {
            DataError::format(path, format!("truncated data: {what} ends early"))
        }
        io::ErrorKind::InvalidInput | io::ErrorKind::InvalidData => {
            DataError::format(path, format!("corrupt compressed data in {what}: {e}"))
        }
        _ => DataError::io(path, e),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decode_types_and_byte_order() {
        assert_eq!(
            decode(&[1, 2, 0xff, 0xfe], Element::I16, true),
            Voxels::I16(vec![0x0102, -2])
        );
        assert_eq!(
            decode(&[1, 2, 3, 4], Element::U16, false),
            Voxels::U16(vec![0x0201, 0x0403])
        );
        assert_eq!(
            decode(&2.5f64.to_be_bytes(), Element::F64, true),
            Voxels::F32(vec![2.5])
        );
        assert_eq!(
            decode(&(-7i64).to_le_bytes(), Element::I64, false),
            Voxels::F32(vec![-7.0])
        );
    }

    #[test]
    fn ascii_values() {
        let p = Path::new("a.nrrd");
        let bytes = parse_ascii(p, " 1 -2,3\n4 5", Element::I16, 4).unwrap();
        assert_eq!(
            decode(&bytes, Element::I16, false),
            Voxels::I16(vec![1, -2, 3, 4])
        );
        let e = parse_ascii(p, "1 2", Element::U8, 3)
            .unwrap_err()
            .to_string();
        assert!(e.contains("2 of the 3"), "{e}");
        let e = parse_ascii(p, "1 300", Element::U8, 2)
            .unwrap_err()
            .to_string();
        assert!(e.contains("`300`"), "{e}");
    }

    #[test]
    fn first_along_an_axis() {
        // 2 (inner) x 3 (axis) x 2 (outer), values = index.
        let bytes: Vec<u8> = (0..12).collect();
        assert_eq!(
            first_along_axis(bytes.clone(), Element::U8, 2, 3),
            [0, 1, 6, 7]
        );
        assert_eq!(
            first_along_axis(bytes.clone(), Element::U8, 1, 2),
            (0..12).step_by(2).collect::<Vec<_>>()
        );
        assert_eq!(
            first_along_axis(bytes, Element::U8, 6, 2),
            (0..6).collect::<Vec<_>>()
        );
    }
}

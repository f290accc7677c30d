//! The values of one data array: ASCII text, or binary data (inline base64, appended raw or
//! base64), uncompressed or in compressed blocks, into [`Voxels`] of the array's own type where
//! hatchery keeps it.

use std::borrow::Cow;
use std::io::Read;

use rayon::prelude::*;

use super::markup::{Appended, ArrayInfo, Compressor, Encoding, Format, Scalar};
use crate::voxels::Voxels;

/// What converting to the voxel type changed, for the volume's `placement` note.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Loss {
    /// Integer values that float32 cannot hold exactly (|v| > 2^24), rounded.
    pub rounded: u64,
    /// Finite Float64 values beyond the float32 range, now ±infinity ("no data").
    pub overflowed: u64,
}

impl Loss {
    pub fn add(&mut self, other: Loss) {
        self.rounded += other.rounded;
        self.overflowed += other.overflowed;
    }
}

/// Decodes the `count` values of a single-component array of type `scalar`; errors are
/// messages about the array.
pub(super) fn read_array(
    array: &ArrayInfo,
    scalar: Scalar,
    count: usize,
    encoding: &Encoding,
    appended: Option<&Appended>,
) -> Result<(Voxels, Loss), String> {
    let text = array.text();
    let mut source = match array.format()? {
        Format::Ascii => return read_ascii(&text, count, scalar),
        Format::Binary => ByteSource::Base64(Base64::new(text.as_bytes())),
        Format::Appended(offset) => {
            let appended = appended.ok_or("format is appended but there is no <AppendedData>")?;
            let data = usize::try_from(offset)
                .ok()
                .and_then(|o| appended.data.get(o..))
                .ok_or_else(|| format!("offset {offset} is past the end of the appended data"))?;
            if appended.base64 {
                ByteSource::Base64(Base64::new(data))
            } else {
                ByteSource::Raw(data)
            }
        }
    };
    let byte_count = count
        .checked_mul(scalar.size())
        .ok_or("the array is too large")?;
    let bytes = if encoding.compressor == Compressor::None {
        let stored = source.header_number(encoding)?;
        if stored != byte_count as u64 {
            return Err(format!(
                "holds {stored} bytes, the extent needs {byte_count}"
            ));
        }
        source.take(byte_count)?
    } else {
        Cow::Owned(read_compressed(&mut source, encoding, byte_count)?)
    };
    Ok(from_bytes(bytes, scalar, encoding.big_endian))
}

/// Compressed layout (vtkXMLDataParser): `[nb][nu][np][nc_1 .. nc_nb]` header numbers, then
/// `nb` independently compressed blocks of `nu` bytes each before compression, the last one
/// `np` bytes (or `nu` when `np` is 0, i.e. the last block is full).
fn read_compressed(
    source: &mut ByteSource,
    encoding: &Encoding,
    byte_count: usize,
) -> Result<Vec<u8>, String> {
    let compressor = &encoding.compressor;
    if let Compressor::Unknown(name) = compressor {
        return Err(format!(
            "compressor {name} is not supported; vtkZLibDataCompressor, vtkLZ4DataCompressor \
             and vtkLZMADataCompressor are"
        ));
    }
    let blocks = source.header_number(encoding)?;
    let block_size = source.header_number(encoding)?;
    let last_size = source.header_number(encoding)?;
    let total = match blocks {
        0 => Some(0),
        n if block_size > 0 && last_size <= block_size => {
            let last = if last_size == 0 {
                block_size
            } else {
                last_size
            };
            (n - 1)
                .checked_mul(block_size)
                .and_then(|t| t.checked_add(last))
        }
        _ => None,
    };
    if total != Some(byte_count as u64) {
        return Err(format!(
            "compression header ({blocks} blocks of {block_size} bytes, last {last_size}) does \
             not match the {byte_count} bytes the extent needs"
        ));
    }
    // blocks <= byte_count here, but the header of their sizes must still be in the file.
    let header_bytes = header_size(encoding) * blocks as usize;
    if header_bytes > source.max_remaining() {
        return Err("truncated compression header".into());
    }
    let mut offsets = Vec::with_capacity(blocks as usize + 1);
    offsets.push(0usize);
    for _ in 0..blocks {
        let size = source.header_number(encoding)?;
        let end = usize::try_from(size)
            .ok()
            .and_then(|s| offsets.last().unwrap_or(&0).checked_add(s))
            .filter(|&end| end <= source.max_remaining())
            .ok_or("compressed blocks are larger than the rest of the file")?;
        offsets.push(end);
    }
    // Each block must be able to hold its share: refuse a header promising more than its
    // compressed blocks can decode to, before allocating for it.
    let ratio = max_ratio(compressor);
    for (i, range) in offsets.windows(2).enumerate() {
        let size = if i + 1 == blocks as usize {
            byte_count as u64 - (blocks - 1) * block_size
        } else {
            block_size
        };
        let stored = (range[1] - range[0]) as u64;
        if size > stored.saturating_mul(ratio) {
            return Err(format!(
                "compressed block {i} has {stored} bytes, too few to hold the {size} bytes the \
                 header says it decompresses to"
            ));
        }
    }
    let compressed = source.take(*offsets.last().unwrap_or(&0))?;

    let mut out = Vec::new();
    out.try_reserve_exact(byte_count)
        .map_err(|_| format!("cannot allocate {byte_count} bytes"))?;
    out.resize(byte_count, 0u8);
    // Blocks are independent, so they decompress in parallel straight into place.
    out.par_chunks_mut(block_size.max(1) as usize)
        .zip(offsets.par_windows(2))
        .enumerate()
        .try_for_each(|(i, (out, range))| {
            decompress_block(compressor, &compressed[range[0]..range[1]], out)
                .map_err(|e| format!("corrupt compressed block {i}: {e}"))
        })?;
    Ok(out)
}

/// Decompresses one block to exactly `out.len()` bytes, as VTK's compressors check it: the
/// stream must end there (with its checksum, for zlib and xz).
fn decompress_block(compressor: &Compressor, block: &[u8], out: &mut [u8]) -> Result<(), String> {
    fn whole(mut reader: impl Read, out: &mut [u8]) -> Result<(), String> {
        reader.read_exact(out).map_err(|e| e.to_string())?;
        match reader.read(&mut [0u8; 1]) {
            Ok(0) => Ok(()),
            Ok(_) => Err(format!("decompresses to more than {} bytes", out.len())),
            Err(e) => Err(e.to_string()),
        }
    }
    match compressor {
        Compressor::Zlib => whole(flate2::bufread::ZlibDecoder::new(block), out),
        Compressor::Lzma => whole(lzma_rust2::XzReader::new(block, false), out),
        Compressor::Lz4 => match lz4_flex::block::decompress_into(block, out) {
            Ok(n) if n == out.len() => Ok(()),
            Ok(n) => Err(format!("decompresses to {n} bytes, not {}", out.len())),
            Err(e) => Err(format!("lz4: {e}")),
        },
        Compressor::None | Compressor::Unknown(_) => Err("not compressed".into()),
    }
}

/// The most bytes one compressed byte of a block can decode to. zlib (deflate): 1032, the
/// format's best case. LZ4 blocks: 255, a match length grows by at most 255 per byte. LZMA (one
/// .xz stream per block): LZMA2 codes at most 2 MiB per chunk and a chunk takes at least six
/// bytes (control, sizes and data); real streams stay far below this loose bound.
fn max_ratio(compressor: &Compressor) -> u64 {
    match compressor {
        Compressor::Zlib => 1032,
        Compressor::Lz4 => 255,
        Compressor::Lzma => (2 << 20) / 6,
        Compressor::None | Compressor::Unknown(_) => 1,
    }
}

fn header_size(encoding: &Encoding) -> usize {
    if encoding.wide_header { 8 } else { 4 }
}

/// Binary values in the file's byte order to voxels: 8- and 16-bit integers and Float32 stay
/// as they are, wider integers and Float64 become float32. Decompressed uint8 bytes become the
/// voxels as they are (no copy: a big volume is held once plus the file's bytes, not more).
fn from_bytes(bytes: Cow<[u8]>, scalar: Scalar, big_endian: bool) -> (Voxels, Loss) {
    macro_rules! values {
        ($t:ty) => {{
            const N: usize = std::mem::size_of::<$t>();
            bytes.par_chunks_exact(N).map(|b| {
                let mut a = [0u8; N];
                a.copy_from_slice(b);
                if big_endian {
                    <$t>::from_be_bytes(a)
                } else {
                    <$t>::from_le_bytes(a)
                }
            })
        }};
    }
    // Integers are compared as i128, which holds every i64 and u64 exactly.
    macro_rules! wide_int {
        ($t:ty) => {{
            let rounded = values!($t)
                .filter(|&v| (v as f32) as i128 != v as i128)
                .count() as u64;
            let voxels = Voxels::F32(values!($t).map(|v| v as f32).collect());
            (
                voxels,
                Loss {
                    rounded,
                    overflowed: 0,
                },
            )
        }};
    }
    let none = Loss::default();
    match scalar {
        Scalar::U8 => (Voxels::U8(bytes.into_owned()), none),
        Scalar::I8 => (Voxels::I8(bytes.iter().map(|&b| b as i8).collect()), none),
        Scalar::U16 => (Voxels::U16(values!(u16).collect()), none),
        Scalar::I16 => (Voxels::I16(values!(i16).collect()), none),
        Scalar::F32 => (Voxels::F32(values!(f32).collect()), none),
        Scalar::I32 => wide_int!(i32),
        Scalar::U32 => wide_int!(u32),
        Scalar::I64 => wide_int!(i64),
        Scalar::U64 => wide_int!(u64),
        Scalar::F64 => {
            let overflowed = values!(f64)
                .filter(|&v| v.is_finite() && !(v as f32).is_finite())
                .count() as u64;
            let voxels = Voxels::F32(values!(f64).map(|v| v as f32).collect());
            (
                voxels,
                Loss {
                    rounded: 0,
                    overflowed,
                },
            )
        }
    }
}

/// ASCII values (`nan` and `inf` included, as VTK writes them). Integer arrays must hold
/// integers in their type's range.
fn read_ascii(text: &str, count: usize, scalar: Scalar) -> Result<(Voxels, Loss), String> {
    let name = scalar.type_name();
    // Integers through i128: f64 cannot tell large 64-bit values apart. `3.0` is an integer too.
    let integer = |token: &str, min: i128, max: i128| -> Result<i128, String> {
        let i = match token.parse::<i128>() {
            Ok(i) => Some(i),
            Err(_) => match token.parse::<f64>() {
                Ok(f) if f.fract() == 0.0 && f.abs() < 1e30 => Some(f as i128),
                Ok(_) => None,
                Err(_) => return Err(format!("`{token}` is not a number")),
            },
        };
        i.filter(|i| (min..=max).contains(i))
            .ok_or_else(|| format!("`{token}` is not an integer from {min} to {max} ({name})"))
    };
    macro_rules! native {
        ($variant:ident, $t:ty) => {
            Voxels::$variant(parse_tokens(text, count, |t| {
                integer(t, <$t>::MIN as i128, <$t>::MAX as i128).map(|i| i as $t)
            })?)
        };
    }
    let mut loss = Loss::default();
    let voxels = match scalar {
        Scalar::U8 => native!(U8, u8),
        Scalar::I8 => native!(I8, i8),
        Scalar::U16 => native!(U16, u16),
        Scalar::I16 => native!(I16, i16),
        Scalar::I32 | Scalar::U32 | Scalar::I64 | Scalar::U64 => {
            let (min, max) = match scalar {
                Scalar::I32 => (i32::MIN as i128, i32::MAX as i128),
                Scalar::U32 => (0, u32::MAX as i128),
                Scalar::I64 => (i64::MIN as i128, i64::MAX as i128),
                _ => (0, u64::MAX as i128),
            };
            Voxels::F32(parse_tokens(text, count, |t| {
                let i = integer(t, min, max)?;
                let f = i as f32;
                loss.rounded += u64::from(f as i128 != i);
                Ok(f)
            })?)
        }
        Scalar::F32 => Voxels::F32(parse_tokens(text, count, |t| {
            t.parse::<f32>()
                .map_err(|_| format!("`{t}` is not a number"))
        })?),
        Scalar::F64 => Voxels::F32(parse_tokens(text, count, |t| {
            let d = t
                .parse::<f64>()
                .map_err(|_| format!("`{t}` is not a number"))?;
            let f = d as f32;
            loss.overflowed += u64::from(d.is_finite() && !f.is_finite());
            Ok(f)
        })?),
    };
    Ok((voxels, loss))
}

/// Exactly `count` whitespace-separated values.
fn parse_tokens<T>(
    text: &str,
    count: usize,
    mut parse: impl FnMut(&str) -> Result<T, String>,
) -> Result<Vec<T>, String> {
    // Each value takes a character and a separator: reserve no more than the text can hold,
    // whatever count the extent promises.
    let room = count.min(text.len() / 2 + 1);
    let mut values = Vec::new();
    values
        .try_reserve_exact(room)
        .map_err(|_| format!("cannot allocate {room} values"))?;
    for token in text.split_ascii_whitespace() {
        if values.len() == count {
            return Err(format!("has more than the {count} values the extent needs"));
        }
        values.push(parse(token)?);
    }
    if values.len() < count {
        return Err(format!(
            "has {} values, the extent needs {count}",
            values.len()
        ));
    }
    Ok(values)
}

/// Where binary array bytes come from: raw appended bytes or base64 text.
enum ByteSource<'a> {
    Raw(&'a [u8]),
    Base64(Base64<'a>),
}

impl<'a> ByteSource<'a> {
    /// The next `n` bytes: borrowed from raw data, decoded from base64.
    fn take(&mut self, n: usize) -> Result<Cow<'a, [u8]>, String> {
        match self {
            ByteSource::Raw(data) => {
                if data.len() < n {
                    return Err(format!(
                        "truncated: needs {n} more bytes, the file has {}",
                        data.len()
                    ));
                }
                let (head, rest) = data.split_at(n);
                *data = rest;
                Ok(Cow::Borrowed(head))
            }
            ByteSource::Base64(b) => b.take(n).map(Cow::Owned),
        }
    }

    /// An upper bound of the bytes left, to refuse absurd sizes before allocating.
    fn max_remaining(&self) -> usize {
        match self {
            ByteSource::Raw(data) => data.len(),
            ByteSource::Base64(b) => (b.text.len() - b.pos) / 4 * 3 + 3,
        }
    }

    /// One number of a binary array's header (sizes and block counts), decoded exactly.
    fn header_number(&mut self, encoding: &Encoding) -> Result<u64, String> {
        let b = self.take(header_size(encoding))?;
        let mut a = [0u8; 8];
        if encoding.big_endian {
            a[8 - b.len()..].copy_from_slice(&b);
            Ok(u64::from_be_bytes(a))
        } else {
            a[..b.len()].copy_from_slice(&b);
            Ok(u64::from_le_bytes(a))
        }
    }
}

/// Incremental base64 decoding that skips whitespace and accepts padding in the middle:
/// VTK writes the header and the data of compressed arrays as separately padded base64
/// strings, and some writers do the same for uncompressed ones. Decoding through the padding
/// yields the concatenated bytes either way.
struct Base64<'a> {
    text: &'a [u8],
    pos: usize,
    bits: u32,
    bit_count: u32,
}

impl<'a> Base64<'a> {
    fn new(text: &'a [u8]) -> Self {
        Self {
            text,
            pos: 0,
            bits: 0,
            bit_count: 0,
        }
    }

    fn take(&mut self, n: usize) -> Result<Vec<u8>, String> {
        // No more than the rest of the text can hold: a header may promise anything.
        let room = n.min((self.text.len() - self.pos) / 4 * 3 + 3);
        let mut out = Vec::new();
        out.try_reserve_exact(room)
            .map_err(|_| format!("cannot allocate {room} bytes"))?;
        while out.len() < n {
            let Some(&c) = self.text.get(self.pos) else {
                return Err(format!(
                    "truncated base64 data: needs {} more bytes",
                    n - out.len()
                ));
            };
            self.pos += 1;
            let v = match c {
                b'A'..=b'Z' => c - b'A',
                b'a'..=b'z' => c - b'a' + 26,
                b'0'..=b'9' => c - b'0' + 52,
                b'+' => 62,
                b'/' => 63,
                // Padding ends a quantum; its leftover bits are zero fill.
                b'=' => {
                    self.bits = 0;
                    self.bit_count = 0;
                    continue;
                }
                c if c.is_ascii_whitespace() => continue,
                c => {
                    return Err(format!(
                        "invalid base64 character {:?} at offset {}",
                        c as char,
                        self.pos - 1
                    ));
                }
            };
            self.bits = (self.bits << 6) | v as u32;
            self.bit_count += 6;
            if self.bit_count >= 8 {
                self.bit_count -= 8;
                out.push((self.bits >> self.bit_count) as u8);
                self.bits &= (1 << self.bit_count) - 1;
            }
        }
        Ok(out)
    }
}

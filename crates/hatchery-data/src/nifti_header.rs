//! NIfTI headers of both versions as one struct: NIfTI-1 (348 bytes, read by the nifti crate)
//! and NIfTI-2 (540 bytes, 64-bit dims and doubles: what tools write for large volumes). The
//! nifti crate reads only NIfTI-1, so the NIfTI-2 header is parsed here by hand, field by field
//! at the offsets of nifti2.h.

use std::io::{self, Read};

use nifti::{NiftiError, NiftiHeader, NiftiType};

/// The fields the loader uses, widened to NIfTI-2's types.
#[derive(Clone, Debug, PartialEq)]
pub struct Header {
    /// 1 or 2.
    pub version: u8,
    /// Bytes before the 4-byte extension flag (348 or 540).
    pub size: u64,
    /// The magic of a separate .hdr/.img pair (`ni1`, `ni2`) rather than a single file.
    pub pair: bool,
    pub big_endian: bool,
    pub dim: [i64; 8],
    pub intent_code: i32,
    /// The datatype code (nifti1.h: 2 = uint8, 4 = int16, …).
    pub datatype: i32,
    pub pixdim: [f64; 8],
    pub vox_offset: f64,
    pub scl_slope: f64,
    pub scl_inter: f64,
    pub qform_code: i32,
    pub sform_code: i32,
    pub quatern: [f64; 3],
    pub qoffset: [f64; 3],
    pub srow: [[f64; 4]; 3],
}

/// Why a header could not be read.
#[derive(Debug)]
pub enum HeaderError {
    Io(io::Error),
    /// Neither a NIfTI-1 nor a NIfTI-2 header (size or magic).
    NotNifti,
    Other(String),
}

/// Reads a NIfTI-1 or NIfTI-2 header from the start of a (decompressed) stream.
pub fn read(source: &mut dyn Read) -> Result<Header, HeaderError> {
    let mut first = [0u8; 4];
    source.read_exact(&mut first).map_err(HeaderError::Io)?;
    let le = i32::from_le_bytes(first);
    let be = i32::from_be_bytes(first);
    if le == 348 || be == 348 {
        let mut chained = io::Cursor::new(first).chain(source);
        let h = NiftiHeader::from_reader(&mut chained).map_err(|e| match e {
            NiftiError::Io(e) => HeaderError::Io(e),
            NiftiError::InvalidFormat => HeaderError::NotNifti,
            other => HeaderError::Other(other.to_string()),
        })?;
        return Ok(from_nifti1(&h));
    }
    if le == 540 || be == 540 {
        let mut bytes = vec![0u8; 540];
        bytes[..4].copy_from_slice(&first);
        source
            .read_exact(&mut bytes[4..])
            .map_err(HeaderError::Io)?;
        return from_nifti2(&bytes, be == 540);
    }
    Err(HeaderError::NotNifti)
}

fn from_nifti1(h: &NiftiHeader) -> Header {
    // The nifti crate keeps dims unsigned; the format's are signed 16-bit.
    let dim = h.dim.map(|d| i64::from(d as i16));
    Header {
        version: 1,
        size: 348,
        pair: &h.magic == nifti::header::MAGIC_CODE_NI1,
        big_endian: h.endianness == nifti::Endianness::Big,
        dim,
        intent_code: i32::from(h.intent_code),
        datatype: i32::from(h.datatype),
        pixdim: h.pixdim.map(f64::from),
        vox_offset: f64::from(h.vox_offset),
        scl_slope: f64::from(h.scl_slope),
        scl_inter: f64::from(h.scl_inter),
        qform_code: i32::from(h.qform_code),
        sform_code: i32::from(h.sform_code),
        quatern: [h.quatern_b, h.quatern_c, h.quatern_d].map(f64::from),
        qoffset: [h.quatern_x, h.quatern_y, h.quatern_z].map(f64::from),
        srow: [h.srow_x, h.srow_y, h.srow_z].map(|r| r.map(f64::from)),
    }
}

/// The NIfTI-2 header (nifti2.h): `bytes` holds its 540 bytes.
fn from_nifti2(bytes: &[u8], big: bool) -> Result<Header, HeaderError> {
    let magic = &bytes[4..12];
    let pair = match magic {
        b"n+2\0\r\n\x1a\n" => false,
        b"ni2\0\r\n\x1a\n" => true,
        _ => return Err(HeaderError::NotNifti),
    };
    let at = |o: usize, n: usize| {
        let mut b = bytes[o..o + n].to_vec();
        if big {
            b.reverse();
        }
        b
    };
    let i16_at = |o| i16::from_le_bytes(at(o, 2).try_into().expect("2 bytes"));
    let i32_at = |o| i32::from_le_bytes(at(o, 4).try_into().expect("4 bytes"));
    let i64_at = |o| i64::from_le_bytes(at(o, 8).try_into().expect("8 bytes"));
    let f64_at = |o| f64::from_le_bytes(at(o, 8).try_into().expect("8 bytes"));
    let row = |o: usize| std::array::from_fn(|i| f64_at(o + 8 * i));
    Ok(Header {
        version: 2,
        size: 540,
        pair,
        big_endian: big,
        datatype: i32::from(i16_at(12)),
        dim: std::array::from_fn(|i| i64_at(16 + 8 * i)),
        pixdim: std::array::from_fn(|i| f64_at(104 + 8 * i)),
        vox_offset: i64_at(168) as f64,
        scl_slope: f64_at(176),
        scl_inter: f64_at(184),
        qform_code: i32_at(344),
        sform_code: i32_at(348),
        quatern: [f64_at(352), f64_at(360), f64_at(368)],
        qoffset: [f64_at(376), f64_at(384), f64_at(392)],
        srow: [row(400), row(432), row(464)],
        intent_code: i32_at(504),
    })
}

/// The datatype of a code (nifti1.h's DT_* values shared by both versions); `None` for codes
/// that are not scalar integers or floats.
pub fn datatype(code: i32) -> Option<NiftiType> {
    use NiftiType::*;
    Some(match code {
        2 => Uint8,
        4 => Int16,
        8 => Int32,
        16 => Float32,
        64 => Float64,
        256 => Int8,
        512 => Uint16,
        768 => Uint32,
        1024 => Int64,
        1280 => Uint64,
        _ => return None,
    })
}

//! A check of a DICOM file's element lengths and sequence nesting before dicom-rs parses it.
//!
//! dicom-parser (0.10) allocates and zero-fills a value's declared length before reading it, so
//! a 2 kB file declaring a 4 GB element costs 4 GB of memory; and dicom-object builds nested
//! sequences recursively, so sequences nested deep enough overflow the stack (an abort, not an
//! error). This walk reads only the element headers, skipping values, and refuses a file
//! whose declared lengths exceed what is left of it, or whose sequences nest deeper than
//! [`MAX_DEPTH`]. Undefined-length values are walked as dicom-parser reads them: PixelData as
//! fragments, every other one as a sequence of items.
//!
//! One exception: an undefined-length element of VR UN in an explicit-VR data set (a private
//! sequence some exports hold) is a sequence encoded in implicit VR little endian (PS3.5
//! 6.2.2), which dicom-parser reads in the data set's explicit VR instead, taking value lengths
//! for VRs. The walk reads it in implicit VR and returns where it lies, so that the file can be
//! parsed without it (see `super::parse`): no attribute hatchery reads is such a sequence.

use std::fs::File;
use std::io::{self, BufReader, Read};
use std::ops::Range;

use std::path::Path;

use dicom_core::dictionary::DataDictionary;
use dicom_core::{Tag, VR};
use dicom_dictionary_std::{StandardDataDictionary, uids};

use crate::DataError;
use crate::raw_voxels::decoded_bound;

/// Sequences and items (two levels per nested sequence) open at once beyond this are refused;
/// real data sets nest a handful of sequences.
pub(super) const MAX_DEPTH: usize = 64;

const UNDEFINED: u32 = 0xFFFF_FFFF;
const ITEM: (u16, u16) = (0xFFFE, 0xE000);
const ITEM_END: (u16, u16) = (0xFFFE, 0xE00D);
const SEQUENCE_END: (u16, u16) = (0xFFFE, 0xE0DD);
const PIXEL_DATA: (u16, u16) = (0x7FE0, 0x0010);
const TRANSFER_SYNTAX: (u16, u16) = (0x0002, 0x0010);
/// Explicit VR Big Endian (retired, so not in `uids`).
const EXPLICIT_VR_BIG_ENDIAN: &str = "1.2.840.10008.1.2.2";

/// Checks a file that has the `DICM` marker at byte 128; returns the byte ranges of the
/// undefined-length UN elements to leave out when parsing it (in ascending order; none in a
/// deflated data set, whose bytes are not the file's).
pub(super) fn check_lengths(path: &Path) -> Result<Vec<Range<u64>>, DataError> {
    let io_error = |e: io::Error| DataError::io(path, e);
    let file = File::open(path).map_err(io_error)?;
    let file_len = file.metadata().map_err(io_error)?.len();
    let mut input = Input {
        reader: Reader::File(BufReader::new(file)),
        pos: 0,
        end: file_len,
    };
    input.skip(132).map_err(io_error)?;

    // The file meta group: explicit VR little endian, defined lengths. dicom-rs reads it as
    // dicom-object's FileMetaTable does: a (0002,0000) group length first, then elements
    // (whatever their group) until that many bytes are read; the data set starts there. Walk
    // the same elements, or the two disagree on where the data set starts and this walk checks
    // other lengths than dicom-rs reads.
    let mut syntax = String::new();
    let walk = Walk::new(path, Encoding::ExplicitLittle);
    let none = |r: Result<(), DataError>| r.map(|()| Vec::new());
    let header = match walk.header(&mut input) {
        Ok(h) => h,
        Err(e) => return none(walk.ended(e)),
    };
    if header.tag != (0x0002, 0x0000) || header.len != 4 {
        // dicom-rs refuses such a file itself.
        return Ok(Vec::new());
    }
    let mut value = [0u8; 4];
    if let Err(e) = input.read_exact(&mut value) {
        return none(walk.ended(e));
    }
    let group_end = input.pos + u64::from(u32::from_le_bytes(value));
    while input.pos < group_end {
        let header = match walk.header(&mut input) {
            Ok(h) => h,
            Err(e) => return none(walk.ended(e)),
        };
        walk.check_length(&input, header)?;
        if header.tag == TRANSFER_SYNTAX && header.len <= 1024 {
            let mut value = vec![0; header.len as usize];
            if let Err(e) = input.read_exact(&mut value) {
                return none(walk.ended(e));
            }
            // Trimmed as dicom-object and its transfer syntax registry trim it (any trailing
            // whitespace, not only the padding space: a "…1.2\n" is implicit VR to them).
            syntax = String::from_utf8_lossy(&value)
                .trim_end_matches(|c: char| c.is_whitespace() || c == '\0')
                .to_string();
        } else if let Err(e) = input.skip(header.len.into()) {
            return none(walk.ended(e));
        }
    }

    let encoding = match syntax.as_str() {
        uids::IMPLICIT_VR_LITTLE_ENDIAN => Encoding::ImplicitLittle,
        EXPLICIT_VR_BIG_ENDIAN => Encoding::ExplicitBig,
        uids::DEFLATED_EXPLICIT_VR_LITTLE_ENDIAN => {
            // The rest of the file is a raw deflate stream of an explicit VR little endian
            // data set, at most deflate's best ratio larger.
            let left = input.end - input.pos;
            let Reader::File(file) = input.reader else {
                return Ok(Vec::new());
            };
            input = Input {
                reader: Reader::Inflated(Box::new(flate2::bufread::DeflateDecoder::new(file))),
                pos: 0,
                end: decoded_bound(left, true),
            };
            Encoding::ExplicitLittle
        }
        // Explicit VR little endian, and the encapsulated (compressed) syntaxes, whose data
        // sets are explicit VR little endian too.
        _ => Encoding::ExplicitLittle,
    };
    let mut walk = Walk::new(path, encoding);
    walk.data_set(&mut input)?;
    walk.finish(file_len);
    Ok(if matches!(input.reader, Reader::File(_)) {
        walk.cuts
    } else {
        Vec::new()
    })
}

#[derive(Clone, Copy, PartialEq)]
enum Encoding {
    ImplicitLittle,
    ExplicitLittle,
    ExplicitBig,
}

#[derive(Clone, Copy)]
struct Header {
    tag: (u16, u16),
    vr: [u8; 2],
    len: u32,
}

enum Reader {
    File(BufReader<File>),
    Inflated(Box<flate2::bufread::DeflateDecoder<BufReader<File>>>),
}

/// The bytes being walked, with the position in them and an upper bound of their end.
struct Input {
    reader: Reader,
    pos: u64,
    end: u64,
}

impl Input {
    fn read_exact(&mut self, buf: &mut [u8]) -> io::Result<()> {
        match &mut self.reader {
            Reader::File(r) => r.read_exact(buf)?,
            Reader::Inflated(r) => r.read_exact(buf)?,
        }
        self.pos += buf.len() as u64;
        Ok(())
    }

    fn skip(&mut self, n: u64) -> io::Result<()> {
        if n > self.end.saturating_sub(self.pos) {
            return Err(io::ErrorKind::UnexpectedEof.into());
        }
        match &mut self.reader {
            Reader::File(r) => r.seek_relative(n as i64)?,
            Reader::Inflated(r) => {
                let skipped = io::copy(&mut r.take(n), &mut io::sink())?;
                if skipped < n {
                    return Err(io::ErrorKind::UnexpectedEof.into());
                }
            }
        }
        self.pos += n;
        Ok(())
    }
}

/// An open sequence or item.
struct Open {
    /// Where it ends (`None`: undefined length, ended by a delimiter).
    end: Option<u64>,
    /// A sequence (holding items) rather than an item (holding elements).
    sequence: bool,
    /// An undefined-length UN sequence read in implicit VR: where its header starts, and the
    /// encoding of the data set around it (restored at its end).
    un: Option<(u64, Encoding)>,
}

/// The walk through a data set: open sequences and items, and whether the current undefined
/// length value holds pixel data fragments.
struct Walk<'a> {
    path: &'a Path,
    encoding: Encoding,
    open: Vec<Open>,
    fragments: bool,
    /// The undefined-length UN elements to leave out (see the module's comment).
    cuts: Vec<Range<u64>>,
}

impl<'a> Walk<'a> {
    fn new(path: &'a Path, encoding: Encoding) -> Self {
        Walk {
            path,
            encoding,
            open: Vec::new(),
            fragments: false,
            cuts: Vec::new(),
        }
    }

    /// The end of the data, or a cut in it, ends the walk: reading the file is dicom-rs's job,
    /// and it reports truncation itself.
    fn ended(&self, e: io::Error) -> Result<(), DataError> {
        match e.kind() {
            io::ErrorKind::UnexpectedEof
            | io::ErrorKind::InvalidInput
            | io::ErrorKind::InvalidData => Ok(()),
            _ => Err(DataError::io(self.path, e)),
        }
    }

    fn header(&self, input: &mut Input) -> io::Result<Header> {
        let big = self.encoding == Encoding::ExplicitBig;
        let u16_at = |b: &[u8]| {
            if big {
                u16::from_be_bytes([b[0], b[1]])
            } else {
                u16::from_le_bytes([b[0], b[1]])
            }
        };
        let u32_at = |b: &[u8]| {
            if big {
                u32::from_be_bytes([b[0], b[1], b[2], b[3]])
            } else {
                u32::from_le_bytes([b[0], b[1], b[2], b[3]])
            }
        };
        let mut buf = [0u8; 8];
        input.read_exact(&mut buf)?;
        let tag = (u16_at(&buf[0..2]), u16_at(&buf[2..4]));
        // Items and delimiters have no VR, in every encoding.
        if tag.0 == 0xFFFE {
            return Ok(Header {
                tag,
                vr: *b"  ",
                len: u32_at(&buf[4..8]),
            });
        }
        // Implicit VR: the VR dicom-encoding's decoder gives the tag (OW for pixel and overlay
        // data, else the dictionary's, else UN), so that values are sized and sequences found
        // as dicom-parser reads them.
        if self.encoding == Encoding::ImplicitLittle {
            let vr = if tag == PIXEL_DATA || (tag.0 >> 8 == 0x60 && tag.1 == 0x3000) {
                VR::OW
            } else {
                StandardDataDictionary
                    .by_tag(Tag(tag.0, tag.1))
                    .map_or(VR::UN, |entry| entry.vr.relaxed())
            };
            return Ok(Header {
                tag,
                vr: vr.to_bytes(),
                len: u32_at(&buf[4..8]),
            });
        }
        let vr = [buf[4], buf[5]];
        // As dicom-encoding reads it: these VRs have a 16-bit length, all others (unknown ones
        // included) two reserved bytes and a 32-bit length.
        const SHORT: [&[u8; 2]; 21] = [
            b"AE", b"AS", b"AT", b"CS", b"DA", b"DS", b"DT", b"FL", b"FD", b"IS", b"LO", b"LT",
            b"PN", b"SH", b"SL", b"SS", b"ST", b"TM", b"UI", b"UL", b"US",
        ];
        let len = if SHORT.contains(&&vr) {
            u16_at(&buf[6..8]) as u32
        } else {
            let mut long = [0u8; 4];
            input.read_exact(&mut long)?;
            u32_at(&long)
        };
        Ok(Header { tag, vr, len })
    }

    fn check_length(&self, input: &Input, header: Header) -> Result<(), DataError> {
        let left = input.end.saturating_sub(input.pos);
        if header.len != UNDEFINED && u64::from(header.len) > left {
            let (group, element) = header.tag;
            return Err(DataError::format(
                self.path,
                format!(
                    "unreadable DICOM file: element ({group:04X},{element:04X}) declares {} \
                     bytes, more than the {left} left in the file",
                    header.len
                ),
            ));
        }
        // dicom-parser reads binary numbers as whole values only: a length that is not a
        // multiple of the value size leaves the rest unread, and it then takes value bytes for
        // the next element's header (lengths of gigabytes from a few bytes). No reader can
        // use such an element (pydicom fails to unpack it too): say so here.
        let size = match &header.vr {
            b"SS" | b"US" | b"OW" => 2,
            b"FL" | b"SL" | b"UL" | b"AT" | b"OF" | b"OL" => 4,
            b"FD" | b"SV" | b"UV" | b"OD" | b"OV" => 8,
            _ => 1,
        };
        if header.len != UNDEFINED && !header.len.is_multiple_of(size) {
            let (group, element) = header.tag;
            return Err(DataError::format(
                self.path,
                format!(
                    "unreadable DICOM file: element ({group:04X},{element:04X}) of VR {} has \
                     {} bytes, not a multiple of its {size}-byte values",
                    String::from_utf8_lossy(&header.vr),
                    header.len
                ),
            ));
        }
        Ok(())
    }

    fn open(&mut self, input: &Input, len: u32, sequence: bool) -> Result<(), DataError> {
        self.open_with(input, len, sequence, None)
    }

    fn open_with(
        &mut self,
        input: &Input,
        len: u32,
        sequence: bool,
        un: Option<(u64, Encoding)>,
    ) -> Result<(), DataError> {
        if self.open.len() >= MAX_DEPTH {
            return Err(DataError::unsupported(
                self.path,
                format!("DICOM sequences nested more than {MAX_DEPTH} deep"),
            ));
        }
        self.open.push(Open {
            end: (len != UNDEFINED).then(|| input.pos + u64::from(len)),
            sequence,
            un,
        });
        Ok(())
    }

    /// Closes the innermost open sequence or item; the end of an undefined-length UN sequence
    /// restores the encoding around it and cuts it.
    fn close(&mut self, input: &Input) {
        if let Some(Open {
            un: Some((start, encoding)),
            ..
        }) = self.open.pop()
        {
            self.encoding = encoding;
            self.cuts.push(start..input.pos);
        }
    }

    /// After the walk: an undefined-length UN sequence still open (the file ends inside it) is
    /// cut to the end of the file, which dicom-parser would otherwise read in the wrong VR
    /// encoding, unchecked.
    fn finish(&mut self, end: u64) {
        if let Some(&Open {
            un: Some((start, _)),
            ..
        }) = self.open.iter().find(|o| o.un.is_some())
        {
            self.cuts.push(start..end);
        }
    }

    fn data_set(&mut self, input: &mut Input) -> Result<(), DataError> {
        loop {
            // Close the defined-length sequences and items that end here.
            while let Some(&Open { end: Some(end), .. }) = self.open.last() {
                if input.pos < end {
                    break;
                }
                self.close(input);
            }
            let start = input.pos;
            let header = match self.header(input) {
                Ok(h) => h,
                Err(e) => return self.ended(e),
            };
            // A sequence holds items only (PS3.5 7.5); dicom-parser's recovery from anything
            // else is not modelled here, and it once allocated a 4 GB value after such a header.
            if !self.fragments
                && matches!(self.open.last(), Some(Open { sequence: true, .. }))
                && !matches!(header.tag, ITEM | SEQUENCE_END)
            {
                let (group, element) = header.tag;
                return Err(DataError::format(
                    self.path,
                    format!(
                        "unreadable DICOM file: element ({group:04X},{element:04X}) inside a \
                         sequence where an item should start"
                    ),
                ));
            }
            // Delimiters have no value (their length is not used); everything else is read.
            if !matches!(header.tag, ITEM_END | SEQUENCE_END) {
                self.check_length(input, header)?;
            }
            let skip = match header.tag {
                ITEM if self.fragments => true,
                ITEM => {
                    self.open(input, header.len, false)?;
                    false
                }
                ITEM_END => {
                    if let Some(Open {
                        end: None,
                        sequence: false,
                        ..
                    }) = self.open.last()
                    {
                        self.close(input);
                    }
                    false
                }
                SEQUENCE_END => {
                    if self.fragments {
                        self.fragments = false;
                    } else if let Some(Open {
                        end: None,
                        sequence: true,
                        ..
                    }) = self.open.last()
                    {
                        self.close(input);
                    }
                    false
                }
                _ if header.len == UNDEFINED => {
                    if header.tag == PIXEL_DATA {
                        self.fragments = true;
                    } else if &header.vr == b"UN"
                        && self.encoding != Encoding::ImplicitLittle
                        && self.open.iter().all(|o| o.end.is_none())
                    {
                        // Only where it can be cut (nothing around it has a defined length the
                        // cut would make wrong); elsewhere walked as dicom-parser reads it.
                        let around = self.encoding;
                        self.open_with(input, header.len, true, Some((start, around)))?;
                        self.encoding = Encoding::ImplicitLittle;
                    } else {
                        // dicom-parser reads every other undefined-length element (an OB or UN
                        // too, whatever its VR) as a sequence of data set items: walk it so.
                        self.open(input, header.len, true)?;
                    }
                    false
                }
                _ if &header.vr == b"SQ" => {
                    self.open(input, header.len, true)?;
                    false
                }
                _ => true,
            };
            if skip && let Err(e) = input.skip(header.len.into()) {
                return self.ended(e);
            }
        }
    }
}

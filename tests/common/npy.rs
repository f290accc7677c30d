//! Reads back the `.npy` files `hatchery render --dump` writes (little-endian f32, format 1.0),
//! so the CLI tests can check shapes and values without numpy.

use hatchery_nodes::export::Array;
use std::path::Path;

/// The array in `path`. Errors (as text, for the test's failure message): not a version 1.0
/// f32 file, a header or shape that does not parse, or data shorter or longer than the shape.
pub fn read_npy(path: &Path) -> Result<Array, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    if bytes.len() < 10 || &bytes[..8] != b"\x93NUMPY\x01\x00" {
        return Err("not a version 1.0 .npy file".into());
    }
    let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let header = bytes.get(10..10 + len).ok_or("the header is cut off")?;
    let header = std::str::from_utf8(header).map_err(|e| e.to_string())?;
    if !header.contains("'descr': '<f4'") {
        return Err("only little-endian f32 arrays are read".into());
    }
    let shape_text = header
        .split("'shape': (")
        .nth(1)
        .and_then(|s| s.split(')').next())
        .ok_or("no shape")?;
    let shape: Vec<usize> = shape_text
        .split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|s| s.trim().parse().map_err(|_| "bad shape"))
        .collect::<Result<_, _>>()?;
    let body = &bytes[10 + len..];
    if body.len() % 4 != 0 || body.len() / 4 != shape.iter().product::<usize>() {
        return Err("data length does not match the shape".into());
    }
    let data = body
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    Ok(Array { shape, data })
}

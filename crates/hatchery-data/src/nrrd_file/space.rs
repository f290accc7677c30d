//! The NRRD geometry: which axes are spatial, `space directions`/`space origin` in the file's
//! `space` turned into RAS+, and the `spacings`/`axis mins` fallback. Frame rules were checked
//! against ITK's NrrdImageIO (through SimpleITK) reading the same headers.

use super::{Header, list, parse};
use crate::DataError;
use crate::geometry::Geometry;

use std::path::Path;

/// Which three axes are spatial; for 4-D files also (elements before the other axis, its size)
/// and a note when more than one volume is there.
pub(super) type Axes = ([usize; 3], (usize, usize), Option<String>);

pub(super) fn spatial_axes(
    path: &Path,
    sizes: &[u64],
    kinds: Option<&[String]>,
    directions: Option<&[Option<[f64; 3]>]>,
) -> Result<Axes, DataError> {
    // Unknown kinds (`???`, `none`) say nothing either way.
    let non_spatial = |k: &str| !matches!(k, "domain" | "space" | "???" | "none" | "unknown");
    if sizes.len() == 3 {
        if let Some(k) = kinds.and_then(|k| k.iter().find(|k| non_spatial(k))) {
            return Err(DataError::unsupported(
                path,
                format!("a 3-D file with a `{k}` axis is not a scalar volume"),
            ));
        }
        return Ok(([0, 1, 2], (1, 1), None));
    }
    let only = |found: Vec<usize>| {
        if found.len() == 1 {
            Some(found[0])
        } else {
            None
        }
    };
    // The space directions decide when given; else the kinds, else an axis of size 1.
    let other = match directions {
        Some(d) => only((0..4).filter(|&a| d[a].is_none()).collect()),
        None => kinds
            .and_then(|k| only((0..4).filter(|&a| non_spatial(&k[a])).collect()))
            .or_else(|| (0..4).find(|&a| sizes[a] == 1)),
    };
    let Some(other) = other else {
        return Err(DataError::format(
            path,
            "4-D file: cannot tell which axis is not spatial (need one `none` space direction, \
             one non-domain kind, or one axis of size 1)",
        ));
    };
    let size = sizes[other] as usize;
    let kind = kinds.map_or("???", |k| k[other].as_str());
    let note = if size == 1 {
        None
    } else if kind == "list" || kind == "time" {
        Some(format!(
            "first of {size} volumes along axis {other} ({kind})"
        ))
    } else {
        return Err(DataError::unsupported(
            path,
            format!(
                "axis {other} holds {size} values per voxel (kind `{kind}`); only scalar volumes \
                 are read, or the first volume of a `list` or `time` axis"
            ),
        ));
    };
    let spatial: Vec<usize> = (0..4).filter(|&a| a != other).collect();
    let inner = sizes[..other].iter().product::<u64>() as usize;
    Ok(([spatial[0], spatial[1], spatial[2]], (inner, size), note))
}

/// `space directions`: one `(x,y,z)` or `none` per axis.
pub(super) fn space_directions(
    path: &Path,
    value: &str,
    dimension: usize,
) -> Result<Vec<Option<[f64; 3]>>, DataError> {
    let bad = || DataError::format(path, format!("bad space directions `{value}`"));
    let mut out = Vec::new();
    let mut rest = value.trim();
    while !rest.is_empty() {
        if let Some(after) = rest.strip_prefix("none") {
            out.push(None);
            rest = after.trim_start();
        } else {
            let end = rest.find(')').ok_or_else(bad)?;
            out.push(Some(vector(path, "space directions", &rest[..=end])?));
            rest = rest[end + 1..].trim_start();
        }
    }
    if out.len() != dimension {
        return Err(bad());
    }
    Ok(out)
}

/// A `(x,y,z)` vector.
fn vector(path: &Path, field: &str, text: &str) -> Result<[f64; 3], DataError> {
    let bad = || DataError::format(path, format!("bad {field} vector `{text}`"));
    let inner = text
        .trim()
        .strip_prefix('(')
        .and_then(|t| t.strip_suffix(')'))
        .ok_or_else(bad)?;
    let v: Vec<f64> = inner
        .split(',')
        .map(|c| c.trim().parse::<f64>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    match v[..] {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok([x, y, z]),
        [_, _, _] => Err(bad()),
        _ => Err(DataError::unsupported(
            path,
            format!("{field} `{text}` is not 3-D; only 3-D spaces are supported"),
        )),
    }
}

pub(super) fn geometry(
    path: &Path,
    h: &Header,
    dimension: usize,
    spatial: &[usize; 3],
    directions: Option<&[Option<[f64; 3]>]>,
) -> Result<(Geometry, String), DataError> {
    // Row signs that take the file's space to RAS+.
    let space = h.get("space");
    let (flip, frame) = match space.map(str::to_ascii_lowercase).as_deref() {
        Some("right-anterior-superior" | "ras") => ([1.0, 1.0, 1.0], "right-anterior-superior"),
        Some("left-posterior-superior" | "lps") => ([-1.0, -1.0, 1.0], "left-posterior-superior"),
        Some("left-anterior-superior" | "las") => ([-1.0, 1.0, 1.0], "left-anterior-superior"),
        Some("3d-right-handed" | "scanner-xyz") => ([1.0; 3], "3D-right-handed, taken as given"),
        Some(_) => {
            return Err(DataError::unsupported(
                path,
                format!(
                    "space `{}` is not supported (RAS, LPS, LAS, 3D-right-handed are)",
                    space.unwrap_or_default()
                ),
            ));
        }
        None => match h.get("spacedimension") {
            Some(d) if parse::<usize>(path, "space dimension", d)? == 3 => {
                ([1.0; 3], "space dimension 3, taken as given")
            }
            Some(d) => {
                return Err(DataError::unsupported(path, format!("space dimension {d}")));
            }
            None => ([1.0; 3], ""),
        },
    };
    let rows = |cols: [[f64; 3]; 3], origin: [f64; 3]| -> [[f64; 4]; 3] {
        std::array::from_fn(|r| {
            let f = flip[r];
            [
                f * cols[0][r],
                f * cols[1][r],
                f * cols[2][r],
                f * origin[r],
            ]
        })
    };
    let in_file = |e: DataError| e.in_file(path);
    if let Some(directions) = directions {
        let mut cols = [[0.0; 3]; 3];
        for (c, &axis) in spatial.iter().enumerate() {
            cols[c] = directions[axis].ok_or_else(|| {
                DataError::format(
                    path,
                    format!("spatial axis {axis} has space direction `none`"),
                )
            })?;
        }
        let origin = match h.get("spaceorigin") {
            Some(o) => vector(path, "space origin", o)?,
            None => [0.0; 3],
        };
        let g = Geometry::from_affine(rows(cols, origin)).map_err(in_file)?;
        let frame = if frame.is_empty() {
            "no space, taken as given"
        } else {
            frame
        };
        return Ok((g, format!("NRRD space directions/space origin ({frame})")));
    }
    if !frame.is_empty() {
        return Err(DataError::format(
            path,
            "`space` or `space dimension` is given without `space directions`",
        ));
    }
    // Per-axis fields; NaN ("nan") marks an axis without a value.
    let per_axis = |name: &str| -> Result<Option<Vec<f64>>, DataError> {
        let Some(v) = h.get(name) else {
            return Ok(None);
        };
        let values: Vec<f64> = list(path, name, v)?;
        if values.len() != dimension {
            return Err(DataError::format(
                path,
                format!("`{name}` needs a value per axis"),
            ));
        }
        Ok(Some(values))
    };
    let spacings = per_axis("spacings")?;
    let mins = per_axis("axismins")?;
    let centers: Option<Vec<String>> = h.get("centers").or(h.get("centerings")).map(|c| {
        c.split_whitespace()
            .map(|s| s.to_ascii_lowercase())
            .collect()
    });
    let mut cols = [[0.0; 3]; 3];
    let mut origin = [0.0; 3];
    for (c, &axis) in spatial.iter().enumerate() {
        let value = |v: &Option<Vec<f64>>| v.as_ref().and_then(|v| v.get(axis).copied());
        let s = value(&spacings).filter(|s| s.is_finite()).unwrap_or(1.0);
        cols[c][c] = s;
        if let Some(min) = value(&mins).filter(|m| m.is_finite()) {
            let node = centers
                .as_ref()
                .and_then(|c| c.get(axis))
                .is_some_and(|c| c == "node");
            origin[c] = if node { min } else { min + s / 2.0 };
        }
    }
    let g = Geometry::from_affine(rows(cols, origin)).map_err(in_file)?;
    let note = if spacings.is_some() || mins.is_some() {
        "NRRD spacings/axis mins (no space, axis-aligned)"
    } else {
        "no NRRD space or spacing fields (unit spacing, axis-aligned)"
    };
    Ok((g, note.into()))
}

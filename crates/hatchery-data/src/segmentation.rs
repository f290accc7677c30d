//! Segmented volumes: an object-id volume on a grid placed in the world, and its object table
//! (id → name). The tutorial's "tagged volume" (Hadwiger §2.1): ids are never interpolated as
//! numbers; renderers filter each object's binary mask instead (§2.3).

use std::collections::BTreeMap;
use std::path::Path;

use crate::geometry::Geometry;
use crate::voxels::Voxel;
use crate::{DataError, VolumeData};

/// The largest object id (ids are stored as u16; 0 is "no object").
pub const MAX_ID: u32 = u16::MAX as u32;

/// An object-id volume: `dims`, voxel → world `geometry`, one id per voxel (i fastest; 0 =
/// background, no object) and a name for every id present (`objects`, background excluded).
#[derive(Debug, Clone, PartialEq)]
pub struct LabelData {
    pub dims: [u32; 3],
    pub geometry: Geometry,
    pub ids: Vec<u16>,
    pub objects: BTreeMap<u16, String>,
}

impl LabelData {
    /// The voxel-index box `[lo, hi]` (inclusive) around every labelled (non-zero) voxel, or
    /// `None` when the map holds background only.
    pub fn object_voxel_bounds(&self) -> Option<([u32; 3], [u32; 3])> {
        let [nx, ny, _] = self.dims.map(|d| d as usize);
        let mut lo = [u32::MAX; 3];
        let mut hi = [0u32; 3];
        for (i, _) in self.ids.iter().enumerate().filter(|(_, id)| **id != 0) {
            let ijk = [
                (i % nx) as u32,
                ((i / nx) % ny) as u32,
                (i / (nx * ny)) as u32,
            ];
            for a in 0..3 {
                lo[a] = lo[a].min(ijk[a]);
                hi[a] = hi[a].max(ijk[a]);
            }
        }
        (lo[0] != u32::MAX).then_some((lo, hi))
    }

    /// The ids of a volume whose values are object ids (a label map in any volume format).
    /// Errors: a value that is not a whole number in 0..=65535 (naming the first such voxel),
    /// or "no data" (NaN). Names default to "object N".
    pub fn from_volume(volume: &VolumeData) -> Result<Self, DataError> {
        let values = volume.values_f32();
        let mut ids = Vec::with_capacity(values.len());
        for (i, &v) in values.iter().enumerate() {
            if !(v.is_finite() && v >= 0.0 && v <= MAX_ID as f32 && v.fract() == 0.0) {
                let [nx, ny, _] = volume.dims.map(|d| d as usize);
                return Err(DataError::Invalid(format!(
                    "voxel ({}, {}, {}) holds {v}: a label volume holds whole numbers 0–{MAX_ID} \
                     (object ids); threshold a scalar volume with LabelsFromThreshold instead",
                    i % nx,
                    (i / nx) % ny,
                    i / (nx * ny)
                )));
            }
            ids.push(v as u16);
        }
        Ok(Self::new(volume.dims, volume.geometry, ids))
    }

    /// Labels from ids, every id present named "object N".
    pub fn new(dims: [u32; 3], geometry: Geometry, ids: Vec<u16>) -> Self {
        let mut present = vec![false; MAX_ID as usize + 1];
        for &id in &ids {
            present[id as usize] = true;
        }
        let objects = (1..=MAX_ID as usize)
            .filter(|&id| present[id])
            .map(|id| (id as u16, format!("object {id}")))
            .collect();
        LabelData {
            dims,
            geometry,
            ids,
            objects,
        }
    }

    /// Object id at voxel (x, y, z).
    pub fn id(&self, x: u32, y: u32, z: u32) -> u16 {
        let [nx, ny, _] = self.dims;
        self.ids[(x + nx * (y + ny * z)) as usize]
    }

    /// Replaces names from a name table (see [`read_names`]); ids not in the table keep
    /// theirs, names of ids not in the volume are ignored.
    pub fn name_objects(&mut self, names: &BTreeMap<u16, String>) {
        for (id, name) in names {
            if let Some(slot) = self.objects.get_mut(id) {
                slot.clone_from(name);
            }
        }
    }
}

/// Object ids by value intervals: a voxel whose value v lies in `[lo, hi)` of an interval gets
/// its id (the first matching interval wins), others 0. "No data" voxels get 0.
pub fn threshold(volume: &VolumeData, intervals: &[(f32, f32, u16)]) -> LabelData {
    let ids = crate::with_voxels!(&volume.voxels, v => v.iter().map(|x| {
        let x = x.to_f32();
        intervals
            .iter()
            .find(|(lo, hi, _)| x >= *lo && x < *hi)
            .map_or(0, |(_, _, id)| *id)
    }).collect());
    LabelData::new(volume.dims, volume.geometry, ids)
}

/// Object ids by arg-max over probability maps on one grid (e.g. grey and white matter):
/// voxel → id `k + 1` of the map with the largest value if that value is ≥ `floor`, else 0.
/// Errors: no maps, or maps on different grids.
pub fn from_maps(maps: &[&VolumeData], floor: f32) -> Result<LabelData, DataError> {
    let Some(first) = maps.first() else {
        return Err(DataError::Invalid("no probability maps given".into()));
    };
    for (k, m) in maps.iter().enumerate() {
        if m.dims != first.dims {
            return Err(DataError::Invalid(format!(
                "map {} is {:?} voxels, map 1 {:?}: they must share the grid",
                k + 1,
                m.dims,
                first.dims
            )));
        }
    }
    let values: Vec<_> = maps.iter().map(|m| m.values_f32()).collect();
    let ids = (0..first.voxel_count())
        .map(|i| {
            let (best, value) = values
                .iter()
                .enumerate()
                .map(|(k, v)| (k, v[i]))
                .filter(|(_, v)| v.is_finite())
                .fold((0, f32::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a });
            if value >= floor { best as u16 + 1 } else { 0 }
        })
        .collect();
    Ok(LabelData::new(first.dims, first.geometry, ids))
}

/// Reads object names: a CSV/TSV/space-separated table `id,name` (a header line and `#`
/// comments are skipped), or an ITK-SNAP label description file (`IDX R G B A VIS MSH
/// "LABEL"` lines). Errors name the file and line.
pub fn read_names(path: &Path) -> Result<BTreeMap<u16, String>, DataError> {
    let bytes = crate::files::read(path).map_err(|e| DataError::io(path, e))?;
    // The error std::fs::read_to_string gives.
    let text = String::from_utf8(bytes).map_err(|_| {
        let invalid = std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            "stream did not contain valid UTF-8",
        );
        DataError::io(path, invalid)
    })?;
    let mut names = BTreeMap::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        // ITK-SNAP: the name is the quoted last field.
        let (first, name) = if let (Some(a), Some(b)) = (line.find('"'), line.rfind('"')) {
            let first = line.split_whitespace().next().unwrap_or("");
            (first, line[a + 1..b.max(a + 1)].to_string())
        } else {
            let mut parts = line.splitn(2, [',', '\t', ';', ' ']);
            let first = parts.next().unwrap_or("").trim();
            (first, parts.next().unwrap_or("").trim().to_string())
        };
        let Ok(id) = first.parse::<u32>() else {
            if names.is_empty() {
                continue; // a header line
            }
            return Err(DataError::format(
                path,
                format!("line {}: `{first}` is not an object id", n + 1),
            ));
        };
        if id > MAX_ID {
            return Err(DataError::format(
                path,
                format!("line {}: object id {id} is larger than {MAX_ID}", n + 1),
            ));
        }
        if id > 0 && !name.is_empty() {
            names.insert(id as u16, name);
        }
    }
    Ok(names)
}

/// Object names a NRRD header carries as 3D Slicer writes segmentations (`.seg.nrrd`):
/// `SegmentK_Name:=NAME` with `SegmentK_LabelValue:=ID` (Slicer's default id is K + 1).
/// Empty for other files; reads the header only (up to its blank line, at most 1 MiB).
pub fn nrrd_segment_names(path: &Path) -> Result<BTreeMap<u16, String>, DataError> {
    use std::io::{BufRead, BufReader, Read};
    let file = crate::files::open(path).map_err(|e| DataError::io(path, e))?;
    let mut reader = BufReader::new(file.take(1 << 20));
    let (mut names, mut values) = (BTreeMap::new(), BTreeMap::new());
    let mut line = Vec::new();
    loop {
        line.clear();
        if reader
            .read_until(b'\n', &mut line)
            .map_err(|e| DataError::io(path, e))?
            == 0
        {
            break;
        }
        let text = String::from_utf8_lossy(&line);
        let text = text.trim_end_matches(['\n', '\r']);
        if text.is_empty() {
            break;
        }
        let Some((key, value)) = text.split_once(":=") else {
            continue;
        };
        let Some(rest) = key.strip_prefix("Segment") else {
            continue;
        };
        let Some((k, field)) = rest.split_once('_') else {
            continue;
        };
        let Ok(k) = k.parse::<u32>() else {
            continue;
        };
        match field {
            "Name" => {
                names.insert(k, value.trim().to_string());
            }
            "LabelValue" => {
                if let Ok(v) = value.trim().parse::<u32>() {
                    values.insert(k, v);
                }
            }
            _ => {}
        }
    }
    Ok(names
        .into_iter()
        .filter_map(|(k, name)| {
            let id = values.get(&k).copied().unwrap_or(k + 1);
            (1..=MAX_ID).contains(&id).then_some((id as u16, name))
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slicer_segment_names_come_from_the_nrrd_header() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.seg.nrrd");
        std::fs::write(
            &path,
            "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\
             Segment0_Name:=skin\nSegment0_LabelValue:=1\nSegment1_Name:=bone\n\
             Segment1_LabelValue:=4\nSegment2_Name:=liver\n\n\u{1}\u{1}\u{4}\u{4}\u{0}\u{0}\u{3}\u{3}",
        )
        .unwrap();
        let names = nrrd_segment_names(&path).unwrap();
        assert_eq!(names.get(&1).map(String::as_str), Some("skin"));
        assert_eq!(names.get(&4).map(String::as_str), Some("bone"));
        // No LabelValue: Slicer's default, index + 1.
        assert_eq!(names.get(&3).map(String::as_str), Some("liver"));
    }

    #[test]
    fn name_tables_read_csv_and_itk_snap_and_errors_name_the_line() {
        let dir = tempfile::tempdir().unwrap();
        let csv = dir.path().join("names.csv");
        std::fs::write(&csv, "id,name\n1,skin\n# comment\n4, bone marrow\n").unwrap();
        let names = read_names(&csv).unwrap();
        assert_eq!(names.get(&4).map(String::as_str), Some("bone marrow"));
        let snap = dir.path().join("labels.txt");
        std::fs::write(
            &snap,
            "# ITK-SNAP Label Description File\n    0     0    0    0        0  0  0    \"Clear Label\"\n    7   255    0    0        1  1  1    \"Left ventricle\"\n",
        )
        .unwrap();
        let names = read_names(&snap).unwrap();
        assert_eq!(names.get(&7).map(String::as_str), Some("Left ventricle"));
        assert!(!names.contains_key(&0));
        std::fs::write(&csv, "1,skin\nx,bone\n").unwrap();
        let e = read_names(&csv).unwrap_err().to_string();
        assert!(e.contains("line 2"), "{e}");
    }
}

/// Object names in a list of objects replaced by their ids, so presets can say `liver` where a
/// label map names its objects (issue 25). `text` is split into entries at `separator`; in each
/// entry the part before `key_end` (the whole entry when `None`) is the object: a number or range
/// stays, a name (matched without regard to case and surrounding spaces) becomes its id. Errors:
/// a name no object has, listing the names there are.
pub fn ids_for_names(
    text: &str,
    separator: char,
    key_end: Option<char>,
    objects: &BTreeMap<u16, String>,
) -> Result<String, DataError> {
    let mut out = Vec::new();
    for entry in text.split(separator) {
        let (key, rest) = match key_end.and_then(|k| entry.split_once(k)) {
            Some((key, rest)) => (key, Some(rest)),
            None => (entry, None),
        };
        let word = key.trim();
        let numeric = word.is_empty()
            || word
                .chars()
                .all(|c| c.is_ascii_digit() || c == '-' || c.is_whitespace());
        let key = if numeric {
            key.to_owned()
        } else {
            let id = objects
                .iter()
                .find(|(_, name)| name.trim().eq_ignore_ascii_case(word))
                .map(|(id, _)| *id)
                .ok_or_else(|| {
                    let names: Vec<&str> = objects.values().map(String::as_str).collect();
                    format!(
                        "no object is named `{word}` (the labels name: {})",
                        if names.is_empty() {
                            "none".to_owned()
                        } else {
                            names.join(", ")
                        }
                    )
                })?;
            format!(" {id}")
        };
        out.push(match (rest, key_end) {
            (Some(rest), Some(k)) => format!("{key}{k}{rest}"),
            _ => key,
        });
    }
    Ok(out.join(&separator.to_string()))
}

#[cfg(test)]
mod name_tests {
    use super::*;

    #[test]
    fn names_become_ids_and_unknown_names_list_the_known_ones() {
        let objects: BTreeMap<u16, String> =
            [(10, "liver".to_owned()), (9, "large intestine".to_owned())].into();
        assert_eq!(
            ids_for_names("Liver, 3-4", ',', None, &objects).unwrap(),
            " 10, 3-4"
        );
        assert_eq!(
            ids_for_names(
                "liver: iso iso; large intestine: tone over",
                ';',
                Some(':'),
                &objects
            )
            .unwrap(),
            " 10: iso iso; 9: tone over"
        );
        let e = ids_for_names("spleen", ',', None, &objects)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`spleen`") && e.contains("large intestine, liver"),
            "{e}"
        );
    }
}

//! Annotations (VolumeShop §6.4 in the tutorial): labelled 3-D anchors, written in the graph
//! (`AnnotationList`) or one per object of a segmentation (`AnnotationsFromLabels`). Laid out
//! by `AnnotationLayout` (crate::annotation_layout), drawn by `AnnotationOverlay`, written by
//! `SaveSvg`.

use crate::value::Labels;
use crate::{Ctx, Value};
use glam::Vec3;
use hatchery_annotation::{Anchor, Layout, ProjectedAnchor};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

/// Anchors and, once laid out, where their labels go.
#[derive(Clone)]
pub struct Annotations {
    pub anchors: Vec<Anchor>,
    /// Per anchor, the world-space box of its object (part of the silhouette hull's footprint);
    /// `None`: the anchor point alone.
    pub bounds: Vec<Option<[Vec3; 2]>>,
    /// Set by `AnnotationLayout`.
    pub placed: Option<Arc<Placed>>,
}

/// A layout of the anchors' labels for one view.
pub struct Placed {
    pub layout: Layout,
    /// The anchors in pixels (top-left origin, y down) and window depth.
    pub projected: Vec<ProjectedAnchor>,
    /// The silhouette hull the labels were placed around (pixels).
    pub hull: Vec<glam::Vec2>,
    pub width: u32,
    pub height: u32,
    /// Label text size, pixels.
    pub font_size: f32,
}

impl Annotations {
    /// The layout, or an error naming `port` when the annotations were not laid out.
    pub fn placed(&self, port: &str) -> Result<&Placed, NodeError> {
        self.placed.as_deref().ok_or_else(|| {
            NodeError::at_port(
                port,
                "these annotations are not laid out: pass them through AnnotationLayout first",
            )
        })
    }
}

/// Parses "x y z: text; …" (or one row per line) into anchors; earlier rows get higher
/// priority. Errors name the row.
pub fn parse_anchor_list(text: &str) -> Result<Vec<Anchor>, String> {
    let rows: Vec<&str> = text
        .split([';', '\n'])
        .map(str::trim)
        .filter(|r| !r.is_empty())
        .collect();
    let n = rows.len();
    rows.iter()
        .enumerate()
        .map(|(i, row)| {
            let (position, label) = row
                .split_once(':')
                .ok_or_else(|| format!("row {} `{row}`: expected `x y z: text`", i + 1))?;
            let numbers: Result<Vec<f32>, _> = position
                .split(|c: char| c == ',' || c.is_whitespace())
                .filter(|s| !s.is_empty())
                .map(str::parse::<f32>)
                .collect();
            match numbers {
                Ok(v) if v.len() == 3 && v.iter().all(|x| x.is_finite()) => Ok(Anchor {
                    position: Vec3::new(v[0], v[1], v[2]),
                    text: label.trim().to_owned(),
                    object: 0,
                    priority: (n - i) as f32,
                }),
                Ok(v) if v.len() == 3 => Err(format!(
                    "row {} `{row}`: `{}` has a number too large for 32-bit floats (x y z, \
                     world units, below about 3.4e38)",
                    i + 1,
                    position.trim()
                )),
                _ => Err(format!(
                    "row {} `{row}`: `{}` is not three numbers (x y z, world units)",
                    i + 1,
                    position.trim()
                )),
            }
        })
        .collect()
}

hatchery_graph::node_params! {
    /// Parameters of `AnnotationList`.
    pub struct AnnotationListParams {
        /// "x y z: text; …" in world units
        pub anchors: String = "0 0 0: centre";
    }
}

pub struct AnnotationListNode;

impl Node<Value, Ctx> for AnnotationListNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "AnnotationList",
            category: "Annotation",
            doc: "Labelled anchors written in the graph: \"x y z: text; …\" (world units), one \
                  label per row; earlier rows have higher priority when labels must be left out.",
            inputs: vec![],
            outputs: vec![PortSpec::output(
                "annotations",
                PortType::Annotations,
                "the anchors",
            )],
            params: AnnotationListParams::specs(),
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        _ctx: &mut Ctx,
        _inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let params = AnnotationListParams::read(p)?;
        let anchors = parse_anchor_list(&params.anchors)
            .map_err(|e| NodeError::new(format!("parameter `anchors`: {e}")))?;
        let bounds = vec![None; anchors.len()];
        Ok(vec![Value::Annotations(Arc::new(Annotations {
            anchors,
            bounds,
            placed: None,
        }))])
    }
}

/// Per object id: voxel count, sum of voxel indices, and index bounds.
struct ObjectVoxels {
    count: u64,
    sum: glam::DVec3,
    lo: glam::UVec3,
    hi: glam::UVec3,
}

/// One anchor per object in `ids` that has voxels: at the object's voxel nearest its centroid
/// (so on the object even where it is concave), with the object's world box as bounds.
fn anchors_for(labels: &Labels, ids: &[u16]) -> (Vec<Anchor>, Vec<Option<[Vec3; 2]>>) {
    let l = &labels.data;
    let [nx, ny, _] = l.dims.map(|d| d as usize);
    let mut stats: Vec<Option<ObjectVoxels>> = (0..ids.len()).map(|_| None).collect();
    let mut slot = vec![usize::MAX; u16::MAX as usize + 1];
    for (i, &id) in ids.iter().enumerate() {
        slot[id as usize] = i;
    }
    let voxel = |i: usize| {
        glam::UVec3::new(
            (i % nx) as u32,
            (i / nx % ny) as u32,
            (i / (nx * ny)) as u32,
        )
    };
    for (i, &id) in l.ids.iter().enumerate() {
        let s = slot[id as usize];
        if s == usize::MAX {
            continue;
        }
        let v = voxel(i);
        let entry = stats[s].get_or_insert(ObjectVoxels {
            count: 0,
            sum: glam::DVec3::ZERO,
            lo: v,
            hi: v,
        });
        entry.count += 1;
        entry.sum += v.as_dvec3();
        entry.lo = entry.lo.min(v);
        entry.hi = entry.hi.max(v);
    }
    let total: u64 = stats.iter().flatten().map(|s| s.count).sum();
    let mut anchors = Vec::new();
    let mut bounds = Vec::new();
    for (s, &id) in stats.iter().zip(ids) {
        let Some(s) = s else {
            continue;
        };
        let centroid = (s.sum / s.count as f64).as_vec3();
        // The object's voxel nearest the centroid (searched within its box).
        let mut best = (f32::INFINITY, s.lo);
        for z in s.lo.z..=s.hi.z {
            for y in s.lo.y..=s.hi.y {
                for x in s.lo.x..=s.hi.x {
                    if l.id(x, y, z) != id {
                        continue;
                    }
                    let d =
                        glam::Vec3::new(x as f32, y as f32, z as f32).distance_squared(centroid);
                    if d < best.0 {
                        best = (d, glam::UVec3::new(x, y, z));
                    }
                }
            }
        }
        let world = |v: Vec3| l.geometry.voxel_to_world(v);
        let corners = hatchery_annotation::box_corners(s.lo.as_vec3(), s.hi.as_vec3()).map(world);
        let lo = corners.iter().copied().fold(Vec3::INFINITY, Vec3::min);
        let hi = corners.iter().copied().fold(Vec3::NEG_INFINITY, Vec3::max);
        anchors.push(Anchor {
            position: world(best.1.as_vec3()),
            text: l
                .objects
                .get(&id)
                .cloned()
                .unwrap_or_else(|| format!("object {id}")),
            object: id,
            priority: s.count as f32 / total.max(1) as f32,
        });
        bounds.push(Some([lo, hi]));
    }
    (anchors, bounds)
}

hatchery_graph::node_params! {
    /// Parameters of `AnnotationsFromLabels`.
    pub struct AnnotationsFromLabelsParams {
        /// label ids to annotate, e.g. "10, 13" (empty: the drawn objects, or all)
        pub objects: String = "";
    }
}

pub struct AnnotationsFromLabelsNode;

impl Node<Value, Ctx> for AnnotationsFromLabelsNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "AnnotationsFromLabels",
            category: "Annotation",
            doc: "One anchor per object of a segmentation: at the object's voxel nearest its \
                  centroid (on the object even where it is concave), named after the labels \
                  (or the object table), with the object's box as its part of the silhouette \
                  hull. Objects: those listed in `objects`, else the drawn rows of the `styles` \
                  input, else every object of the labels. Priority: the importance from the \
                  object table, else the object's share of the voxels.",
            inputs: vec![
                PortSpec::input("labels", PortType::Labels, "the segmentation"),
                PortSpec::optional(
                    "styles",
                    PortType::ObjectStyles,
                    "which objects are drawn, their names and importance",
                ),
            ],
            outputs: vec![PortSpec::output(
                "annotations",
                PortType::Annotations,
                "one anchor per object",
            )],
            params: AnnotationsFromLabelsParams::specs(),
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let params = AnnotationsFromLabelsParams::read(p)?;
        let labels = inputs.require("labels")?.labels("labels")?.clone();
        let styles = match inputs.get("styles") {
            Some(v) => Some(v.object_styles("styles")?.clone()),
            None => None,
        };
        let listed = params.objects.trim();
        let ids: Vec<u16> = if !listed.is_empty() {
            let mut ids: Vec<u16> = Vec::new();
            for s in listed
                .split(|c: char| c == ',' || c.is_whitespace())
                .filter(|s| !s.is_empty())
            {
                match s.parse::<u16>() {
                    Ok(id) if id > 0 => {
                        if !ids.contains(&id) {
                            ids.push(id);
                        }
                    }
                    _ => {
                        return Err(NodeError::new(format!(
                            "parameter `objects`: `{s}` is not a label id (1–65535)"
                        )));
                    }
                }
            }
            ids
        } else if let Some(styles) = &styles {
            styles.iter().filter(|s| s.enabled).map(|s| s.id).collect()
        } else {
            labels
                .data
                .objects
                .keys()
                .copied()
                .filter(|&id| id != 0)
                .collect()
        };
        let (mut anchors, bounds) = anchors_for(&labels, &ids);
        let empty: Vec<String> = ids
            .iter()
            .filter(|id| !anchors.iter().any(|a| a.object == **id))
            .map(|id| id.to_string())
            .collect();
        if !empty.is_empty() {
            ctx.warn(format!(
                "objects {} have no voxel in the labels: no anchor for them",
                empty.join(", ")
            ));
        }
        if let Some(styles) = &styles {
            for a in &mut anchors {
                if let Some(s) = styles.iter().find(|s| s.id == a.object) {
                    a.priority = s.importance;
                }
            }
        }
        Ok(vec![Value::Annotations(Arc::new(Annotations {
            anchors,
            bounds,
            placed: None,
        }))])
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(AnnotationListNode)
        .node(AnnotationsFromLabelsNode);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn anchor_lists_parse_and_name_the_bad_row() {
        let a = parse_anchor_list("1 2 3: piston; 4, 5, 6: cylinder bore\n0 0 -1.5: oil").unwrap();
        assert_eq!(a.len(), 3);
        assert_eq!(a[1].text, "cylinder bore");
        assert_eq!(a[2].position, Vec3::new(0.0, 0.0, -1.5));
        assert!(a[0].priority > a[1].priority && a[1].priority > a[2].priority);
        let e = parse_anchor_list("1 2 3: ok; 1 2: short").unwrap_err();
        assert!(e.contains("row 2") && e.contains("three numbers"), "{e}");
        let e = parse_anchor_list("0 0 0: a; 1e40 0 0: b").unwrap_err();
        assert!(e.contains("row 2") && e.contains("too large"), "{e}");
        assert!(parse_anchor_list("no colon").unwrap_err().contains("row 1"));
    }
}

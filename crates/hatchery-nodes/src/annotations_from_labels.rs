//! `AnnotationsFromLabels`: one annotation per labelled object, at its centre.

use crate::annotations::Annotations;
use crate::annotations::anchors_for;
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

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
    k.node(AnnotationsFromLabelsNode);
}

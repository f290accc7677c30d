//! `AnnotationList`: annotations at world points written in the graph.

use crate::annotations::Annotations;
use crate::annotations::parse_anchor_list;
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

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

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(AnnotationListNode);
}

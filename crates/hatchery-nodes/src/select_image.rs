//! `SelectImage`: passes one of several images through, chosen by a parameter (alternative styles
//! in one preset, switched with `--set node.select=N` or in the editor).

use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};

const INPUTS: [&str; 4] = ["image1", "image2", "image3", "image4"];

hatchery_graph::node_params! {
    /// The parameters of `SelectImage`.
    pub struct SelectImageParams {
        /// which input to pass through
        pub select: i64 = 1, range(1, 4);
    }
}

pub struct SelectImageNode;

impl Node<Value, Ctx> for SelectImageNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "SelectImage",
            category: "Compositing",
            doc: "Outputs input image number `select` (1–4) unchanged; the others are still computed if \
                  connected. For presets that offer alternative styles.",
            inputs: INPUTS
                .iter()
                .map(|name| PortSpec::optional(name, PortType::Image, "an alternative"))
                .collect(),
            outputs: vec![PortSpec::output(
                "image",
                PortType::Image,
                "the selected image",
            )],
            params: SelectImageParams::specs(),
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        _ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let port = INPUTS[(SelectImageParams::read(p)?.select - 1).clamp(0, 3) as usize];
        let value = inputs
            .get(port)
            .ok_or_else(|| NodeError::at_port(port, "the selected input is not connected"))?;
        value.image(port)?;
        Ok(vec![value.clone()])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(SelectImageNode);
}

//! `StyleTransferFunction`: per data value a style and a uniform opacity α_u (Bruckner & Gröller
//! 2007, §3.2 and §4.1: tft, ift and sft lookups, interpolation between whole styles).

use crate::value::TransferFunction;
use crate::{Ctx, Value};
use hatchery_data::style::StyleTransferFunction;
use hatchery_graph::{
    Widget,
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::node_params! {
    /// Parameters of `StyleTransferFunction`.
    pub struct StyleTransferFunctionParams {
        /// value: style opacity; … (every object); a value may be relative to the connected volume:
        /// "percentile(P)", "range(F)", "otsu"
        pub nodes: String = "40: 0 0.02; 90: 1 0.3; 160: 2 1.0", widget(Widget::StyleTransferFunction);
        /// per object of a label volume (§4.2): "LABEL = value: style opacity; … | LABEL = …"
        pub label_nodes: String = "";
    }
}

pub struct StyleTransferFunctionNode;

impl Node<Value, Ctx> for StyleTransferFunctionNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "StyleTransferFunction",
            category: "Volume",
            doc: "A style transfer function: nodes \"value: style opacity; …\" (style = index into the \
                  StyleSet, opacity = uniform α_u). Between two nodes the style index and α_u are \
                  interpolated, so whole styles blend uniformly for every normal; a style may appear \
                  several times (the index function ift of §4.1). `label_nodes` adds the 2-D variant of \
                  §4.2 (value × object): rows for chosen labels of the label volume given to \
                  Raycast's `labels`. Connect to Raycast's `tf`.",
            inputs: vec![
                PortSpec::input("styles", PortType::StyleSet, "the lit-sphere styles"),
                PortSpec::optional(
                    "volume",
                    PortType::Volume,
                    "resolves node values given relative to the data (\"range(0.3): 1 0.5\")",
                ),
            ],
            outputs: vec![PortSpec::output(
                "tf",
                PortType::TransferFunction,
                "the style transfer function",
            )],
            params: StyleTransferFunctionParams::specs(),
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
        let params = StyleTransferFunctionParams::read(p)?;
        let styles = inputs.require("styles")?.style_set("styles")?.clone();
        let volume = match inputs.get("volume") {
            Some(v) => Some(v.volume("volume")?.clone()),
            None => None,
        };
        let text = crate::relative::resolve_point_values(
            params.nodes.as_str(),
            volume.as_ref().map(|v| &*v.data),
        )
        .map_err(|e| NodeError::new(format!("parameter `nodes`: {e}")))?;
        if text != params.nodes.as_str() {
            ctx.note_resolved("nodes", text.clone());
        }
        let nodes = StyleTransferFunction::parse(&text)
            .map_err(|e| NodeError::new(format!("parameter `nodes`: {e}")))?;
        let function = StyleTransferFunction::from_nodes(&nodes, styles.maps.len())
            .map_err(|e| NodeError::new(format!("parameter `nodes`: {e}")))?;
        let mut per_label = Vec::new();
        for row in params
            .label_nodes
            .split('|')
            .map(str::trim)
            .filter(|r| !r.is_empty())
        {
            let bad = |m: &dyn std::fmt::Display| NodeError::new(format!("parameter `label_nodes`, `{row}`: {m}"));
            let (label, nodes) = row
                .split_once('=')
                .ok_or_else(|| bad(&"expected LABEL = nodes"))?;
            let label: i64 = label
                .trim()
                .parse()
                .map_err(|_| bad(&format!("`{}` is not a label number", label.trim())))?;
            let nodes = StyleTransferFunction::parse(nodes).map_err(|e| bad(&e))?;
            per_label.push((
                label,
                StyleTransferFunction::from_nodes(&nodes, styles.maps.len()).map_err(|e| bad(&e))?,
            ));
        }
        Ok(vec![Value::TransferFunction(Arc::new(
            TransferFunction::Style {
                function,
                per_label,
                styles,
            },
        ))])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(StyleTransferFunctionNode);
}

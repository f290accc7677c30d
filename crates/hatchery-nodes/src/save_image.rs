//! `SaveImage`: writes an Image to a PNG file.

use crate::{Ctx, Value, export};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};

hatchery_graph::node_params! {
    /// The parameters of `SaveImage`.
    pub struct SaveImageParams {
        /// the PNG file to write
        pub path: std::path::PathBuf = "hatchery.png";
    }
}

pub struct SaveImageNode;

impl Node<Value, Ctx> for SaveImageNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "SaveImage",
            category: "Output",
            doc: "Writes its image to a PNG file (8-bit RGBA, straight alpha). `hatchery render -o` \
                  replaces the path. Relative paths are relative to the graph file's folder.",
            inputs: vec![PortSpec::input(
                "image",
                PortType::Image,
                "the picture to write",
            )],
            outputs: vec![],
            params: SaveImageParams::specs(),
            frame_dependent: true,
            sink: true,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let image = inputs.require("image")?.image("image")?;
        let path = SaveImageParams::read(p)?.path;
        let pixels = ctx
            .gpu
            .read_texture(&image.texture)
            .map_err(|e| NodeError::new(e.to_string()))?;
        export::write_png(&export::image_to_rgba8(&pixels), &path)
            .map_err(|e| NodeError::new(format!("cannot write {}: {e}", path.display())))?;
        tracing::info!(path = %path.display(), "image written");
        Ok(vec![])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(SaveImageNode);
}

//! What a fusable image-space node kind is: a *stage* of a fused pass ([`crate::fused_pass`]),
//! a WGSL function with its arguments, declared with `Kinds::image_stage`.

use crate::{Ctx, Value};
use hatchery_graph::fusion::Source;
use hatchery_graph::{NodeError, Params, PortType};

/// One argument of a stage's WGSL function, after `p` (the pixel) and the node's uniform block.
pub enum Arg {
    /// An input port read at the pixel: its texel (`vec4<f32>`; a G-buffer port gives its depth
    /// `f32` and its normal `vec4<f32>`), or the value an earlier stage computed for it;
    /// `vec4<f32>(0.0)` where an optional port is not connected.
    At(&'static str),
    /// Both textures of a G-buffer input port (`texture_depth_2d`, `texture_2d<f32>`), read
    /// anywhere; such a port is not pointwise, so its value always comes from outside the pass.
    Textures(&'static str),
    /// A G-buffer input port read at the pixel for its normal only: `1.0` for the depth, then the
    /// normal (`vec4<f32>`) — one texture read fewer where the stage ignores the depth.
    NormalAt(&'static str),
    /// A G-buffer input port's depth at the pixel only (`f32`; 1 where nothing is connected).
    DepthAt(&'static str),
    /// A texture of the node's own (a pattern), read anywhere: `texture_2d<f32>`.
    Texture(wgpu::Texture),
    /// A constant known when the pass is built, as WGSL text: the compiler folds it, one
    /// pipeline per value.
    Constant(String),
}

/// What a node contributes to a fused pass: `library` (a program of [`crate::shaders`], without
/// entry point) defines `function(p: vec2<i32>, u: <uniform struct>, args…) -> vec4<f32>` (no
/// `u` without a uniform); its result is the node's one output, a Mask (in `.r`) or an Image.
pub struct Stage {
    pub library: &'static str,
    pub function: &'static str,
    /// The WGSL struct's name and the bytes of the node's block (a `uniform_block!`).
    pub uniform: Option<(&'static str, Vec<u8>)>,
    pub args: Vec<Arg>,
    pub output: PortType,
}

/// A node kind that runs as a stage of a fused pass. Declared with
/// [`crate::kinds::Kinds::image_stage`], whose one `Node` implementation runs it alone with
/// [`execute`].
pub trait Fusable: Sync {
    /// The kind's schema.
    fn schema(&self) -> hatchery_graph::NodeSchema;
    /// Per input port, in schema order: whether the stage reads it only at the pixel it writes.
    fn pointwise(&self) -> &'static [bool];
    /// Textures the stage binds besides its inputs' (its `Arg::Texture`s).
    fn own_textures(&self) -> u32 {
        0
    }
    /// The stage for `p`. `inputs` holds the values that come from outside the pass (G-buffers,
    /// lights); those computed by earlier stages are only known to be connected.
    fn stage(&self, ctx: &mut Ctx, inputs: &StageInputs, p: &Params) -> Result<Stage, NodeError>;
}

/// A stage's inputs: values from outside the pass, and which ports are connected at all.
pub struct StageInputs<'a> {
    pub(crate) names: Vec<&'static str>,
    pub(crate) sources: &'a [Source<Value>],
}

impl StageInputs<'_> {
    fn source(&self, port: &str) -> Option<&Source<Value>> {
        let i = self.names.iter().position(|n| *n == port)?;
        self.sources.get(i)
    }
    /// Whether anything is connected to `port`.
    pub fn connected(&self, port: &str) -> bool {
        !matches!(self.source(port), None | Some(Source::Absent))
    }
    /// The value on `port`, which must come from outside the pass (not a pointwise port).
    pub fn require(&self, port: &str) -> Result<&Value, NodeError> {
        match self.source(port) {
            Some(Source::External(value)) => Ok(value),
            Some(Source::Member { .. }) => Err(NodeError::at_port(
                port,
                "computed inside a fused pass, where only its pixel is known",
            )),
            _ => Err(NodeError::at_port(port, "input is not connected")),
        }
    }
}

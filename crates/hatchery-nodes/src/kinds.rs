//! What the modules declare (issue 29): each module that has node kinds, shader programs or
//! uniform blocks says so in one `pub fn declare(k: &mut Kinds)`, and lib.rs lists the module
//! once. The registry, the program list and the uniform list are all built from those calls, so
//! a kind is declared in its own module only.

use crate::fused_pass::{self, Fusable};
use crate::uniforms::UniformLayout;
use crate::{Ctx, Registry, Value};
use hatchery_graph::executor::Node;
use hatchery_graph::{NodeError, NodeInputs, NodeSchema, Params};
use std::collections::BTreeMap;

/// A compilable shader program: its name (used in error messages and by [`crate::shaders::source`])
/// and its parts, (file name, WGSL text), concatenated in order (WGSL has no includes).
pub type Program = (&'static str, Vec<(&'static str, &'static str)>);

/// Everything the declaring modules contribute.
#[derive(Default)]
pub struct Kinds {
    pub(crate) registry: Registry,
    pub(crate) stages: Vec<&'static dyn Fusable>,
    pub(crate) programs: Vec<Program>,
    pub(crate) uniforms: Vec<UniformLayout>,
    /// (kind, the file of the `declare` that declared it).
    files: Vec<(&'static str, &'static str)>,
    /// (the file of the `declare` that declared a program, the program's own part).
    program_files: Vec<(&'static str, &'static str)>,
}

/// Where a node kind's code is: the module file that declares it and the shader files of the
/// programs that module declares (their own parts; shared parts are not listed).
#[derive(Clone, Debug, PartialEq)]
pub struct KindSource {
    pub file: &'static str,
    pub shaders: Vec<&'static str>,
}

impl Kinds {
    /// Every module's declarations.
    pub fn all() -> Kinds {
        let mut kinds = Kinds::default();
        for declare in crate::DECLARE {
            declare(&mut kinds);
        }
        kinds
    }

    /// Where each kind's code is, by kind (for docs/nodes.md).
    pub fn sources(&self) -> BTreeMap<&'static str, KindSource> {
        self.files
            .iter()
            .map(|&(kind, file)| {
                let shaders = self
                    .program_files
                    .iter()
                    .filter(|(f, _)| *f == file)
                    .map(|&(_, shader)| shader)
                    .collect();
                (kind, KindSource { file, shaders })
            })
            .collect()
    }

    /// A node kind.
    #[track_caller]
    pub fn node(&mut self, node: impl Node<Value, Ctx> + 'static) -> &mut Self {
        let file = std::panic::Location::caller().file();
        self.files.push((node.schema().kind, file));
        self.registry.register(node);
        self
    }

    /// An image-space kind that runs as a stage of a fused pass ([`crate::fused_pass`]): its
    /// node (whose `execute` runs it as a pass of its own) and its stage.
    #[track_caller]
    pub fn image_stage(&mut self, stage: &'static dyn Fusable) -> &mut Self {
        let file = std::panic::Location::caller().file();
        self.files.push((stage.schema().kind, file));
        self.registry.register(ImageStage(stage));
        self.stages.push(stage);
        self
    }

    /// A shader program; its last part is the declaring module's own shader.
    #[track_caller]
    pub fn program(
        &mut self,
        name: &'static str,
        parts: Vec<(&'static str, &'static str)>,
    ) -> &mut Self {
        let file = std::panic::Location::caller().file();
        if let Some(&(own, _)) = parts.last() {
            self.program_files.push((file, own));
        }
        self.programs.push((name, parts));
        self
    }

    /// A uniform block (checked against its program's WGSL struct by tests/shaders.rs).
    pub fn uniform(&mut self, layout: UniformLayout) -> &mut Self {
        self.uniforms.push(layout);
        self
    }

    /// A uniform block that `program` uses as well as the program it was declared for (a
    /// shared block: the camera of the mesh shaders, the ray casters' `Ray`).
    pub fn uniform_in(&mut self, program: &'static str, layout: UniformLayout) -> &mut Self {
        self.uniform(UniformLayout { program, ..layout })
    }
}

/// The one `Node` implementation of every fusable kind: the schema is the stage's, and
/// `execute` runs the node as a fused pass of one (so fused and unfused frames run the same
/// code).
struct ImageStage(&'static dyn Fusable);

impl Node<Value, Ctx> for ImageStage {
    fn schema(&self) -> NodeSchema {
        self.0.schema()
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        fused_pass::execute(self.0, ctx, inputs, p)
    }
}

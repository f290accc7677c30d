//! What the modules declare (issue 29): each module that has node kinds, shader programs or
//! uniform blocks says so in one `pub fn declare(k: &mut Kinds)`, and lib.rs lists the module
//! once. The registry, the program list and the uniform list are all built from those calls, so
//! a kind is declared in its own module only.

use crate::bindings::BindingLayout;
use crate::stage::Fusable;
use crate::uniforms::{GpuEnumLayout, UniformLayout};
use crate::{Ctx, Registry, Value};
use hatchery_graph::executor::Node;
use std::collections::BTreeMap;
use std::sync::OnceLock;

/// A compilable shader program: its name (used in error messages and by [`source`])
/// and its parts, (file name, WGSL text), concatenated in order (WGSL has no includes).
pub type Program = (&'static str, Vec<(&'static str, &'static str)>);

/// Everything the declaring modules contribute.
#[derive(Default)]
pub struct Kinds {
    pub(crate) registry: Registry,
    pub(crate) stages: Vec<&'static dyn Fusable>,
    pub(crate) programs: Vec<Program>,
    pub(crate) uniforms: Vec<UniformLayout>,
    pub(crate) gpu_enums: Vec<GpuEnumLayout>,
    pub(crate) bind_groups: Vec<BindingLayout>,
    /// (kind, the file of the `declare` that declared it).
    pub(crate) files: Vec<(&'static str, &'static str)>,
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
        let kind = self.registry.register(node);
        self.files.push((kind, file));
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

    /// An enum a program reads as codes (checked against its WGSL constants by
    /// tests/shaders.rs).
    pub fn gpu_enum(&mut self, layout: GpuEnumLayout) -> &mut Self {
        self.gpu_enums.push(layout);
        self
    }

    /// A typed bind group (checked against its program's bindings by tests/shaders.rs).
    pub fn bind_group(&mut self, layout: BindingLayout) -> &mut Self {
        self.bind_groups.push(layout);
        self
    }

    /// A typed bind group that `program` uses as well as the program it was declared for (the
    /// ray casters' shared group 0, the object tables).
    pub fn bind_group_in(&mut self, program: &'static str, layout: BindingLayout) -> &mut Self {
        self.bind_group(BindingLayout { program, ..layout })
    }

    /// A uniform block that `program` uses as well as the program it was declared for (a
    /// shared block: the camera of the mesh shaders, the ray casters' `Ray`).
    pub fn uniform_in(&mut self, program: &'static str, layout: UniformLayout) -> &mut Self {
        self.uniform(UniformLayout { program, ..layout })
    }
}

/// Every compilable program, (name, parts), as the modules declare them. The name is used in
/// error messages.
pub fn programs() -> &'static [Program] {
    static PROGRAMS: OnceLock<Vec<Program>> = OnceLock::new();
    PROGRAMS.get_or_init(|| Kinds::all().programs)
}

/// The full source of a program.
pub fn source(name: &str) -> Option<String> {
    programs()
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, parts)| parts.iter().map(|(_, s)| *s).collect())
}

/// Every uniform block of every node, for the reflection test (as the modules declare them).
pub fn uniform_blocks() -> Vec<UniformLayout> {
    Kinds::all().uniforms
}

/// Every enum mirrored by WGSL constants, for the reflection test.
pub fn gpu_enums() -> Vec<GpuEnumLayout> {
    Kinds::all().gpu_enums
}

/// Every typed bind group of every program, for the reflection test.
pub fn bind_groups() -> Vec<BindingLayout> {
    Kinds::all().bind_groups
}

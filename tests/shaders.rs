//! Every WGSL shader is validated by naga, so a typo fails here before any GPU runs it.

mod common;

use std::collections::BTreeSet;

fn validate(name: &str, source: &str) {
    let module = naga::front::wgsl::parse_str(source).unwrap_or_else(|e| {
        panic!(
            "shader {name} does not parse:\n{}",
            e.emit_to_string(source)
        )
    });
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        // 64-bit integers and their atomics: DepthLayers' k-buffer, which runs only where the
        // adapter has them (and falls back to depth peeling elsewhere).
        naga::valid::Capabilities::default()
            | naga::valid::Capabilities::SHADER_INT64
            | naga::valid::Capabilities::SHADER_INT64_ATOMIC_ALL_OPS,
    )
    .validate(&module)
    .unwrap_or_else(|e| {
        panic!(
            "shader {name} does not validate:\n{}",
            e.emit_to_string(source)
        )
    });
}

#[test]
fn every_shader_program_validates() {
    let programs = hatchery_nodes::kinds::programs();
    assert!(!programs.is_empty());
    for (name, _) in programs {
        validate(name, &hatchery_nodes::kinds::source(name).unwrap());
    }
}

#[test]
fn every_wgsl_file_is_part_of_a_program() {
    let used: BTreeSet<&str> = hatchery_nodes::kinds::programs()
        .iter()
        .flat_map(|(_, parts)| parts.iter().map(|(file, _)| *file))
        .collect();
    let on_disk: BTreeSet<String> = std::fs::read_dir(common::repo_root().join("shaders"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".wgsl"))
        .collect();
    let on_disk: BTreeSet<&str> = on_disk.iter().map(String::as_str).collect();
    assert_eq!(
        on_disk, used,
        "a shader file on disk is not compiled by any program (or the reverse)"
    );
}

#[test]
fn a_broken_shader_is_reported_by_name_not_by_a_panic() {
    let gpu = hatchery_gpu::GpuContext::new().unwrap();
    let err = gpu
        .shader(
            "custom_node",
            "@fragment fn fs_main() -> @location(0) vec4<f32> { return vec4<f32>(1.0, oops); }",
        )
        .unwrap_err();
    let message = err.to_string();
    assert!(message.starts_with("shader custom_node:"), "{message}");
    assert!(message.contains("oops"), "{message}");
}

/// (member name, byte offset, byte size, the Rust type that mirrors it: `f32`, `u32`, `i32`,
/// `[f32; 4]` for a vec4<f32>, `[[f32; 4]; 4]` for a mat4x4<f32>).
type Member = (String, u32, u32, String);

/// The Rust type a WGSL uniform member is mirrored by (no spaces), or its WGSL description.
fn rust_type(module: &naga::Module, ty: naga::Handle<naga::Type>) -> String {
    let scalar = |s: &naga::Scalar| {
        match (s.kind, s.width) {
            (naga::ScalarKind::Float, 4) => "f32",
            (naga::ScalarKind::Uint, 4) => "u32",
            (naga::ScalarKind::Sint, 4) => "i32",
            _ => "?",
        }
        .to_owned()
    };
    match &module.types[ty].inner {
        naga::TypeInner::Scalar(s) => scalar(s),
        naga::TypeInner::Vector { size, scalar: s } => format!("[{};{}]", scalar(s), *size as u32),
        naga::TypeInner::Matrix {
            columns,
            rows,
            scalar: s,
        } => {
            format!("[[{};{}];{}]", scalar(s), *rows as u32, *columns as u32)
        }
        naga::TypeInner::Array {
            base,
            size: naga::ArraySize::Constant(n),
            ..
        } => format!("[{};{n}]", rust_type(module, *base)),
        other => format!("{other:?}"),
    }
}

/// The WGSL struct `name` of a program: (size, members).
fn wgsl_struct(module: &naga::Module, name: &str) -> Option<(u32, Vec<Member>)> {
    module.types.iter().find_map(|(_, ty)| match &ty.inner {
        naga::TypeInner::Struct { members, span } if ty.name.as_deref() == Some(name) => Some((
            *span,
            members
                .iter()
                .map(|m| {
                    let size = module.types[m.ty].inner.size(module.to_ctx());
                    let name = m.name.clone().unwrap_or_default();
                    (name, m.offset, size, rust_type(module, m.ty))
                })
                .collect(),
        )),
        _ => None,
    })
}

#[test]
fn every_uniform_block_matches_its_wgsl_struct_field_by_field() {
    let layouts = hatchery_nodes::kinds::uniform_blocks();
    assert!(!layouts.is_empty());
    for layout in &layouts {
        let source = hatchery_nodes::kinds::source(layout.program)
            .unwrap_or_else(|| panic!("no program `{}`", layout.program));
        let module = naga::front::wgsl::parse_str(&source).unwrap();
        let (span, members) = wgsl_struct(&module, layout.wgsl_struct).unwrap_or_else(|| {
            panic!(
                "program {} has no struct {}",
                layout.program, layout.wgsl_struct
            )
        });
        let rust: Vec<Member> = layout
            .fields
            .iter()
            .map(|(n, o, s, t)| (n.to_string(), *o as u32, *s as u32, t.replace(' ', "")))
            .collect();
        assert_eq!(
            rust, members,
            "{}::{}: Rust fields (name, offset, size, type) differ from WGSL",
            layout.program, layout.wgsl_struct
        );
        assert_eq!(
            layout.size as u32, span,
            "{}::{}: struct sizes differ",
            layout.program, layout.wgsl_struct
        );
    }
}

#[test]
fn every_uniform_buffer_in_every_program_has_a_typed_rust_block() {
    let layouts = hatchery_nodes::kinds::uniform_blocks();
    for (program, _) in hatchery_nodes::kinds::programs() {
        let source = hatchery_nodes::kinds::source(program).unwrap();
        let module = naga::front::wgsl::parse_str(&source).unwrap();
        for (_, global) in module.global_variables.iter() {
            if global.space != naga::AddressSpace::Uniform {
                continue;
            }
            let ty = module.types[global.ty].name.clone().unwrap_or_default();
            assert!(
                layouts
                    .iter()
                    .any(|l| l.program == *program && l.wgsl_struct == ty),
                "program {program}: `var<uniform> {}: {ty}` has no typed block in \
                 hatchery_nodes::kinds::uniform_blocks()",
                global.name.clone().unwrap_or_default()
            );
        }
    }
}

/// The value of the WGSL `const NAME: u32 = …;` of a module, if it has one.
fn wgsl_u32_constant(module: &naga::Module, name: &str) -> Option<u32> {
    module.constants.iter().find_map(|(_, c)| {
        if c.name.as_deref() != Some(name) {
            return None;
        }
        match module.global_expressions[c.init] {
            naga::Expression::Literal(naga::Literal::U32(v)) => Some(v),
            ref other => panic!("WGSL constant {name} is {other:?}, not a u32 literal"),
        }
    })
}

#[test]
fn every_gpu_enum_matches_its_wgsl_constants() {
    let enums = hatchery_nodes::kinds::gpu_enums();
    assert!(!enums.is_empty());
    for e in &enums {
        let source = hatchery_nodes::kinds::source(e.program)
            .unwrap_or_else(|| panic!("no program `{}`", e.program));
        let module = naga::front::wgsl::parse_str(&source).unwrap();
        assert!(!e.constants.is_empty(), "{}: no variants", e.rust_enum);
        for &(name, value) in &e.constants {
            let wgsl = wgsl_u32_constant(&module, name).unwrap_or_else(|| {
                panic!(
                    "{}: program {} declares no `const {name}: u32`",
                    e.rust_enum, e.program
                )
            });
            assert_eq!(
                wgsl, value,
                "{}: WGSL {name} = {wgsl} in {}, the Rust code is {value}",
                e.rust_enum, e.program
            );
        }
    }
}

/// The bindings of a module: (group, binding) → variable name.
fn wgsl_bindings(module: &naga::Module) -> std::collections::BTreeMap<(u32, u32), String> {
    module
        .global_variables
        .iter()
        .filter_map(|(_, g)| {
            let b = g.binding.as_ref()?;
            Some(((b.group, b.binding), g.name.clone().unwrap_or_default()))
        })
        .collect()
}

#[test]
fn every_typed_bind_group_matches_its_program_binding_by_binding() {
    use std::collections::{BTreeMap, BTreeSet};
    let layouts = hatchery_nodes::kinds::bind_groups();
    assert!(!layouts.is_empty());
    let programs: BTreeSet<&str> = layouts.iter().map(|l| l.program).collect();
    for program in programs {
        let source = hatchery_nodes::kinds::source(program)
            .unwrap_or_else(|| panic!("no program `{program}`"));
        let module = naga::front::wgsl::parse_str(&source).unwrap();
        let wgsl = wgsl_bindings(&module);
        // What the Rust structs declare for this program, (group, binding) → (name, struct).
        let mut declared: BTreeMap<(u32, u32), (String, &str)> = BTreeMap::new();
        for l in layouts.iter().filter(|l| l.program == program) {
            for (i, name) in l.names.iter().enumerate() {
                let at = (l.group, l.first + i as u32);
                if let Some((other, by)) = declared.insert(at, (name.to_string(), l.rust_struct)) {
                    panic!(
                        "{program}: group {} binding {} declared twice ({other} by {by}, {name} by {})",
                        at.0, at.1, l.rust_struct
                    );
                }
            }
        }
        for (&(group, binding), (name, by)) in &declared {
            let actual = wgsl.get(&(group, binding)).unwrap_or_else(|| {
                panic!("{program}: {by}.{name} is group {group} binding {binding}, which WGSL does not declare")
            });
            assert_eq!(
                actual, name,
                "{program}: group {group} binding {binding} is `{actual}` in WGSL, `{name}` in {by}"
            );
        }
        for ((group, binding), name) in &wgsl {
            assert!(
                declared.contains_key(&(*group, *binding)),
                "{program}: `{name}` (group {group} binding {binding}) is in no typed bind group"
            );
        }
    }
}

#[test]
fn every_ray_caster_binds_the_shared_ray_group() {
    let layouts = hatchery_nodes::kinds::bind_groups();
    for (program, _) in hatchery_nodes::kinds::programs() {
        let source = hatchery_nodes::kinds::source(program).unwrap();
        if !source.contains("var<uniform> ray: Ray;") {
            continue;
        }
        assert!(
            layouts
                .iter()
                .any(|l| l.program == *program && l.rust_struct == "RayBindings"),
            "program {program} includes ray_common.wgsl but declares no RayBindings"
        );
    }
}

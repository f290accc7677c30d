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
        naga::valid::Capabilities::default(),
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
    let programs = hatchery_nodes::shaders::programs();
    assert!(!programs.is_empty());
    for (name, _) in &programs {
        validate(name, &hatchery_nodes::shaders::source(name).unwrap());
    }
}

#[test]
fn every_wgsl_file_is_part_of_a_program() {
    let used: BTreeSet<&str> = hatchery_nodes::shaders::programs()
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

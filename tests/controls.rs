//! Controls (graph format v3, issue 33): the parameters a figure's reader may change, declared in
//! the graph. Parsed and validated with the real node kinds, written back by saving, kept through
//! renames, and refused with one line naming the control and its line.

use hatchery_graph::controls::{Control, ControlKind};
use hatchery_graph::{Graph, GraphDocument, edit};

fn graph(text: &str) -> Result<Graph, String> {
    let registry = hatchery_nodes::registry();
    let (doc, source) = GraphDocument::parse(text, None).map_err(|e| e.to_string())?;
    Graph::from_document(&doc, &source, &registry, None).map_err(|e| e.to_string())
}

/// A small valid graph with a node of each parameter type a control can take, and `controls` as
/// given.
fn with_controls(controls: &str) -> String {
    format!(
        r#"(
    version: 3,
    controls: [
{controls}
    ],
    nodes: [
        (id: "camera", kind: "Camera", params: {{}}),
        (id: "light", kind: "Light", params: {{}}),
        (id: "cubes", kind: "ProceduralVolume", params: {{ "resolution": 16 }}),
        (id: "surface", kind: "MarchingCubes", params: {{}}),
        (id: "layer", kind: "GBuffer", params: {{}}),
        (id: "shade", kind: "DiffuseIntensity", params: {{}}),
        (id: "hatching", kind: "Halftone", params: {{}}),
        (id: "both", kind: "MaskCombine", params: {{}}),
        (id: "paper", kind: "Fill", params: {{}}),
        (id: "tint", kind: "MixByMask", params: {{}}),
        (id: "lines", kind: "MultiplyByMask", params: {{}}),
    ],
    edges: [
        (from: ("cubes", "volume"), to: ("surface", "volume")),
        (from: ("surface", "mesh"), to: ("layer", "mesh")),
        (from: ("camera", "camera"), to: ("layer", "camera")),
        (from: ("layer", "gbuffer"), to: ("shade", "gbuffer")),
        (from: ("light", "light"), to: ("shade", "light")),
        (from: ("shade", "intensity"), to: ("hatching", "intensity")),
        (from: ("hatching", "mask"), to: ("both", "a")),
        (from: ("hatching", "mask"), to: ("both", "b")),
        (from: ("paper", "image"), to: ("tint", "base")),
        (from: ("both", "mask"), to: ("tint", "mask")),
        (from: ("tint", "image"), to: ("lines", "image")),
        (from: ("hatching", "mask"), to: ("lines", "mask")),
    ],
)"#
    )
}

#[test]
fn the_default_preset_declares_sliders_and_colours() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/graphs/default.ron"))
        .unwrap();
    let g = graph(&text).unwrap();
    let control = |node: &str, param: &str| -> &Control {
        g.controls()
            .iter()
            .find(|c| c.node == node && c.param == param)
            .unwrap_or_else(|| panic!("{node}.{param} not among {:?}", g.controls()))
    };
    assert_eq!(g.controls().len(), 4);
    let theta = control("hatching", "theta");
    assert_eq!(theta.label, "hatching angle");
    assert_eq!(
        theta.kind,
        ControlKind::Slider {
            min: 0.0,
            max: 180.0,
            integer: false
        }
    );
    assert_eq!(control("back_layer", "color").kind, ControlKind::Colour);
}

#[test]
fn every_kind_of_control_and_its_defaults() {
    let g = graph(&with_controls(
        r#"        (node: "hatching", param: "cell"),
        (node: "cubes", param: "resolution", min: Some(8.0), max: Some(64.0)),
        (node: "lines", param: "invert", label: "inverted"),
        (node: "both", param: "operation"),
        (node: "tint", param: "color"),"#,
    ))
    .unwrap();
    let kinds: Vec<(&str, &ControlKind)> = g
        .controls()
        .iter()
        .map(|c| (c.label.as_str(), &c.kind))
        .collect();
    // A number without min/max spans its parameter's range (Halftone's cell: 1 … 256).
    assert_eq!(
        kinds[0],
        (
            "cell",
            &ControlKind::Slider {
                min: 1.0,
                max: 256.0,
                integer: false
            }
        )
    );
    assert_eq!(
        kinds[1],
        (
            "resolution",
            &ControlKind::Slider {
                min: 8.0,
                max: 64.0,
                integer: true
            }
        )
    );
    assert_eq!(kinds[2], ("inverted", &ControlKind::Toggle));
    assert!(matches!(kinds[3], ("operation", ControlKind::Menu(names)) if names.contains(&"and")));
    assert_eq!(kinds[4], ("color", &ControlKind::Colour));
}

#[test]
fn saving_writes_the_controls_back() {
    let text = with_controls(
        r#"        (node: "hatching", param: "theta", label: "angle", min: Some(0.0), max: Some(90.5)),
        (node: "tint", param: "color"),"#,
    );
    let registry = hatchery_nodes::registry();
    let g = graph(&text).unwrap();
    let saved = g.to_document(&registry).to_ron_string();
    assert!(
        saved.contains(r#"(node: "hatching", param: "theta", label: "angle", min: Some(0.0), max: Some(90.5)),"#),
        "{saved}"
    );
    let again = graph(&saved).unwrap();
    assert_eq!(again.controls(), g.controls());
}

#[test]
fn renaming_a_node_keeps_its_controls_and_removing_it_drops_them() {
    let text = with_controls(r#"        (node: "hatching", param: "theta"),"#);
    let (mut doc, _) = GraphDocument::parse(&text, None).unwrap();
    edit::rename_node(&mut doc, "hatching", "screen").unwrap();
    assert_eq!(doc.controls[0].node, "screen");
    let g = graph(&doc.to_ron_string()).unwrap();
    assert_eq!(g.controls()[0].node, "screen");
    edit::remove_node(&mut doc, "screen").unwrap();
    assert!(doc.controls.is_empty());
    assert!(!doc.to_ron_string().contains("controls:"));
}

#[test]
fn wrong_controls_are_refused_naming_the_control_and_its_line() {
    let cases = [
        (
            r#"(node: "nothing", param: "theta"),"#,
            "control `nothing.theta`: there is no node `nothing`",
        ),
        (
            r#"(node: "hatching", param: "angle"),"#,
            "Halftone has no parameter `angle` (its parameters are: theta, cell, c_cross)",
        ),
        (
            r#"(node: "camera", param: "target"),"#,
            "`target` is a vec3 parameter; controls are for numbers",
        ),
        (
            r#"(node: "hatching", param: "theta", min: Some(-400.0)),"#,
            "within the parameter's range [-360, 360]",
        ),
        (
            r#"(node: "hatching", param: "theta", min: Some(10.0), max: Some(5.0)),"#,
            "must be increasing",
        ),
        (
            r#"(node: "cubes", param: "resolution", min: Some(8.5)),"#,
            "must be whole numbers for an integer",
        ),
        (
            r#"(node: "tint", param: "color", max: Some(1.0)),"#,
            "`min` and `max` are for numbers; `color` is a color parameter",
        ),
        // Fields in another order: still found on its line.
        (
            r#"(param: "angle", label: "angle", node: "hatching"),"#,
            "Halftone has no parameter `angle`",
        ),
    ];
    for (control, needle) in cases {
        let text = with_controls(&format!("        {control}"));
        let err = graph(&text).expect_err(control);
        // The control's is the only error: the rest of the graph is valid.
        assert!(!err.contains("more)"), "{control}: {err}");
        assert!(err.contains(needle), "{control}: {err}");
        // The line of the control (the fourth of the file), in one line.
        assert!(err.starts_with("4:"), "{control}: {err}");
        assert!(!err.contains('\n'), "{err}");
    }
    let twice = with_controls(
        r#"        (node: "hatching", param: "theta"),
        (node: "hatching", param: "theta"),"#,
    );
    let err = graph(&twice).unwrap_err();
    assert!(err.contains("declared twice"), "{err}");
}

/// Deleting a node also deletes the input bindings to it (an input left bound to nothing goes),
/// so the saved file stays loadable; renaming it renames its bindings.
#[test]
fn removing_or_renaming_a_bound_node_keeps_the_inputs_valid() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/graphs/brain_surface.ron"
    ))
    .unwrap();
    let (mut doc, _) = GraphDocument::parse(&text, None).unwrap();
    assert_eq!(doc.inputs[0].to, [("mri".to_owned(), "path".to_owned())]);
    edit::rename_node(&mut doc, "mri", "scan").unwrap();
    assert_eq!(doc.inputs[0].to, [("scan".to_owned(), "path".to_owned())]);
    edit::remove_node(&mut doc, "scan").unwrap();
    assert!(doc.inputs.is_empty(), "{:?}", doc.inputs);
}

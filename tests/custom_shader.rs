//! CustomShader: ports and parameters from the shader's declarations, pictures equal to CPU
//! computations of the same formulas, errors naming file:line:col, live re-reading. Every case
//! writes a shader and a graph file into a temporary folder and loads them as the CLI does.

mod common;

use hatchery_graph::{Graph, ParamKind, ParamValue, PortType, SchemaLookup};
use hatchery_nodes::{Session, Value};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

const W: u32 = 64;
const H: u32 = 48;

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// A graph of `nodes` (RON node entries) and `edges`.
fn graph_text(nodes: &str, edges: &str) -> String {
    format!("(version: 2, nodes: [{nodes}], edges: [{edges}])")
}

fn open(dir: &Path, graph: &str) -> Session {
    let path = write(dir, "graph.ron", graph);
    Session::open(&path, W, H).unwrap_or_else(|e| panic!("{e}"))
}

fn pixels(session: &mut Session, node: &str, port: &str) -> hatchery_gpu::TextureData {
    session.run(&[node]).unwrap_or_else(|e| panic!("{e}"));
    let texture = match session.output(node, port).unwrap() {
        Value::Image(i) => i.texture.clone(),
        Value::Mask(m) => m.texture.clone(),
        other => panic!("{node}.{port} is {}", other.port_type()),
    };
    session.ctx.gpu.read_texture(&texture).unwrap()
}

const GRADIENT: &str = "// A test gradient: red along x, green along y.
@fragment
fn fs_main(@location(0) uv: vec2<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(uv.x, uv.y, 0.25, 1.0);
}
";

const CHECKER: &str = "
@fragment
fn fs_main(@builtin(position) p: vec4<f32>) -> @location(0) f32 {
    let c = vec2<i32>(floor(p.xy)) / 8;
    return f32((c.x + c.y) % 2);
}
";

const MIX: &str = "// Tints the picture where the mask is set.
@group(0) @binding(0) var picture: texture_2d<f32>;
@group(0) @binding(1) var where_mask: texture_2d<f32>;
struct Params {
    amount: f32, // default = 0.25, range = 0..2, how much tint
    tint: vec4<f32>, // default = [0.0, 0.0, 1.0, 1.0], the tint colour
    steps: i32, // range = 1..16, posterisation levels
    offset: vec3<f32>, // added to the colour
}
@group(0) @binding(2) var<uniform> params: Params;

@fragment
fn fs_main(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let q = vec2<i32>(floor(p.xy));
    let c = textureLoad(picture, q, 0);
    let m = textureLoad(where_mask, q, 0).r;
    let levels = f32(params.steps);
    let t = floor(params.amount * m * levels) / levels;
    return vec4<f32>(mix(c.rgb, params.tint.rgb, t) + params.offset, 1.0);
}
";

fn custom(id: &str, shader: &str, params: &str) -> String {
    format!(
        "(id: \"{id}\", kind: \"CustomShader\", params: {{\"shader\": \"{shader}\", {params}}}),"
    )
}

#[test]
fn ports_and_parameters_come_from_the_declarations() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "mix.wgsl", MIX);
    let registry = hatchery_nodes::registry();
    let raw = BTreeMap::from([("shader".to_owned(), ron::Value::String("mix.wgsl".into()))]);
    let own = registry
        .own_schema("CustomShader", &raw, Some(dir.path()))
        .expect("CustomShader has an own schema");
    assert_eq!(own.error, None);
    let schema = own.schema.expect("readable shader");
    let inputs: Vec<(&str, PortType)> = schema.inputs.iter().map(|p| (p.name, p.ty)).collect();
    assert_eq!(
        inputs,
        [("picture", PortType::Image), ("where_mask", PortType::Mask)]
    );
    let outputs: Vec<(&str, PortType)> = schema.outputs.iter().map(|p| (p.name, p.ty)).collect();
    assert_eq!(outputs, [("image", PortType::Image)]);
    let names: Vec<&str> = schema.params.iter().map(|p| p.name).collect();
    assert_eq!(names, ["shader", "amount", "tint", "steps", "offset"]);
    let amount = schema.param("amount").unwrap();
    assert_eq!(amount.kind, ParamKind::Float { min: 0.0, max: 2.0 });
    assert_eq!(amount.default, ParamValue::Float(0.25));
    assert_eq!(amount.doc, "how much tint");
    assert_eq!(
        schema.param("tint").unwrap().default,
        ParamValue::Color([0.0, 0.0, 1.0, 1.0])
    );
    assert_eq!(
        schema.param("steps").unwrap().kind,
        ParamKind::Int { min: 1, max: 16 }
    );
    assert_eq!(schema.param("offset").unwrap().kind, ParamKind::Vec3);
    // The file's header comment describes the node.
    assert_eq!(schema.doc, "Tints the picture where the mask is set.");
    assert_ne!(own.fingerprint, 0);
    drop(path);

    // A G-buffer: a depth binding makes the port, `<name>_normal` joins it; f32 → a mask.
    write(
        dir.path(),
        "g.wgsl",
        "@group(0) @binding(0) var g: texture_depth_2d;
@group(0) @binding(1) var g_normal: texture_2d<f32>;
@group(0) @binding(2) var s: sampler;
@fragment fn main(@builtin(position) p: vec4<f32>) -> @location(0) f32 {
    return textureLoad(g, vec2<i32>(p.xy), 0) + textureLoad(g_normal, vec2<i32>(p.xy), 0).w;
}",
    );
    let raw = BTreeMap::from([("shader".to_owned(), ron::Value::String("g.wgsl".into()))]);
    let own = registry
        .own_schema("CustomShader", &raw, Some(dir.path()))
        .unwrap();
    let schema = own.schema.unwrap_or_else(|| panic!("{:?}", own.error));
    let inputs: Vec<(&str, PortType)> = schema.inputs.iter().map(|p| (p.name, p.ty)).collect();
    assert_eq!(inputs, [("g", PortType::GBuffer)]);
    assert_eq!(schema.outputs[0].name, "mask");
    assert_eq!(schema.outputs[0].ty, PortType::Mask);
}

#[test]
fn uv_and_position_address_pixels_from_the_top_left() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "uv.wgsl",
        "@fragment
fn fs_main(@builtin(position) p: vec4<f32>, @location(0) uv: vec2<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(uv, p.x / 64.0, p.y / 64.0);
}",
    );
    let mut session = open(dir.path(), &graph_text(&custom("uv", "uv.wgsl", ""), ""));
    let data = pixels(&mut session, "uv", "image");
    let mut samples = Vec::new();
    for (x, y) in [(0, 0), (W - 1, 0), (0, H - 1), (W - 1, H - 1), (17, 29)] {
        let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
        let expected = [cx / W as f32, cy / H as f32, cx / 64.0, cy / 64.0];
        let got = data.texel(x, y);
        samples.push(common::Sample {
            x,
            y,
            what: format!("{got:?} vs {expected:?}"),
            error: common::channel_difference(got, &expected) as f64,
        });
    }
    // Rgba16Float keeps 11 significant bits: 1/2048 relative.
    common::assert_samples("custom shader uv", &samples, 1e-3, None);
}

#[test]
fn chained_shaders_equal_the_cpu_formula() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "gradient.wgsl", GRADIENT);
    write(dir.path(), "checker.wgsl", CHECKER);
    write(dir.path(), "mix.wgsl", MIX);
    let nodes = [
        custom("gradient", "gradient.wgsl", ""),
        custom("checker", "checker.wgsl", ""),
        custom(
            "mix",
            "mix.wgsl",
            "\"amount\": 0.8, \"steps\": 4, \"tint\": [1.0, 0.5, 0.0, 1.0], \"offset\": [0.0, 0.0, 0.125]",
        ),
    ]
    .join("\n");
    let edges = "(from: (\"gradient\", \"image\"), to: (\"mix\", \"picture\")),
                 (from: (\"checker\", \"mask\"), to: (\"mix\", \"where_mask\")),";
    let mut session = open(dir.path(), &graph_text(&nodes, edges));
    let picture = pixels(&mut session, "gradient", "image");
    let mask = pixels(&mut session, "checker", "mask");
    let out = pixels(&mut session, "mix", "image");
    let mut expected = Vec::new();
    let mut masked = 0;
    for y in 0..H {
        for x in 0..W {
            let (c, m) = (picture.texel(x, y), mask.texel(x, y)[0]);
            let expected_mask = (((x / 8) + (y / 8)) % 2) as f32;
            assert_eq!(m, expected_mask, "checker at ({x}, {y})");
            masked += m as u32;
            let t = (0.8f32 * m * 4.0).floor() / 4.0;
            let tint = [1.0, 0.5, 0.0];
            let offset = [0.0, 0.0, 0.125];
            let [r, g, b] = [0, 1, 2].map(|i| c[i] + (tint[i] - c[i]) * t + offset[i]);
            expected.push([r, g, b, 1.0]);
        }
    }
    assert!(
        masked > 0 && masked < W * H,
        "the checker masks part of the frame"
    );
    let got = common::texels(&out);
    common::assert_images_close(
        "custom shader mix",
        &got,
        &expected,
        W,
        common::f32_at_most(2e-3),
    );

    // A parameter set the way the CLI's --set does re-runs the node with the new value.
    session.set_param_text("mix", "amount", "0").unwrap();
    let plain = pixels(&mut session, "mix", "image");
    let (c, got) = (picture.texel(8, 0), plain.texel(8, 0));
    assert!((got[0] - c[0]).abs() < 2e-3 && (got[2] - (c[2] + 0.125)).abs() < 2e-3);
}

#[test]
fn a_gbuffer_port_binds_depth_and_normals() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "g.wgsl",
        "@group(0) @binding(0) var g: texture_depth_2d;
@group(0) @binding(1) var g_normal: texture_2d<f32>;
@fragment fn fs_main(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let q = vec2<i32>(floor(p.xy));
    let n = textureLoad(g_normal, q, 0);
    return vec4<f32>(n.xyz * 0.5 + 0.5, textureLoad(g, q, 0));
}",
    );
    let nodes = format!(
        "(id: \"shells\", kind: \"ProceduralVolume\", params: {{\"resolution\": 48, \"shape\": \"shells\"}}),
         (id: \"surface\", kind: \"MarchingCubes\", params: {{\"iso\": 0.0}}),
         (id: \"camera\", kind: \"Camera\", params: {{\"distance\": 3.5}}),
         (id: \"gbuffer\", kind: \"GBuffer\", params: {{}}),
         {}",
        custom("show", "g.wgsl", "")
    );
    let edges = "(from: (\"shells\", \"volume\"), to: (\"surface\", \"volume\")),
        (from: (\"surface\", \"mesh\"), to: (\"gbuffer\", \"mesh\")),
        (from: (\"camera\", \"camera\"), to: (\"gbuffer\", \"camera\")),
        (from: (\"gbuffer\", \"gbuffer\"), to: (\"show\", \"g\")),";
    let mut session = open(dir.path(), &graph_text(&nodes, edges));
    let out = pixels(&mut session, "show", "image");
    let Value::GBuffer(g) = session.output("gbuffer", "gbuffer").unwrap().clone() else {
        panic!("not a G-buffer");
    };
    let depth = session.ctx.gpu.read_texture(&g.depth).unwrap();
    let normal = session.ctx.gpu.read_texture(&g.normal).unwrap();
    let mut expected = Vec::new();
    let mut covered = 0;
    for y in 0..H {
        for x in 0..W {
            let (n, d) = (normal.texel(x, y), depth.texel(x, y)[0]);
            covered += (d < 1.0) as u32;
            expected.push([n[0] * 0.5 + 0.5, n[1] * 0.5 + 0.5, n[2] * 0.5 + 0.5, d]);
        }
    }
    assert!(
        covered > 100,
        "the surface covers the frame ({covered} pixels)"
    );
    let got = common::texels(&out);
    common::assert_images_close(
        "custom shader gbuffer",
        &got,
        &expected,
        W,
        common::f32_at_most(1e-3),
    );
}

/// The first error of loading `graph` (its text) from `dir`.
fn load_error(dir: &Path, graph: &str) -> String {
    let path = write(dir, "graph.ron", graph);
    let registry = hatchery_nodes::registry();
    match Graph::load_file(&path, &registry) {
        Ok(_) => panic!("the graph loaded"),
        Err(e) => {
            e.0.iter()
                .map(|e| e.to_string())
                .collect::<Vec<_>>()
                .join("\n")
        }
    }
}

#[test]
fn shader_errors_name_the_node_the_file_the_line_and_the_column() {
    let dir = tempfile::tempdir().unwrap();
    let one = |shader: &str| graph_text(&custom("mine", shader, ""), "");
    // (file, text, what the message holds): each kind of mistake, located.
    let cases: [(&str, &str, &[&str]); 14] = [
        // Syntax: the missing `;` at the end of line 3 is reported where the parser stops.
        (
            "syntax.wgsl",
            "@fragment\nfn fs_main() -> @location(0) vec4<f32> {\n    let a = 1.0\n    return vec4<f32>(a);\n}\n",
            &["node `mine`", "syntax.wgsl:4:5: ", "expected"],
        ),
        // Types (naga's validation): the line of the offending statement.
        (
            "types.wgsl",
            "@fragment\nfn fs_main() -> @location(0) vec4<f32> {\n    let a: f32 = vec2<f32>(1.0);\n    return vec4<f32>(a);\n}\n",
            &["types.wgsl:3:"],
        ),
        // A binding the node cannot feed, on its own line.
        (
            "storage.wgsl",
            "// header\n@group(0) @binding(0) var<storage, read> data: array<f32>;\n@fragment\nfn fs_main() -> @location(0) vec4<f32> {\n    return vec4<f32>(data[0]);\n}\n",
            &["storage.wgsl:2:", "`data`"],
        ),
        // A uniform member of a type without a widget.
        (
            "member.wgsl",
            "struct P {\n    a: f32,\n    b: mat2x2<f32>,\n}\n@group(0) @binding(0) var<uniform> p: P;\n@fragment\nfn fs_main() -> @location(0) vec4<f32> {\n    return vec4<f32>(p.a + p.b[0][0]);\n}\n",
            &["member.wgsl:3:5: uniform member `b`"],
        ),
        // A bad range in the comment.
        (
            "comment.wgsl",
            "struct P {\n    a: f32, // range = 1..0\n}\n@group(0) @binding(0) var<uniform> p: P;\n@fragment\nfn fs_main() -> @location(0) vec4<f32> {\n    return vec4<f32>(p.a);\n}\n",
            &["comment.wgsl:2:5:", "range = min..max"],
        ),
        // What would otherwise only fail when the pipeline is made (found by a review).
        (
            "sampled_mask.wgsl",
            "@group(0) @binding(0) var edge_mask: texture_2d<f32>;\n@group(0) @binding(1) var s: sampler;\n@fragment\nfn fs_main(@location(0) uv: vec2<f32>) -> @location(0) f32 {\n    return textureSample(edge_mask, s, uv).r;\n}\n",
            &[
                "sampled_mask.wgsl:1:",
                "`edge_mask` is read with a sampler",
                "textureLoad",
            ],
        ),
        (
            "flat.wgsl",
            "@fragment\nfn fs_main(@location(0) @interpolate(flat) uv: vec2<f32>) -> @location(0) f32 {\n    return uv.x;\n}\n",
            &["flat.wgsl:2:", "no @interpolate"],
        ),
        (
            "override.wgsl",
            "override k: f32;\n@fragment\nfn fs_main() -> @location(0) f32 {\n    return k;\n}\n",
            &["override.wgsl:1:", "override `k` needs a value"],
        ),
        // Comments that cannot be told apart or make no sense.
        (
            "one_line.wgsl",
            "struct P { a: f32, b: f32, // default = 0.5\n}\n@group(0) @binding(0) var<uniform> p: P;\n@fragment\nfn fs_main() -> @location(0) f32 {\n    return p.a + p.b;\n}\n",
            &["one_line.wgsl:1:1:", "put each member on a line of its own"],
        ),
        (
            "twice.wgsl",
            "struct P {\n    a: f32, // default = 0.5, default = 0.7\n}\n@group(0) @binding(0) var<uniform> p: P;\n@fragment\nfn fs_main() -> @location(0) f32 {\n    return p.a;\n}\n",
            &["twice.wgsl:2:", "`default` is given twice"],
        ),
        (
            "ints.wgsl",
            "struct P {\n    a: i32, // range = -5000000000..0\n}\n@group(0) @binding(0) var<uniform> p: P;\n@fragment\nfn fs_main() -> @location(0) f32 {\n    return f32(p.a);\n}\n",
            &["ints.wgsl:2:", "an i32 holds -2147483648 to 2147483647"],
        ),
        (
            "vec_range.wgsl",
            "struct P {\n    c: vec4<f32>, // range = 0..1\n}\n@group(0) @binding(0) var<uniform> p: P;\n@fragment\nfn fs_main() -> @location(0) f32 {\n    return p.c.x;\n}\n",
            &["vec_range.wgsl:2:", "`range` applies to numbers"],
        ),
        (
            "infinite.wgsl",
            "struct P {\n    a: f32, // range = 0..inf\n}\n@group(0) @binding(0) var<uniform> p: P;\n@fragment\nfn fs_main() -> @location(0) f32 {\n    return p.a;\n}\n",
            &["infinite.wgsl:2:", "finite"],
        ),
        // The entry point's line, not a comment that mentions it; columns in characters.
        (
            "entry.wgsl",
            "// fn fs_main( is described here\n// λ\n@fragment\nfn fs_main() -> @location(0) vec3<f32> {\n    return vec3<f32>(1.0);\n}\n",
            &["entry.wgsl:4:1: ", "must return"],
        ),
    ];
    for (file, text, needles) in cases {
        write(dir.path(), file, text);
        let e = load_error(dir.path(), &one(file));
        for needle in needles {
            assert!(e.contains(needle), "{file}: `{needle}` not in: {e}");
        }
    }
    // No fragment stage, a missing file, no file at all.
    write(
        dir.path(),
        "none.wgsl",
        "@vertex fn vs() -> @builtin(position) vec4<f32> { return vec4<f32>(0.0); }",
    );
    let e = load_error(dir.path(), &one("none.wgsl"));
    assert!(e.contains("exactly one @fragment entry point"), "{e}");
    let e = load_error(dir.path(), &one("missing.wgsl"));
    assert!(e.contains("missing.wgsl: cannot read the shader"), "{e}");
    // Not a regular file: a folder, a device that never ends.
    std::fs::create_dir(dir.path().join("folder.wgsl")).unwrap();
    let e = load_error(dir.path(), &one("folder.wgsl"));
    assert!(e.contains("not a regular file"), "{e}");
    let e = load_error(dir.path(), &one("/dev/zero"));
    assert!(e.contains("not a regular file"), "{e}");
    // A column after a non-ASCII character counts characters.
    write(
        dir.path(),
        "lambda.wgsl",
        "@fragment\nfn fs_main() -> @location(0) f32 {\n    let λ = 1.0; let b: f32 = vec2<f32>(λ);\n    return b;\n}\n",
    );
    let e = load_error(dir.path(), &one("lambda.wgsl"));
    assert!(e.contains("lambda.wgsl:3:22:"), "{e}");
    let e = load_error(
        dir.path(),
        &graph_text("(id: \"mine\", kind: \"CustomShader\", params: {}),", ""),
    );
    assert!(e.contains("no shader file"), "{e}");
}

#[test]
fn an_edit_of_the_file_is_seen_and_a_broken_file_keeps_the_last_good_ports() {
    let dir = tempfile::tempdir().unwrap();
    let shader = write(dir.path(), "mix.wgsl", MIX);
    let registry = hatchery_nodes::registry();
    let raw = BTreeMap::from([("shader".to_owned(), ron::Value::String("mix.wgsl".into()))]);
    let read = || {
        registry
            .own_schema("CustomShader", &raw, Some(dir.path()))
            .unwrap()
    };
    let first = read();
    assert_eq!(first.error, None);
    // A live edit: a new member appears as a parameter, the fingerprint changes.
    std::fs::write(
        &shader,
        MIX.replace(
            "    steps: i32,",
            "    gamma: f32, // default = 2.2, range = 1..3\n    steps: i32,",
        ),
    )
    .unwrap();
    let second = read();
    assert_eq!(second.error, None);
    assert_ne!(second.fingerprint, first.fingerprint);
    let gamma = second.schema.as_ref().unwrap().param("gamma").unwrap();
    assert_eq!(gamma.default, ParamValue::Float(2.2));
    // A deliberate syntax error: the error is reported, the last good ports stay.
    std::fs::write(&shader, MIX.replace("let m =", "let m = = ")).unwrap();
    let broken = read();
    let message = broken.error.expect("broken file");
    assert!(message.contains("mix.wgsl:"), "{message}");
    let kept = broken.schema.expect("last good schema");
    assert_eq!(kept.input_names(), ["picture", "where_mask"]);
    assert!(kept.param("gamma").is_some());
}

#[test]
fn the_executor_reruns_a_custom_shader_when_its_file_changes() {
    let dir = tempfile::tempdir().unwrap();
    let shader = write(dir.path(), "solid.wgsl", GRADIENT);
    let graph = write(
        dir.path(),
        "graph.ron",
        &graph_text(&custom("g", "solid.wgsl", ""), ""),
    );
    let registry = hatchery_nodes::registry();
    let mut session = Session::open(&graph, W, H).unwrap();
    assert!((pixels(&mut session, "g", "image").texel(3, 3)[2] - 0.25).abs() < 1e-3);
    std::fs::write(&shader, GRADIENT.replace("0.25, 1.0", "0.750, 1.0")).unwrap();
    // What the editor does on a file change: validate again, run with the kept cache.
    session.graph = Graph::load_file(&graph, &registry).unwrap();
    let report = session.run(&["g"]).unwrap();
    assert_eq!(report.executed, ["g"]);
    assert!((pixels(&mut session, "g", "image").texel(3, 3)[2] - 0.75).abs() < 1e-3);
    // Unchanged: cached.
    session.graph = Graph::load_file(&graph, &registry).unwrap();
    assert_eq!(session.run(&["g"]).unwrap().cached, ["g"]);
}

#[test]
fn tolerant_of_what_editors_and_generators_write() {
    let dir = tempfile::tempdir().unwrap();
    // A byte-order mark (Windows editors), CRLF line ends, an attribute before a member.
    write(
        dir.path(),
        "bom.wgsl",
        "\u{feff}struct P {\r\n    @align(16) level: f32, // default = 0.5, range = 0..1\r\n}\r\n@group(0) @binding(0) var<uniform> p: P;\r\n@fragment\r\nfn fs_main() -> @location(0) vec4<f32> {\r\n    return vec4<f32>(p.level, 0.0, 0.0, 1.0);\r\n}\r\n",
    );
    // A machine-written shader with a 30,000-term expression (deeper than a normal stack).
    let long = vec!["1.0"; 30_000].join(" + ");
    write(
        dir.path(),
        "long.wgsl",
        &format!(
            "@fragment\nfn fs_main() -> @location(0) f32 {{\n    return ({long}) / 30000.0;\n}}\n"
        ),
    );
    let nodes = [
        custom("bom", "bom.wgsl", ""),
        custom("long", "long.wgsl", ""),
    ]
    .join("\n");
    let mut session = open(dir.path(), &graph_text(&nodes, ""));
    let red = pixels(&mut session, "bom", "image").texel(1, 1)[0];
    assert!(
        (red - 0.5).abs() < 1e-3,
        "the default from the comment: {red}"
    );
    let one = pixels(&mut session, "long", "mask").texel(1, 1)[0];
    assert!((one - 1.0).abs() < 1e-3, "{one}");
}

#[test]
fn a_value_for_a_uniform_the_shader_no_longer_declares_is_kept_but_unused() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "mix.wgsl", MIX);
    write(dir.path(), "gradient.wgsl", GRADIENT);
    write(dir.path(), "checker.wgsl", CHECKER);
    // `old_amount` was renamed in the shader: the graph still validates and renders.
    let nodes = [
        custom("gradient", "gradient.wgsl", ""),
        custom("checker", "checker.wgsl", ""),
        custom("mix", "mix.wgsl", "\"old_amount\": 0.5, \"amount\": 0.0"),
    ]
    .join("\n");
    let edges = "(from: (\"gradient\", \"image\"), to: (\"mix\", \"picture\")),
                 (from: (\"checker\", \"mask\"), to: (\"mix\", \"where_mask\")),";
    let path = write(dir.path(), "graph.ron", &graph_text(&nodes, edges));
    let registry = hatchery_nodes::registry();
    let graph = Graph::load_file(&path, &registry).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        graph
            .node("mix")
            .unwrap()
            .params
            .get("old_amount")
            .is_none()
    );
    // The document keeps it (nothing the user wrote is lost).
    let (doc, _) = hatchery_graph::GraphDocument::load(&path).unwrap();
    assert!(doc.node("mix").unwrap().params.contains_key("old_amount"));
    // Ordinary nodes still refuse unknown parameters.
    let bad = graph_text(
        "(id: \"camera\", kind: \"Camera\", params: {\"zoom\": 2.0}),",
        "",
    );
    assert!(load_error(dir.path(), &bad).contains("has no parameter `zoom`"));
}

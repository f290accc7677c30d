//! Vector export: `hatchery render -o figure.svg` on a graph with SaveSvg, read back by real SVG
//! libraries (roxmltree for the document, usvg to parse, resvg to rasterise): the line layer
//! matches the mask it was traced from, labels are <text> at the layout's places.

mod common;

use hatchery_nodes::{Session, export};
use std::process::Command;

const GRAPH: &str = r#"(
    version: 2,
    nodes: [
        (id: "camera", kind: "Camera", params: {"distance": 3.2, "azimuth": 20.0, "elevation": 15.0}),
        (id: "field", kind: "ProceduralVolume", params: {"shape": "torus", "resolution": 64}),
        (id: "surface", kind: "MarchingCubes", params: {"iso": 0.0}),
        (id: "layer", kind: "GBuffer"),
        (id: "lines", kind: "Silhouette"),
        (id: "light", kind: "Light"),
        (id: "shade", kind: "ShadedSurface"),
        (id: "parts", kind: "AnnotationList", params: {"anchors": "0.7 0 0: rim; -0.7 0 0: far rim; 0 0.15 0.7: top & <front>"}),
        (id: "layout", kind: "AnnotationLayout", params: {"font_size": 14.0}),
        (id: "svg", kind: "SaveSvg", params: {"path": "unused.svg", "color1": [0.8, 0.1, 0.1, 1.0], "width1": 1.0}),
        (id: "png", kind: "SaveImage", params: {"path": "unused.png"}),
    ],
    edges: [
        (from: ("field", "volume"), to: ("surface", "volume")),
        (from: ("surface", "mesh"), to: ("layer", "mesh")),
        (from: ("camera", "camera"), to: ("layer", "camera")),
        (from: ("layer", "gbuffer"), to: ("lines", "gbuffer")),
        (from: ("surface", "mesh"), to: ("shade", "mesh")),
        (from: ("camera", "camera"), to: ("shade", "camera")),
        (from: ("light", "light"), to: ("shade", "light")),
        (from: ("shade", "image"), to: ("svg", "image")),
        (from: ("shade", "image"), to: ("png", "image")),
        (from: ("lines", "mask"), to: ("svg", "lines1")),
        (from: ("parts", "annotations"), to: ("layout", "annotations")),
        (from: ("camera", "camera"), to: ("layout", "camera")),
        (from: ("layout", "annotations"), to: ("svg", "annotations")),
    ],
)"#;

const SIZE: (u32, u32) = (240, 180);

#[test]
fn render_to_svg_writes_layers_whose_lines_match_the_mask_and_whose_labels_are_the_layouts() {
    let dir = tempfile::tempdir().unwrap();
    let graph = dir.path().join("figure.ron");
    std::fs::write(&graph, GRAPH).unwrap();
    let svg_path = dir.path().join("out.svg");
    let status = Command::new(env!("CARGO_BIN_EXE_hatchery"))
        .args([
            "render",
            graph.to_str().unwrap(),
            "-o",
            svg_path.to_str().unwrap(),
        ])
        .args(["--size", &format!("{}x{}", SIZE.0, SIZE.1)])
        .status()
        .unwrap();
    assert!(status.success());
    // -o out.svg also wrote the graph's PNG as out.png.
    assert!(dir.path().join("out.png").exists());
    let text = std::fs::read_to_string(&svg_path).unwrap();

    // The same graph in-process: the mask and the layout the SVG was made from.
    let mut session = Session::open(&graph, SIZE.0, SIZE.1).unwrap();
    session.run(&["lines", "layout"]).unwrap();
    let mask =
        export::to_array(session.output("lines", "mask").unwrap(), &session.ctx.gpu).unwrap();
    let annotations = match session.output("layout", "annotations").unwrap() {
        hatchery_nodes::Value::Annotations(a) => a.clone(),
        _ => unreachable!(),
    };
    let placed = annotations.placed("annotations").unwrap();

    // The document: six Inkscape layers; the lines layer holds paths; labels are <text>.
    let doc = roxmltree::Document::parse(&text).unwrap();
    let layer = |id: &str| {
        doc.descendants()
            .find(|n| n.tag_name().name() == "g" && n.attribute("id") == Some(id))
            .unwrap_or_else(|| panic!("no layer {id}"))
    };
    for id in ["picture", "strokes", "lines", "leaders", "arrows", "labels"] {
        let g = layer(id);
        assert_eq!(
            g.attribute(("http://www.inkscape.org/namespaces/inkscape", "groupmode")),
            Some("layer")
        );
    }
    assert!(
        layer("picture")
            .descendants()
            .any(|n| n.tag_name().name() == "image")
    );
    // One filled path for the mask (`lines_as = shapes`), a sub-path per traced contour.
    let paths: Vec<_> = layer("lines")
        .descendants()
        .filter(|n| n.tag_name().name() == "path")
        .collect();
    assert_eq!(paths.len(), 1);
    let contours = paths[0].attribute("d").unwrap().matches('M').count();
    assert!(contours >= 2, "{contours} traced contours");
    let texts: Vec<_> = layer("labels")
        .descendants()
        .filter(|n| n.tag_name().name() == "text")
        .collect();
    let shown: Vec<_> = placed.layout.shown().collect();
    assert!(!shown.is_empty());
    for label in &shown {
        let want = &annotations.anchors[label.anchor].text;
        let node = texts
            .iter()
            .find(|t| t.text() == Some(want.as_str()))
            .unwrap_or_else(|| panic!("no <text> {want}"));
        let x: f32 = node.attribute("x").unwrap().parse().unwrap();
        let y: f32 = node.attribute("y").unwrap().parse().unwrap();
        let ascent = hatchery_nodes::label_font::ascent(placed.font_size);
        let pad = hatchery_nodes::annotation_layout::LABEL_PADDING;
        assert!((x - (label.rect.min.x + pad)).abs() < 0.01, "{want}: x {x}");
        assert!(
            (y - (label.rect.min.y + pad + ascent)).abs() < 0.01,
            "{want}: y {y}"
        );
    }

    // usvg parses it; resvg draws the lines layer alone, which lies on the mask: every mask
    // pixel has a drawn pixel within 1 px (the outlines of lines one to three pixels wide).
    let lines_only = {
        let mut t = text.clone();
        for id in ["picture", "leaders", "arrows", "labels"] {
            let start = t.find(&format!("id=\"{id}\"")).unwrap();
            let open = t[..start].rfind("<g").unwrap();
            let close = open
                + t[open..]
                    .find("</g>")
                    .map(|e| e + 4)
                    .unwrap_or_else(|| t[open..].find("/>").unwrap() + 2);
            t.replace_range(open..close, "");
        }
        t
    };
    let tree = usvg::Tree::from_str(&lines_only, &usvg::Options::default()).unwrap();
    let mut pixmap = tiny_skia::Pixmap::new(SIZE.0, SIZE.1).unwrap();
    resvg::render(
        &tree,
        tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    let drawn = |x: i64, y: i64| {
        x >= 0
            && y >= 0
            && x < SIZE.0 as i64
            && y < SIZE.1 as i64
            && pixmap.pixel(x as u32, y as u32).unwrap().alpha() > 25
    };
    let (w, h) = (mask.shape[1], mask.shape[0]);
    let (mut on, mut total) = (0usize, 0usize);
    for y in 0..h {
        for x in 0..w {
            if mask.data[y * w + x] <= 0.5 {
                continue;
            }
            total += 1;
            let near = (-1..=1).any(|dy| (-1..=1).any(|dx| drawn(x as i64 + dx, y as i64 + dy)));
            on += usize::from(near);
        }
    }
    assert!(total > 200, "{total} mask pixels");
    // And the other way: what is drawn lies on the mask (no hole filled, nothing outside).
    let in_mask = |x: i64, y: i64| {
        x >= 0
            && y >= 0
            && (x as usize) < w
            && (y as usize) < h
            && mask.data[y as usize * w + x as usize] > 0.5
    };
    let (mut inked, mut supported) = (0usize, 0usize);
    for y in 0..h as i64 {
        for x in 0..w as i64 {
            if pixmap.pixel(x as u32, y as u32).unwrap().alpha() > 128 {
                inked += 1;
                supported +=
                    usize::from((-1..=1).any(|dy| (-1..=1).any(|dx| in_mask(x + dx, y + dy))));
            }
        }
    }
    assert!(
        supported as f64 >= 0.99 * inked as f64,
        "{supported} of {inked} drawn pixels lie within 1 px of the mask"
    );
    assert!(
        on as f64 >= 0.99 * total as f64,
        "{on} of {total} mask pixels have a drawn line pixel within 1 px"
    );
}

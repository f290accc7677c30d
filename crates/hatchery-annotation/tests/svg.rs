//! SVG export: structure (parsed with usvg and roxmltree), label texts and positions equal to the
//! layout's, and the line layer of a traced ellipse rasterised with resvg against the mask.

mod common;

use common::{FRAME, Rng, random_scene};
use glam::Vec2;
use hatchery_annotation::{
    Color, LabelStyle, Layer, LayoutParams, PathData, PathStyle, Stroke, SvgDocument,
    label_baseline, layout, trace_mask,
};
use usvg::roxmltree;

fn count_nodes(group: &usvg::Group, paths: &mut usize, texts: &mut usize, images: &mut usize) {
    for node in group.children() {
        match node {
            usvg::Node::Group(g) => count_nodes(g, paths, texts, images),
            usvg::Node::Path(_) => *paths += 1,
            usvg::Node::Text(_) => *texts += 1,
            usvg::Node::Image(_) => *images += 1,
        }
    }
}

fn png_bytes(width: u32, height: u32) -> Vec<u8> {
    let mut pixmap = tiny_skia::Pixmap::new(width, height).unwrap();
    pixmap.fill(tiny_skia::Color::from_rgba8(200, 220, 240, 255));
    pixmap.encode_png().unwrap()
}

#[test]
fn document_structure_texts_and_positions() {
    let mut rng = Rng::new(42);
    let scene = loop {
        let s = random_scene(&mut rng);
        if s.anchors.len() >= 10 {
            break s;
        }
    };
    let result = layout(
        &scene.anchors,
        &scene.sizes,
        &scene.hull_points,
        FRAME,
        &LayoutParams::default(),
        None,
    );
    let texts: Vec<String> = (0..scene.anchors.len())
        .map(|i| format!("label {i} <&> \"q\""))
        .collect();
    let style = LabelStyle::default();
    let mut doc = SvgDocument::new(FRAME.x, FRAME.y);
    doc.picture_png(&png_bytes(80, 60));
    // Lines: the hull as a closed polyline, and two open strokes.
    let hull = hatchery_annotation::Polyline {
        points: result.path.vertices().to_vec(),
        closed: true,
    };
    doc.polyline(&hull, Stroke::new(Color::BLACK, 1.5));
    for k in 0..2 {
        let y = 50.0 + 10.0 * k as f32;
        let line = hatchery_annotation::Polyline {
            points: vec![Vec2::new(10.0, y), Vec2::new(100.0, y + 5.0)],
            closed: false,
        };
        doc.polyline(&line, Stroke::new(Color(40, 40, 40), 1.0));
    }
    // Arrows: a filled triangle and a curve.
    doc.path(
        Layer::Arrows,
        PathData::new()
            .move_to(Vec2::new(700.0, 500.0))
            .line_to(Vec2::new(720.0, 510.0))
            .line_to(Vec2::new(700.0, 520.0))
            .close(),
        PathStyle {
            fill: Some((Color(200, 0, 0), 0.8)),
            stroke: None,
        },
    );
    doc.path(
        Layer::Arrows,
        PathData::new().move_to(Vec2::new(600.0, 500.0)).cubic_to(
            Vec2::new(620.0, 450.0),
            Vec2::new(650.0, 550.0),
            Vec2::new(690.0, 510.0),
        ),
        PathStyle {
            fill: None,
            stroke: Some(Stroke::new(Color(200, 0, 0), 2.0)),
        },
    );
    doc.annotations(&result, &texts, &style, Stroke::new(Color::BLACK, 1.0));
    let svg = doc.to_svg_string();
    let shown: Vec<_> = result.shown().collect();
    assert!(shown.len() >= 5);

    // XML structure: six layers in order, texts and positions as laid out.
    let xml = roxmltree::Document::parse(&svg).expect("well-formed XML");
    let inkscape = "http://www.inkscape.org/namespaces/inkscape";
    let layers: Vec<_> = xml
        .root_element()
        .children()
        .filter(|n| n.is_element())
        .collect();
    let ids: Vec<&str> = layers.iter().map(|g| g.attribute("id").unwrap()).collect();
    assert_eq!(
        ids,
        [
            "picture",
            "covered-lines",
            "strokes",
            "lines",
            "leaders",
            "arrows",
            "labels"
        ]
    );
    // Covered lines are hidden (the figure stays the picture); the others show.
    for g in &layers {
        let hidden = g.attribute("style") == Some("display:none");
        assert_eq!(hidden, g.attribute("id") == Some("covered-lines"));
        assert_eq!(g.tag_name().name(), "g");
        assert_eq!(g.attribute((inkscape, "groupmode")), Some("layer"));
        assert!(g.attribute((inkscape, "label")).is_some());
    }
    let image = layers[0]
        .children()
        .find(|n| n.has_tag_name("image"))
        .unwrap();
    assert!(
        image
            .attribute("href")
            .unwrap()
            .starts_with("data:image/png;base64,iVBORw0KGgo")
    );
    let text_nodes: Vec<_> = layers[6]
        .children()
        .filter(|n| n.has_tag_name("text"))
        .collect();
    assert_eq!(text_nodes.len(), shown.len());
    for (node, label) in text_nodes.iter().zip(&shown) {
        assert_eq!(node.text(), Some(texts[label.anchor].as_str()));
        let at = label_baseline(&label.rect, style.font_size);
        let x: f32 = node.attribute("x").unwrap().parse().unwrap();
        let y: f32 = node.attribute("y").unwrap().parse().unwrap();
        assert!(
            (x - at.x).abs() <= 5e-4 && (y - at.y).abs() <= 5e-4,
            "{x},{y} vs {at}"
        );
        assert_eq!(node.attribute("paint-order"), Some("stroke"));
    }
    let leaders: Vec<_> = layers[4]
        .children()
        .filter(|n| n.has_tag_name("path"))
        .collect();
    assert_eq!(leaders.len(), shown.len());

    // usvg's tree: 3 line paths + leaders + 2 arrows, one image; texts when fonts exist here.
    let mut options = usvg::Options::default();
    options.fontdb_mut().load_system_fonts();
    let fonts = options.fontdb.len();
    let tree = usvg::Tree::from_str(&svg, &options).expect("usvg parses the document");
    let (mut paths, mut text_count, mut images) = (0, 0, 0);
    count_nodes(tree.root(), &mut paths, &mut text_count, &mut images);
    assert_eq!(paths, 3 + shown.len() + 2);
    assert_eq!(images, 1);
    if fonts > 0 {
        assert_eq!(text_count, shown.len());
    } else {
        println!("no system fonts: usvg drops texts, checked through the XML only");
    }
    println!(
        "{} shown labels; usvg: {paths} paths, {text_count} texts, {images} image ({fonts} font faces)",
        shown.len()
    );
}

#[test]
fn traced_ellipse_line_layer_matches_the_mask_boundary() {
    let (w, h) = (180usize, 140usize);
    let (c, radii, angle) = (Vec2::new(91.3, 68.7), Vec2::new(70.0, 45.0), 0.4f32);
    let (s, co) = angle.sin_cos();
    let inside = |x: usize, y: usize| {
        let d = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) - c;
        let local = Vec2::new(co * d.x + s * d.y, -s * d.x + co * d.y) / radii;
        local.length_squared() <= 1.0
    };
    let mask: Vec<f32> = (0..w * h)
        .map(|i| f32::from(inside(i % w, i / w)))
        .collect();
    let lines = trace_mask(&mask, w, h, 0.5, 0.5);
    assert_eq!(lines.len(), 1);
    let mut doc = SvgDocument::new(w as f32, h as f32);
    for line in &lines {
        doc.polyline(line, Stroke::new(Color::BLACK, 1.0));
    }
    let svg = doc.to_svg_string();
    let tree = usvg::Tree::from_str(&svg, &usvg::Options::default()).unwrap();
    let mut pixmap = tiny_skia::Pixmap::new(w as u32, h as u32).unwrap();
    resvg::render(
        &tree,
        tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    let alpha = |x: usize, y: usize| pixmap.pixels()[y * w + x].alpha();

    // Boundary pixels: inside pixels with a 4-neighbour outside.
    let mut boundary = Vec::new();
    for y in 0..h {
        for x in 0..w {
            if !inside(x, y) {
                continue;
            }
            let out = |dx: isize, dy: isize| {
                let (nx, ny) = (x as isize + dx, y as isize + dy);
                nx < 0
                    || ny < 0
                    || nx >= w as isize
                    || ny >= h as isize
                    || !inside(nx as usize, ny as usize)
            };
            if out(-1, 0) || out(1, 0) || out(0, -1) || out(0, 1) {
                boundary.push((x, y));
            }
        }
    }
    let near_line = |x: usize, y: usize, reach: isize, min_alpha: u8| {
        (-reach..=reach).any(|dy| {
            (-reach..=reach).any(|dx| {
                let (nx, ny) = (x as isize + dx, y as isize + dy);
                nx >= 0
                    && ny >= 0
                    && nx < w as isize
                    && ny < h as isize
                    && alpha(nx as usize, ny as usize) >= min_alpha
            })
        })
    };
    let covered = boundary
        .iter()
        .filter(|&&(x, y)| near_line(x, y, 1, 64))
        .count();
    let fraction = covered as f64 / boundary.len() as f64;
    // And the other way: drawn pixels lie near the boundary.
    boundary.sort_unstable();
    let is_boundary = |x: usize, y: usize| boundary.binary_search(&(x, y)).is_ok();
    let drawn: Vec<(usize, usize)> = (0..w * h)
        .filter(|&i| alpha(i % w, i / w) >= 64)
        .map(|i| (i % w, i / w))
        .collect();
    let stray = drawn
        .iter()
        .filter(|&&(x, y)| {
            !(-2isize..=2).any(|dy| {
                (-2isize..=2).any(|dx| {
                    let (nx, ny) = (x as isize + dx, y as isize + dy);
                    nx >= 0 && ny >= 0 && is_boundary(nx as usize, ny as usize)
                })
            })
        })
        .count();
    println!(
        "ellipse: {} boundary pixels, {:.2} % with a line pixel within 1 px; {} drawn pixels, {stray} \
         farther than 2 px from the boundary; {} vertices",
        boundary.len(),
        100.0 * fraction,
        drawn.len(),
        lines[0].points.len()
    );
    assert!(fraction >= 0.99, "{fraction}");
    assert_eq!(stray, 0);
}

//! Every preset in graphs/ loads, validates and renders a non-blank picture, so none can rot.

mod common;

use hatchery_nodes::{Session, export};

#[test]
fn every_preset_loads_validates_and_renders() {
    let mut rendered = Vec::new();
    let presets = common::presets();
    for path in presets {
        let mut session =
            Session::open(&path, 320, 240).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        // Render what each SaveImage would write, without writing into graphs/.
        let savers = common::savers(&session);
        assert!(
            !savers.is_empty(),
            "{}: a preset must save an image",
            path.display()
        );
        for saver in savers {
            let picture = common::saver_input(&mut session, &saver)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let fraction = common::non_background_fraction(&picture);
            if !(0.005..0.98).contains(&fraction) {
                let saved = common::save_failure(&format!("preset_{saver}"), &picture);
                panic!(
                    "{}: {saver} covers {fraction:.3} of the frame (blank?); see {}",
                    path.display(),
                    saved.display()
                );
            }
            rendered.push(path.file_name().unwrap().to_string_lossy().into_owned());
        }
    }
    assert!(
        rendered.contains(&"shaded_surface.ron".to_owned())
            && rendered.contains(&"brain_surface.ron".to_owned())
    );
}

/// The presets on the shared MRI and frog render as they did before volumes carried a full
/// voxel → world transform and kept their native voxel types: 256×192 renders by the binary of
/// commit 96c2639 are in tests/fixtures/before_world_space/, the five ray-cast ones
/// (context_preserving_brain, style_tf_*, tf1d_phong_brain, volume_toon) re-drawn when the first
/// sample's jitter changed hash (issue 33, PCG instead of fract(sin(x)·43758), whose bits rested
/// on each driver's sin): only the jitter noise moved, worst 15–30/255 on the brains, single
/// pixels on the frog's thin bones and the toon outline; the other five still match 96c2639's. Their cameras are held at the fixed
/// target and distance they were written with (`framing` "fixed"; they frame their data now), so
/// this also shows that their data-relative values (iso "range(80/255)", …) resolve to the
/// numbers they replaced.
///
/// Tolerance: every channel within 1/255. One exception, by kind: where a label volume picks the
/// transfer function's row (§4.2 of Bruckner & Gröller 2007: the label at the *nearest* voxel),
/// a sample that lies within float rounding of a voxel face between two labels can take the other
/// label now that rays march in voxel space (q = q₀ + t·dq instead of (p − origin) / spacing);
/// there at most 1 in 10,000 channels may differ by more, none beyond 16/255 (style_tf_frog: 8 of
/// 49,152 pixels).
#[test]
fn shared_data_presets_render_as_before_the_world_space_change() {
    const SAMPLERS: [&str; 6] = [
        "Raycast",
        "IsoSurfaceRaycast",
        "TwoLevelRaycast",
        "SelectionRender",
        "Curvature",
        "CurvatureContours",
    ];
    let dir = common::repo_root().join("tests/fixtures/before_world_space");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    names.sort();
    assert!(names.len() >= 10, "the reference renders are missing");
    let mut failures = Vec::new();
    for reference in names {
        let name = reference
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        let graph = common::repo_root()
            .join("graphs")
            .join(format!("{name}.ron"));
        let mut session = Session::open(&graph, 256, 192).unwrap();
        session
            .set_param_text("camera", "framing", "fixed")
            .unwrap();
        // The references were drawn with GBuffer + DepthPeel; a preset on DepthLayers is
        // compared in its `peel` method (the same two passes). The one-pass k-buffer's few
        // flipped line pixels are bounded in tests/depth_layers.rs.
        let k_buffers: Vec<String> = session
            .graph
            .nodes()
            .filter(|n| n.kind == "DepthLayers")
            .map(|n| n.id.clone())
            .collect();
        for id in k_buffers {
            session.set_param_text(&id, "method", "peel").unwrap();
        }
        // Likewise a preset on the B-spline (issue 36) is compared with the trilinear filter
        // the references were drawn with; tests/reconstruction.rs checks the B-spline.
        let samplers: Vec<String> = session
            .graph
            .nodes()
            .filter(|n| SAMPLERS.contains(&n.kind.as_str()))
            .map(|n| n.id.clone())
            .collect();
        for id in samplers {
            session
                .set_param_text(&id, "reconstruction", "trilinear")
                .unwrap();
        }
        let nearest_label_rows = session.graph.nodes().any(|n| {
            n.kind == "StyleTransferFunction" && !n.params.text("label_nodes").trim().is_empty()
        });
        let saver = session
            .graph
            .nodes()
            .find(|n| n.kind == "SaveImage")
            .unwrap()
            .id
            .clone();
        let (source, port) = {
            let sources = session.graph.input_sources(&saver);
            let (node, port) = sources[&0];
            (node.to_owned(), port)
        };
        session.run(&[&source]).unwrap();
        let value = session.executor.output(&source, port).unwrap().clone();
        let picture = export::to_rgba8(&value, &session.ctx.gpu).unwrap();
        let before = common::read_png(&reference);
        // Channel by channel: the pictures as rows of 4 × width single channels.
        let (now, then) = (picture.as_raw().as_slice(), before.as_raw().as_slice());
        let diff = common::diff_images(now, then, 4 * picture.width(), |_| true, 1.0);
        let worst = (diff.worst as u8, diff.x / 4, diff.y);
        let over_one = diff.over.len();
        let channels = 4 * picture.width() as usize * picture.height() as usize;
        eprintln!(
            "{name}: worst channel difference {}/255 at ({}, {}); {over_one} of {channels} \
             channels differ by more than 1/255",
            worst.0, worst.1, worst.2
        );
        let allowed = if nearest_label_rows {
            channels / 10_000
        } else {
            0
        };
        if worst.0 > 16 || over_one > allowed {
            let saved = common::save_failure(&format!("before_{name}"), &picture);
            failures.push(format!(
                "{name}: off by {}/255 at ({}, {}) ({over_one} channels over 1/255); now {:?}, \
                 before {:?}; see {}",
                worst.0,
                worst.1,
                worst.2,
                picture.get_pixel(worst.1, worst.2),
                before.get_pixel(worst.1, worst.2),
                saved.display()
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

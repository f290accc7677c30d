//! Every preset in graphs/ loads, validates and renders a non-blank picture, so none can rot.

mod common;

use hatchery_nodes::{Session, export};

#[test]
fn every_preset_loads_validates_and_renders() {
    let mut rendered = Vec::new();
    let mut presets: Vec<_> = std::fs::read_dir(common::repo_root().join("graphs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    presets.sort();
    for path in presets {
        let mut session =
            Session::open(&path, 320, 240).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        // Render what each SaveImage would write, without writing into graphs/.
        let savers: Vec<String> = session
            .graph
            .nodes()
            .filter(|n| n.kind == "SaveImage")
            .map(|n| n.id.clone())
            .collect();
        assert!(
            !savers.is_empty(),
            "{}: a preset must save an image",
            path.display()
        );
        for saver in savers {
            let (source, port) = {
                let sources = session.graph.input_sources(&saver);
                let (node, port) = sources[&0];
                (node.to_owned(), port)
            };
            session
                .run(&[&source])
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let value = session.executor.output(&source, port).unwrap().clone();
            let picture = export::to_rgba8(&value, &session.ctx.gpu).unwrap();
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

//! Data-relative parameter values (issue 25): on each preset's own data they resolve to the
//! absolute numbers the preset held before (its version 2 copy in tests/fixtures/v2_presets/),
//! and on other data to values of that data's own range.

mod common;

use hatchery_graph::{GraphDocument, ParamValue};
use hatchery_nodes::{Session, Value};

/// Numbers of "value: …; value: …" entries.
fn entry_values(text: &str) -> Vec<f32> {
    text.split(';')
        .filter_map(|e| e.split_once(':'))
        .map(|(v, _)| v.trim().parse::<f32>().unwrap())
        .collect()
}

/// The volume feeding `node`'s input `port` in the session, after running its source.
fn input_volume(session: &mut Session, node: &str, port: &str) -> hatchery_data::VolumeData {
    let schema = session
        .graph
        .node(node)
        .unwrap()
        .schema(&session.registry)
        .unwrap();
    let index = schema.input_index(port).unwrap();
    let (source, out) = session.graph.input_sources(node)[&index];
    let source = source.to_owned();
    session.run(&[&source]).unwrap();
    match session.executor.output(&source, out).unwrap() {
        Value::Volume(v) => (*v.data).clone(),
        other => panic!("{node}.{port} is fed a {}", other.port_type()),
    }
}

#[test]
fn relative_values_resolve_to_the_numbers_they_replaced_on_the_presets_own_data() {
    let mut checked = 0;
    for preset in common::presets() {
        let name = preset.file_name().unwrap().to_owned();
        let old = common::repo_root()
            .join("tests/fixtures/v2_presets")
            .join(&name);
        // Presets written after issue 25 had no version 2 with absolute numbers.
        if !old.exists() {
            continue;
        }
        let (old, _) = GraphDocument::load(&old).unwrap();
        let mut session = Session::open(&preset, 64, 48).unwrap();
        let ids: Vec<String> = session.graph.node_ids().map(str::to_owned).collect();
        for id in ids {
            let values = session.graph.node(&id).unwrap().params.values().clone();
            for (param, value) in values {
                let Some(before) = old.node(&id).and_then(|n| n.params.get(&param)) else {
                    continue;
                };
                let what = format!("{}: {id}.{param}", name.to_string_lossy());
                match (&value, before) {
                    (ParamValue::Relative(r, _), ron::Value::Number(n)) => {
                        session
                            .run(&[&id])
                            .unwrap_or_else(|e| panic!("{what}: {e}"));
                        let text = &session.ctx.resolved()[&id][&param];
                        let resolved: f64 = text.rsplit("= ").next().unwrap().parse().unwrap();
                        assert!(
                            (resolved - n.into_f64()).abs() < 1e-4,
                            "{what}: {r} resolves to {resolved}, was {}",
                            n.into_f64()
                        );
                        checked += 1;
                    }
                    (ParamValue::Text(now), ron::Value::String(was))
                        if now != was && (param == "points" || param == "nodes") =>
                    {
                        let volume = input_volume(&mut session, &id, "volume");
                        let resolved =
                            hatchery_nodes::relative::resolve_point_values(now, Some(&volume))
                                .unwrap();
                        assert_eq!(entry_values(&resolved), entry_values(was), "{what}: {now}");
                        checked += 1;
                    }
                    _ => {}
                }
            }
        }
    }
    // 15 iso values and map floors, 8 transfer-function texts.
    assert!(checked >= 23, "only {checked} relative values checked");
}

#[test]
fn relative_values_follow_the_range_of_other_data() {
    use hatchery_graph::RelativeValue::{Otsu, Percentile, Range};
    use hatchery_nodes::relative::resolve;
    // A probability map in 0–1: the presets' map floor range(128/255) is one half.
    let map = common::field_on_cube(25, |p| (1.0 - p.length()).clamp(0.0, 1.0));
    assert!((resolve(Range(128.0 / 255.0), &map).unwrap() - 0.502).abs() < 1e-3);
    // An int16-like head, 0–1500: the MRI iso range(80/255) lands between air and tissue.
    let head = common::field_on_cube(24, |p| if p.length() < 0.7 { 1500.0 } else { 3.0 });
    let iso = resolve(Range(80.0 / 255.0), &head).unwrap();
    assert!(iso > 3.0 && iso < 1500.0, "{iso}");
    let otsu = resolve(Otsu, &head).unwrap();
    assert!(otsu > 3.0 && otsu <= 1500.0, "{otsu}");
    assert_eq!(resolve(Percentile(100.0), &head).unwrap(), 1500.0);
    // A constant volume has no two classes: a clear error, not a number.
    let flat = common::field_on_cube(8, |_| 7.0);
    assert!(
        resolve(Otsu, &flat)
            .unwrap_err()
            .to_string()
            .contains("two classes")
    );
}

//! The graph's controls (its `controls` section, hatchery_graph::controls) described for the page,
//! which builds a slider, switch, menu or colour picker for each.

use hatchery_graph::ParamValue;
use hatchery_graph::controls::ControlKind;
use hatchery_nodes::Session;
use serde_json::{Value, json};

/// `[{node, param, label, type, value, …}]`: `type` is `float` or `int` (with `min`, `max`),
/// `bool`, `choice` (with `choices`) or `color` (`value` "#rrggbb" and `alpha` kept as set).
pub fn describe(session: &Session) -> String {
    let controls: Vec<Value> = session
        .graph
        .controls()
        .iter()
        .map(|c| {
            let value = session
                .graph
                .node(&c.node)
                .and_then(|n| n.params.get(&c.param));
            let mut out = json!({ "node": c.node, "param": c.param, "label": c.label });
            let fields = match (&c.kind, value) {
                (ControlKind::Slider { min, max, integer }, v) => json!({
                    "type": if *integer { "int" } else { "float" },
                    "min": min, "max": max,
                    "value": match v {
                        Some(ParamValue::Float(x)) => *x,
                        Some(ParamValue::Int(i)) => *i as f64,
                        _ => *min,
                    },
                }),
                (ControlKind::Toggle, v) => json!({
                    "type": "bool", "value": matches!(v, Some(ParamValue::Bool(true))),
                }),
                (ControlKind::Menu(names), v) => json!({
                    "type": "choice", "choices": names,
                    "value": match v { Some(ParamValue::Choice(c)) => c.as_str(), _ => "" },
                }),
                (ControlKind::Colour, v) => {
                    let [r, g, b, a] = match v {
                        Some(ParamValue::Color(c)) => *c,
                        _ => [0.0, 0.0, 0.0, 1.0],
                    };
                    let byte = |x: f64| (x.clamp(0.0, 1.0) * 255.0).round() as u8;
                    json!({
                        "type": "color",
                        "value": format!("#{:02x}{:02x}{:02x}", byte(r), byte(g), byte(b)),
                        "alpha": a,
                    })
                }
            };
            if let (Value::Object(out), Value::Object(fields)) = (&mut out, fields) {
                out.extend(fields);
            }
            out
        })
        .collect();
    Value::Array(controls).to_string()
}

//! What a context controls in a pass, with a mock context: the pixel scale of lengths in
//! pixels (`ParamSpec::pixels`, `hatchery render --scale`), the steps planned (progress) and
//! cancelling between steps (the editor's newer request) with what ran kept.

use hatchery_graph::executor::{ExecContext, Node, NodeInputs};
use hatchery_graph::{
    Executor, Graph, GraphDocument, NodeError, NodeSchema, ParamSpec, Params, PortSpec, PortType,
    Registry,
};

#[derive(Default)]
struct Ctx {
    scale: f64,
    planned: Vec<String>,
    begun: Vec<String>,
    /// Cancel once this many nodes have begun.
    cancel_after: Option<usize>,
}

impl ExecContext for Ctx {
    fn pixel_scale(&self) -> f64 {
        self.scale
    }
    fn begin_pass(&mut self, planned: &[&str]) {
        self.planned = planned.iter().map(|s| s.to_string()).collect();
    }
    fn cancelled(&self) -> bool {
        self.cancel_after.is_some_and(|n| self.begun.len() >= n)
    }
    fn begin_node(&mut self, node: &str) {
        self.begun.push(node.to_owned());
    }
}

/// `Line`: outputs `width` (a length in pixels) + `offset` (not a length) + its input.
struct LineNode;

impl Node<f64, Ctx> for LineNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Line",
            category: "Test",
            doc: "",
            inputs: vec![PortSpec::optional("a", PortType::Mask, "")],
            outputs: vec![PortSpec::output("out", PortType::Mask, "")],
            params: vec![
                ParamSpec::float("width", 1.5, 0.0, 8.0, "").pixels(),
                ParamSpec::int("taps", 1, 1, 8, "").pixels(),
                ParamSpec::float("offset", 0.25, -1e9, 1e9, ""),
            ],
            frame_dependent: false,
            sink: false,
        }
    }
    fn execute(
        &self,
        _ctx: &mut Ctx,
        inputs: &NodeInputs<f64>,
        params: &Params,
    ) -> Result<Vec<f64>, NodeError> {
        let a = inputs.get("a").copied().unwrap_or(0.0);
        Ok(vec![
            a + params.float("width") + params.float("offset") + 100.0 * params.int("taps") as f64,
        ])
    }
}

fn setup() -> (Registry<f64, Ctx>, Graph) {
    let mut registry = Registry::default();
    registry.register(LineNode);
    let text = "(version: 2, nodes: [(id: \"p\", kind: \"Line\"), (id: \"q\", kind: \"Line\"), \
                (id: \"r\", kind: \"Line\")], edges: [(from: (\"p\", \"out\"), to: (\"q\", \"a\")), \
                (from: (\"q\", \"out\"), to: (\"r\", \"a\"))])";
    let (doc, source) = GraphDocument::parse(text, None).unwrap();
    let graph = Graph::from_document(&doc, &source, &registry, None).unwrap();
    (registry, graph)
}

fn ctx(scale: f64) -> Ctx {
    Ctx {
        scale,
        ..Ctx::default()
    }
}

#[test]
fn lengths_in_pixels_are_scaled_before_a_node_reads_them() {
    let (registry, graph) = setup();
    let mut executor = Executor::new();
    executor
        .run(&graph, &registry, &mut ctx(1.0), &["p"])
        .unwrap();
    assert_eq!(executor.output("p", 0), Some(&(1.5 + 0.25 + 100.0)));
    // At scale 2 the width and the tap count double; the offset does not. The graph itself
    // keeps the values as written.
    let mut two = ctx(2.0);
    let report = executor.run(&graph, &registry, &mut two, &["p"]).unwrap();
    assert_eq!(
        report.executed,
        vec!["p"],
        "a change of scale re-runs the node"
    );
    assert_eq!(executor.output("p", 0), Some(&(3.0 + 0.25 + 200.0)));
    assert_eq!(graph.node("p").unwrap().params.float("width"), 1.5);
    let report = executor.run(&graph, &registry, &mut two, &["p"]).unwrap();
    assert!(report.executed.is_empty(), "same scale: cached");
}

#[test]
fn a_cancelled_pass_stops_between_steps_and_keeps_what_ran() {
    let (registry, graph) = setup();
    let mut executor = Executor::new();
    let mut c = ctx(1.0);
    c.cancel_after = Some(2);
    let error = executor.run(&graph, &registry, &mut c, &["r"]).unwrap_err();
    assert!(error.is_cancelled(), "{error}");
    assert_eq!(error.node, "r", "stopped before the third step");
    assert_eq!(
        c.planned,
        vec!["p", "q", "r"],
        "the steps planned, in order"
    );
    assert_eq!(c.begun, vec!["p", "q"]);
    // The next pass goes on from what ran.
    let mut c = ctx(1.0);
    let report = executor.run(&graph, &registry, &mut c, &["r"]).unwrap();
    assert_eq!(report.executed, vec!["r"]);
    assert_eq!(report.cached, vec!["p", "q"]);
    assert_eq!(c.planned, vec!["r"]);
    assert_eq!(executor.output("r", 0), Some(&(3.0 * 101.75)));
}

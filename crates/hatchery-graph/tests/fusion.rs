//! The executor's fused passes with a mock context: which nodes share a pass, what is kept, what
//! re-runs, and that a fused pass computes what the nodes compute one by one.

use hatchery_graph::executor::{ExecContext, Node, NodeInputs};
use hatchery_graph::fusion::{Fuser, Member, Outside, Source};
use hatchery_graph::{
    Executor, Graph, GraphDocument, NodeError, NodeSchema, ParamSpec, Params, PortSpec, PortType,
    Registry,
};

/// Records the passes: each a list of node ids (one id: a node alone).
#[derive(Default)]
struct Ctx {
    passes: Vec<Vec<String>>,
    max_group: usize,
    current: String,
}

impl ExecContext for Ctx {
    fn begin_node(&mut self, node: &str) {
        self.current = node.to_owned();
    }
}

/// Passes as written in a test.
fn passes(list: &[&[&str]]) -> Vec<Vec<String>> {
    list.iter()
        .map(|p| p.iter().map(|s| s.to_string()).collect())
        .collect()
}

fn schema(kind: &'static str, inputs: &[&'static str], params: Vec<ParamSpec>) -> NodeSchema {
    NodeSchema {
        kind,
        category: "Test",
        doc: "",
        inputs: inputs
            .iter()
            .map(|n| PortSpec::input(n, PortType::Mask, ""))
            .collect(),
        outputs: vec![PortSpec::output("out", PortType::Mask, "")],
        params,
        frame_dependent: false,
        sink: false,
    }
}

/// `Value`: no inputs, outputs its parameter. Not fusable.
struct ValueNode;
/// `Add`: a + b + k, pointwise in both inputs.
struct AddNode;
/// `Blur`: 2·a, reading its input around the pixel (not pointwise).
struct BlurNode;
/// `Opaque`: a + 100, never fused.
struct OpaqueNode;

fn evaluate(kind: &str, params: &Params, inputs: &[f64]) -> f64 {
    match kind {
        "Value" => params.float("v"),
        "Add" => inputs[0] + inputs[1] + params.float("k"),
        "Blur" => 2.0 * inputs[0],
        _ => inputs[0] + 100.0,
    }
}

fn run_alone(
    kind: &str,
    ctx: &mut Ctx,
    inputs: &NodeInputs<f64>,
    names: &[&str],
    params: &Params,
) -> Result<Vec<f64>, NodeError> {
    let values: Result<Vec<f64>, NodeError> =
        names.iter().map(|n| inputs.require(n).copied()).collect();
    ctx.passes.push(vec![ctx.current.clone()]);
    Ok(vec![evaluate(kind, params, &values?)])
}

impl Node<f64, Ctx> for ValueNode {
    fn schema(&self) -> NodeSchema {
        schema(
            "Value",
            &[],
            vec![ParamSpec::float("v", 1.0, -1e9, 1e9, "")],
        )
    }
    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<f64>,
        params: &Params,
    ) -> Result<Vec<f64>, NodeError> {
        run_alone("Value", ctx, inputs, &[], params)
    }
}

impl Node<f64, Ctx> for AddNode {
    fn schema(&self) -> NodeSchema {
        schema(
            "Add",
            &["a", "b"],
            vec![ParamSpec::float("k", 0.0, -1e9, 1e9, "")],
        )
    }
    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<f64>,
        params: &Params,
    ) -> Result<Vec<f64>, NodeError> {
        run_alone("Add", ctx, inputs, &["a", "b"], params)
    }
}

impl Node<f64, Ctx> for BlurNode {
    fn schema(&self) -> NodeSchema {
        schema("Blur", &["a"], Vec::new())
    }
    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<f64>,
        params: &Params,
    ) -> Result<Vec<f64>, NodeError> {
        run_alone("Blur", ctx, inputs, &["a"], params)
    }
}

impl Node<f64, Ctx> for OpaqueNode {
    fn schema(&self) -> NodeSchema {
        schema("Opaque", &["a"], Vec::new())
    }
    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<f64>,
        params: &Params,
    ) -> Result<Vec<f64>, NodeError> {
        run_alone("Opaque", ctx, inputs, &["a"], params)
    }
}

struct MockFuser;

impl Fuser<f64, Ctx> for MockFuser {
    fn pointwise(&self, kind: &str, _params: &Params) -> Option<Vec<bool>> {
        match kind {
            "Add" => Some(vec![true, true]),
            "Blur" => Some(vec![false]),
            _ => None,
        }
    }

    fn fits(&self, ctx: &Ctx, group: &[Member<'_, Outside<'_>>]) -> bool {
        group.len() <= ctx.max_group
    }

    fn run(
        &self,
        ctx: &mut Ctx,
        group: &[Member<'_, f64>],
    ) -> Result<Vec<Vec<Option<f64>>>, (usize, NodeError)> {
        let mut values: Vec<f64> = Vec::new();
        for (i, member) in group.iter().enumerate() {
            let mut inputs = Vec::new();
            for source in &member.inputs {
                inputs.push(match source {
                    Source::External(v) => *v,
                    Source::Member { member, .. } => {
                        assert!(*member < i, "a member reads a later one");
                        values[*member]
                    }
                    Source::Absent => {
                        return Err((i, NodeError::at_port("a", "input is not connected")));
                    }
                });
            }
            values.push(evaluate(member.kind, member.params, &inputs));
        }
        ctx.passes
            .push(group.iter().map(|m| m.id.to_owned()).collect());
        Ok(group
            .iter()
            .zip(values)
            .map(|(m, v)| vec![m.keep[0].then_some(v)])
            .collect())
    }
}

fn registry() -> Registry<f64, Ctx> {
    let mut r = Registry::default();
    r.register(ValueNode);
    r.register(AddNode);
    r.register(BlurNode);
    r.register(OpaqueNode);
    r.set_fuser(MockFuser);
    r
}

/// A graph from `nodes` (id, kind, params) and `edges` ((from, to, port)).
fn graph(
    registry: &Registry<f64, Ctx>,
    nodes: &[(&str, &str, &str)],
    edges: &[(&str, &str, &str)],
) -> Graph {
    let nodes: Vec<String> = nodes
        .iter()
        .map(|(id, kind, params)| format!("(id: \"{id}\", kind: \"{kind}\", params: {{{params}}})"))
        .collect();
    let edges: Vec<String> = edges
        .iter()
        .map(|(from, to, port)| {
            format!("(from: (\"{from}\", \"out\"), to: (\"{to}\", \"{port}\"))")
        })
        .collect();
    let text = format!(
        "(version: 2, nodes: [{}], edges: [{}])",
        nodes.join(", "),
        edges.join(", ")
    );
    let (doc, source) = GraphDocument::parse(&text, None).unwrap();
    Graph::from_document(&doc, &source, registry, None).unwrap()
}

/// x = 1, y = 2; s = x + y; t = s + y (+10); u = t + x; all Adds fuse into one pass.
fn chain(registry: &Registry<f64, Ctx>) -> Graph {
    graph(
        registry,
        &[
            ("x", "Value", "\"v\": 1.0"),
            ("y", "Value", "\"v\": 2.0"),
            ("s", "Add", ""),
            ("t", "Add", "\"k\": 10.0"),
            ("u", "Add", ""),
        ],
        &[
            ("x", "s", "a"),
            ("y", "s", "b"),
            ("s", "t", "a"),
            ("y", "t", "b"),
            ("t", "u", "a"),
            ("x", "u", "b"),
        ],
    )
}

fn ctx() -> Ctx {
    Ctx {
        max_group: 16,
        ..Ctx::default()
    }
}

#[test]
fn a_chain_of_pointwise_nodes_runs_as_one_pass_with_the_same_result() {
    let registry = registry();
    let graph = chain(&registry);
    let mut fused = Executor::new();
    let mut c = ctx();
    let report = fused.run(&graph, &registry, &mut c, &["u"]).unwrap();
    assert_eq!(report.executed.len(), 5);
    c.passes.sort();
    assert_eq!(c.passes, passes(&[&["s", "t", "u"], &["x"], &["y"]]));
    assert_eq!(fused.output("u", 0), Some(&(1.0 + 2.0 + 2.0 + 10.0 + 1.0)));
    // Inside the pass, only the target was written.
    assert_eq!(fused.output("s", 0), None);
    assert_eq!(fused.stats()["s"].fused_with, ["s", "t", "u"]);

    let mut alone = Executor::new();
    alone.set_fusion(false);
    let mut c2 = ctx();
    alone.run(&graph, &registry, &mut c2, &["u"]).unwrap();
    assert_eq!(c2.passes.len(), 5, "unfused: a pass per node");
    assert_eq!(alone.output("u", 0), fused.output("u", 0));
    assert_eq!(alone.output("s", 0), Some(&3.0));
}

#[test]
fn nothing_changed_nothing_runs_and_a_change_reruns_its_part() {
    let registry = registry();
    let mut graph = chain(&registry);
    let mut executor = Executor::new();
    let mut c = ctx();
    executor.run(&graph, &registry, &mut c, &["u"]).unwrap();
    c.passes.clear();

    let again = executor.run(&graph, &registry, &mut c, &["u"]).unwrap();
    assert!(again.executed.is_empty(), "{again:?}");
    assert!(c.passes.is_empty());

    // t's parameter: t and u run, fused; s stays cached although its output was not written.
    graph
        .set_param(&registry, "t", "k", hatchery_graph::ParamValue::Float(20.0))
        .unwrap();
    let changed = executor.run(&graph, &registry, &mut c, &["u"]).unwrap();
    assert_eq!(c.passes, passes(&[&["s", "t", "u"]]));
    assert_eq!(executor.output("u", 0), Some(&26.0));
    // s had to run again: t reads it and the last pass did not keep it.
    assert!(changed.executed.contains(&"s".to_owned()), "{changed:?}");
}

#[test]
fn a_node_asked_for_later_is_run_again_when_its_output_was_not_kept() {
    let registry = registry();
    let graph = chain(&registry);
    let mut executor = Executor::new();
    let mut c = ctx();
    executor.run(&graph, &registry, &mut c, &["u"]).unwrap();
    c.passes.clear();
    // s was fused and not kept: asking for it re-runs it (alone: nothing else is stale).
    let report = executor.run(&graph, &registry, &mut c, &["s"]).unwrap();
    assert_eq!(report.executed, ["s"]);
    assert_eq!(executor.output("s", 0), Some(&3.0));
    // That recomputed the same value: what reads s stays cached.
    let again = executor.run(&graph, &registry, &mut c, &["u"]).unwrap();
    assert!(again.executed.is_empty(), "{again:?}");
    // Both targets in one pass: both kept.
    let mut fresh = Executor::new();
    fresh.run(&graph, &registry, &mut c, &["u", "s"]).unwrap();
    assert_eq!(fresh.output("s", 0), Some(&3.0));
    assert_eq!(fresh.output("u", 0), Some(&16.0));
    assert_eq!(fresh.output("t", 0), None);
}

#[test]
fn a_path_through_an_unfusable_node_keeps_the_group_apart() {
    // s → o (Opaque) → w, and s → w: s and w cannot share a pass (o needs s first, w needs o).
    let registry = registry();
    let graph = graph(
        &registry,
        &[
            ("x", "Value", ""),
            ("s", "Add", ""),
            ("o", "Opaque", ""),
            ("w", "Add", ""),
        ],
        &[
            ("x", "s", "a"),
            ("x", "s", "b"),
            ("s", "o", "a"),
            ("o", "w", "a"),
            ("s", "w", "b"),
        ],
    );
    let mut executor = Executor::new();
    let mut c = ctx();
    executor.run(&graph, &registry, &mut c, &["w"]).unwrap();
    assert_eq!(c.passes.len(), 4, "{:?}", c.passes);
    assert_eq!(executor.output("w", 0), Some(&(102.0 + 2.0)));
    assert_eq!(executor.output("s", 0), Some(&2.0), "read by o: kept");
}

#[test]
fn a_non_pointwise_input_is_never_fed_from_inside_the_pass() {
    // s → Blur: the blur reads s around the pixel, so s must be written first; the blur may
    // still share a pass with what follows it.
    let registry = registry();
    let graph = graph(
        &registry,
        &[
            ("x", "Value", ""),
            ("s", "Add", ""),
            ("b", "Blur", ""),
            ("w", "Add", ""),
        ],
        &[
            ("x", "s", "a"),
            ("x", "s", "b"),
            ("s", "b", "a"),
            ("b", "w", "a"),
            ("x", "w", "b"),
        ],
    );
    let mut executor = Executor::new();
    let mut c = ctx();
    executor.run(&graph, &registry, &mut c, &["w"]).unwrap();
    assert_eq!(c.passes, passes(&[&["x"], &["s"], &["b", "w"]]));
    assert_eq!(executor.output("w", 0), Some(&5.0));
}

#[test]
fn the_context_can_refuse_a_group_that_does_not_fit() {
    let registry = registry();
    let graph = chain(&registry);
    let mut executor = Executor::new();
    let mut c = Ctx {
        max_group: 2,
        ..Ctx::default()
    };
    executor.run(&graph, &registry, &mut c, &["u"]).unwrap();
    let sizes: Vec<usize> = c.passes.iter().map(Vec::len).collect();
    assert!(sizes.iter().all(|&n| n <= 2), "{:?}", c.passes);
    assert_eq!(executor.output("u", 0), Some(&16.0));
}

#[test]
fn two_groups_that_would_need_each_other_are_not_formed() {
    // d reads s1 and y = Opaque(s2); c reads s2 and x = Opaque(s1). {s1, d} and {s2, c} are
    // each fine alone, but each needs the other's Opaque node, which needs the other group.
    let registry = registry();
    let graph = graph(
        &registry,
        &[
            ("v", "Value", "\"v\": 1.0"),
            ("s1", "Add", ""),
            ("s2", "Add", "\"k\": 1.0"),
            ("x", "Opaque", ""),
            ("y", "Opaque", ""),
            ("d", "Add", ""),
            ("c", "Add", ""),
        ],
        &[
            ("v", "s1", "a"),
            ("v", "s1", "b"),
            ("v", "s2", "a"),
            ("v", "s2", "b"),
            ("s1", "x", "a"),
            ("s2", "y", "a"),
            ("s1", "d", "a"),
            ("y", "d", "b"),
            ("s2", "c", "a"),
            ("x", "c", "b"),
        ],
    );
    let mut executor = Executor::new();
    let mut c = ctx();
    executor
        .run(&graph, &registry, &mut c, &["d", "c"])
        .unwrap();
    // s1 = 2, s2 = 3, x = 102, y = 103, d = 2 + 103, c = 3 + 102.
    assert_eq!(executor.output("d", 0), Some(&105.0));
    assert_eq!(executor.output("c", 0), Some(&105.0));
    // One of the two pairs still shares a pass (the planner refused only the second).
    let fused: Vec<&Vec<String>> = c.passes.iter().filter(|p| p.len() > 1).collect();
    assert_eq!(fused.len(), 1, "{:?}", c.passes);
    // A second pass after changing s2 reads fresh values everywhere.
    let mut graph = graph;
    graph
        .set_param(&registry, "s2", "k", hatchery_graph::ParamValue::Float(5.0))
        .unwrap();
    executor
        .run(&graph, &registry, &mut c, &["d", "c"])
        .unwrap();
    assert_eq!(executor.output("d", 0), Some(&(2.0 + 107.0)));
    assert_eq!(executor.output("c", 0), Some(&(7.0 + 102.0)));
}

//! The caching executor: pulls from target nodes in topological order and re-runs a node only
//! when its parameters or its inputs' versions changed.

use crate::fusion::{self, Member, Source, Unit};
use crate::graph::{Graph, NodeInstance};
pub use crate::registry::{ExecContext, Node, NodeInputs, Registry};
use crate::schema::{NodeSchema, SchemaLookup};
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::fmt;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::time::Duration;
use web_time::Instant;

/// An execution error, naming the node and, where known, the port.
#[derive(Clone, Debug, PartialEq)]
pub struct ExecError {
    pub node: String,
    pub kind: String,
    pub port: Option<String>,
    pub message: String,
}

impl fmt::Display for ExecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "node `{}` ({})", self.node, self.kind)?;
        if let Some(port) = &self.port {
            write!(f, ", port `{port}`")?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for ExecError {}

/// The message of a pass the context cancelled ([`ExecContext::cancelled`]).
pub const CANCELLED: &str = "cancelled: a newer request superseded this render";

impl ExecError {
    /// Whether the pass stopped because the context asked it to (nothing failed; the nodes
    /// that ran are cached and the next pass goes on from them).
    pub fn is_cancelled(&self) -> bool {
        self.message == CANCELLED
    }
}

/// What the executor measured for one node.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodeStats {
    /// How many times `execute` ran.
    pub executions: u64,
    /// How many passes reused the cached output.
    pub cache_hits: u64,
    /// CPU time of the last execution (encoding GPU work, or the CPU work itself).
    pub cpu_time: Duration,
    /// GPU time of the last execution, where the adapter has timestamp queries.
    pub gpu_time: Option<Duration>,
    /// The nodes of the fused pass the last execution ran in, in order, this one included (empty:
    /// a pass of its own). The pass's times are on its last node; the others show zero.
    pub fused_with: Vec<String>,
}

struct CacheEntry<V> {
    key: u64,
    version: u64,
    /// `None` where a fused pass did not write the output.
    outputs: Vec<Option<V>>,
}

/// What one pass did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PassReport {
    /// Nodes that ran, in order.
    pub executed: Vec<String>,
    /// Nodes whose cached output was reused.
    pub cached: Vec<String>,
}

/// Runs graphs, keeping every node's outputs between passes.
pub struct Executor<V> {
    cache: HashMap<String, CacheEntry<V>>,
    next_version: u64,
    pub(crate) stats: BTreeMap<String, NodeStats>,
    fusion: bool,
    /// Fused passes keep the outputs an edit of their members needs (see [`Self::set_keep_fused`]).
    keep_fused: bool,
    /// Nodes whose own parameters changed in an earlier pass of this session (with
    /// `keep_fused`): the edits a fused pass prepares for.
    edited: BTreeSet<String>,
}

impl<V> Default for Executor<V> {
    fn default() -> Self {
        Self {
            cache: HashMap::new(),
            next_version: 1,
            stats: BTreeMap::new(),
            fusion: true,
            keep_fused: false,
            edited: BTreeSet::new(),
        }
    }
}

impl<V: Clone> Executor<V> {
    pub fn new() -> Self {
        Self::default()
    }

    /// Runs what is needed for `targets` (node ids); with no targets, every sink node (or, if the
    /// graph has none, every node whose outputs go nowhere). Image-space nodes that read their
    /// inputs pointwise run fused into one pass where the registry has a [`Fuser`] (see
    /// [`crate::fusion`]) and fusion is on.
    pub fn run<C: ExecContext>(
        &mut self,
        graph: &Graph,
        registry: &Registry<V, C>,
        ctx: &mut C,
        targets: &[&str],
    ) -> Result<PassReport, ExecError> {
        // A render at k times the designed size: its nodes read lengths in pixels times k (the
        // cache keys hash the scaled values, so a change of scale re-runs what it changes).
        let scale = ctx.pixel_scale();
        let scaled;
        let graph = if scale == 1.0 {
            graph
        } else {
            scaled = graph.with_pixel_scale(registry, scale);
            &scaled
        };
        let (wanted, roots) = self.needed_nodes(graph, registry, targets)?;
        // Forget nodes that left the graph.
        self.cache.retain(|id, _| graph.node(id).is_some());
        self.stats.retain(|id, _| graph.node(id).is_some());
        self.edited.retain(|id| graph.node(id).is_some());

        let order: Vec<&str> = graph
            .topological_order()
            .into_iter()
            .filter(|id| wanted.contains(id))
            .collect();
        let (dirty, forced) = self.predict(graph, registry, ctx, &order, &roots);
        // Members that write every output something reads: those re-run only because an earlier
        // pass did not write their outputs (an edit downstream of them: once written, the next
        // such edit leaves them cached), and in an interactive session those that feed what a
        // member edited before re-runs, so alternating edits (orbit, θ, orbit…) stay cached.
        let mut keep_all = forced.clone();
        if self.keep_fused {
            for &id in &dirty {
                let node = graph.node(id).expect("id from the graph");
                let own_edit = self.cache.contains_key(id)
                    && !forced.contains(id)
                    && !Self::kind_of(registry, node).0.sink
                    && graph
                        .input_sources(id)
                        .values()
                        .all(|(s, _)| !dirty.contains(s) || forced.contains(s));
                if own_edit {
                    self.edited.insert(id.to_owned());
                }
            }
            keep_all.extend(fusion::feeding_edits(graph, &order, &dirty, &self.edited));
        }
        let keep_all = &keep_all;
        let units = match (&registry.fuser, self.fusion) {
            (Some(fuser), true) => fusion::plan(
                graph,
                registry,
                fuser.as_ref(),
                ctx,
                &order,
                (&dirty, &roots, keep_all),
            ),
            _ => order.iter().map(|&id| Unit::Single(id)).collect(),
        };
        // The steps that will execute (a cached node costs nothing), for progress reports.
        let planned: Vec<&str> = units
            .iter()
            .filter_map(|unit| match unit {
                Unit::Single(id) => dirty.contains(id).then_some(*id),
                Unit::Group(members) => members.last().map(|(id, _)| *id),
            })
            .collect();
        ctx.begin_pass(&planned);
        let mut report = PassReport::default();
        for unit in units {
            // Between steps: a cancelled pass keeps what it computed so far.
            if ctx.cancelled() {
                let id = match &unit {
                    Unit::Single(id) => *id,
                    Unit::Group(members) => members[0].0,
                };
                return Err(ExecError {
                    node: id.to_owned(),
                    kind: graph.node(id).map(|n| n.kind.clone()).unwrap_or_default(),
                    port: None,
                    message: CANCELLED.into(),
                });
            }
            match unit {
                Unit::Single(id) => {
                    self.run_single(graph, registry, ctx, id, forced.contains(id), &mut report)?
                }
                Unit::Group(members) => {
                    self.run_group(graph, registry, ctx, &members, &mut report)?
                }
            }
        }
        for (node, gpu) in ctx.finish_pass() {
            if let Some(stats) = self.stats.get_mut(&node) {
                stats.gpu_time = Some(gpu);
            }
        }
        Ok(report)
    }

    /// Turns fusion on or off (on by default; off runs every node as its own pass).
    pub fn set_fusion(&mut self, on: bool) {
        self.fusion = on;
    }

    pub fn fusion(&self) -> bool {
        self.fusion
    }

    /// With `on` (an interactive session: the editor), the executor learns which nodes the user
    /// edits (their own parameters changed) and a fused pass also writes the member outputs that
    /// the part downstream of an edited node reads, so the next edit of that node re-runs only
    /// it and what follows, even after an edit upstream of the whole pass (a camera orbit). A
    /// pass with no edited member downstream writes only what it needs, as a one-shot render
    /// does (off, the default). Either way, a member re-run only because an earlier pass did not
    /// write its outputs writes them all.
    pub fn set_keep_fused(&mut self, on: bool) {
        self.keep_fused = on;
    }

    pub fn keep_fused(&self) -> bool {
        self.keep_fused
    }

    /// The node's schema and behaviour.
    pub(crate) fn kind_of<'r, C>(
        registry: &'r Registry<V, C>,
        node: &'r NodeInstance,
    ) -> (&'r NodeSchema, &'r dyn Node<V, C>) {
        let (kind_schema, behaviour) = registry
            .kinds
            .get(node.kind.as_str())
            .expect("validated kind");
        (
            node.own_schema.as_deref().unwrap_or(kind_schema),
            behaviour.as_ref(),
        )
    }

    /// The cache key of `node` from its parameters and its inputs' current versions, with the
    /// input values; `None` when an input has not run.
    pub(crate) fn key_and_inputs<C: ExecContext>(
        &self,
        graph: &Graph,
        schema: &NodeSchema,
        node: &NodeInstance,
        ctx: &C,
    ) -> Option<(u64, Vec<Option<&V>>)> {
        let mut hasher = DefaultHasher::new();
        node.kind.hash(&mut hasher);
        node.params.values().hash(&mut hasher);
        node.fingerprint.hash(&mut hasher);
        if schema.frame_dependent {
            ctx.frame_key().hash(&mut hasher);
        }
        let sources = graph.input_sources(&node.id);
        let mut values = Vec::with_capacity(schema.inputs.len());
        for port in 0..schema.inputs.len() {
            let value = match sources.get(&port) {
                Some(&(source, out_port)) => {
                    let entry = self.cache.get(source)?;
                    (port, source, entry.version, out_port).hash(&mut hasher);
                    entry.outputs.get(out_port).and_then(Option::as_ref)
                }
                None => None,
            };
            values.push(value);
        }
        Some((hasher.finish(), values))
    }

    /// Which nodes of `order` will run in this pass (`dirty`): sinks, nodes whose parameters or
    /// inputs changed, and (`forced`) nodes whose outputs an earlier fused pass did not write
    /// while a node running now, or a target, reads them.
    fn predict<'g, C: ExecContext>(
        &self,
        graph: &'g Graph,
        registry: &Registry<V, C>,
        ctx: &C,
        order: &[&'g str],
        roots: &BTreeSet<&'g str>,
    ) -> (BTreeSet<&'g str>, BTreeSet<&'g str>) {
        let mut forced: BTreeSet<&str> = BTreeSet::new();
        // Nodes whose outputs change; a forced node recomputes the same outputs (same key, same
        // version: see `store`), so its consumers stay valid.
        let mut changed: BTreeSet<&str> = BTreeSet::new();
        for &id in order {
            let node = graph.node(id).expect("id from the graph");
            let (schema, _) = Self::kind_of(registry, node);
            let stale = schema.sink
                || graph
                    .input_sources(id)
                    .values()
                    .any(|(s, _)| changed.contains(s))
                || match (
                    self.cache.get(id),
                    self.key_and_inputs(graph, schema, node, ctx),
                ) {
                    (Some(entry), Some((key, _))) => entry.key != key,
                    _ => true,
                };
            if stale {
                changed.insert(id);
            }
        }
        loop {
            let dirty: BTreeSet<&str> = changed.union(&forced).copied().collect();
            let unwritten = |id: &str, port: Option<usize>| {
                self.cache.get(id).is_some_and(|e| match port {
                    Some(port) => e.outputs.get(port).is_some_and(Option::is_none),
                    None => e.outputs.iter().any(Option::is_none),
                })
            };
            let mut more = false;
            for &id in order {
                if roots.contains(id) && !dirty.contains(id) && unwritten(id, None) {
                    more |= forced.insert(id);
                }
                if dirty.contains(id) {
                    for (source, port) in graph.input_sources(id).into_values() {
                        if !dirty.contains(source) && unwritten(source, Some(port)) {
                            more |= forced.insert(source);
                        }
                    }
                }
            }
            if !more {
                return (dirty, forced);
            }
        }
    }

    /// Runs one node unless its cached outputs are still valid.
    fn run_single<C: ExecContext>(
        &mut self,
        graph: &Graph,
        registry: &Registry<V, C>,
        ctx: &mut C,
        id: &str,
        forced: bool,
        report: &mut PassReport,
    ) -> Result<(), ExecError> {
        let node = graph.node(id).expect("id from the graph");
        let (schema, behaviour) = Self::kind_of(registry, node);
        let fail = |port: Option<String>, message: String| ExecError {
            node: id.to_owned(),
            kind: node.kind.clone(),
            port,
            message,
        };
        let (key, values) = self
            .key_and_inputs(graph, schema, node, ctx)
            .ok_or_else(|| fail(None, "an input has not run (executor order)".into()))?;
        if !schema.sink && !forced && self.cache.get(id).is_some_and(|e| e.key == key) {
            self.stats.entry(id.to_owned()).or_default().cache_hits += 1;
            report.cached.push(id.to_owned());
            return Ok(());
        }
        let values: Vec<Option<V>> = values.into_iter().map(|v| v.cloned()).collect();
        let sources = graph.input_sources(id);
        if let Some(port) =
            (0..values.len()).find(|p| sources.contains_key(p) && values[*p].is_none())
        {
            return Err(fail(
                Some(schema.inputs[port].name.to_owned()),
                "the input's value was not kept (executor planning)".into(),
            ));
        }

        let inputs = NodeInputs::new(schema.inputs.iter().map(|p| p.name).collect(), values);
        tracing::debug!(node = id, kind = node.kind, "executing");
        ctx.begin_node(id);
        let start = Instant::now();
        let result = behaviour.execute(ctx, &inputs, &node.params);
        let elapsed = start.elapsed();
        ctx.end_node(id);
        let outputs = result.map_err(|e| fail(e.port, e.message))?;
        if outputs.len() != schema.outputs.len() {
            return Err(fail(
                None,
                format!(
                    "produced {} outputs, its schema declares {}",
                    outputs.len(),
                    schema.outputs.len()
                ),
            ));
        }
        let stats = self.stats.entry(id.to_owned()).or_default();
        stats.executions += 1;
        stats.cpu_time = elapsed;
        stats.gpu_time = None;
        stats.fused_with.clear();
        self.store(
            id,
            key,
            outputs.into_iter().map(Some).collect(),
            schema.sink,
        );
        report.executed.push(id.to_owned());
        Ok(())
    }

    /// Caches `outputs` of `id` under `key`. The same key as before means the same parameters and
    /// inputs, so the same outputs (a node re-run because a fused pass did not write them): the
    /// version stays and consumers keep their cached results — except for a sink, which runs
    /// every pass for its effect, so what reads it (if anything) runs again too.
    pub(crate) fn store(&mut self, id: &str, key: u64, outputs: Vec<Option<V>>, sink: bool) {
        let version = match self.cache.get(id) {
            Some(entry) if entry.key == key && !sink => entry.version,
            _ => {
                self.next_version += 1;
                self.next_version - 1
            }
        };
        self.cache.insert(
            id.to_owned(),
            CacheEntry {
                key,
                version,
                outputs,
            },
        );
    }

    fn needed_nodes<'g, C>(
        &self,
        graph: &'g Graph,
        registry: &Registry<V, C>,
        targets: &[&str],
    ) -> Result<(BTreeSet<&'g str>, BTreeSet<&'g str>), ExecError> {
        let mut stack: Vec<&str> = Vec::new();
        for &target in targets {
            let node = graph.node(target).ok_or_else(|| ExecError {
                node: target.to_owned(),
                kind: String::new(),
                port: None,
                message: "no node with this id in the graph".into(),
            })?;
            stack.push(node.id.as_str());
        }
        if targets.is_empty() {
            let sinks: Vec<&str> = graph
                .nodes()
                .filter(|n| registry.schema(&n.kind).is_some_and(|s| s.sink))
                .map(|n| n.id.as_str())
                .collect();
            stack = if sinks.is_empty() {
                graph
                    .nodes()
                    .filter(|n| !graph.has_consumers(&n.id))
                    .map(|n| n.id.as_str())
                    .collect()
            } else {
                sinks
            };
        }
        let roots: BTreeSet<&str> = stack.iter().copied().collect();
        let mut needed = BTreeSet::new();
        while let Some(id) = stack.pop() {
            if needed.insert(id) {
                stack.extend(graph.input_sources(id).values().map(|(source, _)| *source));
            }
        }
        Ok((needed, roots))
    }

    /// A node's output from the last pass that ran it.
    /// `None` also where a fused pass did not write it (nothing outside the pass read it): run
    /// the node as a target to have it.
    pub fn output(&self, node: &str, port: usize) -> Option<&V> {
        self.cache
            .get(node)
            .and_then(|e| e.outputs.get(port))
            .and_then(Option::as_ref)
    }

    pub fn stats(&self) -> &BTreeMap<String, NodeStats> {
        &self.stats
    }

    /// Drops every cached output (the next pass re-runs everything).
    pub fn clear(&mut self) {
        self.cache.clear();
    }

    /// Drops `node`'s cached outputs: the next pass re-runs it, and what depends on it when its
    /// outputs change version (a streamed view refined after a coarse first frame).
    pub fn invalidate(&mut self, node: &str) {
        self.cache.remove(node);
    }
}

impl<V: Clone> Executor<V> {
    /// Runs a fused group (members in topological order with the outputs to keep) as one pass;
    /// its times are reported on the last member.
    pub(crate) fn run_group<C: ExecContext>(
        &mut self,
        graph: &Graph,
        registry: &Registry<V, C>,
        ctx: &mut C,
        members: &[(&str, Vec<bool>)],
        report: &mut PassReport,
    ) -> Result<(), ExecError> {
        let fuser = registry.fuser.as_deref().expect("groups only with a fuser");
        let index: BTreeMap<&str, usize> = members
            .iter()
            .enumerate()
            .map(|(i, (m, _))| (*m, i))
            .collect();
        let fail = |id: &str, port: Option<String>, message: String| ExecError {
            node: id.to_owned(),
            kind: graph.node(id).map(|n| n.kind.clone()).unwrap_or_default(),
            port,
            message,
        };
        let mut group = Vec::with_capacity(members.len());
        for (id, keep) in members {
            let node = graph.node(id).expect("id from the graph");
            let (schema, _) = Self::kind_of(registry, node);
            let sources = graph.input_sources(id);
            let mut inputs = Vec::with_capacity(schema.inputs.len());
            for port in 0..schema.inputs.len() {
                inputs.push(match sources.get(&port) {
                    None => Source::Absent,
                    Some(&(source, out)) => match index.get(source) {
                        Some(&member) => Source::Member { member, port: out },
                        None => Source::External(self.output(source, out).cloned().ok_or_else(
                            || {
                                fail(
                                    id,
                                    Some(schema.inputs[port].name.to_owned()),
                                    "the input's value was not kept (executor planning)".into(),
                                )
                            },
                        )?),
                    },
                });
            }
            group.push(Member {
                id,
                kind: node.kind.as_str(),
                params: &node.params,
                inputs,
                keep: keep.clone(),
            });
        }
        let carrier = members.last().expect("groups have members").0;
        for (id, _) in &members[..members.len() - 1] {
            tracing::debug!(node = id, fused_into = carrier, "executing (fused)");
            ctx.begin_node(id);
            ctx.end_node(id);
        }
        tracing::debug!(
            node = carrier,
            members = members.len(),
            "executing a fused pass"
        );
        ctx.begin_node(carrier);
        let start = Instant::now();
        let result = fuser.run(ctx, &group);
        let elapsed = start.elapsed();
        ctx.end_node(carrier);
        let outputs = result
            .map_err(|(i, e)| fail(members[i.min(members.len() - 1)].0, e.port, e.message))?;
        if outputs.len() != members.len() {
            return Err(fail(carrier, None, "the fused pass lost members".into()));
        }
        let ids: Vec<String> = members.iter().map(|(m, _)| (*m).to_owned()).collect();
        for ((id, keep), outputs) in members.iter().zip(outputs) {
            let node = graph.node(id).expect("id from the graph");
            let (schema, _) = Self::kind_of(registry, node);
            if outputs.len() != schema.outputs.len()
                || keep.iter().zip(&outputs).any(|(k, o)| *k && o.is_none())
            {
                return Err(fail(
                    id,
                    None,
                    "the fused pass did not write a kept output".into(),
                ));
            }
            let (key, _) = self
                .key_and_inputs(graph, schema, node, ctx)
                .ok_or_else(|| fail(id, None, "an input has not run (executor order)".into()))?;
            let stats = self.stats.entry((*id).to_owned()).or_default();
            stats.executions += 1;
            stats.cpu_time = if *id == carrier {
                elapsed
            } else {
                Duration::ZERO
            };
            stats.gpu_time = None;
            stats.fused_with = ids.clone();
            self.store(id, key, outputs, schema.sink);
            report.executed.push((*id).to_owned());
        }
        Ok(())
    }
}

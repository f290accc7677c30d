//! Fused passes: the executor hands a connected set of image-space nodes that read their inputs
//! only at the pixel they write to one [`Fuser::run`] call, so the context can evaluate them in
//! one full-frame pass. Graphs stay made of small composable nodes while a frame pays for fewer
//! passes (each pass writes a render target and reads it back; on lavapipe a trivial pass costs
//! 5–11 ms at 1024×768).
//!
//! A group is formed only from nodes that run in this pass, joined along edges into *pointwise*
//! ports, and only while the graph of steps (each group contracted to one) stays acyclic — no
//! path leaves a group and comes back, directly or through other groups — so every group runs as
//! one step after all its outside inputs. Every member's outputs go into the cache as usual where something outside the
//! group reads them (a consumer that runs in this pass, or a target); the others are not written
//! (`None` in the cache), and a later pass that needs one re-runs its node.

use crate::graph::Graph;
use crate::param::Params;
use crate::port::PortType;
use crate::schema::{NodeError, SchemaLookup};
use std::collections::{BTreeMap, BTreeSet, HashMap};

/// Where a fused member's input comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Source<T> {
    /// Nothing is connected (an optional port).
    Absent,
    /// From outside the group: the value (when running), or its type and origin (when planning).
    External(T),
    /// Output `port` of the group's `member`-th node (an earlier one).
    Member { member: usize, port: usize },
}

/// An input from outside a group being planned: its type and the output it comes from (two
/// members reading one output bind it once).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outside<'a> {
    pub ty: PortType,
    pub node: &'a str,
    pub port: usize,
}

/// One node of a fused group.
#[derive(Clone, Debug)]
pub struct Member<'a, T> {
    pub id: &'a str,
    pub kind: &'a str,
    pub params: &'a Params,
    /// Per input port, in schema order.
    pub inputs: Vec<Source<T>>,
    /// Per output port: whether something outside the group reads it (write it to a texture).
    pub keep: Vec<bool>,
}

/// What the context offers the executor for fusing (registered with
/// [`crate::Registry::set_fuser`]).
pub trait Fuser<V, C>: Send + Sync {
    /// Per input port of a node of `kind`: whether the node reads that input only at the pixel it
    /// writes. `None`: nodes of this kind are never fused.
    fn pointwise(&self, kind: &str, params: &Params) -> Option<Vec<bool>>;
    /// Whether `group` (members in execution order) fits one pass on `ctx`: bindings, colour
    /// attachments. External inputs are given by type and origin.
    fn fits(&self, ctx: &C, group: &[Member<'_, Outside<'_>>]) -> bool;
    /// Runs `group` as one pass. Per member, one value per output port: `Some` where `keep` says.
    /// An error names the member (index) it belongs to.
    fn run(
        &self,
        ctx: &mut C,
        group: &[Member<'_, V>],
    ) -> Result<Vec<Vec<Option<V>>>, (usize, NodeError)>;
}

/// One step of a pass: a node alone, or a fused group (members in topological order, with the
/// output ports to keep).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Unit<'g> {
    Single(&'g str),
    Group(Vec<(&'g str, Vec<bool>)>),
}

/// The node ids that read each node's outputs: (consumer, input port, output port).
type Consumers<'g> = HashMap<&'g str, Vec<(&'g str, usize, usize)>>;

/// Groups the `dirty` nodes of `order` (topological, only what the pass needs) and orders the
/// steps so every step comes after its inputs. `roots` are the pass's targets (always kept);
/// members in `keep_all` write every output something reads, inside the group or not, so a
/// later pass that changes only what is downstream of them finds their outputs cached.
pub(crate) fn plan<'g, V, C>(
    graph: &'g Graph,
    schemas: &dyn SchemaLookup,
    fuser: &dyn Fuser<V, C>,
    ctx: &C,
    order: &[&'g str],
    (dirty, roots, keep_all): (&BTreeSet<&'g str>, &BTreeSet<&'g str>, &BTreeSet<&'g str>),
) -> Vec<Unit<'g>> {
    let position: HashMap<&str, usize> = order.iter().enumerate().map(|(i, &id)| (id, i)).collect();
    let mut consumers: Consumers = HashMap::new();
    for &id in order {
        for (port, (source, out)) in graph.input_sources(id) {
            consumers.entry(source).or_default().push((id, port, out));
        }
    }
    let pointwise: HashMap<&str, Vec<bool>> = order
        .iter()
        .filter(|id| dirty.contains(*id))
        .filter_map(|&id| {
            let node = graph.node(id)?;
            if node.own_schema.is_some() {
                return None;
            }
            fuser
                .pointwise(&node.kind, &node.params)
                .map(|flags| (id, flags))
        })
        .collect();
    let planner = Planner {
        graph,
        schemas,
        dirty,
        roots,
        keep_all,
        consumers: &consumers,
        pointwise: &pointwise,
        order,
    };

    // Greedy: each fusable node joins the groups of the members it reads pointwise, where the
    // union stays fusable.
    let mut groups: Vec<Vec<&str>> = Vec::new();
    let mut group_of: HashMap<&str, usize> = HashMap::new();
    for &id in order {
        if !pointwise.contains_key(id) {
            continue;
        }
        group_of.insert(id, groups.len());
        groups.push(vec![id]);
        for (port, (source, _)) in graph.input_sources(id) {
            let (Some(&a), Some(&b)) = (group_of.get(source), group_of.get(id)) else {
                continue;
            };
            if a == b || !pointwise[id].get(port).copied().unwrap_or(false) {
                continue;
            }
            let mut union: Vec<&str> = groups[a].iter().chain(&groups[b]).copied().collect();
            union.sort_by_key(|m| position[m]);
            let mut merged = group_of.clone();
            for &m in &groups[b] {
                merged.insert(m, a);
            }
            if planner.fusable(&union, fuser, ctx) && planner.orderable(&merged) {
                for &m in &groups[b] {
                    group_of.insert(m, a);
                }
                groups[b].clear();
                groups[a] = union;
            }
        }
    }

    // Steps in an order that respects every edge: repeatedly the first step whose outside inputs
    // are done (`orderable` kept the groups' graph acyclic, so one always is).
    let mut pending: Vec<Vec<&str>> = Vec::new();
    let mut seen = BTreeSet::new();
    for &id in order {
        if seen.contains(id) {
            continue;
        }
        let members = match group_of.get(id) {
            Some(&g) => groups[g].clone(),
            None => vec![id],
        };
        seen.extend(members.iter().copied());
        pending.push(members);
    }
    let mut done: BTreeSet<&str> = BTreeSet::new();
    let mut units = Vec::new();
    while !pending.is_empty() {
        let ready = pending.iter().position(|members| {
            members.iter().all(|&m| {
                graph
                    .input_sources(m)
                    .values()
                    .all(|(s, _)| done.contains(s) || members.contains(s))
            })
        });
        let Some(ready) = ready else {
            // Cannot happen (see above); if it did, the rest runs node by node in topological
            // order, which is always valid.
            let rest: BTreeSet<&str> = pending.iter().flatten().copied().collect();
            units.extend(
                order
                    .iter()
                    .filter(|id| rest.contains(*id))
                    .map(|&id| Unit::Single(id)),
            );
            break;
        };
        let members = pending.remove(ready);
        done.extend(members.iter().copied());
        units.push(if members.len() == 1 {
            Unit::Single(members[0])
        } else {
            Unit::Group(
                members
                    .iter()
                    .map(|&m| (m, planner.keep(m, &members)))
                    .collect(),
            )
        });
    }
    units
}

/// The `dirty` nodes that are not downstream of an `edited` node but feed one that is, or the
/// edited node itself: what a later edit of those nodes reads from the cache.
pub(crate) fn feeding_edits<'g>(
    graph: &'g Graph,
    order: &[&'g str],
    dirty: &BTreeSet<&'g str>,
    edited: &BTreeSet<String>,
) -> BTreeSet<&'g str> {
    // Per edited node, not their union: an orbit edits the camera, and all is downstream of it.
    let mut feeding = BTreeSet::new();
    for edit in edited {
        let mut below: BTreeSet<&str> = BTreeSet::new();
        for &id in order {
            if id == edit
                || graph
                    .input_sources(id)
                    .values()
                    .any(|(s, _)| below.contains(s))
            {
                below.insert(id);
            }
        }
        for &id in &below {
            for (source, _) in graph.input_sources(id).into_values() {
                if !below.contains(source) && dirty.contains(source) {
                    feeding.insert(source);
                }
            }
        }
    }
    feeding
}

struct Planner<'p, 'g> {
    graph: &'g Graph,
    schemas: &'p dyn SchemaLookup,
    dirty: &'p BTreeSet<&'g str>,
    roots: &'p BTreeSet<&'g str>,
    keep_all: &'p BTreeSet<&'g str>,
    consumers: &'p Consumers<'g>,
    pointwise: &'p HashMap<&'g str, Vec<bool>>,
    order: &'p [&'g str],
}

impl<'g> Planner<'_, 'g> {
    /// Per output port of `id`: whether a target or a consumer outside `group` that runs in this
    /// pass reads it — or, for a member of `keep_all`, any consumer at all.
    fn keep(&self, id: &str, group: &[&str]) -> Vec<bool> {
        let all = self.keep_all.contains(id);
        let outputs = self
            .graph
            .node(id)
            .and_then(|n| n.schema(self.schemas))
            .map_or(0, |s| s.outputs.len());
        (0..outputs)
            .map(|port| {
                self.roots.contains(id)
                    || self
                        .consumers
                        .get(id)
                        .into_iter()
                        .flatten()
                        .any(|&(c, _, out)| {
                            out == port && (all || (!group.contains(&c) && self.dirty.contains(c)))
                        })
            })
            .collect()
    }

    /// Whether `group` can run as one pass: every edge inside it enters a pointwise port and the
    /// context says it fits.
    fn fusable<V, C>(&self, group: &[&'g str], fuser: &dyn Fuser<V, C>, ctx: &C) -> bool {
        for &m in group {
            for (port, (source, _)) in self.graph.input_sources(m) {
                if group.contains(&source) && !self.pointwise[m].get(port).copied().unwrap_or(false)
                {
                    return false;
                }
            }
        }
        let members = self.describe(group);
        members.len() == group.len() && fuser.fits(ctx, &members)
    }

    /// Whether the steps can still be ordered with the groups of `group_of` (node → group): the
    /// graph with every group contracted to one vertex has no cycle. A cycle is a path that leaves
    /// a group and comes back — through plain nodes, or through another group that itself needs
    /// this one — so the group would have to run both before and after it.
    fn orderable(&self, group_of: &HashMap<&str, usize>) -> bool {
        // A step per group, and one per node outside every group.
        let step = |id: &str, i: usize| group_of.get(id).copied().unwrap_or(usize::MAX - i);
        let mut edges: BTreeSet<(usize, usize)> = BTreeSet::new();
        let mut steps: BTreeSet<usize> = BTreeSet::new();
        let position: HashMap<&str, usize> = self
            .order
            .iter()
            .enumerate()
            .map(|(i, &id)| (id, i))
            .collect();
        for (i, &id) in self.order.iter().enumerate() {
            let to = step(id, i);
            steps.insert(to);
            for (source, _) in self.graph.input_sources(id).into_values() {
                if let Some(&j) = position.get(source) {
                    let from = step(source, j);
                    if from != to {
                        edges.insert((from, to));
                    }
                }
            }
        }
        // Kahn's algorithm: every step can be taken iff there is no cycle.
        let mut waiting: BTreeMap<usize, usize> = steps.iter().map(|&s| (s, 0)).collect();
        for &(_, to) in &edges {
            *waiting.entry(to).or_default() += 1;
        }
        let mut ready: Vec<usize> = waiting
            .iter()
            .filter(|(_, n)| **n == 0)
            .map(|(&s, _)| s)
            .collect();
        let mut taken = 0;
        while let Some(s) = ready.pop() {
            taken += 1;
            for &(from, to) in edges.range((s, 0)..=(s, usize::MAX)) {
                debug_assert_eq!(from, s);
                let n = waiting.get_mut(&to).expect("every step counted");
                *n -= 1;
                if *n == 0 {
                    ready.push(to);
                }
            }
        }
        taken == steps.len()
    }

    /// The group as the fuser sees it when planning: outside inputs by type and origin.
    fn describe(&self, group: &[&'g str]) -> Vec<Member<'g, Outside<'g>>> {
        let index: BTreeMap<&str, usize> = group.iter().enumerate().map(|(i, &m)| (m, i)).collect();
        group
            .iter()
            .filter_map(|&id| {
                let node = self.graph.node(id)?;
                let schema = node.schema(self.schemas)?;
                let sources = self.graph.input_sources(id);
                let inputs = (0..schema.inputs.len())
                    .map(|port| match sources.get(&port) {
                        None => Source::Absent,
                        Some(&(source, out)) => match index.get(source) {
                            Some(&member) => Source::Member { member, port: out },
                            None => self
                                .graph
                                .node(source)
                                .and_then(|n| n.schema(self.schemas))
                                .and_then(|s| s.outputs.get(out))
                                .map_or(Source::Absent, |o| {
                                    Source::External(Outside {
                                        ty: o.ty,
                                        node: source,
                                        port: out,
                                    })
                                }),
                        },
                    })
                    .collect();
                Some(Member {
                    id,
                    kind: node.kind.as_str(),
                    params: &node.params,
                    inputs,
                    keep: self.keep(id, group),
                })
            })
            .collect()
    }
}

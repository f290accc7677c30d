//! Fused passes: the executor hands a connected set of image-space nodes that read their inputs
//! only at the pixel they write to one [`Fuser::run`] call, so the context can evaluate them in
//! one full-frame pass. Graphs stay made of small composable nodes while a frame pays for fewer
//! passes (each pass writes a render target and reads it back; on lavapipe a trivial pass costs
//! 5–11 ms at 1024×768).
//!
//! A group is formed only from nodes that run in this pass, joined along edges into *pointwise*
//! ports; it is convex (no path leaves it and comes back), so it runs as one step after all its
//! outside inputs. Every member's outputs go into the cache as usual where something outside the
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
    /// From outside the group: the value (when running) or its port type (when planning).
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
/// steps so every step comes after its inputs. `roots` are the pass's targets (always kept).
pub(crate) fn plan<'g, V, C>(
    graph: &'g Graph,
    schemas: &dyn SchemaLookup,
    fuser: &dyn Fuser<V, C>,
    ctx: &C,
    order: &[&'g str],
    dirty: &BTreeSet<&'g str>,
    roots: &BTreeSet<&'g str>,
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
    // Nodes reachable from each node (within the pass: its nodes are closed under inputs).
    let mut reach: HashMap<&str, BTreeSet<&str>> = HashMap::new();
    for &id in order.iter().rev() {
        let mut set = BTreeSet::new();
        for &(consumer, _, _) in consumers.get(id).into_iter().flatten() {
            set.insert(consumer);
            set.extend(reach.get(consumer).into_iter().flatten().copied());
        }
        reach.insert(id, set);
    }
    let planner = Planner {
        graph,
        schemas,
        dirty,
        roots,
        consumers: &consumers,
        pointwise: &pointwise,
        reach: &reach,
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
            if planner.fusable(&union, fuser, ctx) {
                for &m in &groups[b] {
                    group_of.insert(m, a);
                }
                groups[b].clear();
                groups[a] = union;
            }
        }
    }

    // Steps in an order that respects every edge: repeatedly the first step whose outside inputs
    // are done (a convex group's condensation is acyclic, so one always is).
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
        let ready = pending
            .iter()
            .position(|members| {
                members.iter().all(|&m| {
                    graph
                        .input_sources(m)
                        .values()
                        .all(|(s, _)| done.contains(s) || members.contains(s))
                })
            })
            // Cannot happen for convex groups; run the rest in order rather than loop forever.
            .unwrap_or(0);
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

struct Planner<'p, 'g> {
    graph: &'g Graph,
    schemas: &'p dyn SchemaLookup,
    dirty: &'p BTreeSet<&'g str>,
    roots: &'p BTreeSet<&'g str>,
    consumers: &'p Consumers<'g>,
    pointwise: &'p HashMap<&'g str, Vec<bool>>,
    reach: &'p HashMap<&'g str, BTreeSet<&'g str>>,
}

impl<'g> Planner<'_, 'g> {
    /// Per output port of `id`: whether a target or a consumer outside `group` that runs in this
    /// pass reads it.
    fn keep(&self, id: &str, group: &[&str]) -> Vec<bool> {
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
                            out == port && !group.contains(&c) && self.dirty.contains(c)
                        })
            })
            .collect()
    }

    /// Whether `group` can run as one pass: every edge inside it enters a pointwise port, no path
    /// leaves it and comes back, and the context says it fits.
    fn fusable<V, C>(&self, group: &[&'g str], fuser: &dyn Fuser<V, C>, ctx: &C) -> bool {
        for &m in group {
            for (port, (source, _)) in self.graph.input_sources(m) {
                if group.contains(&source) && !self.pointwise[m].get(port).copied().unwrap_or(false)
                {
                    return false;
                }
            }
        }
        let inside: BTreeSet<&str> = group.iter().copied().collect();
        let leaves: BTreeSet<&str> = group
            .iter()
            .flat_map(|m| self.reach[m].iter().copied())
            .filter(|x| !inside.contains(x))
            .collect();
        if leaves
            .iter()
            .any(|x| self.reach[x].iter().any(|y| inside.contains(y)))
        {
            return false;
        }
        let members = self.describe(group);
        members.len() == group.len() && fuser.fits(ctx, &members)
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

//! Annotation layout after VolumeShop (Bruckner & Gröller 2005, §6.4 "Annotations").
//!
//! Guidelines (§6.4): annotations must not overlap; connecting (leader) lines must not cross;
//! annotations should not occlude other structures; an annotation should be as close as possible to
//! its anchor. Labels are placed outside the convex hull of the visible objects' projected bounding
//! volumes, at a position given by one parameter `t ∈ [0, 1)` of the hull's arc-length
//! parameterisation ([`HullPath`]), initially the hull position closest to the anchor. Then, until
//! nothing is left to resolve or `max_iterations` is reached:
//!
//! 1. if the leader lines of two labels cross, the labels exchange positions;
//! 2. if exchanging the positions of two labels brings both closer to their anchors, they exchange;
//! 3. if a label overlaps its predecessor (along the hull), it moves by a small δ.
//!
//! Remaining crossings and overlaps are removed by disabling labels one at a time (§6.4: "annotations
//! whose reference structures are farther away will be disabled first"); see [`layout`] for the exact
//! rule and this implementation's choices.

use crate::anchor::ProjectedAnchor;
use crate::geometry::{Rect, rect_intersects_convex_polygon, segments_cross};
use crate::hull::{HullPath, convex_hull, parameter_delta};
use glam::Vec2;

/// Tuning of [`layout`]. All lengths are pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct LayoutParams {
    /// Distance between the hull and the labels: the hull is grown by this much and labels touch
    /// the grown path from outside. Default 8 px.
    pub margin: f32,
    /// Smallest empty space between two shown labels; closer counts as an overlap. Default 2 px.
    pub label_gap: f32,
    /// The δ of step 3: how far (arc length along the grown hull) an overlapping label moves per
    /// iteration. Default 2 px.
    pub delta: f32,
    /// Iterations of steps 1–3 before labels are disabled. Default 300.
    pub max_iterations: u32,
    /// Iterations of steps 1–3 after each disabled label, letting the rest use the freed space.
    /// Default 40.
    pub iterations_after_disable: u32,
    /// Leader-line opacity of the farthest anchor (the nearest gets 1). Default 0.3.
    pub min_opacity: f32,
    /// Window-depth range mapped to opacity 1 … `min_opacity`; `None` takes the smallest and
    /// largest depth among the visible anchors. Default `None`.
    pub depth_range: Option<(f32, f32)>,
    /// Move labels that would stick out of the frame back inside, unless that makes them touch
    /// the hull. Default true.
    pub keep_in_frame: bool,
}

impl Default for LayoutParams {
    fn default() -> Self {
        Self {
            margin: 8.0,
            label_gap: 2.0,
            delta: 2.0,
            max_iterations: 300,
            iterations_after_disable: 40,
            min_opacity: 0.3,
            depth_range: None,
            keep_in_frame: true,
        }
    }
}

/// One label of a [`Layout`], in anchor order.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedLabel {
    /// Index of the anchor (and label size) this label belongs to.
    pub anchor: usize,
    /// The label's box, px (top-left origin, y down). Its size is the given label size.
    pub rect: Rect,
    /// Position along the grown hull path, t ∈ [0, 1).
    pub parameter: f32,
    /// The point of the grown hull path at `parameter`, px; the label touches the path there
    /// (from outside) unless it was moved back into the frame.
    pub path_point: Vec2,
    /// The hull polygon point the label belongs to (`path_point` moved back by the margin), px.
    pub hull_point: Vec2,
    /// The parameter closest to the anchor, where the label started (without `previous`).
    pub home: f32,
    /// The grown-path point at `home`, px.
    pub home_point: Vec2,
    /// Leader (connecting) line from the anchor to the label's attachment point (the point of
    /// `rect` closest to the anchor), px.
    pub leader: [Vec2; 2],
    /// Leader-line opacity in [0, 1] from the anchor's depth (see [`layout`]); 0 when the anchor
    /// is not visible.
    pub opacity: f32,
    /// Whether the label is drawn. False for invisible anchors and disabled labels.
    pub shown: bool,
    /// Whether `rect` lies inside the frame.
    pub inside_frame: bool,
}

/// The result of [`layout`].
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// One entry per anchor, in anchor order (shown or not).
    pub labels: Vec<PlacedLabel>,
    /// The grown hull path the labels were placed along.
    pub path: HullPath,
    /// Iterations of steps 1–3 run, all rounds together.
    pub iterations: u32,
    /// Position exchanges made by steps 1 and 2.
    pub swaps: u32,
    /// Labels disabled to remove remaining conflicts (invisible anchors not counted).
    pub disabled: u32,
}

impl Layout {
    /// The labels that are drawn.
    pub fn shown(&self) -> impl Iterator<Item = &PlacedLabel> {
        self.labels.iter().filter(|l| l.shown)
    }
}

/// Lays out one label per anchor around the convex hull of `hull_points` (§6.4).
///
/// * `anchors`: projected anchors (px, window depth), see [`project_anchors`](crate::project_anchors).
/// * `sizes`: label box width × height per anchor, px; must have the same length as `anchors`
///   (panics otherwise).
/// * `hull_points`: the projected footprint of the visible objects (e.g. bounding-box corners,
///   [`project_footprint`](crate::project_footprint)), px; any number, the hull is computed here.
///   With no points the anchors themselves are used.
/// * `frame`: width × height of the frame, px.
/// * `previous`: the layout of the previous frame for temporal coherence: each label that was
///   shown there starts from its previous position (re-projected onto the new hull) moved along the
///   hull by as much as its anchor's closest hull position moved; other labels start at the hull
///   position closest to their anchor. `previous` must come from the same anchor list.
///
/// Choices where §6.4 leaves room:
/// * Labels are placed outside the hull grown by `margin`: the label box touches the grown path at
///   `t` from outside (its centre is moved along the outward normal `n` by its support distance
///   `|n.x|·w/2 + |n.y|·h/2`), so it never intersects the hull.
/// * Step 3's "predecessor" is any overlapping label behind along the hull (the shorter way round);
///   both labels of an overlapping pair move apart by δ (the one ahead forwards, the other backwards),
///   which spreads clusters symmetrically instead of pushing them all one way.
/// * Disabling: among the labels involved in a remaining overlap or crossing, the one with the
///   lowest [`ProjectedAnchor::priority`] goes first; among equal priorities the one with the largest anchor depth
///   (farthest, as in §6.4); then the larger index. After each, steps 1–3 run again for
///   `iterations_after_disable` iterations. This ends with no overlaps and no crossings among shown
///   labels.
/// * Leader opacity: with `(d₀, d₁)` the depth range (`params.depth_range`, or the visible anchors'
///   smallest and largest depth), `opacity = 1 − s·(1 − min_opacity)`, `s = clamp((depth − d₀)/(d₁ − d₀), 0, 1)`
///   (1 when d₁ = d₀); 0 for anchors that are not visible, whose labels are never shown.
///
pub fn layout(
    anchors: &[ProjectedAnchor],
    sizes: &[Vec2],
    hull_points: &[Vec2],
    frame: Vec2,
    params: &LayoutParams,
    previous: Option<&Layout>,
) -> Layout {
    assert_eq!(anchors.len(), sizes.len(), "one label size per anchor");
    let hull = if hull_points.is_empty() {
        let pts: Vec<Vec2> = anchors
            .iter()
            .filter(|a| a.visible)
            .map(|a| a.screen)
            .collect();
        convex_hull(&pts)
    } else {
        convex_hull(hull_points)
    };
    let path = HullPath::new(&hull, params.margin.max(0.5));
    let mut solver = Solver::new(anchors, sizes, &path, frame, params);

    // Initial positions: the closest hull position, or the previous frame's.
    for i in 0..anchors.len() {
        if !solver.active[i] {
            continue;
        }
        let prev = previous
            .and_then(|p| p.labels.get(i))
            .filter(|l| l.shown && l.anchor == i);
        solver.t[i] = match prev {
            Some(l) => {
                let moved = parameter_delta(path.parameter_of(l.home_point), solver.home[i]);
                (path.parameter_of(l.path_point) + moved).rem_euclid(1.0)
            }
            None => solver.home[i],
        };
        solver.update(i);
    }

    let mut budget = params.max_iterations;
    let mut disabled = 0;
    loop {
        solver.iterate(budget);
        let involved = solver.conflicting();
        let victim = involved.into_iter().min_by(|&a, &b| {
            anchors[a]
                .priority
                .total_cmp(&anchors[b].priority)
                .then(anchors[b].depth.total_cmp(&anchors[a].depth))
                .then(b.cmp(&a))
        });
        let Some(victim) = victim else { break };
        solver.active[victim] = false;
        disabled += 1;
        budget = params.iterations_after_disable;
    }

    let (d0, d1) = params.depth_range.unwrap_or_else(|| {
        anchors
            .iter()
            .filter(|a| a.visible)
            .fold((f32::MAX, f32::MIN), |(lo, hi), a| {
                (lo.min(a.depth), hi.max(a.depth))
            })
    });
    let labels = (0..anchors.len())
        .map(|i| {
            let g = &solver.geo[i];
            let a = &anchors[i];
            let opacity = if !a.visible {
                0.0
            } else if d1 > d0 {
                let s = ((a.depth - d0) / (d1 - d0)).clamp(0.0, 1.0);
                1.0 - s * (1.0 - params.min_opacity)
            } else {
                1.0
            };
            PlacedLabel {
                anchor: i,
                rect: g.rect,
                parameter: solver.t[i].rem_euclid(1.0),
                path_point: g.path_point,
                hull_point: g.hull_point,
                home: solver.home[i],
                home_point: path.point_at(solver.home[i]),
                leader: [a.screen, g.end],
                opacity,
                shown: solver.active[i],
                inside_frame: g.rect.inside_frame(frame),
            }
        })
        .collect();
    Layout {
        labels,
        iterations: solver.iterations,
        swaps: solver.swaps,
        disabled,
        path,
    }
}

/// Where one label sits for its current parameter.
#[derive(Clone, Copy, Debug)]
struct Geo {
    rect: Rect,
    /// `rect` grown by half the label gap, for overlap tests.
    padded: Rect,
    /// Leader end (attachment point).
    end: Vec2,
    path_point: Vec2,
    hull_point: Vec2,
}

struct Solver<'a> {
    anchors: &'a [ProjectedAnchor],
    sizes: &'a [Vec2],
    path: &'a HullPath,
    frame: Vec2,
    params: &'a LayoutParams,
    t: Vec<f32>,
    home: Vec<f32>,
    active: Vec<bool>,
    geo: Vec<Geo>,
    iterations: u32,
    swaps: u32,
}

impl<'a> Solver<'a> {
    fn new(
        anchors: &'a [ProjectedAnchor],
        sizes: &'a [Vec2],
        path: &'a HullPath,
        frame: Vec2,
        params: &'a LayoutParams,
    ) -> Self {
        let home: Vec<f32> = anchors
            .iter()
            .map(|a| path.parameter_of(a.screen))
            .collect();
        let active = anchors
            .iter()
            .map(|a| a.visible && a.screen.is_finite())
            .collect();
        let mut s = Self {
            anchors,
            sizes,
            path,
            frame,
            params,
            t: home.clone(),
            home,
            active,
            geo: Vec::with_capacity(anchors.len()),
            iterations: 0,
            swaps: 0,
        };
        s.geo = (0..anchors.len()).map(|i| s.place(i, s.t[i])).collect();
        s
    }

    /// The label box of label `i` at parameter `t`.
    fn place(&self, i: usize, t: f32) -> Geo {
        let s = self.path.sample(t);
        let size = self.sizes[i].max(Vec2::ZERO);
        let support = s.normal.x.abs() * size.x * 0.5 + s.normal.y.abs() * size.y * 0.5;
        let mut rect = Rect::from_center_size(s.point + s.normal * support, size);
        if self.params.keep_in_frame && !rect.inside_frame(self.frame) {
            let shift_axis = |lo: f32, hi: f32, extent: f32| {
                if lo < 0.0 {
                    -lo
                } else if hi > extent {
                    (extent - hi).max(-lo)
                } else {
                    0.0
                }
            };
            let shift = Vec2::new(
                shift_axis(rect.min.x, rect.max.x, self.frame.x),
                shift_axis(rect.min.y, rect.max.y, self.frame.y),
            );
            let moved = rect.translated(shift);
            // Keep at least half the margin from the hull when moving back into the frame.
            let clearance = moved.expanded(0.5 * self.path.margin());
            if !rect_intersects_convex_polygon(&clearance, self.path.vertices()) {
                rect = moved;
            }
        }
        Geo {
            rect,
            padded: rect.expanded(0.5 * self.params.label_gap),
            end: rect.closest_point(self.anchors[i].screen),
            path_point: s.point,
            hull_point: s.base,
        }
    }

    fn update(&mut self, i: usize) {
        self.geo[i] = self.place(i, self.t[i]);
    }

    fn crosses(&self, i: usize, j: usize) -> bool {
        segments_cross(
            self.anchors[i].screen,
            self.geo[i].end,
            self.anchors[j].screen,
            self.geo[j].end,
        )
    }

    fn overlaps(&self, i: usize, j: usize) -> bool {
        self.geo[i].padded.overlaps(&self.geo[j].padded)
    }

    fn swap(&mut self, i: usize, j: usize) {
        self.t.swap(i, j);
        self.update(i);
        self.update(j);
        self.swaps += 1;
    }

    /// Runs steps 1–3 until an iteration finds nothing to do, at most `budget` times.
    fn iterate(&mut self, budget: u32) {
        let ids: Vec<usize> = (0..self.t.len()).filter(|&i| self.active[i]).collect();
        let step = self.params.delta / self.path.length().max(1e-6);
        let mut push = vec![0i32; self.t.len()];
        for _ in 0..budget {
            let mut busy = false;
            // Step 1: crossing leaders exchange positions.
            for (k, &i) in ids.iter().enumerate() {
                for &j in &ids[k + 1..] {
                    if self.crosses(i, j) {
                        self.swap(i, j);
                        busy = true;
                    }
                }
            }
            // Step 2: exchange when both get closer to their anchors.
            for (k, &i) in ids.iter().enumerate() {
                for &j in &ids[k + 1..] {
                    let (ai, aj) = (self.anchors[i].screen, self.anchors[j].screen);
                    let di = ai.distance(self.geo[i].end);
                    let dj = aj.distance(self.geo[j].end);
                    // Cheap test with the other label's current box first.
                    if ai.distance(self.geo[j].rect.closest_point(ai)) >= di
                        || aj.distance(self.geo[i].rect.closest_point(aj)) >= dj
                    {
                        continue;
                    }
                    let gi = self.place(i, self.t[j]);
                    let gj = self.place(j, self.t[i]);
                    if ai.distance(gi.end) < di - 1e-3 && aj.distance(gj.end) < dj - 1e-3 {
                        self.swap(i, j);
                        busy = true;
                    }
                }
            }
            // Step 3: overlapping labels move apart along the hull by δ.
            for (k, &i) in ids.iter().enumerate() {
                for &j in &ids[k + 1..] {
                    if self.overlaps(i, j) {
                        let ahead = parameter_delta(self.t[i], self.t[j]);
                        let (back, front) = if ahead >= 0.0 { (i, j) } else { (j, i) };
                        push[front] += 1;
                        push[back] -= 1;
                        busy = true;
                    }
                }
            }
            for &i in &ids {
                if push[i] != 0 {
                    self.t[i] = (self.t[i] + step * push[i].signum() as f32).rem_euclid(1.0);
                    self.update(i);
                    push[i] = 0;
                }
            }
            self.iterations += 1;
            if !busy {
                break;
            }
        }
    }

    /// Active labels involved in an overlap or a crossing, ascending.
    fn conflicting(&self) -> Vec<usize> {
        let ids: Vec<usize> = (0..self.t.len()).filter(|&i| self.active[i]).collect();
        let mut involved = vec![false; self.t.len()];
        for (k, &i) in ids.iter().enumerate() {
            for &j in &ids[k + 1..] {
                if self.overlaps(i, j) || self.crosses(i, j) {
                    involved[i] = true;
                    involved[j] = true;
                }
            }
        }
        (0..self.t.len()).filter(|&i| involved[i]).collect()
    }
}

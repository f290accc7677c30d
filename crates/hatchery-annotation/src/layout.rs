//! Annotation layout after VolumeShop (Bruckner & Gröller 2005, §6.4 "Annotations").
//!
//! Guidelines (§6.4): annotations must not overlap; connecting (leader) lines must not cross;
//! annotations should not occlude other structures; an annotation should be as close as possible to
//! its anchor. Labels are placed outside the convex hull of the visible objects' projected bounding
//! volumes, at a position given by one parameter `t ∈ [0, 1)` of an arc-length parameterisation
//! ([`HullPath`]), initially the position closest to the anchor. Then, until nothing is left to
//! resolve or `max_iterations` is reached:
//!
//! 1. if the leader lines of two labels cross, the labels exchange positions;
//! 2. if exchanging the positions of two labels brings both closer to their anchors, they exchange;
//! 3. if a label overlaps its predecessor (along the hull), it moves by a small δ.
//!
//! Remaining crossings and overlaps are removed by disabling labels one at a time (§6.4: "annotations
//! whose reference structures are farther away will be disabled first"); see [`layout`] for the exact
//! rule and this implementation's choices.
//!
//! Over 600 lines: one algorithm (§6.4's layout loop: initial placement, the swap/shift
//! iterations, the crossing and overlap tests it needs), kept together so its steps read in order.

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
    /// Move labels that would stick out of the frame back inside, as far as that keeps half the
    /// margin between label and hull. Default true.
    pub keep_in_frame: bool,
    /// Temporal coherence: with a previous layout, how far (arc length) a label may move from its
    /// previous position towards the hull position closest to its anchor before the iterations,
    /// per call. Default 4 px.
    pub coherence_pull: f32,
    /// Step 3 from scratch (no previous layout): an overlapping label moves by this multiple of
    /// the overlap's depth (the smaller of its x and y extents, px), at least δ. Labels start
    /// piled up at the hull points nearest their anchors; moving by δ alone takes hundreds of
    /// iterations to spread such a pile. With a previous layout labels move by δ only, so
    /// animation stays smooth. 0 = δ always. Default 1.5.
    pub overlap_shift: f32,
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
            coherence_pull: 4.0,
            overlap_shift: 1.5,
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
    /// Position along [`Layout::path`] (the hull grown by the margin), t ∈ [0, 1): the parameter of
    /// the path point closest to the label's centre.
    pub parameter: f32,
    /// The path point at `parameter`, px. The label touches the path near it, from outside.
    pub path_point: Vec2,
    /// The hull polygon point the label belongs to (`path_point` moved back by the margin), px.
    pub hull_point: Vec2,
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
    /// Whether this label exchanged places with another one (steps 1 and 2) in this layout; the
    /// jumps of a label between frames come from these (or from labels shown or hidden).
    pub swapped: bool,
}

/// The result of [`layout`].
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// One entry per anchor, in anchor order (shown or not).
    pub labels: Vec<PlacedLabel>,
    /// The convex hull grown by the margin: the silhouette the labels sit on.
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
/// * `anchors`: projected anchors (px, window depth, priority), see
///   [`project_anchors`](crate::project_anchors).
/// * `sizes`: label box width × height per anchor, px; must have the same length as `anchors`
///   (panics otherwise).
/// * `hull_points`: the projected footprint of the visible objects (e.g. bounding-box corners,
///   [`project_footprint`](crate::project_footprint)), px; any number, the hull is computed here.
///   With no points the visible anchors themselves are used.
/// * `frame`: width × height of the frame, px.
/// * `previous`: the layout of the previous frame, for temporal coherence (`None`: every label
///   starts at the position closest to its anchor, as in §6.4). Each label that was shown there
///   starts from its previous place (the closest place to its previous centre on the new hull),
///   then moves towards the place closest to its anchor by at most `params.coherence_pull` px
///   where that creates no overlap or crossing, so labels follow their anchors smoothly and stay
///   put in a still scene. Labels not shown there start at the closest place. `previous` must come
///   from the same anchor list.
///
/// Choices where §6.4 leaves room:
/// * Placement: label `i` at parameter `t` has its centre at the point `t` of its own path, the
///   boundary of *hull ⊕ margin disc ⊕ label box* (Minkowski sum), parameterised by arc length
///   from the point nearest the hull path's `t = 0`. So the box touches the grown hull from outside
///   (never intersecting the hull) and its centre moves exactly as far as the parameter does, also
///   around corners, where a box that merely touched the hull at `t` would swing by half its width.
///   The shared [`Layout::path`] parameter is reported in [`PlacedLabel::parameter`].
/// * "Exchange positions" gives each label the place on its own path closest to the other's
///   centre. Step 1 keeps an exchange only if it uncrosses the pair. Step 3's "predecessor" is any overlapping label behind it along the hull (by the polar
///   angle of the centres around the hull's centroid, the shorter way round); both labels of an
///   overlapping pair move apart by δ (the one ahead forwards, the other backwards), spreading
///   clusters symmetrically instead of pushing them all one way. From scratch the step is
///   `overlap_shift` × the deepest overlap of the label instead, when that is larger than δ
///   (the initial piles spread in tens of iterations instead of hundreds).
/// * Disabling: among the labels involved in a remaining overlap or crossing, the one with the
///   lowest [`ProjectedAnchor::priority`] goes first; among equal priorities one that was not shown
///   in `previous` (hysteresis against flicker while depths reorder during a rotation); then the
///   one with the largest anchor depth (farthest, as in §6.4); then the larger index. After each,
///   steps 1–3 run again for `iterations_after_disable` iterations. This ends with no overlaps and
///   no crossings among shown labels.
/// * Leader opacity: with `(d₀, d₁)` the depth range (`params.depth_range`, or the visible anchors'
///   smallest and largest depth), `opacity = 1 − s·(1 − min_opacity)`,
///   `s = clamp((depth − d₀)/(d₁ − d₀), 0, 1)` (1 when d₁ = d₀); 0 for anchors that are not
///   visible, whose labels are never shown.
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
    let margin = params.margin.max(0.0);
    let path = HullPath::new(&hull, margin);
    let mut solver = Solver::new(anchors, sizes, &path, frame, params);
    if previous.is_some() {
        solver.overlap_shift = 0.0;
    }

    let mut was_shown = vec![false; anchors.len()];
    if let Some(prev) = previous {
        for (i, shown) in was_shown.iter_mut().enumerate() {
            let Some(l) = prev.labels.get(i).filter(|l| l.shown && l.anchor == i) else {
                continue;
            };
            *shown = true;
            if solver.active[i] {
                solver.t[i] = solver.parameter_near(i, l.rect.center());
                solver.update(i);
            }
        }
        solver.pull(&was_shown, params.coherence_pull);
    }

    let mut budget = params.max_iterations;
    let mut disabled = 0;
    loop {
        solver.iterate(budget);
        let victim = solver.conflicting().into_iter().min_by(|&a, &b| {
            anchors[a]
                .priority
                .total_cmp(&anchors[b].priority)
                .then(was_shown[a].cmp(&was_shown[b]))
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
            let parameter = path.parameter_of(g.rect.center());
            let sample = path.sample(parameter);
            PlacedLabel {
                anchor: i,
                rect: g.rect,
                parameter,
                path_point: sample.point,
                hull_point: sample.base,
                leader: [a.screen, g.end],
                opacity,
                shown: solver.active[i],
                inside_frame: g.rect.inside_frame(frame),
                swapped: solver.swapped[i],
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

/// The path of label centres for a box of `size` around `hull` grown by `margin`: the boundary of
/// hull ⊕ disc(margin) ⊕ box, with its parameter origin moved to the point closest to `origin`.
fn centre_path(hull: &[Vec2], size: Vec2, margin: f32, origin: Vec2) -> (HullPath, f32) {
    let half = size.max(Vec2::ZERO) * 0.5;
    let corners = [
        Vec2::new(-half.x, -half.y),
        Vec2::new(half.x, -half.y),
        Vec2::new(half.x, half.y),
        Vec2::new(-half.x, half.y),
    ];
    let sum: Vec<Vec2> = hull.iter().flat_map(|&v| corners.map(|c| v + c)).collect();
    let path = HullPath::new(&convex_hull(&sum), margin);
    let offset = path.parameter_of(origin);
    (path, offset)
}

/// Where one label sits for its current parameter.
#[derive(Clone, Copy, Debug)]
struct Geo {
    rect: Rect,
    /// `rect` grown by half the label gap, for overlap tests.
    padded: Rect,
    /// Leader end (attachment point).
    end: Vec2,
    /// The leader's bounding box, for a quick rejection before the crossing test.
    leader_box: Rect,
    /// Squared leader length, px².
    leader_len2: f32,
    /// Polar angle of the centre around the hull centroid, for "ahead"/"behind".
    angle: f32,
}

struct Solver<'a> {
    anchors: &'a [ProjectedAnchor],
    sizes: &'a [Vec2],
    path: &'a HullPath,
    frame: Vec2,
    params: &'a LayoutParams,
    centroid: Vec2,
    /// Per label: its centre path and the offset of that path's parameter origin.
    loci: Vec<HullPath>,
    origins: Vec<f32>,
    /// Per label: parameter on its own centre path (relative to its origin).
    t: Vec<f32>,
    home: Vec<f32>,
    active: Vec<bool>,
    swapped: Vec<bool>,
    /// Multiple of the overlap depth step 3 moves a label by (0 with a previous layout).
    overlap_shift: f32,
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
        let hull = path.vertices();
        let centroid = if hull.is_empty() {
            frame * 0.5
        } else {
            hull.iter().sum::<Vec2>() / hull.len() as f32
        };
        let origin = path.point_at(0.0);
        let active: Vec<bool> = anchors
            .iter()
            .map(|a| a.visible && a.screen.is_finite())
            .collect();
        let (loci, origins): (Vec<HullPath>, Vec<f32>) = sizes
            .iter()
            .zip(&active)
            .map(|(&size, &on)| {
                if on {
                    centre_path(hull, size, params.margin.max(0.0), origin)
                } else {
                    (HullPath::new(&[], 0.0), 0.0)
                }
            })
            .unzip();
        let home: Vec<f32> = (0..anchors.len())
            .map(|i| (loci[i].parameter_of(anchors[i].screen) - origins[i]).rem_euclid(1.0))
            .collect();
        let mut s = Self {
            anchors,
            sizes,
            path,
            frame,
            params,
            centroid,
            loci,
            origins,
            t: home.clone(),
            home,
            swapped: vec![false; anchors.len()],
            overlap_shift: params.overlap_shift.max(0.0),
            active,
            geo: Vec::with_capacity(anchors.len()),
            iterations: 0,
            swaps: 0,
        };
        s.geo = (0..anchors.len()).map(|i| s.place(i, s.t[i])).collect();
        s
    }

    /// Parameter of label `i`'s place closest to point `p`.
    fn parameter_near(&self, i: usize, p: Vec2) -> f32 {
        (self.loci[i].parameter_of(p) - self.origins[i]).rem_euclid(1.0)
    }

    /// The label box of label `i` at parameter `t`.
    fn place(&self, i: usize, t: f32) -> Geo {
        let center = self.loci[i].point_at(t + self.origins[i]);
        let mut rect = Rect::from_center_size(center, self.sizes[i].max(Vec2::ZERO));
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
            // Move by the largest part of `shift` that keeps half the margin from the hull (found
            // by bisection, so the result varies continuously as the hull moves).
            let clear = |f: f32| {
                let moved = rect
                    .translated(shift * f)
                    .expanded(0.5 * self.path.margin());
                !rect_intersects_convex_polygon(&moved, self.path.vertices())
            };
            let fraction = if clear(1.0) {
                1.0
            } else {
                let (mut lo, mut hi) = (0.0f32, 1.0f32);
                for _ in 0..10 {
                    let mid = 0.5 * (lo + hi);
                    if clear(mid) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                lo
            };
            rect = rect.translated(shift * fraction);
        }
        let d = rect.center() - self.centroid;
        let anchor = self.anchors[i].screen;
        let end = rect.closest_point(anchor);
        Geo {
            rect,
            padded: rect.expanded(0.5 * self.params.label_gap),
            end,
            leader_box: Rect {
                min: anchor.min(end),
                max: anchor.max(end),
            },
            leader_len2: anchor.distance_squared(end),
            angle: d.y.atan2(d.x),
        }
    }

    fn update(&mut self, i: usize) {
        self.geo[i] = self.place(i, self.t[i]);
    }

    fn crosses(&self, i: usize, j: usize) -> bool {
        let (a, b) = (&self.geo[i].leader_box, &self.geo[j].leader_box);
        if a.max.x < b.min.x || b.max.x < a.min.x || a.max.y < b.min.y || b.max.y < a.min.y {
            return false;
        }
        segments_cross(
            self.anchors[i].screen,
            self.geo[i].end,
            self.anchors[j].screen,
            self.geo[j].end,
        )
    }

    /// Depth of the overlap of labels `i` and `j` (smallest of the x and y overlaps of the padded
    /// boxes, px), `None` when they do not overlap.
    fn penetration(&self, i: usize, j: usize) -> Option<f32> {
        let (a, b) = (&self.geo[i].padded, &self.geo[j].padded);
        let x = a.max.x.min(b.max.x) - a.min.x.max(b.min.x);
        let y = a.max.y.min(b.max.y) - a.min.y.max(b.min.y);
        (x > 0.0 && y > 0.0).then(|| x.min(y))
    }

    fn overlaps(&self, i: usize, j: usize) -> bool {
        self.geo[i].padded.overlaps(&self.geo[j].padded)
    }

    /// Exchanges the places of labels `i` and `j` (each to its place nearest the other's centre).
    fn swap(&mut self, i: usize, j: usize) {
        let ti = self.parameter_near(i, self.geo[j].rect.center());
        let tj = self.parameter_near(j, self.geo[i].rect.center());
        self.t[i] = ti;
        self.t[j] = tj;
        self.update(i);
        self.update(j);
        self.swaps += 1;
    }

    /// Step 1: exchanges `i` and `j`, keeping it only if that uncrosses their leaders; returns
    /// whether it was kept.
    fn uncross(&mut self, i: usize, j: usize) -> bool {
        let (ti, tj) = (self.t[i], self.t[j]);
        self.swap(i, j);
        if self.crosses(i, j) {
            self.t[i] = ti;
            self.t[j] = tj;
            self.update(i);
            self.update(j);
            self.swaps -= 1;
            false
        } else {
            self.swapped[i] = true;
            self.swapped[j] = true;
            true
        }
    }

    /// Runs steps 1–3 at most `budget` times, until an iteration changes nothing (then it is
    /// resolved, or stuck on crossings that an exchange does not undo, which more iterations
    /// would not change either).
    fn iterate(&mut self, budget: u32) {
        let ids: Vec<usize> = (0..self.t.len()).filter(|&i| self.active[i]).collect();
        let mut push = vec![0i32; self.t.len()];
        let mut reach = vec![0f32; self.t.len()];
        for _ in 0..budget {
            let mut changed = false;
            // Step 1: crossing leaders exchange positions (kept only where that uncrosses them:
            // two labels stacked on one place cross either way, and step 3 separates them first).
            for (k, &i) in ids.iter().enumerate() {
                for &j in &ids[k + 1..] {
                    if self.crosses(i, j) && self.uncross(i, j) {
                        changed = true;
                    }
                }
            }
            // Step 2: exchange when both get closer to their anchors.
            for (k, &i) in ids.iter().enumerate() {
                for &j in &ids[k + 1..] {
                    let (ai, aj) = (self.anchors[i].screen, self.anchors[j].screen);
                    let (di2, dj2) = (self.geo[i].leader_len2, self.geo[j].leader_len2);
                    // Cheap test with the other label's current box first.
                    if ai.distance_squared(self.geo[j].rect.closest_point(ai)) >= di2
                        || aj.distance_squared(self.geo[i].rect.closest_point(aj)) >= dj2
                    {
                        continue;
                    }
                    let gi = self.place(i, self.parameter_near(i, self.geo[j].rect.center()));
                    let gj = self.place(j, self.parameter_near(j, self.geo[i].rect.center()));
                    let (di, dj) = (di2.sqrt(), dj2.sqrt());
                    if ai.distance(gi.end) < di - 1e-3 && aj.distance(gj.end) < dj - 1e-3 {
                        self.swap(i, j);
                        self.swapped[i] = true;
                        self.swapped[j] = true;
                        changed = true;
                    }
                }
            }
            // Step 3: overlapping labels move apart along the hull by δ.
            for (k, &i) in ids.iter().enumerate() {
                for &j in &ids[k + 1..] {
                    if let Some(depth) = self.penetration(i, j) {
                        let ahead = angle_delta(self.geo[i].angle, self.geo[j].angle);
                        let (back, front) = if ahead >= 0.0 { (i, j) } else { (j, i) };
                        push[front] += 1;
                        push[back] -= 1;
                        reach[front] = reach[front].max(depth);
                        reach[back] = reach[back].max(depth);
                    }
                }
            }
            for &i in &ids {
                if push[i] != 0 {
                    changed = true;
                    let px = (self.overlap_shift * reach[i]).max(self.params.delta);
                    let step = px / self.loci[i].length().max(1e-6);
                    self.t[i] = (self.t[i] + step * push[i].signum() as f32).rem_euclid(1.0);
                    self.update(i);
                    push[i] = 0;
                }
                // Also where the pushes cancelled: the depth is this iteration's only.
                reach[i] = 0.0;
            }
            self.iterations += 1;
            if !changed {
                break;
            }
        }
    }

    /// Whether label `i` overlaps or crosses any other active label.
    fn in_conflict(&self, i: usize) -> bool {
        (0..self.t.len())
            .any(|j| j != i && self.active[j] && (self.overlaps(i, j) || self.crosses(i, j)))
    }

    /// Moves each label in `which` towards its home by at most `max_px` of arc length, taking the
    /// largest of max_px, max_px/2, max_px/4 that creates no conflict for it (none if all do, or
    /// if it is in conflict already). Labels farthest from home go first.
    fn pull(&mut self, which: &[bool], max_px: f32) {
        let gap = |s: &Self, i: usize| parameter_delta(s.t[i], s.home[i]);
        let mut order: Vec<usize> = (0..self.t.len())
            .filter(|&i| which[i] && self.active[i])
            .collect();
        order.sort_by(|&a, &b| gap(self, b).abs().total_cmp(&gap(self, a).abs()));
        for i in order {
            let want = gap(self, i);
            if want == 0.0 || self.in_conflict(i) {
                continue;
            }
            let limit = max_px / self.loci[i].length().max(1e-6);
            let start = self.t[i];
            for fraction in [1.0, 0.5, 0.25] {
                self.t[i] = (start + want.clamp(-limit, limit) * fraction).rem_euclid(1.0);
                self.update(i);
                if !self.in_conflict(i) {
                    break;
                }
                self.t[i] = start;
                self.update(i);
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

/// Signed difference `b − a` of two angles, wrapped into [−π, π).
fn angle_delta(a: f32, b: f32) -> f32 {
    use std::f32::consts::{PI, TAU};
    (b - a + PI).rem_euclid(TAU) - PI
}

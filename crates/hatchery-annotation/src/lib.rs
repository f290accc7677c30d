//! hatchery's annotations, on the CPU: label layout around the silhouette hull, mask tracing and
//! vector (SVG) export.
//!
//! The layout follows VolumeShop (S. Bruckner and M. E. Gröller, "VolumeShop: An Interactive
//! System for Direct Volume Illustration", IEEE Visualization 2005, §6.4 "Annotations"):
//!
//! 1. [`project_anchors`] takes the labelled 3-D anchors to pixels and window depth;
//!    [`project_footprint`] the visible objects' bounding volumes (e.g. [`box_corners`]).
//! 2. [`convex_hull`] of the footprint is the silhouette polygon; [`HullPath`] parameterises it
//!    (grown by a margin) by arc length in [0, 1).
//! 3. [`layout`] places one label per anchor on that path, resolves crossings and overlaps, and
//!    disables what it cannot resolve, farthest first.
//!
//! For vector output, [`trace_mask`] turns a mask (e.g. a rendered line or silhouette buffer) into
//! simplified polylines, and [`SvgDocument`] writes the picture, lines, leaders, arrows and labels
//! as Inkscape layers.
//!
//! Units: pixels with the origin at the frame's top-left corner and y down, unless stated.
#![forbid(unsafe_code)]

mod anchor;
mod geometry;
mod hull;
mod layout;
mod simplify;
mod svg;
mod trace;

pub use anchor::{
    Anchor, ProjectedAnchor, box_corners, project_anchors, project_footprint, project_point,
};
pub use geometry::{Rect, point_segment_distance, rect_intersects_convex_polygon, segments_cross};
pub use hull::{HullPath, PathSample, convex_contains, convex_hull, parameter_delta, signed_area};
pub use layout::{Layout, LayoutParams, PlacedLabel, layout};
pub use simplify::simplify;
pub use svg::{
    Color, DESCENT, LINE_HEIGHT, LabelStyle, Layer, MEAN_ADVANCE, PathCommand, PathData, PathStyle,
    Stroke, SvgDocument, estimate_label_size, label_baseline,
};
pub use trace::{Polyline, trace_mask};

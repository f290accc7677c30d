//! The closed set of data types that flow along edges.

use std::fmt;

/// Type of a port. An edge may only connect an output to an input of the same type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PortType {
    /// Scalar field (3-D texture) with dims, spacing, origin and value range.
    Volume,
    /// Object-id volume; never interpolated across objects.
    Labels,
    /// Triangle mesh with normals and bounds.
    Mesh,
    /// View and projection (perspective or orthographic).
    Camera,
    /// Lighting parameters.
    Light,
    /// Screen-space depth + view-space normal of one surface layer.
    GBuffer,
    /// RGBA colour image (premultiplied alpha).
    Image,
    /// One-channel float image (silhouette response, intensity, coverage, ...).
    Mask,
    /// Value → colour/opacity mapping.
    TransferFunction,
    /// A set of lit-sphere style maps.
    StyleSet,
    /// Per-object rendering settings of a segmented volume (two-level volume rendering).
    ObjectStyles,
    /// Per-pixel importance-driven rendering data of one frame: focus footprint, countersink
    /// depth and importance sums (Viola et al., importance compositing).
    Importance,
    /// Labelled 3-D anchors and, once laid out, their labels' places (VolumeShop §6.4).
    Annotations,
    /// Hatching strokes as polylines in pixels (HatchStrokes), for vector export.
    Strokes,
    /// A 3-component field on a grid (a flow's velocity): the `vector` of Svakhine et al. 2005's
    /// Table 1.
    VectorField,
}

impl PortType {
    pub const ALL: [PortType; 15] = [
        PortType::Volume,
        PortType::Labels,
        PortType::Mesh,
        PortType::Camera,
        PortType::Light,
        PortType::GBuffer,
        PortType::Image,
        PortType::Mask,
        PortType::TransferFunction,
        PortType::StyleSet,
        PortType::ObjectStyles,
        PortType::Importance,
        PortType::Annotations,
        PortType::Strokes,
        PortType::VectorField,
    ];

    pub fn name(self) -> &'static str {
        match self {
            PortType::Volume => "Volume",
            PortType::Labels => "Labels",
            PortType::Mesh => "Mesh",
            PortType::Camera => "Camera",
            PortType::Light => "Light",
            PortType::GBuffer => "GBuffer",
            PortType::Image => "Image",
            PortType::Mask => "Mask",
            PortType::TransferFunction => "TransferFunction",
            PortType::StyleSet => "StyleSet",
            PortType::ObjectStyles => "ObjectStyles",
            PortType::Importance => "Importance",
            PortType::Annotations => "Annotations",
            PortType::Strokes => "Strokes",
            PortType::VectorField => "VectorField",
        }
    }
}

impl fmt::Display for PortType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

"""The node kinds of hatchery, one class each: its documentation, ports and parameters.

Generated from the node schemas by ``python -m hatchery._generate``; do not edit.
``help(hatchery.kinds.Silhouette)`` reads a kind's documentation; the class attributes
are the parameters' defaults, typed (usable with ``Graph.set``).
"""

from typing import Literal, Tuple, Union

Kind = Literal[
    'AnnotationLayout',
    'AnnotationList',
    'AnnotationOverlay',
    'AnnotationsFromLabels',
    'Arrow',
    'BoundingBox',
    'Camera',
    'Curvature',
    'CurvatureColor',
    'CurvatureContours',
    'CurvatureFlow',
    'CustomShader',
    'DepthLayers',
    'DepthPeel',
    'DepthTestMask',
    'DiffuseIntensity',
    'DistanceToObject',
    'ExplodedView',
    'Fan',
    'Fill',
    'GBuffer',
    'Halftone',
    'HatchStrokes',
    'ImportanceCompositing',
    'IsoSurfaceRaycast',
    'LabelFile',
    'LabelMask',
    'LabelsFromMaps',
    'LabelsFromThreshold',
    'Light',
    'MarchingCubes',
    'MaskCombine',
    'MeshFile',
    'MeshTransform',
    'MixByMask',
    'MultiplyByMask',
    'ObjectStyles',
    'Over',
    'PaintLabels',
    'ProceduralVectorField',
    'ProceduralVolume',
    'Raycast',
    'RidgeValley',
    'SaveImage',
    'SaveSvg',
    'Schlieren',
    'SecondaryGeometry',
    'SelectImage',
    'SelectionRender',
    'ShadedSurface',
    'Silhouette',
    'Stipple',
    'StyleSet',
    'StyleTransferFunction',
    'TransferFunction1D',
    'TransferFunction2D',
    'TwoLevelRaycast',
    'VectorField',
    'VectorOperator',
    'VolumeFile',
]
"""Every node kind's name."""


class AnnotationLayout:
    """Annotation layout (VolumeShop, the tutorial's §6.4): anchors projected with the camera; the
        convex hull of the visible objects' footprint (their boxes, or the `footprint` mask's
        pixels) parameterised by arc length; each label placed outside the hull at the point
        nearest its anchor, then crossing leader lines swapped, labels swapped when both get
        closer, and overlapping ones shifted by δ (from scratch by 1.5× their overlap, so piles
        spread fast), until resolved or `max_iterations`; what stays unresolved is left out,
        lowest priority and farthest (screen depth) first. Leader opacity falls with the
        anchor's depth; anchors hidden behind the `gbuffer` surface get no label. Starts from
        this node's previous layout (temporal coherence) when the labels and frame size are
        unchanged.

    Inputs:
        annotations (Annotations, required): the anchors
        camera (Camera, required): the view
        gbuffer (GBuffer, optional): the rendered surface: anchors behind it are hidden
        footprint (Mask, optional): the visible objects' footprint (> 0.5), instead of their
            boxes

    Outputs:
        annotations (Annotations): the anchors with their labels placed

    Parameters:
        font_size (float in [6, 96]; default 13.0): label text size, pixels
        margin (float in [0, 200]; default 10.0): distance of the labels from the hull, pixels
        max_iterations (int in [1, 10000]; default 300): iterations of the swap/shift loop
            before labels are left out
        depth_tolerance (float in [0, 1e+06]; default 5.0): with a gbuffer: an anchor this far
            (world units) behind the surface still counts as visible
        coherent (bool; default True): start from the previous layout (labels move little
            between frames)

    """

    kind = 'AnnotationLayout'
    category = 'Annotation'
    font_size: float = 13.0
    margin: float = 10.0
    max_iterations: int = 300
    depth_tolerance: float = 5.0
    coherent: bool = True

class AnnotationList:
    """Labelled anchors written in the graph: "x y z: text; …" (world units), one label per row;
        earlier rows have higher priority when labels must be left out.

    Outputs:
        annotations (Annotations): the anchors

    Parameters:
        anchors (text; default '0 0 0: centre'): "x y z: text; …" in world units

    """

    kind = 'AnnotationList'
    category = 'Annotation'
    anchors: str = '0 0 0: centre'

class AnnotationOverlay:
    """Draws laid-out annotations over an image (VolumeShop §6.4): for every shown label its leader
        line from the anchor to the label's attachment point and a dot at the anchor, both at
        the label's depth opacity, then its text (at the layout's font size) over a halo. Anti-
        aliased on the GPU; pixels, top-left origin, y down.

    Inputs:
        image (Image, required): the picture to annotate
        annotations (Annotations, required): annotations laid out by AnnotationLayout for this
            image's size

    Outputs:
        image (Image): the picture with the labels

    Parameters:
        text_color (RGBA in [0, 1]; default (0.0, 0.0, 0.0, 1.0)): label text colour
        halo_color (RGBA in [0, 1]; default (1.0, 1.0, 1.0, 1.0)): colour of the halo around the
            text (alpha 0: none)
        halo_width (float in [0, 8]; default 2.0): halo width around the glyphs, pixels
        leader_color (RGBA in [0, 1]; default (0.2, 0.2, 0.2, 1.0)): leader line and anchor dot
            colour (alpha times the label's opacity)
        leader_width (float in [0, 16]; default 1.0): leader line width, pixels
        dot_radius (float in [0, 32]; default 2.5): radius of the dot at the anchor, pixels (0:
            none)

    """

    kind = 'AnnotationOverlay'
    category = 'Annotation'
    text_color: Tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)
    halo_color: Tuple[float, float, float, float] = (1.0, 1.0, 1.0, 1.0)
    halo_width: float = 2.0
    leader_color: Tuple[float, float, float, float] = (0.2, 0.2, 0.2, 1.0)
    leader_width: float = 1.0
    dot_radius: float = 2.5

class AnnotationsFromLabels:
    """One anchor per object of a segmentation: at the object's voxel nearest its centroid (on the
        object even where it is concave), named after the labels (or the object table), with the
        object's box as its part of the silhouette hull. Objects: those listed in `objects`,
        else the drawn rows of the `styles` input, else every object of the labels. Priority:
        the importance from the object table, else the object's share of the voxels.

    Inputs:
        labels (Labels, required): the segmentation
        styles (ObjectStyles, optional): which objects are drawn, their names and importance

    Outputs:
        annotations (Annotations): one anchor per object

    Parameters:
        objects (text; default ''): label ids to annotate, e.g. "10, 13" (empty: the drawn
            objects, or all)

    """

    kind = 'AnnotationsFromLabels'
    category = 'Annotation'
    objects: str = ''

class Arrow:
    """A curved arrow from the ghost (anchor 0) to the selection (anchor 1), VolumeShop §6.3
        "Arrows": the head at the selection. The screen-space depth difference bends it, so
        ghost and selection that project close together still get a readable arrow: the
        selection's view-space depth minus the ghost's (world units, positive = nearer the
        viewer) times the pixels per world unit at their midpoint gives Δ pixels; the curve's
        greatest distance from the straight chord is curvature × Δ, to the left of the direction
        of travel on screen when the selection moved towards the viewer, to the right when away.
        Equal depths: a straight arrow.

    Inputs:
        image (Image, required): the picture to draw over
        annotations (Annotations, required): anchor 0 = ghost, anchor 1 = selection (world
            positions)
        camera (Camera, required): the view the picture was rendered with

    Outputs:
        image (Image): the picture with the drawing

    Parameters:
        color (RGBA in [0, 1]; default (0.8, 0.1, 0.1, 1.0)): colour of the arrow's shaft and
            head
        width (float in [0.1, 32]; default 2.0): shaft width, pixels
        curvature (float in [0, 4]; default 0.5): greatest distance from the chord per pixel of
            depth difference

    """

    kind = 'Arrow'
    category = 'Annotation'
    color: Tuple[float, float, float, float] = (0.8, 0.1, 0.1, 1.0)
    width: float = 2.0
    curvature: float = 0.5

class BoundingBox:
    """The 12 edges of the ghost's (anchor 0) and/or the selection's (anchor 1) world box projected
        with the camera, VolumeShop §6.3 "Boxes": cues on an object's position and orientation
        while arranging an illustration. Edges are clipped at the near plane; all edges are
        drawn (no occlusion).

    Inputs:
        image (Image, required): the picture to draw over
        annotations (Annotations, required): anchor 0 = ghost, anchor 1 = selection, with world
            boxes as bounds
        camera (Camera, required): the view the picture was rendered with

    Outputs:
        image (Image): the picture with the drawing

    Parameters:
        which (one of 'ghost', 'selection', 'both'; default 'selection'): whose box to draw
        color (RGBA in [0, 1]; default (0.1, 0.4, 0.9, 1.0)): colour of the box's edges
        width (float in [0.1, 32]; default 1.0): edge width, pixels

    """

    kind = 'BoundingBox'
    category = 'Annotation'
    which: Literal['ghost', 'selection', 'both'] = 'selection'
    color: Tuple[float, float, float, float] = (0.1, 0.4, 0.9, 1.0)
    width: float = 1.0

class Camera:
    """Orbit camera around a target point, perspective or orthographic. The field of view spans the
        frame's shorter side; orthographic views show 2·distance·tan(fov/2) across it; azimuth
        0, elevation 0 with up "y" looks along -z (axis-aligned). With data connected (a volume,
        labels, a mesh, or several) and `framing` "fit", it frames them: the target is the
        centre of their bounds (moved by `pan_x`, `pan_y`), the distance (or orthographic
        extent) makes them fill `fill` of the frame's width or height from this azimuth and
        elevation; `near` and `far` scale with the framed distance relative to `distance` (so
        depth-based thresholds act alike on data of any size), widened to enclose the data;
        `target` goes unused.

    Inputs:
        volume (Volume, optional): data to frame: the volume's foreground (voxels at or above
            Otsu's threshold)
        labels (Labels, optional): data to frame: the labelled objects (not the background)
        mesh (Mesh, optional): data to frame: the mesh's vertices

    Outputs:
        camera (Camera): view and projection for the frame

    Parameters:
        azimuth (float in [-360, 360]; default 30.0): rotation around the up axis, degrees
        elevation (float in [-90, 90]; default 20.0): angle above the horizontal plane, degrees
        distance (float in [0.0001, 1e+06]; default 3.5): distance from the target, world units
        target ((x, y, z); default (0.0, 0.0, 0.0)): point looked at, world units
        fov (float in [1, 170]; default 40.0): field of view across the frame's shorter side
            (the height of a wide frame), degrees
        projection (one of 'perspective', 'orthographic'; default 'perspective'): perspective,
            or orthographic (parallel rays: sizes do not shrink with depth)
        up (one of 'y', 'z'; default 'y'): world axis that points up on screen
        near (float in [1e-05, 1e+06]; default 0.05): near clipping distance
        far (float in [0.0001, 1e+07]; default 100.0): far clipping distance
        framing (one of 'fit', 'fixed'; default 'fit'): fit: frame the connected data; fixed:
            use target and distance (also when nothing is connected)
        fill (float in [0.05, 20]; default 0.8): framing: the fraction of the frame's width or
            height the data fills (above 1: closer, part of the data)
        pan_x (float in [-10, 10]; default 0.0): framing: target shift to the right, in frame
            widths (shorter side)
        pan_y (float in [-10, 10]; default 0.0): framing: target shift upwards, in frame heights
            (shorter side)

    """

    kind = 'Camera'
    category = 'Scene'
    azimuth: float = 30.0
    elevation: float = 20.0
    distance: float = 3.5
    target: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    fov: float = 40.0
    projection: Literal['perspective', 'orthographic'] = 'perspective'
    up: Literal['y', 'z'] = 'y'
    near: float = 0.05
    far: float = 100.0
    framing: Literal['fit', 'fixed'] = 'fit'
    fill: float = 0.8
    pan_x: float = 0.0
    pan_y: float = 0.0

class Curvature:
    """Principal curvatures of the iso-surface in a G-buffer (Hadwiger's deferred iso-surface
        shading, the tutorial's §1): at each pixel's surface point the volume's gradient g and
        Hessian H (central differences of the gradient at ±`step` voxels along the world axes,
        or the tricubic B-spline's own second derivatives with reconstruction bspline), the
        shape operator −P H P / |g| in the tangent plane, its eigenvalues κ1 ≥ κ2 (world
        units⁻¹, positive where the surface bulges towards lower values) and the first principal
        direction. Output image channels (32-bit float data): (κ1, κ2, θ1, θ2) with θ1, θ2 the
        principal directions' screen angles (radians, x right, y down, in [−π/2, π/2)); θ1 = θ2
        = −10 where there is no surface. Connect the G-buffer of IsoSurfaceRaycast (or Raycast,
        mode iso) over the same volume.

    Inputs:
        gbuffer (GBuffer, required): the iso-surface's depth
        volume (Volume, required): the scalar field it is a level of

    Outputs:
        curvature (Image): (κ1, κ2, θ1, θ2) per pixel (data, not colour)

    Parameters:
        step (float in [0.25, 8]; default 1.0): finite-difference step of the Hessian, voxels
            (of the smallest spacing)
        reconstruction (one of 'trilinear', 'bspline'; default 'trilinear'): reconstruction:
            trilinear with the Hessian by central differences of the gradient at ±`step`, or the
            tricubic B-spline's own gradient and second derivatives (Hadwiger §1.3; `step`
            unused)

    """

    kind = 'Curvature'
    category = 'Volume'
    step: float = 1.0
    reconstruction: Literal['trilinear', 'bspline'] = 'trilinear'

class CurvatureColor:
    """Curvature colour mapping (Hadwiger's deferred iso-surface shading, the tutorial's §1, Fig.
        10): a measure of Curvature's principal curvatures — curvedness √(κ1² + κ2²), κ1, κ2,
        mean (κ1 + κ2)/2 or Gaussian κ1·κ2, in world units⁻¹ (⁻² for Gaussian) — through a 1-D
        transfer function whose domain is in the same units (TransferFunction1D with custom
        points, e.g. "-2: …; 2: …"); or, with measure `k1_k2`, both curvatures through a 2-D
        transfer function: the image `map` (x: κ1 from −`range` to `range`, y: κ2 from `range`
        at the top to −`range`), or without a map the built-in shape-class map (shape index cup
        blue, rut cyan, saddle green, ridge yellow, cap red; flat regions light). Transparent
        where there is no surface.

    Inputs:
        curvature (Image, required): Curvature's output
        tf (TransferFunction, optional): measure → colour (all measures but k1_k2)

    Outputs:
        image (Image): premultiplied colour

    Parameters:
        measure (one of 'curvedness', 'k1', 'k2', 'mean', 'gaussian', 'k1_k2'; default
            'curvedness'): which curvature the colour shows (k1_k2: the 2-D map)
        map (path; default ''): k1_k2: a 2-D transfer function image (PNG, …); empty = the
            built-in map
        range (float in [1e-09, 1e+09]; default 0.25): k1_k2: |κ| at the map's edges, world
            units⁻¹

    """

    kind = 'CurvatureColor'
    category = 'Volume'
    measure: Literal['curvedness', 'k1', 'k2', 'mean', 'gaussian', 'k1_k2'] = 'curvedness'
    map: str = ''
    range: float = 0.25

class CurvatureContours:
    """Curvature-controlled contours (Kindlmann et al. 2003 §5, the tutorial's §1): a pixel of the
        iso-surface is on the contour where |n·v| ≤ √(T κv (2 − T κv)), κv the normal curvature
        along the view direction projected into the tangent plane (from the volume's Hessian, as
        Curvature computes it) and T `thickness` pixels at the point's depth, so the band is
        about `thickness` pixels wide on screen whatever the curvature (a plain |n·v| threshold
        is thin on sharp bends and thick on flat ones). No contour where the surface is concave
        along the view. Connect the G-buffer of IsoSurfaceRaycast and its volume.

    Inputs:
        gbuffer (GBuffer, required): the iso-surface's depth
        volume (Volume, required): the scalar field it is a level of

    Outputs:
        mask (Mask): 1 on the contours

    Parameters:
        thickness (float in [0.25, 32]; default 2.0): contour width, pixels
        step (float in [0.25, 8]; default 1.0): finite-difference step of the Hessian, voxels
            (as Curvature's)
        reconstruction (one of 'trilinear', 'bspline'; default 'trilinear'): reconstruction of
            the gradient and Hessian (as Curvature's)

    """

    kind = 'CurvatureContours'
    category = 'Volume'
    thickness: float = 2.0
    step: float = 1.0
    reconstruction: Literal['trilinear', 'bspline'] = 'trilinear'

class CurvatureFlow:
    """Flow along curvature directions (the tutorial's §1, Fig. 11/14): a line integral convolution
        of 3-D value noise along Curvature's principal-direction field in image space — each
        surface pixel averages the noise at the surface points along its streamline (`length`
        pixels, RK2 steps of `step`), so the streaks follow the larger-|κ| direction (or the
        smaller) and stay on the surface as the view moves. A mask in [0, 1] (`mean` on
        average), 0 off the surface; mix it with MixByMask or multiply a shaded image by it.

    Inputs:
        curvature (Image, required): Curvature's output
        gbuffer (GBuffer, required): the surface (the G-buffer Curvature read)

    Outputs:
        flow (Mask): streaks along the principal direction

    Parameters:
        length (float in [2, 200]; default 20.0): streamline length, pixels
        step (float in [0.25, 4]; default 1.0): integration step along a streamline, pixels
            (smaller follows curved fields more closely)
        direction (one of 'max_curvature', 'min_curvature'; default 'max_curvature'): the
            principal direction of the larger or of the smaller |κ|
        grain (float in [1e-06, 1e+06]; default 1.0): noise cell size on the surface, world
            units (about a pixel's footprint)
        contrast (float in [0, 4]; default 1.0): how strongly the streaks stand out from the
            surface around them
        mean (float in [0, 1]; default 0.5): average output (e.g. 0.8 to multiply a colour image
            by the streaks)

    """

    kind = 'CurvatureFlow'
    category = 'Volume'
    length: float = 20.0
    step: float = 1.0
    direction: Literal['max_curvature', 'min_curvature'] = 'max_curvature'
    grain: float = 1.0
    contrast: float = 1.0
    mean: float = 0.5

class CustomShader:
    """A fragment shader of your own (WGSL file): its texture bindings become input ports (Image,
        Mask, GBuffer), its uniform struct's members parameters, its result the output (vec4 →
        image, f32 → mask). Re-read when the file changes. See docs/custom_shader.md.

    Parameters:
        shader (path; default ''): the WGSL file (relative to the graph file's folder); ports
            and parameters follow its declarations

    """

    kind = 'CustomShader'
    category = 'Compositing'
    shader: str = ''

class DepthLayers:
    """The nearest surface of a mesh and the one behind it (Fischer et al. 2005, §3.1) from one
        geometry pass: a k-buffer of the two smallest (depth, normal) keys per pixel, kept with
        64-bit atomics (Bavoil et al. 2007). The same layers as GBuffer + DepthPeel, which draw
        the mesh twice (normals within 2e-3: 16 bits per octahedral coordinate; with coincident
        triangles the fragment kept may differ). Without 64-bit atomics, or when the frame needs
        a k-buffer larger than the adapter's storage binding limit (16 bytes per pixel), it
        draws those two passes.

    Inputs:
        mesh (Mesh, required): the surface
        camera (Camera, required): the view

    Outputs:
        layer1 (GBuffer): depth + normal of the nearest surface
        layer2 (GBuffer): depth + normal of the surface behind it

    Parameters:
        method (one of 'auto', 'peel'; default 'auto'): auto: one pass where the adapter has
            64-bit atomics, else two; peel: always the two passes of GBuffer + DepthPeel (to
            compare)

    """

    kind = 'DepthLayers'
    category = 'Rendering'
    method: Literal['auto', 'peel'] = 'auto'

class DepthPeel:
    """Depth peeling (Fischer et al. 2005, §3.1): rasterises the mesh again, keeping only fragments
        strictly behind the previous layer's depth, then the nearest of those. Chain peels for
        layers 3, 4, …

    Inputs:
        mesh (Mesh, required): the surface (the same mesh as the previous layer)
        camera (Camera, required): the view
        previous (GBuffer, required): the layer in front (GBuffer or another DepthPeel)

    Outputs:
        gbuffer (GBuffer): depth + normal of the next layer

    """

    kind = 'DepthPeel'
    category = 'Rendering'

class DepthTestMask:
    """1 where the window-space depths of layers a and b compare true, else 0. With a = layer 2 and
        b = the secondary geometry, `a<=b` is the depth test of Fischer et al. 2005, eq. 10.
        Empty pixels have depth 1.

    Inputs:
        a (GBuffer, required): first layer
        b (GBuffer, required): second layer

    Outputs:
        mask (Mask): the test result, 0 or 1

    Parameters:
        compare (one of 'a<=b', 'a<b', 'a>=b', 'a>b'; default 'a<=b'): the mask is 1 where layer
            a is in front of b (a<b, a<=b: smaller depth is nearer) or behind it (a>b, a>=b)

    """

    kind = 'DepthTestMask'
    category = 'Compositing'
    compare: Literal['a<=b', 'a<b', 'a>=b', 'a>b'] = 'a<=b'

class DiffuseIntensity:
    """Diffuse intensity I = max(n · lightDir, 0) per pixel of a G-buffer layer (Fischer et al.
        2005, eq. 1/6), with the light's direction in view space. Pixels without surface get
        `empty` (1 = paper stays white under halftoning).

    Inputs:
        gbuffer (GBuffer, required): the layer
        light (Light, required): the light

    Outputs:
        intensity (Mask): intensity in [0, 1]

    Parameters:
        empty (float in [0, 1]; default 1.0): value where the layer has no surface
        two_sided (bool; default False): light back faces with the flipped normal

    """

    kind = 'DiffuseIntensity'
    category = 'Illustration'
    empty: float = 1.0
    two_sided: bool = False

class DistanceToObject:
    """Distance to a risk structure (Preim/Tietjen, neck dissection planning §4.3): per voxel of
        the label map, the Euclidean distance in world units (mm) from its centre to the nearest
        voxel centre of `objects` — exact, with each axis's spacing and the grid's placement in
        the world. Feed it to TwoLevelRaycast's `volume` with the same labels and give the
        structures a transfer function over millimetres (e.g. red to 2 mm, yellow to 5 mm) to
        colour them by their distance to the objects.

    Inputs:
        labels (Labels, required): the segmentation (object ids and names)

    Outputs:
        volume (Volume): distance in world units (mm) on the labels' grid

    Parameters:
        objects (text; default '1'): the objects distances are measured to: ids or names of the
            labels, separated by commas (e.g. "liver" or "10, 14")
        signed (bool; default False): negative inside the objects (minus the distance to the
            nearest voxel outside them) instead of 0 there

    """

    kind = 'DistanceToObject'
    category = 'Data'
    objects: str = '1'
    signed: bool = False

class ExplodedView:
    """Exploded views of a segmented volume (Viola et al., the Vis 2005 tutorial §3, volume
        splitting): the `parts` — objects, halves of objects split by a plane through their
        centre (logical splitting) or halves of the whole volume (geometrical splitting) — are
        moved by their displacements; each sample is looked up in every part at its position
        minus the part's displacement, the first part (in the written order) holding a drawn
        object there owns it, and it is classified with that object's transfer function and
        rendering mode from ObjectStyles and composited front to back. Objects no part names
        stay in place. Guides: an arrow from each part's original centre to its moved one.

    Inputs:
        volume (Volume, required): the scalar field
        labels (Labels, required): object ids on the volume's grid
        styles (ObjectStyles, required): the object table (over or iso compositing)
        camera (Camera, required): the view
        light (Light, optional): the light (default: a headlight)

    Outputs:
        image (Image): premultiplied colour, with the guides where `guides` is on
        gbuffer (GBuffer): depth and normal where opaque
        annotations (Annotations): per part its original centre (anchor 2k) and moved centre (2k
            + 1) with their boxes: anchors 0 and 1 are what Arrow and Fan draw

    Parameters:
        parts (text; default 'volume: split x 20'): the parts and how they move, `;`-separated:
            `OBJECT: split AXIS DISTANCE` (its halves either side of the plane through its
            centre normal to x, y or z, moved ±DISTANCE along it) or `OBJECT: move DX DY DZ`;
            world units, or `%` of the labelled objects' largest extent; OBJECT a label id, an
            object's name or `volume` (the whole volume); earlier parts own overlapping samples
        guides (bool; default True): draw guides: an arrow from each moved part's original
            centre (a dot) to its moved one
        guide_color (RGBA in [0, 1]; default (0.15, 0.15, 0.15, 0.9)): colour of the guides
        guide_width (float in [0.1, 32]; default 1.5): width of the guides, pixels
        boundary (one of 'filtered', 'point'; default 'filtered'): boundary filtering of the
            object ids (as TwoLevelRaycast) or the nearest voxel's id
        normals (one of 'data', 'objects'; default 'data'): shading normals from the data's
            gradient or each object's own filtered mask (label maps without intensities)
        surface_smoothing (float in [0, 4]; default 0.0): with normals = objects: smooth iso-
            surfaces' mask gradient over ±this many voxels
        step (float in [0.05, 8]; default 0.5): sample distance in voxels (of the smallest
            spacing)
        reconstruction (one of 'trilinear', 'bspline'; default 'trilinear'): reconstruction of
            the data between voxels
        ambient (float in [0, 1]; default 0.15): ambient light: brightness of every shaded
            sample, lit or not (c_a of eq. 3)
        diffuse (float in [0, 4]; default 0.85): diffuse light: brightness where the surface
            faces the light (c_d of eq. 3)
        specular (float in [0, 4]; default 0.4): specular light: strength of the highlight (c_s
            of eq. 3)
        exponent (float in [1, 512]; default 32.0): shininess: higher makes the highlight
            smaller and sharper (c_e of eq. 3)
        jitter (bool; default True): jitter the first sample per pixel
        early_termination (float in [0.5, 1]; default 0.99): stop a ray at this opacity (1 =
            never)
        kernel (one of 'auto', 'fragment', 'compute'; default 'auto'): GPU path: fragment shader
            or compute kernel (same picture)

    """

    kind = 'ExplodedView'
    category = 'Volume'
    parts: str = 'volume: split x 20'
    guides: bool = True
    guide_color: Tuple[float, float, float, float] = (0.15, 0.15, 0.15, 0.9)
    guide_width: float = 1.5
    boundary: Literal['filtered', 'point'] = 'filtered'
    normals: Literal['data', 'objects'] = 'data'
    surface_smoothing: float = 0.0
    step: float = 0.5
    reconstruction: Literal['trilinear', 'bspline'] = 'trilinear'
    ambient: float = 0.15
    diffuse: float = 0.85
    specular: float = 0.4
    exponent: float = 32.0
    jitter: bool = True
    early_termination: float = 0.99
    kernel: Literal['auto', 'fragment', 'compute'] = 'auto'

class Fan:
    """A fan between ghost (anchor 0) and selection (anchor 1), VolumeShop §6.3 "Fans": the screen-
        space bounding rectangles of their world boxes (the projected 8 corners each), outlined,
        joined by the two outer common tangents (the edges of the convex hull of both
        rectangles' corners that go from one rectangle to the other; none when one rectangle
        contains the other), with a translucent fill between them that leaves both rectangles'
        insides clear.

    Inputs:
        image (Image, required): the picture to draw over
        annotations (Annotations, required): anchor 0 = ghost, anchor 1 = selection, with world
            boxes as bounds
        camera (Camera, required): the view the picture was rendered with

    Outputs:
        image (Image): the picture with the drawing

    Parameters:
        color (RGBA in [0, 1]; default (0.2, 0.2, 0.2, 1.0)): outline and line colour
        width (float in [0.1, 32]; default 1.5): line width, pixels
        fill (RGBA in [0, 1]; default (0.3, 0.3, 0.3, 0.15)): colour between the rectangles
            (alpha 0: no fill)

    """

    kind = 'Fan'
    category = 'Annotation'
    color: Tuple[float, float, float, float] = (0.2, 0.2, 0.2, 1.0)
    width: float = 1.5
    fill: Tuple[float, float, float, float] = (0.3, 0.3, 0.3, 0.15)

class Fill:
    """An image of the frame size filled with one colour (e.g. paperColor of Fischer et al. 2005,
        §3.3.4).

    Outputs:
        image (Image): the filled frame

    Parameters:
        color (RGBA in [0, 1]; default (1.0, 1.0, 1.0, 1.0)): the colour that fills the whole
            frame (alpha = opacity)

    """

    kind = 'Fill'
    category = 'Compositing'
    color: Tuple[float, float, float, float] = (1.0, 1.0, 1.0, 1.0)

class GBuffer:
    """Rasterises a mesh into a G-buffer: window-space depth in [0, 1] (1 where empty) and the
        view-space unit normal with coverage in w. The first layer of depth peeling.

    Inputs:
        mesh (Mesh, required): the surface
        camera (Camera, required): the view

    Outputs:
        gbuffer (GBuffer): depth + normal of the nearest surface

    """

    kind = 'GBuffer'
    category = 'Rendering'

class Halftone:
    """Black-and-white hatching by procedural screening (Fischer et al. 2005, eq. 7–9): the pixel
        (x, y) is rotated by θ, (s, t) = ((x' mod n)/n, (y' mod n)/n), τ = c_cross·t if s ≤
        c_cross else (1 − c_cross)·s + c_cross, output 1 where intensity ≥ τ, else 0 (ink).
        Pattern in screen pixels.

    Inputs:
        intensity (Mask, required): intensity in [0, 1]

    Outputs:
        mask (Mask): 1 = paper, 0 = ink

    Parameters:
        theta (float in [-360, 360]; default 20.0): rotation of the pattern, degrees
        cell (float in [1, 256]; default 4.0): spacing of the hatching lines: the pattern's cell
            size n in pixels
        c_cross (float in [0, 1]; default 0.9): intensity below which cross-hatching appears

    """

    kind = 'Halftone'
    category = 'Illustration'
    theta: float = 20.0
    cell: float = 4.0
    c_cross: float = 0.9

class HatchStrokes:
    """Hatching strokes along principal curvature directions (Nagy et al. 2002; Yuan & Chen 2005
        §4.4). Seeds are the vertices of `seeds`, a mesh of the same surface (MarchingCubes of
        the volume at the iso value): a seed draws when it is visible in the G-buffer and its
        random number (a hash of its index, so strokes stay on the surface as the view moves) is
        below `density` × its darkness (1 − `tone`, or 1 − the headlight Lambert term of the
        G-buffer normal without a tone). Each stroke is integrated both ways from the seed with
        RK4 in image space through Curvature's direction field (the larger-|κ| principal
        direction, or the smaller), stopping where the surface ends, the depth jumps or the
        field turns; where the darkness exceeds `cross_hatching` a second stroke follows the
        other direction. Drawn anti-aliased with tapered ends into `mask`; `strokes` carries the
        polylines for SaveSvg.

    Inputs:
        curvature (Image, required): Curvature's output
        gbuffer (GBuffer, required): the surface (the G-buffer Curvature read)
        seeds (Mesh, required): candidate seeds: a mesh of the same surface (its vertices)
        tone (Mask, optional): brightness in [0, 1] (e.g. DiffuseIntensity); darker = more
            strokes

    Outputs:
        mask (Mask): stroke coverage
        strokes (Strokes): the strokes as polylines

    Parameters:
        density (float in [0, 1]; default 0.05): chance that a seed at full darkness draws a
            stroke
        length (float in [2, 256]; default 24.0): stroke length, pixels (at most 256 RK4 steps)
        width (float in [0.25, 8]; default 1.2): stroke width in the middle, pixels
        taper (float in [0, 0.5]; default 0.3): fraction of the length over which each end thins
            to nothing
        step (float in [0.25, 4]; default 1.0): integration step along a stroke (RK4), pixels
            (smaller follows curved fields more closely)
        direction (one of 'max_curvature', 'min_curvature'; default 'max_curvature'): the
            principal direction of the larger or of the smaller |κ|
        cross_hatching (float in [0, 1]; default 0.6): darkness above which a second stroke
            crosses the first (1 = never)
        depth_tolerance (float in [0, 1]; default 0.01): visibility and fold test: depth
            difference allowed, as a fraction of the seed mesh's bounding-box diagonal
        max_strokes (int in [1, 1e+06]; default 20000): most strokes drawn
        seed (int in [0, 1.04858e+06]; default 0): varies the random numbers

    """

    kind = 'HatchStrokes'
    category = 'Volume'
    density: float = 0.05
    length: float = 24.0
    width: float = 1.2
    taper: float = 0.3
    step: float = 1.0
    direction: Literal['max_curvature', 'min_curvature'] = 'max_curvature'
    cross_hatching: float = 0.6
    depth_tolerance: float = 0.01
    max_strokes: int = 20000
    seed: int = 0

class ImportanceCompositing:
    """Importance compositing (Viola et al., importance-driven feature enhancement): per pixel, the
        focus object's footprint (its first and last hit along the ray), the countersink depth
        e_i = e_max − d_i·s_c (eq. 1; d_i the distance to the footprint by jump flooding, e_max
        the footprint's deepest last hit) and the importance sum Σ I of the objects the ray
        meets, their footprints dilated and averaged over `transition` pixels (image-space AImC,
        eq. 2). Feed it to TwoLevelRaycast's `importance` input with the same camera. Methods:
        mimp (maximum importance projection, §IV.A: per ray only the most important object it
        meets behind the countersink is drawn, so only the focus in its footprint, and the
        context cut away in front of the countersink), cutaway (the same cut, but every object
        behind it drawn as usual), aimc_image / aimc_object (average importance compositing:
        levels of sparseness S_o = I_o / Σ I for every sample, or for the context in front of
        the countersink only), vpimc (visibility preserving: the occluding context's opacity
        scaled by S_o / α_avg, eq. 3). Importance comes from ObjectStyles' `importance=`.

    Inputs:
        labels (Labels, required): object ids on the volume's grid
        styles (ObjectStyles, required): the object table: drawn objects and their importance
        camera (Camera, required): the view

    Outputs:
        importance (Importance): footprint, countersink and importance sums of this view

    Parameters:
        method (one of 'mimp', 'cutaway', 'aimc_image', 'aimc_object', 'vpimc'; default 'mimp'):
            how importance decides what is drawn: mimp (per ray only its most important object,
            the focus's countersink cut away), cutaway (only the countersink cut away, the other
            objects drawn as usual), aimc_image, aimc_object (levels of sparseness I_o / Σ I) or
            vpimc (the occluders' opacity kept constant)
        focus (int in [0, 65535]; default 0): the focus object's id (0: the drawn object of
            highest importance)
        countersink (one of 'conical', 'cylindrical'; default 'conical'): conical (eq. 1) or
            cylindrical (the footprint swept along the rays)
        slope (float in [0.05, 20]; default 1.0): the cut-away's slope: how much deeper it gets
            per unit of distance from the focus on screen, a cone around the focus (s_c of eq.
            1; both in world units)
        transition (float in [0, 64]; default 0.0): image-space AImC: dilate and average the
            footprints over this radius (pixels) for smooth transitions between levels of
            sparseness
        step (float in [0.05, 8]; default 0.5): sample distance along the rays in voxels (of the
            smallest spacing)
        boundary (one of 'filtered', 'point'; default 'filtered'): object membership, as
            TwoLevelRaycast's

    """

    kind = 'ImportanceCompositing'
    category = 'Volume'
    method: Literal['mimp', 'cutaway', 'aimc_image', 'aimc_object', 'vpimc'] = 'mimp'
    focus: int = 0
    countersink: Literal['conical', 'cylindrical'] = 'conical'
    slope: float = 1.0
    transition: float = 0.0
    step: float = 0.5
    boundary: Literal['filtered', 'point'] = 'filtered'

class IsoSurfaceRaycast:
    """First hit of an iso value along each ray (refined linearly between samples) as a G-buffer:
        window depth and the view-space normal −∇f/|∇f|. Feeds Silhouette, DiffuseIntensity,
        Halftone and the compositing nodes with no mesh at all.

    Inputs:
        volume (Volume, required): the scalar field
        camera (Camera, required): the view

    Outputs:
        gbuffer (GBuffer): depth + normal of the iso-surface

    Parameters:
        iso (float in [-1e+12, 1e+12], or data-relative text; default 0.0): iso value, in the
            volume's units, or relative to its values: "percentile(60)", "range(0.3)", "otsu"
        step (float in [0.05, 8]; default 0.25): sample distance in voxels
        reconstruction (one of 'trilinear', 'bspline'; default 'trilinear'): reconstruction
            between voxels: trilinear, or the tricubic B-spline's values and normals (a smooth
            surface where trilinear shows the voxel lattice)

    """

    kind = 'IsoSurfaceRaycast'
    category = 'Volume'
    iso: Union[float, str] = 0.0
    step: float = 0.25
    reconstruction: Literal['trilinear', 'bspline'] = 'trilinear'

class LabelFile:
    """Reads a label map (object id per voxel, whole numbers 0–65535, 0 = background) from any
        volume format VolumeFile reads, placed in the world the same way. Object names come from
        `names` (a CSV/TSV table `id,name` or an ITK-SNAP label description file) or from the
        file itself (3D Slicer's segment names in a .seg.nrrd header, an OME-Zarr label image's
        properties); objects without a name are called "object N".

    Outputs:
        labels (Labels): object ids on the volume's grid, with names

    Parameters:
        path (path; default ''): the label map file, or a DICOM folder
        array (text; default ''): the named data array to read (VTK; OME-Zarr: a label image of
            labels/); empty: the active scalars (OME-Zarr: the first label image)
        names (path; default ''): object names: CSV `id,name` or ITK-SNAP label file (optional)

    """

    kind = 'LabelFile'
    category = 'Data'
    path: str = ''
    array: str = ''
    names: str = ''

class LabelMask:
    """1 where a voxel's label is in `labels`, else 0, then blurred by a Gaussian of `smooth`
        voxels so that MarchingCubes at iso 0.5 gives a smooth surface instead of voxel stairs.
        The labels come from `objects` (a segmented volume: LabelFile, LabelsFromThreshold, …)
        or, as in graphs made before labels had their own type, from `volume` (values rounded to
        integers); connect one of the two. Labels not present are an error that lists the labels
        the volume has.

    Inputs:
        objects (Labels, optional): a segmented volume (e.g. LabelFile of the frog)
        volume (Volume, optional): or a label volume read as numbers

    Outputs:
        mask (Volume): the selected objects, values in [0, 1]

    Parameters:
        labels (text; default '1'): labels to select: "3", "3, 7", "1-29", "2-4, 9"
        smooth (float in [0, 8]; default 1.0): Gaussian sigma in voxels (0 = hard mask)

    """

    kind = 'LabelMask'
    category = 'Geometry'
    labels: str = '1'
    smooth: float = 1.0

class LabelsFromMaps:
    """Object ids from probability maps on one grid (e.g. the MRI's grey- and white-matter maps):
        each voxel gets the id of the map with the largest value (a = 1, b = 2, c = 3) if that
        value is at least `floor`, else background.

    Inputs:
        a (Volume, required): map of object 1
        b (Volume, optional): map of object 2
        c (Volume, optional): map of object 3

    Outputs:
        labels (Labels): object ids on the volume's grid, with names

    Parameters:
        floor (float in [-1e+12, 1e+12], or data-relative text; default 128.0): smallest value
            that makes a voxel part of an object (data units of map a, or "percentile(P)",
            "range(F)", "otsu" of map a)
        names (text; default ''): object names, "a name, b name, …" (optional)

    """

    kind = 'LabelsFromMaps'
    category = 'Data'
    floor: Union[float, str] = 128.0
    names: str = ''

class LabelsFromThreshold:
    """Object ids by value intervals: a voxel whose value lies in [lo, hi) of an interval gets its
        id (the first matching interval wins), others background.

    Inputs:
        volume (Volume, required): the scalar field

    Outputs:
        labels (Labels): object ids on the volume's grid, with names

    Parameters:
        intervals (text; default '80..140: 1; 140..256: 2'): "lo..hi: id; …" in data units;
            bounds may be "percentile(P)", "range(F)" or "otsu" of the volume

    """

    kind = 'LabelsFromThreshold'
    category = 'Data'
    intervals: str = '80..140: 1; 140..256: 2'

class Light:
    """Directional light. In view space the light follows the camera (the usual choice for
        illustration); in world space it stays fixed to the data.

    Outputs:
        light (Light): the light

    Parameters:
        direction ((x, y, z); default (0.4, 0.5, 1.0)): vector towards the light (normalised)
        space (one of 'view', 'world'; default 'view'): space the direction is given in
        color (RGBA in [0, 1]; default (1.0, 1.0, 1.0, 1.0)): light colour (alpha unused)
        intensity (float in [0, 100]; default 1.0): scale of the diffuse and specular terms
        ambient (float in [0, 1]; default 0.15): ambient term added everywhere

    """

    kind = 'Light'
    category = 'Scene'
    direction: Tuple[float, float, float] = (0.4, 0.5, 1.0)
    space: Literal['view', 'world'] = 'view'
    color: Tuple[float, float, float, float] = (1.0, 1.0, 1.0, 1.0)
    intensity: float = 1.0
    ambient: float = 0.15

class MarchingCubes:
    """Lorensen–Cline marching cubes on the CPU, parallel over slabs. Vertices are shared between
        cells; normals are the negated, normalised volume gradient (pointing towards lower
        values).

    Inputs:
        volume (Volume, required): the scalar field

    Outputs:
        mesh (Mesh): the iso-surface in world units

    Parameters:
        iso (float in [-1e+12, 1e+12], or data-relative text; default 0.0): iso value, in the
            volume's units, or relative to its values: "percentile(60)", "range(0.3)", "otsu"

    """

    kind = 'MarchingCubes'
    category = 'Geometry'
    iso: Union[float, str] = 0.0

class MaskCombine:
    """Combines masks a and b per pixel: and = a·b, or = max(a, b), min, add and subtract (clamped
        to [0, 1]), a_not_b = a·(1 − b). E.g. eq. 10 of Fischer et al. 2005 is I_S a_not_b
        (silhouette_P2 and depth test).

    Inputs:
        a (Mask, required): first mask
        b (Mask, required): second mask

    Outputs:
        mask (Mask): the result

    Parameters:
        operation (one of 'and', 'or', 'min', 'add', 'subtract', 'a_not_b'; default 'and'): how
            the two masks combine per pixel (and, or, min, add, subtract, a_not_b)

    """

    kind = 'MaskCombine'
    category = 'Compositing'
    operation: Literal['and', 'or', 'min', 'add', 'subtract', 'a_not_b'] = 'and'

class MeshFile:
    """Reads a triangle mesh from .obj, .ply (ASCII or binary) or .stl; polygons are triangulated,
        missing normals are computed. Relative paths are relative to the graph file's folder.

    Outputs:
        mesh (Mesh): the mesh

    Parameters:
        path (path; default ''): the mesh file

    """

    kind = 'MeshFile'
    category = 'Data'
    path: str = ''

class MeshTransform:
    """Applies p' = R·(s ⊙ p) + t to every vertex (rotation R from Euler angles x, then y, then z,
        in degrees) and transforms normals accordingly; `flip_normals` reverses normals and
        winding.

    Inputs:
        mesh (Mesh, required): the mesh to transform

    Outputs:
        mesh (Mesh): the transformed mesh

    Parameters:
        scale ((x, y, z); default (1.0, 1.0, 1.0)): scale per axis (non-zero)
        rotate ((x, y, z); default (0.0, 0.0, 0.0)): Euler angles about x, y, z in degrees
        translate ((x, y, z); default (0.0, 0.0, 0.0)): offset, world units
        flip_normals (bool; default False): point normals the other way

    """

    kind = 'MeshTransform'
    category = 'Geometry'
    scale: Tuple[float, float, float] = (1.0, 1.0, 1.0)
    rotate: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    translate: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    flip_normals: bool = False

class MixByMask:
    """Per pixel mix(base, over, m) = (1 − m)·base + m·over with m the mask clamped to [0, 1];
        `over` is the `over` image if connected, else `color`. The mix() lines of Fischer et al.
        2005, §3.3.4.

    Inputs:
        base (Image, required): the image underneath
        mask (Mask, required): how much of `over` to take
        over (Image, optional): the image mixed in (else `color`)

    Outputs:
        image (Image): the mixed image

    Parameters:
        color (RGBA in [0, 1]; default (0.0, 0.0, 0.0, 1.0)): colour mixed in when `over` is not
            connected

    """

    kind = 'MixByMask'
    category = 'Compositing'
    color: Tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)

class MultiplyByMask:
    """Colour × m (or × (1 − m) with `invert`), alpha kept: the `pixelColor *= …` lines of Fischer
        et al. 2005, §3.3.4 (black silhouettes, black hatching).

    Inputs:
        image (Image, required): the image
        mask (Mask, required): the factor, clamped to [0, 1]

    Outputs:
        image (Image): the darkened image

    Parameters:
        invert (bool; default False): multiply by 1 − mask instead

    """

    kind = 'MultiplyByMask'
    category = 'Compositing'
    invert: bool = False

class ObjectStyles:
    """The object table of a segmented volume for TwoLevelRaycast: one row per object, "ID: mode
        compositing [tf=…] [iso=…] [importance=…] [off]; …". Rendering modes: dvr, shaded_dvr,
        tone (cool-to-warm by N·L), contours (gradient magnitude × (1 − |N·V|)^8), mip, iso.
        Local compositing: over, mip, iso (first hit of iso=…), sum. tf=PRESET uses a
        TransferFunction1D preset over the volume's range, tf=1…3 the inputs tf1–tf3; default:
        the `tf` input, else the grey ramp. Objects not listed are not drawn. Names come from
        the labels.

    Inputs:
        labels (Labels, required): the segmented volume (names, ids)
        volume (Volume, optional): value range for presets
        tf (TransferFunction, optional): default transfer function
        tf1 (TransferFunction, optional): transfer function tf=1
        tf2 (TransferFunction, optional): transfer function tf=2
        tf3 (TransferFunction, optional): transfer function tf=3

    Outputs:
        styles (ObjectStyles): per-object transfer function, rendering and compositing mode

    Parameters:
        objects (text; default '1: shaded_dvr over'): "ID: mode compositing [tf=…] [iso=…]
            [importance=…] [off]; …"

    """

    kind = 'ObjectStyles'
    category = 'Volume'
    objects: str = '1: shaded_dvr over'

class Over:
    """front + (1 − α_front)·back per pixel, on premultiplied colours (Porter–Duff over).

    Inputs:
        front (Image, required): the image on top
        back (Image, required): the image underneath

    Outputs:
        image (Image): the composite

    """

    kind = 'Over'
    category = 'Compositing'

class PaintLabels:
    """Volume painting (VolumeShop §6.1): object ids painted onto a volume's grid with a spherical
        brush — every voxel whose centre lies within a dab's radius (world units) gets its id,
        in the order of the dabs — on top of `labels` where connected, else on an empty map of
        `volume`'s grid. In the editor, select the node and turn on the viewport's paint tool: a
        drag paints where the pointer meets the first visible surface.

    Inputs:
        volume (Volume, optional): the grid to paint on when no labels are connected
        labels (Labels, optional): a segmentation to paint over (its grid is used)

    Outputs:
        labels (Labels): object ids on the volume's grid, with names

    Parameters:
        strokes (text; default ''): the brush dabs, in order: "x y z r id; …" — a ball of radius
            r (world units, mm) around (x, y, z) filled with object id (0 erases); the editor's
            paint tool writes them
        radius (float in [0.1, 500]; default 4.0): the radius (world units, mm) of the dabs the
            editor's paint tool adds
        id (int in [0, 65535]; default 1): the object id the editor's paint tool paints (0: the
            tool erases)
        name (text; default 'selection'): the name of painted objects the labels do not name yet

    """

    kind = 'PaintLabels'
    category = 'Data'
    strokes: str = ''
    radius: float = 4.0
    id: int = 1
    name: str = 'selection'

class ProceduralVectorField:
    """Analytic vector fields on a resolution³ grid over [-1, 1]³ (the grid of ProceduralVolume):
        convection, the velocity of Rayleigh–Bénard convection rolls (U = (∂ψ/∂y, −∂ψ/∂x, 0) of
        ψ = a(z)·sin(2π(x + 1))·sin(π(y + 1)/2), four rolls across x, divergence-free), the flow
        of ProceduralVolume's convection temperature; abc, the Arnold–Beltrami–Childress flow U
        = (A sin πz + C cos πy, B sin πx + A cos πz, C sin πy + B cos πx), a Beltrami field (∇×U
        = π·U).

    Outputs:
        field (VectorField): the generated vector field

    Parameters:
        shape (one of 'convection', 'abc'; default 'convection'): which field: convection (the
            velocity of Rayleigh–Bénard rolls, ProceduralVolume convection's flow) or abc (the
            Arnold–Beltrami–Childress flow, whose curl is π·U)
        resolution (int in [4, 512]; default 96): voxels along each axis
        abc ((x, y, z); default (1.0, 0.8, 0.6)): abc: the coefficients A, B, C

    """

    kind = 'ProceduralVectorField'
    category = 'Data'
    shape: Literal['convection', 'abc'] = 'convection'
    resolution: int = 96
    abc: Tuple[float, float, float] = (1.0, 0.8, 0.6)

class ProceduralVolume:
    """Analytic distance fields on a resolution³ grid over [-1, 1]³ (positive inside, iso 0 is the
        surface): three nested spherical shells (centre radii 0.8, 0.5, 0.2, half-thickness
        0.05), a sphere, a torus in the xy plane, an engine-like block (a box with two vertical
        bores and a horizontal one) and the two pistons that sit in its bores; and one density
        field, not a distance: plume, the air around a hot plume rising along +y from a small
        heated ball (1 in still air, lower where it is hot), a subject for Schlieren; and
        convection, the temperature of Rayleigh–Bénard convection rolls between a hot floor (y =
        −1, 1) and a cold lid (y = 1, 0), whose velocity ProceduralVectorField's convection
        gives (Svakhine et al. 2005 Fig. 4's subject).

    Outputs:
        volume (Volume): the generated scalar field

    Parameters:
        shape (one of 'shells', 'sphere', 'torus', 'engine_block', 'pistons', 'plume',
            'convection'; default 'shells'): which field to generate
        resolution (int in [4, 512]; default 96): voxels along each axis
        radius (float in [0.01, 1]; default 0.7): sphere radius, or torus major radius
        minor_radius (float in [0.01, 1]; default 0.25): torus tube radius

    """

    kind = 'ProceduralVolume'
    category = 'Data'
    shape: Literal['shells', 'sphere', 'torus', 'engine_block', 'pistons', 'plume', 'convection'] = 'shells'
    resolution: int = 96
    radius: float = 0.7
    minor_radius: float = 0.25

class Raycast:
    """GPU ray casting of a volume. Front-to-back compositing (eq. 1 of the context-preserving
        paper) with opacity correction for the sample distance, early ray termination, jittered
        start, trilinear sampling with gradients by central differences in voxel space
        (respecting spacing) or tricubic B-spline values and gradients (Hadwiger §1.3);
        perspective or orthographic. Modes: dvr, mip (maximum intensity), iso (first hit,
        refined linearly). Shading: none, phong (eq. 3), lighting (VolumeShop lighting transfer
        function, eq. 8), context_preserving (eq. 5; κt = 0 is plain DVR). A
        StyleTransferFunction on `tf` switches to style shading (Bruckner & Gröller 2007: lit
        spheres, style contours eq. 1, illustrative transparency eq. 2). Strokes (a mask with
        the depth of its surface) are embedded as Yuan & Chen 2005 §5 do: rays stop at a stroke
        and its colour lies under what is in front; `rho` scales every sample's opacity (DVR).
        Svakhine et al. 2005's Table 1 enhancements of each sample's opacity (DVR): boundary
        enhancement |∇P|^n, silhouette enhancement (1 − |∇P̂·V|)^n and the banding widget ((1 +
        sin(o·π·m)) / 2)^n, measuring the rendered field, a second field's gradient (`second`)
        or a vector field U (`vector`: |U|^n, (1 − |Û·V|)^n); a 2-D transfer function over value
        × gradient magnitude, Laplacian or the second field (docs/enhancement.md).

    Inputs:
        volume (Volume, required): the scalar field
        camera (Camera, required): the view
        tf (TransferFunction, required): colour/opacity or style transfer function
        light (Light, optional): the light (default: a headlight)
        labels (Volume, optional): object labels on the same grid (per-label style rows, §4.2)
        second (Volume, optional): a second scalar field on the same grid (Svakhine et al. 2005
            §3.2–3.3): a 2-D transfer function's second_field axis, or enhancement_field second
        vector (VectorField, optional): a vector field on the same grid, for enhancement_field
            vector (Table 1's U)
        strokes (Mask, optional): lines or strokes to embed (Yuan & Chen §5), with
            `strokes_depth`
        strokes_depth (GBuffer, optional): the depth of the surface the strokes were drawn on

    Outputs:
        image (Image): premultiplied colour
        gbuffer (GBuffer): depth and normal where opacity first reaches `hit_opacity`

    Parameters:
        mode (one of 'dvr', 'mip', 'iso'; default 'dvr'): how the samples along a ray make the
            pixel: dvr (composited front to back), mip (the largest value) or iso (the first
            surface at the iso value)
        iso (float in [-1e+12, 1e+12], or data-relative text; default 0.5): iso value for mode
            iso (data units, or "percentile(P)", "range(F)", "otsu")
        step (float in [0.05, 8]; default 0.5): sample distance in voxels (of the smallest
            spacing)
        shading (one of 'none', 'phong', 'lighting', 'context_preserving'; default 'phong'):
            shading (style TFs always use their styles)
        lighting_model (one of 'phong', 'phong_contour', 'cartoon', 'metal'; default
            'phong_contour'): lighting transfer function for `lighting`
        ambient (float in [0, 1]; default 0.15): ambient light: brightness of every shaded
            sample, lit or not (c_a of eq. 3)
        diffuse (float in [0, 4]; default 0.85): diffuse light: brightness where the surface
            faces the light (c_d of eq. 3)
        specular (float in [0, 4]; default 0.4): specular light: strength of the highlight (c_s
            of eq. 3)
        exponent (float in [1, 512]; default 32.0): shininess: higher makes the highlight
            smaller and sharper (c_e of eq. 3)
        kappa_t (float in [0, 1000]; default 0.0): how deep to look inside: more shows more of
            the interior through weakly lit, flat regions (κt of eq. 5; 0 = plain DVR)
        kappa_s (float in [0, 100]; default 0.5): how sharply the view into the interior starts
            (κs of eq. 5)
        fast_exponent (bool; default False): context_preserving: Schlick's rational
            approximation of eq. 5's two exponentiations (the paper's §6, eq. 6–7) instead of
            pow
        contours (bool; default True): draw dark contour lines where the surface turns away from
            the viewer (§3.3)
        thickness (float in [0, 1000]; default 2.0): contour thickness T, world units
        transparency (bool; default True): see-through styles: a style's opacity falls where it
            faces the viewer, so inner structures show (eq. 2)
        mip_bias (float in [-4, 8]; default 0.0): bias of the style mip level
        jitter (bool; default True): jitter the first sample per pixel (hides wood-grain
            artefacts)
        reconstruction (one of 'trilinear', 'bspline'; default 'trilinear'): reconstruction
            between voxels: trilinear (fast), or the tricubic B-spline's values and gradients
            (no voxel lattice on sharp boundaries; about 4× the fetches)
        preintegrated (bool; default False): DVR: a pre-integrated transfer function (Engel et
            al. 2001) — each sample composites the whole segment from the previous one, so sharp
            opacity ramps between samples are not missed (a 1-D colour transfer function,
            shading none or phong)
        boundary_enhancement (float in [0, 16]; default 0.0): boundary enhancement n (Svakhine
            et al. 2005 §3.2, Table 1: o_e = o_o · |∇P|^n): samples on strong boundaries keep
            their opacity, flat regions fade; |∇P| is the gradient magnitude divided by the
            volume's largest, so 1 on the sharpest boundary; larger n keeps only sharper
            boundaries (0 = off; DVR)
        silhouette_enhancement (float in [0, 16]; default 0.0): silhouette enhancement n
            (Svakhine et al. 2005 §3.2, Table 1: o_e = o_o · (1 − |∇P̂·V|)^n): samples whose
            boundary faces the viewer fade, those seen edge-on (the outlines) keep their
            opacity; larger n gives thinner outlines (0 = off; DVR)
        banding (float in [0, 64]; default 0.0): banding widget period m (Svakhine et al. 2005
            §3.3, Table 1: o_e = ((1 + sin(o_o·π·m)) / 2)^n): the transfer function's opacity is
            mapped through a sine, so the volume shows as alternating opaque and clear contour
            shells; more m, more and thinner bands (0 = off; DVR, where the transfer function is
            not transparent)
        banding_power (float in [0.05, 16]; default 1.0): banding widget power n (Svakhine et
            al. 2005 §3.3, Table 1): above 1 makes the bands thinner and sharper, below 1 softer
            and wider
        enhancement_field (one of 'rendered', 'second', 'vector'; default 'rendered'): what
            boundary and silhouette enhancement measure (Svakhine et al. 2005 §3.2, Table 1):
            rendered (∇P of the rendered field), second (the gradient of the field on the
            `second` input, e.g. temperature while density is rendered) or vector (the vector
            field U on the `vector` input itself: |U|^n, divided by the largest |U|, and (1 −
            |Û·V|)^n, so flow seen side-on keeps its opacity)
        rho (float in [0, 1]; default 1.0): global alpha ρ (Yuan & Chen §5): every sample's
            opacity × ρ (DVR), so embedded strokes show through
        stroke_color (RGBA in [0, 1]; default (0.0, 0.0, 0.0, 1.0)): colour of embedded strokes
        early_termination (float in [0.5, 1]; default 0.99): stop a ray at this opacity (1 =
            never)
        hit_opacity (float in [0.001, 1]; default 0.5): accumulated opacity that defines the
            G-buffer depth
        skip_empty (bool; default True): jump over 8³-voxel bricks that cannot change the
            picture (DVR: values the transfer function makes transparent; iso: all below the iso
            value) — same picture, fewer samples. MIP never skips: its plain loop is faster
        kernel (one of 'auto', 'fragment', 'compute'; default 'auto'): GPU path: fragment shader
            or compute kernel (same picture); auto picks the faster one for the adapter

    """

    kind = 'Raycast'
    category = 'Volume'
    mode: Literal['dvr', 'mip', 'iso'] = 'dvr'
    iso: Union[float, str] = 0.5
    step: float = 0.5
    shading: Literal['none', 'phong', 'lighting', 'context_preserving'] = 'phong'
    lighting_model: Literal['phong', 'phong_contour', 'cartoon', 'metal'] = 'phong_contour'
    ambient: float = 0.15
    diffuse: float = 0.85
    specular: float = 0.4
    exponent: float = 32.0
    kappa_t: float = 0.0
    kappa_s: float = 0.5
    fast_exponent: bool = False
    contours: bool = True
    thickness: float = 2.0
    transparency: bool = True
    mip_bias: float = 0.0
    jitter: bool = True
    reconstruction: Literal['trilinear', 'bspline'] = 'trilinear'
    preintegrated: bool = False
    boundary_enhancement: float = 0.0
    silhouette_enhancement: float = 0.0
    banding: float = 0.0
    banding_power: float = 1.0
    enhancement_field: Literal['rendered', 'second', 'vector'] = 'rendered'
    rho: float = 1.0
    stroke_color: Tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)
    early_termination: float = 0.99
    hit_opacity: float = 0.5
    skip_empty: bool = True
    kernel: Literal['auto', 'fragment', 'compute'] = 'auto'

class RidgeValley:
    """Ridge and valley lines of an iso-surface (the tutorial's §1, Fig. 12) from Curvature's
        image: ridges where κ1 > threshold and κ1 is a maximum along its principal direction,
        valleys where κ2 < −threshold and κ2 is a minimum along the second principal direction
        (the extremality test: a parabola through the curvature one pixel before, at and after,
        along the direction on screen, with a clear maximum: constant curvature draws no line).
        Lines `thickness` pixels wide, as masks.

    Inputs:
        curvature (Image, required): Curvature's output

    Outputs:
        ridges (Mask): 1 on ridge lines
        valleys (Mask): 1 on valley lines

    Parameters:
        threshold (float in [0, 1e+06]; default 1.0): smallest |κ| of a line, world units⁻¹
        thickness (float in [0.5, 3]; default 1.5): line width, pixels (up to 3)

    """

    kind = 'RidgeValley'
    category = 'Volume'
    threshold: float = 1.0
    thickness: float = 1.5

class SaveImage:
    """Writes its image to a PNG file (8-bit RGBA, straight alpha). `hatchery render -o` replaces
        the path. Relative paths are relative to the graph file's folder.

    Inputs:
        image (Image, required): the picture to write

    Parameters:
        path (path; default 'hatchery.png'): the PNG file to write

    """

    kind = 'SaveImage'
    category = 'Output'
    path: str = 'hatchery.png'

class SaveSvg:
    """Writes an SVG figure whose Inkscape layers are: the picture (the `image` as an embedded
        PNG), lines (each `lines` mask's region above 0.5, traced by marching squares and
        simplified, as a filled path in its own colour, or its outlines as strokes; a lines
        input with `shown` off goes to a hidden layer), hatching `strokes` as their tapered
        outlines in a layer of their own, leader lines, arrows, and labels as <text> (from laid-
        out `annotations`). Open it in Inkscape or Illustrator to edit lines and text. `hatchery
        render -o x.svg` replaces the path. Relative paths are relative to the graph file's
        folder.

    Inputs:
        image (Image, optional): the picture
        annotations (Annotations, optional): labels placed by AnnotationLayout
        lines1 (Mask, optional): a line or silhouette mask
        lines2 (Mask, optional): another, with its own stroke
        lines3 (Mask, optional): a third
        strokes (Strokes, optional): hatching strokes (HatchStrokes): one open polyline each,
            round caps
        selection (Annotations, optional): ghost (anchor 0) and selection (anchor 1), e.g.
            SelectionRender's: arrow, fan and boxes as paths
        camera (Camera, optional): the view of the picture (for `selection`)

    Parameters:
        path (path; default 'figure.svg'): the SVG file to write
        embed_picture (bool; default True): embed the `image` as a PNG layer under the lines
        lines_as (one of 'shapes', 'outlines'; default 'shapes'): traced masks as filled shapes
            (the mask's exact extent, one path per input) or as stroked outlines (one path per
            contour)
        simplify (float in [0, 10]; default 0.5): Douglas–Peucker tolerance of the traced lines,
            pixels
        text_color (RGBA in [0, 1]; default (0.0, 0.0, 0.0, 1.0)): label text colour
        halo_color (RGBA in [0, 1]; default (1.0, 1.0, 1.0, 1.0)): label halo colour
        halo_width (float in [0, 20]; default 2.0): label halo width, pixels (0: none)
        leader_color (RGBA in [0, 1]; default (0.2, 0.2, 0.2, 1.0)): leader line colour
        leader_width (float in [0.1, 20]; default 1.0): leader line width, pixels
        arrow (bool; default True): with `selection`: the arrow ghost → selection
        fan (bool; default False): with `selection`: the fan between their rectangles
        boxes (one of 'none', 'ghost', 'selection', 'both'; default 'none'): with `selection`:
            whose world box to draw
        convention_color (RGBA in [0, 1]; default (0.8, 0.1, 0.1, 1.0)): colour of the arrow,
            fan and boxes
        convention_width (float in [0.1, 32]; default 2.0): line width of the arrow, fan and
            boxes, pixels
        curvature (float in [0, 4]; default 0.5): the arrow's bend per pixel of depth difference
            (as Arrow's)
        strokes_color (RGBA in [0, 1]; default (0.0, 0.0, 0.0, 1.0)): colour of the hatching
            `strokes`
        color1 (RGBA in [0, 1]; default (0.0, 0.0, 0.0, 1.0)): stroke colour of the lines traced
            from this input
        shown1 (bool; default True): these lines visible over the picture; off: in the hidden
            'Covered lines' layer, for lines the picture draws under its surfaces (hidden edges
            under hatching), so that the SVG shows what the PNG does
        width1 (float in [0.1, 50]; default 1.5): stroke width of those lines, pixels
        color2 (RGBA in [0, 1]; default (0.0, 0.0, 0.0, 1.0)): stroke colour of the lines traced
            from this input
        shown2 (bool; default True): these lines visible over the picture; off: in the hidden
            'Covered lines' layer, for lines the picture draws under its surfaces (hidden edges
            under hatching), so that the SVG shows what the PNG does
        width2 (float in [0.1, 50]; default 1.5): stroke width of those lines, pixels
        color3 (RGBA in [0, 1]; default (0.0, 0.0, 0.0, 1.0)): stroke colour of the lines traced
            from this input
        shown3 (bool; default True): these lines visible over the picture; off: in the hidden
            'Covered lines' layer, for lines the picture draws under its surfaces (hidden edges
            under hatching), so that the SVG shows what the PNG does
        width3 (float in [0.1, 50]; default 1.5): stroke width of those lines, pixels

    """

    kind = 'SaveSvg'
    category = 'Output'
    path: str = 'figure.svg'
    embed_picture: bool = True
    lines_as: Literal['shapes', 'outlines'] = 'shapes'
    simplify: float = 0.5
    text_color: Tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)
    halo_color: Tuple[float, float, float, float] = (1.0, 1.0, 1.0, 1.0)
    halo_width: float = 2.0
    leader_color: Tuple[float, float, float, float] = (0.2, 0.2, 0.2, 1.0)
    leader_width: float = 1.0
    arrow: bool = True
    fan: bool = False
    boxes: Literal['none', 'ghost', 'selection', 'both'] = 'none'
    convention_color: Tuple[float, float, float, float] = (0.8, 0.1, 0.1, 1.0)
    convention_width: float = 2.0
    curvature: float = 0.5
    strokes_color: Tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)
    color1: Tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)
    shown1: bool = True
    width1: float = 1.5
    color2: Tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)
    shown2: bool = True
    width2: float = 1.5
    color3: Tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)
    shown3: bool = True
    width3: float = 1.5

class Schlieren:
    """Simulated Schlieren photographs and shadowgraphs of a density volume (Svakhine, Ebert et al.
        2005, §4, eq. 1–5). Each ray integrates over the volume the density gradient across the
        ray along the picture's x and y axes, the light's deflection ε = (∫∂ρ/∂x dz, ∫∂ρ/∂y dz)
        (eq. 1), and the Laplacian across the ray, L = ∫(∂²ρ/∂x² + ∂²ρ/∂y²) dz (eq. 2), by
        central differences at ±`difference` voxels; ε is measured in value ranges of the
        volume, L in value ranges per voxel. Intensity: s(1 + g ε·k)/2 with k the knife edge's
        normal (eq. 3), s g|ε| (eq. 4), a colour wheel (hue the direction of ε, saturation
        g|ε|), or s(1 + g L)/2 (eq. 5), clamped to [0, 1]; g is `gain`, s `brightness`.

    Inputs:
        volume (Volume, required): the density (refractive index) field
        camera (Camera, required): the view (the light runs along its rays)

    Outputs:
        image (Image): the photograph (opaque)
        deflection (Image): data, not colour: (ε_x, ε_y, L, 1) per pixel before the gain (x
            right, y up)

    Parameters:
        mode (one of 'schlieren', 'schlieren_circular', 'schlieren_color', 'shadowgraph',
            'shadowgraph_abs'; default 'schlieren'): what the picture shows (§4): schlieren is
            the knife-edge photograph, grey plus or minus the deflection along the knife's
            normal (eq. 3); schlieren_circular the deflection's length through a circular cutoff
            (eq. 4); schlieren_color its direction as hue and length as saturation (colour
            Schlieren); shadowgraph grey plus or minus the Laplacian across the rays (eq. 2, 5);
            shadowgraph_abs its absolute value (Fig. 13e)
        knife_angle (float in [-360, 360]; default 0.0): direction of the knife edge's normal k
            in the picture, degrees counter-clockwise from the picture's right: 0 brightens
            where the density grows to the right (a vertical knife edge), 90 where it grows
            upwards (eq. 3, §4)
        gain (float in [-10000, 10000]; default 1.0): sensitivity, the constant of eq. 1: how
            strongly a deflection of one value range of the volume (one voxel for the
            shadowgraph) shows (§4); negative turns the sign round (a real shadowgraph darkens
            where eq. 5 brightens: gain below 0)
        brightness (float in [0, 4]; default 1.0): the coefficient s of eq. 3–5 that scales the
            whole picture: 1 gives a mid-grey background (§4)
        threshold (float in [0, 1]; default 0.0): samples whose density gradient across the ray
            is below this (per voxel, as a fraction of the value range) add nothing: removes
            weak gradients (§4, Fig. 10b)
        step (float in [0.05, 8]; default 0.5): distance between samples along the ray, voxels
            (of the smallest spacing)
        difference (float in [0.25, 8]; default 1.0): spacing of the central differences across
            the ray, voxels (of the smallest spacing): larger smooths the derivatives
        reconstruction (one of 'trilinear', 'bspline'; default 'trilinear'): reconstruction of
            the data between voxels: trilinear, or the tricubic B-spline (smoother derivatives,
            Hadwiger §1.3)
        kernel (one of 'auto', 'fragment', 'compute'; default 'auto'): GPU path: fragment shader
            or compute kernel (same picture)

    """

    kind = 'Schlieren'
    category = 'Volume'
    mode: Literal['schlieren', 'schlieren_circular', 'schlieren_color', 'shadowgraph', 'shadowgraph_abs'] = 'schlieren'
    knife_angle: float = 0.0
    gain: float = 1.0
    brightness: float = 1.0
    threshold: float = 0.0
    step: float = 0.5
    difference: float = 1.0
    reconstruction: Literal['trilinear', 'bspline'] = 'trilinear'
    kernel: Literal['auto', 'fragment', 'compute'] = 'auto'

class SecondaryGeometry:
    """Renders secondary geometry S with its own depth test. Intensity I_S = max(n · lightDir, 0)
        (eq. 1) times 1 in front of layer 1, α between layers 1 and 2, β behind layer 2 (eq. 2,
        Fischer et al. 2005 §3.2). Outputs the intensity (0 where no S) and S's own G-buffer
        (its depth for eq. 10).

    Inputs:
        mesh (Mesh, required): the secondary geometry S
        camera (Camera, required): the view
        light (Light, required): the light
        layer1 (GBuffer, required): first iso-surface layer (GBuffer)
        layer2 (GBuffer, required): second iso-surface layer (DepthPeel)

    Outputs:
        intensity (Mask): attenuated intensity I_S
        gbuffer (GBuffer): depth and normal of S

    Parameters:
        alpha (float in [0, 1]; default 0.7): how much of the secondary geometry shows behind
            one surface layer (α)
        beta (float in [0, 1]; default 0.21): how much shows behind two surface layers, less
            than behind one (β < α)
        two_sided (bool; default True): light back faces with the flipped normal

    """

    kind = 'SecondaryGeometry'
    category = 'Illustration'
    alpha: float = 0.7
    beta: float = 0.21
    two_sided: bool = True

class SelectImage:
    """Outputs input image number `select` (1–4) unchanged; the others are still computed if
        connected. For presets that offer alternative styles.

    Inputs:
        image1 (Image, optional): an alternative
        image2 (Image, optional): an alternative
        image3 (Image, optional): an alternative
        image4 (Image, optional): an alternative

    Outputs:
        image (Image): the selected image

    Parameters:
        select (int in [1, 4]; default 1): which input to pass through

    """

    kind = 'SelectImage'
    category = 'Compositing'
    select: int = 1

class SelectionRender:
    """VolumeShop selective illustration (Bruckner & Gröller, the tutorial's §4, §6.2–6.3): the
        labels listed in `objects` form the selection; the volume is drawn as background (tf),
        ghost (the selection where it was, tf_ghost) and selection (moved by translate/rotate,
        tf_selection), combined by eq. 1–5 (fuzzy sets: membership = min(selection degree,
        opacity); colour = membership-weighted mean, opacity = max). Cutaways act on the
        background in front of the ghost and/or the selection; `ghosting` goes from 0 (no
        ghosting) to 1 (full cutaway), combined with the lighting transfer function's opacity
        enhancement (eq. 8) so that enhanced contours survive ghosting. Placement: integrated
        (moves with the scene), pinned (its centre fixed on screen at `pin`, turning with the
        view) or decoupled (fixed on screen and in orientation).

    Inputs:
        volume (Volume, required): the scalar field f_V
        labels (Labels, required): object ids on the volume's grid; `objects` picks the
            selection
        camera (Camera, required): the view
        tf (TransferFunction, required): the background's colour TF
        tf_ghost (TransferFunction, optional): the ghost's (default: tf)
        tf_selection (TransferFunction, optional): the selection's (default: tf)
        light (Light, optional): the light (default: a headlight)

    Outputs:
        image (Image): premultiplied colour
        gbuffer (GBuffer): depth and normal where opaque
        annotations (Annotations): anchor 0: the ghost's centre, anchor 1: the selection's, with
            their boxes (for Arrow, Fan, BoundingBox and labels)

    Parameters:
        objects (text; default '1'): label ids of the selection, e.g. "10" or "10, 11"
        translate ((x, y, z); default (0.0, 0.0, 0.0)): integrated: the selection's move, world
            units
        rotate ((x, y, z); default (0.0, 0.0, 0.0)): rotation about the selection's centre, XYZ
            Euler degrees (world axes; view axes when decoupled)
        placement (one of 'integrated', 'pinned', 'decoupled'; default 'integrated'): where the
            selection is drawn: in place in the volume (integrated), moved with its ghost left
            behind (pinned), or in a view of its own (decoupled) (§6.3)
        pin_x (float in [0, 1]; default 0.75): pinned/decoupled: the centre's screen position,
            fraction of the width from the left
        pin_y (float in [0, 1]; default 0.3): pinned/decoupled: fraction of the height from the
            top
        cutaway (one of 'ghost', 'selection', 'both', 'none'; default 'ghost'): whose far side
            the background is cut in front of
        ghosting (float in [0, 1]; default 0.7): 0: no ghosting … 1: full cutaway
        shading (one of 'phong_contour', 'phong', 'cartoon', 'metal', 'none'; default
            'phong_contour'): how the selection is lit: a lighting transfer function that
            darkens it where it faces away from the light (eq. 8), or none
        step (float in [0.05, 8]; default 0.5): sample distance in voxels (of the smallest
            spacing)
        reconstruction (one of 'trilinear', 'bspline'; default 'trilinear'): reconstruction of
            the data between voxels: trilinear, or the tricubic B-spline's values and gradients
            (Hadwiger §1.3)
        surface_smoothing (float in [0, 4]; default 0.0): shade the selection and its ghost with
            the selection mask's gradient averaged over ±this many voxels (the 3-D Sobel
            operator at this spacing) instead of the data's: for label maps given as the data,
            whose gradient steps at every slice; 0: the data's
        jitter (bool; default True): jitter the first sample per pixel
        early_termination (float in [0.5, 1]; default 0.99): stop a ray at this opacity (1 =
            never)
        kernel (one of 'auto', 'fragment', 'compute'; default 'auto'): GPU path: fragment shader
            or compute kernel (same picture)

    """

    kind = 'SelectionRender'
    category = 'Volume'
    objects: str = '1'
    translate: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    rotate: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    placement: Literal['integrated', 'pinned', 'decoupled'] = 'integrated'
    pin_x: float = 0.75
    pin_y: float = 0.3
    cutaway: Literal['ghost', 'selection', 'both', 'none'] = 'ghost'
    ghosting: float = 0.7
    shading: Literal['phong_contour', 'phong', 'cartoon', 'metal', 'none'] = 'phong_contour'
    step: float = 0.5
    reconstruction: Literal['trilinear', 'bspline'] = 'trilinear'
    surface_smoothing: float = 0.0
    jitter: bool = True
    early_termination: float = 0.99
    kernel: Literal['auto', 'fragment', 'compute'] = 'auto'

class ShadedSurface:
    """Blinn–Phong shaded mesh over a background colour: ambient + diffuse max(n·l, 0) + specular
        max(n·h, 0)^shininess, lit from the Light input. Output is premultiplied RGBA.

    Inputs:
        mesh (Mesh, required): the surface
        camera (Camera, required): the view
        light (Light, required): the light

    Outputs:
        image (Image): the shaded picture

    Parameters:
        color (RGBA in [0, 1]; default (0.85, 0.78, 0.7, 1.0)): surface colour (alpha = opacity)
        background (RGBA in [0, 1]; default (1.0, 1.0, 1.0, 1.0)): colour where there is no
            surface
        specular (float in [0, 10]; default 0.25): strength of the specular highlight
        shininess (float in [1, 1024]; default 32.0): Blinn–Phong exponent
        two_sided (bool; default True): light back faces with the flipped normal

    """

    kind = 'ShadedSurface'
    category = 'Rendering'
    color: Tuple[float, float, float, float] = (0.85, 0.78, 0.7, 1.0)
    background: Tuple[float, float, float, float] = (1.0, 1.0, 1.0, 1.0)
    specular: float = 0.25
    shininess: float = 32.0
    two_sided: bool = True

class Silhouette:
    """Binary silhouette mask of a G-buffer layer: Sobel magnitude of the window-space depth ≥
        depth_threshold (eq. 3) OR the sum of the dot products with the four neighbour normals <
        normal_threshold (eq. 4–5), Fischer et al. 2005. PIP (Yuan & Chen 2005, eq. 2) scales
        every tap offset by P(x, y): a constant (line width), a tiled PNG, value noise or a dot
        matrix (stippled, felt-tip lines); P = 0 detects nothing.

    Inputs:
        gbuffer (GBuffer, required): the layer

    Outputs:
        mask (Mask): 1 on silhouettes, 0 elsewhere

    Parameters:
        depth_threshold (float in [0, 100]; default 0.001): threshold on the Sobel depth-
            gradient magnitude
        normal_threshold (float in [-4, 4]; default 3.98): threshold on the summed neighbour
            normal dot products
        tap_distance (float in [1, 16]; default 1.0): distance of the depth and normal taps from
            the pixel (rounded to whole pixels; 1: the paper's neighbours): lines are about
            twice this wide
        use_depth (bool; default True): draw lines where the depth jumps: outlines against the
            background and other parts (eq. 3)
        use_normals (bool; default True): draw lines where the surface bends sharply: creases
            and edges (eq. 4–5)
        pip (one of 'none', 'constant', 'texture', 'noise', 'dots'; default 'none'):
            perturbation P(x, y) of the sampling positions
        pip_amount (float in [0, 16]; default 1.0): P's scale in pixels (the constant for
            `constant`)
        pip_scale (float in [1, 256]; default 8.0): pattern size in pixels for `noise` and
            `dots`
        pip_seed (int in [0, 1e+06]; default 0): seed of the `noise` pattern
        pip_texture (path; default ''): grey-scale PNG tiled over the frame for `texture`

    """

    kind = 'Silhouette'
    category = 'Illustration'
    depth_threshold: float = 0.001
    normal_threshold: float = 3.98
    tap_distance: float = 1.0
    use_depth: bool = True
    use_normals: bool = True
    pip: Literal['none', 'constant', 'texture', 'noise', 'dots'] = 'none'
    pip_amount: float = 1.0
    pip_scale: float = 8.0
    pip_seed: int = 0
    pip_texture: str = ''

class Stipple:
    """Stippling of a surface (Preim & Tietjen, Viola et al. 2005 tutorial, §2.1, §6 and "Efficient
        Texture-based Stippling"): round ink dots of `radius` pixels whose density gives the
        tone, ink coverage = darkness 1 − intensity (up to 1 − exp(−π·radius²/spacing²)). The
        dots are a solid texture in world space — one jittered point with a random threshold per
        lattice cell, kept where its threshold is below the density and it lies within half a
        cell of the surface — so they stay on the surface when the camera orbits; the lattice's
        cell follows `spacing` pixels through power-of-two levels of detail, cross-faded.

    Inputs:
        intensity (Mask, required): shading intensity in [0, 1] (e.g. DiffuseIntensity); darker
            = more dots
        gbuffer (GBuffer, required): the surface: its depth places the dots in world space, its
            normal orients them

    Outputs:
        mask (Mask): 1 = paper, 0 = ink (anti-aliased dot edges)

    Parameters:
        spacing (float in [1, 64]; default 3.0): distance in pixels between neighbouring dots
            where the tone is darkest (the stipple lattice's cell on screen; Preim & Tietjen's
            "adjustable level of sparseness")
        radius (float in [0.3, 64]; default 1.2): radius of each dot in pixels, at most
            `spacing` (above half of it the pass searches 125 lattice cells per level instead of
            27)
        foreshortening (bool; default True): thin the dots where the surface turns away from the
            viewer (by n·v), so a tilted surface shows the tone its shading asks for rather than
            more dots per pixel
        seed (int in [0, 1e+06]; default 0): number that picks another random dot pattern (the
            same seed gives the same dots)

    """

    kind = 'Stipple'
    category = 'Illustration'
    spacing: float = 3.0
    radius: float = 1.2
    foreshortening: bool = True
    seed: int = 0

class StyleSet:
    """A list of lit-sphere styles (sphere maps indexed by the eye-space normal, §3.1): `styles`
        names them in order, comma-separated — procedural ones (shaded, toon2, toon3, gooch,
        metal, ink_rim, flat), each optionally tinted as name:r,g,b, or a path to a square PNG
        or JPEG with a power-of-two size (relative to the graph file). Style k of a
        StyleTransferFunction is the k-th entry. Each keeps its own mip chain.

    Outputs:
        styles (StyleSet): the styles

    Parameters:
        styles (text; default 'shaded:0.9,0.85,0.8, toon2:0.85,0.3,0.25, gooch:0.6,0.7,0.9'):
            styles in order: name[:r,g,b] or a PNG or JPEG path

    """

    kind = 'StyleSet'
    category = 'Volume'
    styles: str = 'shaded:0.9,0.85,0.8, toon2:0.85,0.3,0.25, gooch:0.6,0.7,0.9'

class StyleTransferFunction:
    """A style transfer function: nodes "value: style opacity; …" (style = index into the StyleSet,
        opacity = uniform α_u). Between two nodes the style index and α_u are interpolated, so
        whole styles blend uniformly for every normal; a style may appear several times (the
        index function ift of §4.1). `label_nodes` adds the 2-D variant of §4.2 (value ×
        object): rows for chosen labels of the label volume given to Raycast's `labels`. Connect
        to Raycast's `tf`.

    Inputs:
        styles (StyleSet, required): the lit-sphere styles
        volume (Volume, optional): resolves node values given relative to the data ("range(0.3):
            1 0.5")

    Outputs:
        tf (TransferFunction): the style transfer function

    Parameters:
        nodes (text; default '40: 0 0.02; 90: 1 0.3; 160: 2 1.0'): value: style opacity; …
            (every object); a value may be relative to the connected volume: "percentile(P)",
            "range(F)", "otsu"
        label_nodes (text; default ''): per object of a label volume (§4.2): "LABEL = value:
            style opacity; … | LABEL = …"

    """

    kind = 'StyleTransferFunction'
    category = 'Volume'
    nodes: str = '40: 0 0.02; 90: 1 0.3; 160: 2 1.0'
    label_nodes: str = ''

class TransferFunction1D:
    """A 1-D transfer function: colour and opacity (per voxel of path) per data value, linear
        between control points, sampled into a 256-entry table. Either a preset spread over the
        volume's value range, or `points` as "value: r g b a; value: r g b a; …" in data units.

    Inputs:
        volume (Volume, optional): sets the value range of presets (and resolves relative point
            values)

    Outputs:
        tf (TransferFunction): the transfer function

    Parameters:
        preset (one of 'custom', 'grey_ramp', 'bone', 'skin_bone', 'brain_mri', 'rainbow';
            default 'grey_ramp'): a preset, or `custom` to use `points`
        points (text; default '0: 0 0 0 0; 255: 1 1 1 1'): control points for `custom`; a value
            may be relative to the connected volume ("percentile(5): 0 0 0 0", "range(0.5): …",
            "otsu: …")
        range_min (float in [-1e+12, 1e+12]; default 0.0): value range of presets when no volume
            is connected
        range_max (float in [-1e+12, 1e+12]; default 255.0): value range of presets when no
            volume is connected

    """

    kind = 'TransferFunction1D'
    category = 'Volume'
    preset: Literal['custom', 'grey_ramp', 'bone', 'skin_bone', 'brain_mri', 'rainbow'] = 'grey_ramp'
    points: str = '0: 0 0 0 0; 255: 1 1 1 1'
    range_min: float = 0.0
    range_max: float = 255.0

class TransferFunction2D:
    """A 2-D transfer function (Kniss et al. 2002; Svakhine et al. 2005 §3.3): colour and opacity
        per voxel of path over the data value × a second coordinate — the gradient magnitude as
        a fraction of the volume's largest, the Laplacian in data units per voxel², or a second
        field's value (Raycast's `second` input: another variable, or a vector field's |U| or
        |∇×U| from VectorOperator) — drawn by rectangle and triangle widgets (`widgets`) and
        baked into a 256×256 table. `Raycast` (mode dvr) classifies each sample with it; the
        other consumers of `tf` refuse it (docs/transfer_functions_2d.md).

    Outputs:
        tf (TransferFunction): the 2-D transfer function

    Parameters:
        axis (one of 'gradient_magnitude', 'laplacian', 'second_field'; default
            'gradient_magnitude'): the second axis: gradient_magnitude (|∇f| as a fraction of
            the volume's largest, 0..1), laplacian (∇²f by second differences, data units per
            voxel²) or second_field (the value of the field on Raycast's `second` input, its
            data units)
        value_min (float in [-1e+12, 1e+12]; default 0.0): first data value of the table (data
            units)
        value_max (float in [-1e+12, 1e+12]; default 255.0): last data value of the table (data
            units)
        second_min (float in [-1e+12, 1e+12]; default 0.0): first second-axis coordinate of the
            table (a fraction of the largest gradient for gradient_magnitude, data units per
            voxel² for laplacian, the second field's data units for second_field)
        second_max (float in [-1e+12, 1e+12]; default 1.0): last second-axis coordinate of the
            table (same units as second_min)
        widgets (text; default 'tri 128 x 0..1 width 60: 1 1 1 0.5'): widgets, ';'-separated:
            "rect V0..V1 x S0..S1: r g b a" (a box) or "tri C x S0..S1 width W: r g b a"
            (Kniss's triangle: apex at value C and S0, W data units wide at S1, opacity falling
            from the centre line to the edges); overlaps take the largest opacity and the
            opacity-weighted mean colour

    """

    kind = 'TransferFunction2D'
    category = 'Volume'
    axis: Literal['gradient_magnitude', 'laplacian', 'second_field'] = 'gradient_magnitude'
    value_min: float = 0.0
    value_max: float = 255.0
    second_min: float = 0.0
    second_max: float = 1.0
    widgets: str = 'tri 128 x 0..1 width 60: 1 1 1 0.5'

class TwoLevelRaycast:
    """Two-level volume rendering of a segmented volume (Hadwiger §2.2–2.4): each ray is split into
        segments where it passes through one object (object membership by boundary filtering,
        §2.3: each object's binary mask filtered trilinearly and thresholded at 0.5); each
        segment is composited with its object's local mode and rendering mode from ObjectStyles,
        and the segments are combined front to back with the global mode: over, mip (per-channel
        maximum) or sum. Same camera, light and jitter rules as Raycast.

    Inputs:
        volume (Volume, required): the scalar field
        labels (Labels, required): object ids on the volume's grid
        styles (ObjectStyles, required): the object table
        camera (Camera, required): the view
        light (Light, optional): the light (default: a headlight)
        importance (Importance, optional): importance-driven rendering: ImportanceCompositing of
            the same view

    Outputs:
        image (Image): premultiplied colour
        gbuffer (GBuffer): depth and normal of the first visible segment

    Parameters:
        global (one of 'over', 'mip', 'sum'; default 'over'): global compositing of the segments
        boundary (one of 'filtered', 'point'; default 'filtered'): object membership: filtered
            binary masks (§2.3) or the nearest voxel's id
        normals (one of 'data', 'objects'; default 'data'): shading normals from the data's
            gradient, or from each object's filtered mask (for label maps without intensities)
        surface_smoothing (float in [0, 4]; default 0.0): with normals `objects`: the normals of
            iso-surfaces averaged over ±this many voxels (the 3-D Sobel operator of the object's
            mask at this spacing), so a label map segmented slice by slice does not show every
            slice as a terrace; 0: central differences of neighbouring voxels
        step (float in [0.05, 8]; default 0.5): sample distance in voxels (of the smallest
            spacing)
        reconstruction (one of 'trilinear', 'bspline'; default 'trilinear'): reconstruction of
            the data between voxels: trilinear, or the tricubic B-spline's values and gradients
            (Hadwiger §1.3)
        ambient (float in [0, 1]; default 0.15): ambient light: brightness of every shaded
            sample, lit or not (c_a of eq. 3)
        diffuse (float in [0, 4]; default 0.85): diffuse light: brightness where the surface
            faces the light (c_d of eq. 3)
        specular (float in [0, 4]; default 0.4): specular light: strength of the highlight (c_s
            of eq. 3)
        exponent (float in [1, 512]; default 32.0): shininess: higher makes the highlight
            smaller and sharper (c_e of eq. 3)
        jitter (bool; default True): jitter the first sample per pixel
        early_termination (float in [0.5, 1]; default 0.99): stop a ray at this opacity with
            global over (1 = never)
        skip_empty (bool; default True): jump over 8³-voxel bricks that no drawn object reaches
            — same picture, fewer samples
        kernel (one of 'auto', 'fragment', 'compute'; default 'auto'): GPU path: fragment shader
            or compute kernel (same picture)
        sparseness (one of 'opacity', 'saturation', 'screen_door', 'style', 'thinning'; default
            'opacity'): with `importance` (AImC): how a level of sparseness S shows — opacity ×
            S, opacity and colour saturation × S, a screen door keeping S of the voxels, a
            sparse rendering style where S < 1, or volume thinning (a context sample kept only
            where its strength key, gradient-magnitude level then curvature magnitude, exceeds 1
            − S)
        sparse_mode (one of 'contours', 'dvr', 'shaded_dvr', 'tone', 'mip'; default 'contours'):
            the sparse style's rendering mode
        sparse_compositing (one of 'mip', 'over', 'sum'; default 'mip'): the sparse style's
            local compositing
        thinning_levels (int in [1, 64]; default 4): volume thinning: levels B of the normalised
            gradient magnitude, the first sorting key; within a level the curvature magnitude
            orders the samples (1: curvature alone)

    """

    kind = 'TwoLevelRaycast'
    category = 'Volume'
    global_: Literal['over', 'mip', 'sum'] = 'over'
    boundary: Literal['filtered', 'point'] = 'filtered'
    normals: Literal['data', 'objects'] = 'data'
    surface_smoothing: float = 0.0
    step: float = 0.5
    reconstruction: Literal['trilinear', 'bspline'] = 'trilinear'
    ambient: float = 0.15
    diffuse: float = 0.85
    specular: float = 0.4
    exponent: float = 32.0
    jitter: bool = True
    early_termination: float = 0.99
    skip_empty: bool = True
    kernel: Literal['auto', 'fragment', 'compute'] = 'auto'
    sparseness: Literal['opacity', 'saturation', 'screen_door', 'style', 'thinning'] = 'opacity'
    sparse_mode: Literal['contours', 'dvr', 'shaded_dvr', 'tone', 'mip'] = 'contours'
    sparse_compositing: Literal['mip', 'over', 'sum'] = 'mip'
    thinning_levels: int = 4

class VectorField:
    """A vector field U = (x, y, z) made of three scalar volumes on one grid, each the component
        along a world axis (e.g. velocity components a simulation wrote as separate files).
        Raycast's `vector` input reads it for Svakhine et al. 2005's vector enhancements;
        VectorOperator makes scalar fields of it (|U|, ∇·U, |∇×U|).

    Inputs:
        x (Volume, required): U_x, the component along world x
        y (Volume, required): U_y, on the same grid
        z (Volume, required): U_z, on the same grid

    Outputs:
        field (VectorField): the vector field

    """

    kind = 'VectorField'
    category = 'Data'

class VectorOperator:
    """A scalar field of a vector field by one of Svakhine et al. 2005's Table 1 operators: the
        magnitude |U|, the divergence ∇·U or the curl's magnitude |∇×U| (vortex cores), on the
        field's grid. Derivatives are central differences (one-sided at the border) with respect
        to world coordinates, so rotated and anisotropic grids give the field's own numbers.
        Computed once on the CPU (data preparation). Render it, or give it to Raycast's `second`
        input: a 2-D transfer function over value × it, or enhancement by its gradient.

    Inputs:
        field (VectorField, required): the vector field U

    Outputs:
        volume (Volume): the operator's value at every voxel

    Parameters:
        operator (one of 'magnitude', 'divergence', 'curl_magnitude'; default 'magnitude'):
            magnitude |U| (U's units), divergence ∇·U or curl_magnitude |∇×U| (U's units per
            world unit; Svakhine et al. 2005 Table 1)

    """

    kind = 'VectorOperator'
    category = 'Volume'
    operator: Literal['magnitude', 'divergence', 'curl_magnitude'] = 'magnitude'

class VolumeFile:
    """Reads a volume: NIfTI-1 or NIfTI-2 (.nii, .nii.gz, scl_slope/scl_inter applied), FreeSurfer
        MGH/MGZ (.mgh, .mgz), VTK XML image data (.vti), NRRD (.nrrd, .nhdr), MetaImage (.mha,
        .mhd), a multi-page TIFF stack (.tif) or a DICOM series (a folder, or one .dcm of it).
        The file's voxel → world transform (origin, spacing, direction; NIfTI sform/qform)
        places the voxels in hatchery's RAS+ world in mm (LPS formats are converted; see
        docs/data.md). NaN voxels are "no data". Relative paths are relative to the graph file's
        folder.

    Outputs:
        volume (Volume): the volume, in world units (mm)

    Parameters:
        path (path; default ''): the volume file, or a folder holding a DICOM series
        array (text; default ''): the named data array to read from a file with several (VTK;
            OME-Zarr: a label image of labels/); empty: the file's active scalars, else the
            first array (OME-Zarr: the image)

    """

    kind = 'VolumeFile'
    category = 'Data'
    path: str = ''
    array: str = ''

//! Drawing table-top results: the scene graph (Fig. 4.17 - 4.23, lower left) and the boxes
//! projected into the camera image (upper right).
//!
//! Colours follow the dissertation: false estimates red ([`FALSE_RGBA`]), objects implying a
//! hidden object under them cyan ([`HIDDEN_RGBA`]). In the graph, arrows are stable support
//! (from the supporting box to the supported one) and plain lines other contact; under it, the
//! query probabilities are listed as in the figures (`false(o1)=0.046, hidden(o1)=0.424`).
//!
//! As everywhere in [`crate::render`], anti-aliasing is off, so the same input gives the same
//! pixels natively and in the browser.
//!
//! ```
//! use ksmcmc::render::tabletop::{draw_graph, draw_view, marks, ViewOptions};
//! use ksmcmc::tabletop::{synth, ChainConfig, TabletopChain};
//!
//! let scene = synth::generate(&synth::SynthConfig::default(), 5).unwrap();
//! let chain = TabletopChain::new(scene, ChainConfig::default(), 1).unwrap();
//! let analysis = chain.best_analysis().unwrap();
//! let graph = draw_graph(&analysis.graph);
//! assert!(graph.width() >= 200 && graph.height() >= 100);
//! let poses: Vec<_> = analysis.objects.iter().map(|o| o.pose).collect();
//! let view = draw_view(chain.scene(), &poses, &marks(&analysis), &ViewOptions::default());
//! assert_eq!(view.width(), 1024); // the 1280-pixel image scaled to fit
//! ```

use super::draw_tag;
use super::font;
use crate::tabletop::geometry::Obb;
use crate::tabletop::graph::{levels, EdgeKind, GraphNode, SceneGraph};
use crate::tabletop::scene::{Pose, Projector, Scene, NEAR};
use crate::tabletop::{Analysis, Decision};
use nalgebra::{Vector2, Vector3};
use petgraph::visit::EdgeRef;
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Stroke, Transform};

/// False estimates: red.
pub const FALSE_RGBA: [u8; 4] = [220, 30, 30, 255];
/// Objects implying a hidden object: cyan.
pub const HIDDEN_RGBA: [u8; 4] = [0, 200, 230, 255];
/// Other nodes of the graph: white.
pub const NODE_RGBA: [u8; 4] = [255, 255, 255, 255];
/// Outlines, support arrows and text: black.
pub const INK_RGBA: [u8; 4] = [0, 0, 0, 255];
/// Contact edges: gray.
pub const CONTACT_RGBA: [u8; 4] = [120, 120, 120, 255];
/// The background of both pictures.
pub const BACKGROUND_RGBA: [u8; 4] = [245, 245, 245, 255];
/// The table top in the view.
pub const TABLE_RGBA: [u8; 4] = [214, 196, 164, 255];
/// Observed keypoints in the view.
pub const OBSERVED_RGBA: [u8; 4] = [0, 170, 255, 255];
/// Model keypoints projected at the analysed pose.
pub const PROJECTED_RGBA: [u8; 4] = [255, 0, 0, 255];
/// Lines joining observed and projected keypoints (Fig. 4.15 b).
pub const MATCH_RGBA: [u8; 4] = [230, 200, 0, 255];

/// Colours of the other objects in the view, in turn: muted hues far from red and cyan.
pub const OBJECT_PALETTE: [[u8; 3]; 8] = [
    [120, 170, 90],
    [110, 130, 200],
    [205, 165, 95],
    [150, 110, 190],
    [230, 190, 70],
    [150, 150, 150],
    [175, 120, 80],
    [200, 130, 190],
];

/// Radius of an object node, pixels.
const NODE_RADIUS: f32 = 24.0;
/// Horizontal distance between nodes of a row.
const NODE_DX: f32 = 92.0;
/// Vertical distance between rows.
const ROW_DY: f32 = 86.0;
/// Margin around the picture.
const MARGIN: f32 = 30.0;
/// Size of the table node.
const TABLE_W: f32 = 120.0;
const TABLE_H: f32 = 34.0;

fn paint(rgba: [u8; 4]) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(rgba[0], rgba[1], rgba[2], rgba[3]));
    p.anti_alias = false;
    p
}

fn stroke(width: f32) -> Stroke {
    Stroke { width, ..Stroke::default() }
}

fn line(pixmap: &mut Pixmap, a: (f32, f32), b: (f32, f32), width: f32, rgba: [u8; 4]) {
    let mut pb = PathBuilder::new();
    pb.move_to(a.0, a.1);
    pb.line_to(b.0, b.1);
    if let Some(path) = pb.finish() {
        pixmap.stroke_path(&path, &paint(rgba), &stroke(width), Transform::identity(), None);
    }
}

fn polygon(pixmap: &mut Pixmap, pts: &[(f32, f32)], fill: Option<[u8; 4]>, outline: Option<([u8; 4], f32)>) {
    if pts.len() < 3 || pts.iter().any(|p| !p.0.is_finite() || !p.1.is_finite()) {
        return;
    }
    let mut pb = PathBuilder::new();
    pb.move_to(pts[0].0, pts[0].1);
    for p in &pts[1..] {
        pb.line_to(p.0, p.1);
    }
    pb.close();
    let Some(path) = pb.finish() else { return };
    if let Some(rgba) = fill {
        pixmap.fill_path(&path, &paint(rgba), FillRule::Winding, Transform::identity(), None);
    }
    if let Some((rgba, w)) = outline {
        pixmap.stroke_path(&path, &paint(rgba), &stroke(w), Transform::identity(), None);
    }
}

/// Where the nodes of a graph go: the table on top, objects in rows ([`levels`]), each row
/// ordered by the mean position of the nodes above it is joined to (fewer crossings).
fn layout(g: &SceneGraph) -> (Vec<(f32, f32)>, f32, f32) {
    let level = levels(g);
    let rows = level.iter().copied().max().unwrap_or(0) as usize + 1;
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); rows];
    for (i, &l) in level.iter().enumerate() {
        members[l as usize].push(i);
    }
    let widest = members.iter().map(|m| m.len()).max().unwrap_or(1).max(1) as f32;
    let width = (2.0 * MARGIN + (widest - 1.0) * NODE_DX + 2.0 * NODE_RADIUS).max(2.0 * MARGIN + TABLE_W);
    let height = 2.0 * MARGIN + TABLE_H / 2.0 + (rows as f32 - 1.0) * ROW_DY + NODE_RADIUS + 16.0;
    let mut pos = vec![(f32::NAN, 0.0); g.node_count()];
    for (r, m) in members.iter_mut().enumerate() {
        // Mean x of the already placed neighbours; nodes without any keep their order at the end.
        let key = |i: usize| {
            let xs: Vec<f32> = g
                .neighbors_undirected(petgraph::graph::NodeIndex::new(i))
                .map(|j| pos[j.index()].0)
                .filter(|x: &f32| x.is_finite())
                .collect();
            if xs.is_empty() {
                f32::INFINITY
            } else {
                xs.iter().sum::<f32>() / xs.len() as f32
            }
        };
        let mut keyed: Vec<(f32, usize)> = m.iter().map(|&i| (key(i), i)).collect();
        keyed.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let y = MARGIN + TABLE_H / 2.0 + r as f32 * ROW_DY;
        let span = (m.len() as f32 - 1.0).max(0.0) * NODE_DX;
        for (k, &(_, i)) in keyed.iter().enumerate() {
            pos[i] = (width / 2.0 - span / 2.0 + k as f32 * NODE_DX, y);
        }
    }
    (pos, width, height)
}

/// Moves the end `to` of a segment `from -> to` back to the boundary of node `node`.
fn clip_to_node(from: (f32, f32), to: (f32, f32), table: bool) -> (f32, f32) {
    let (dx, dy) = (to.0 - from.0, to.1 - from.1);
    let len = (dx * dx + dy * dy).sqrt();
    if len < 1e-3 {
        return to;
    }
    let back = if table {
        // Distance from the centre to the rectangle's boundary along the segment.
        let tx = if dx.abs() > 1e-6 { (TABLE_W / 2.0) / dx.abs() } else { f32::INFINITY };
        let ty = if dy.abs() > 1e-6 { (TABLE_H / 2.0) / dy.abs() } else { f32::INFINITY };
        tx.min(ty) * len
    } else {
        NODE_RADIUS
    };
    (to.0 - dx / len * back, to.1 - dy / len * back)
}

/// The probability lines under the graph, as in the dissertation's figures.
pub fn probability_lines(g: &SceneGraph) -> Vec<String> {
    g.node_weights()
        .filter(|n| !n.is_table)
        .map(|n| {
            format!(
                "false({})={:.3}, hidden({})={:.3}",
                n.id, n.probabilities.false_estimate, n.id, n.probabilities.hidden
            )
        })
        .collect()
}

/// How wide (in pixels) the page shows the graph picture at its default size: the narrow
/// column of the table-top page on a laptop screen. Pictures wider than this are shrunk to it.
pub const GRAPH_DISPLAY_WIDTH: f32 = 430.0;

/// The text factor of the probability lines under a graph picture `width` pixels wide: large
/// enough that, with the picture shrunk to [`GRAPH_DISPLAY_WIDTH`], capitals are still about
/// 11 pixels tall (at least 2, so they are 14 pixels in the picture itself).
pub fn probability_text_factor(width: f32) -> u32 {
    let wanted = 11.0 * width / GRAPH_DISPLAY_WIDTH / font::CAP_HEIGHT as f32;
    (wanted.ceil() as u32).clamp(2, 8)
}

/// Draws an edge of the graph: a support arrow from the supporting node to the supported one,
/// or a plain gray line for other contact.
fn draw_edge(pixmap: &mut Pixmap, from: (f32, f32), to: (f32, f32), kind: EdgeKind) {
    match kind {
        EdgeKind::Support => {
            line(pixmap, from, to, 2.0, INK_RGBA);
            let (dx, dy) = (to.0 - from.0, to.1 - from.1);
            let len = (dx * dx + dy * dy).sqrt().max(1e-3);
            let (ux, uy) = (dx / len, dy / len);
            let (bx, by) = (to.0 - ux * 12.0, to.1 - uy * 12.0);
            let head = [to, (bx - uy * 6.0, by + ux * 6.0), (bx + uy * 6.0, by - ux * 6.0)];
            polygon(pixmap, &head, Some(INK_RGBA), None);
        }
        EdgeKind::Contact => line(pixmap, from, to, 2.0, CONTACT_RGBA),
    }
}

/// Draws the table node: a white rectangle labelled "Table", centred at `(x, y)`.
fn draw_table_node(pixmap: &mut Pixmap, (x, y): (f32, f32)) {
    let rect = [
        (x - TABLE_W / 2.0, y - TABLE_H / 2.0),
        (x + TABLE_W / 2.0, y - TABLE_H / 2.0),
        (x + TABLE_W / 2.0, y + TABLE_H / 2.0),
        (x - TABLE_W / 2.0, y + TABLE_H / 2.0),
    ];
    polygon(pixmap, &rect, Some(NODE_RGBA), Some((INK_RGBA, 2.0)));
    let (tw, th) = font::text_size("Table", 2);
    font::draw_text(pixmap, (x - tw as f32 / 2.0) as i32, (y - th as f32 / 2.0) as i32, "Table", 2, INK_RGBA);
}

/// Draws an object node at `(x, y)`: a circle coloured by its flags (red false estimate, cyan
/// hidden object under it), with its id inside, or in a tag below when it does not fit.
fn draw_object_node(pixmap: &mut Pixmap, n: &GraphNode, (x, y): (f32, f32)) {
    let fill = if n.false_flag() {
        FALSE_RGBA
    } else if n.hidden_flag() {
        HIDDEN_RGBA
    } else {
        NODE_RGBA
    };
    if let Some(circle) = PathBuilder::from_circle(x, y, NODE_RADIUS) {
        pixmap.fill_path(&circle, &paint(fill), FillRule::Winding, Transform::identity(), None);
        // A false estimate that also implies a hidden object gets a cyan ring.
        let (ring, width) = if n.false_flag() && n.hidden_flag() { (HIDDEN_RGBA, 5.0) } else { (INK_RGBA, 2.0) };
        pixmap.stroke_path(&circle, &paint(ring), &stroke(width), Transform::identity(), None);
    }
    let factor = if font::text_size(&n.id, 2).0 as f32 <= 2.0 * NODE_RADIUS - 8.0 { 2 } else { 1 };
    let (tw, th) = font::text_size(&n.id, factor);
    if tw as f32 <= 2.0 * NODE_RADIUS - 4.0 {
        font::draw_text(pixmap, (x - tw as f32 / 2.0) as i32, (y - th as f32 / 2.0) as i32, &n.id, factor, INK_RGBA);
    } else {
        draw_tag(pixmap, x as f64, (y + NODE_RADIUS + 10.0) as f64, &n.id, 1);
    }
}

/// Draws a scene graph: the table on top, objects below their supporters, support arrows,
/// contact lines, red false estimates, cyan objects with hidden objects under them, and the
/// query probabilities underneath, in text that scales with the picture
/// ([`probability_text_factor`]) so it stays readable when the page shrinks the picture.
pub fn draw_graph(g: &SceneGraph) -> Pixmap {
    let (pos, nodes_w, graph_h) = layout(g);
    let lines = probability_lines(g);
    let text_w = |f: u32| lines.iter().map(|l| font::text_size(l, f).0).max().unwrap_or(0) as f32;
    // The factor for the nodes' width; if the text then widens the picture, the factor for
    // that width is no larger (the text alone is narrower than the display width per factor).
    let factor = probability_text_factor(nodes_w);
    let width = nodes_w.max(text_w(factor) + 2.0 * MARGIN);
    // Re-centre the nodes if the text made the picture wider.
    let shift = (width - nodes_w) / 2.0;
    let pos: Vec<(f32, f32)> = pos.iter().map(|p| (p.0 + shift, p.1)).collect();
    let line_h = ((font::GLYPH_HEIGHT + 3) * factor) as f32;
    let height = graph_h + lines.len() as f32 * line_h + if lines.is_empty() { 0.0 } else { MARGIN / 2.0 };
    let (w, h) = (width.ceil().clamp(1.0, 8192.0) as u32, height.ceil().clamp(1.0, 8192.0) as u32);
    let Some(mut pixmap) = Pixmap::new(w, h) else {
        return Pixmap::new(1, 1).expect("a 1x1 pixmap is always valid");
    };
    let [r, gr, b, a] = BACKGROUND_RGBA;
    pixmap.fill(Color::from_rgba8(r, gr, b, a));

    for e in g.edge_references() {
        let (s, t) = (e.source().index(), e.target().index());
        let from = clip_to_node(pos[t], pos[s], g[e.source()].is_table);
        let to = clip_to_node(pos[s], pos[t], g[e.target()].is_table);
        draw_edge(&mut pixmap, from, to, e.weight().kind);
    }

    for (i, n) in g.node_weights().enumerate() {
        if n.is_table {
            draw_table_node(&mut pixmap, pos[i]);
        } else {
            draw_object_node(&mut pixmap, n, pos[i]);
        }
    }

    for (k, l) in lines.iter().enumerate() {
        let y = graph_h + MARGIN / 4.0 + k as f32 * line_h;
        font::draw_text(&mut pixmap, MARGIN as i32, y as i32, l, factor, INK_RGBA);
    }
    pixmap
}

/// How an object is marked in the view.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Mark {
    /// Flagged as implying a hidden object (drawn cyan).
    pub hidden: bool,
    /// Flagged as a false estimate (drawn red).
    pub false_estimate: bool,
}

/// The marks of an analysis' objects: flags where the decision is true.
pub fn marks(analysis: &Analysis) -> Vec<Mark> {
    analysis
        .objects
        .iter()
        .map(|o| Mark { hidden: o.hidden == Decision::True, false_estimate: o.false_estimate == Decision::True })
        .collect()
}

/// Options of the view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewOptions {
    /// The picture is the camera image scaled down to at most this width (default 1024).
    pub max_width: u32,
    /// Draw keypoints: observed (blue), projected at the pose (red) and their match (yellow).
    pub keypoints: bool,
    /// Draw each object's id.
    pub labels: bool,
}

impl Default for ViewOptions {
    fn default() -> Self {
        ViewOptions { max_width: 1024, keypoints: true, labels: true }
    }
}

/// Draws the table and the objects' boxes at `poses` as the camera sees them, over an empty
/// image plane: the table top, then the boxes from far to near with their camera-facing sides
/// filled (red for false estimates, cyan for objects with a hidden one under them, colours of
/// [`OBJECT_PALETTE`] otherwise) and their edges outlined. Boxes are drawn in order of the
/// depth of their centres, semi-transparent, so that overlaps stay readable.
pub fn draw_view(scene: &Scene, poses: &[Pose], marks: &[Mark], options: &ViewOptions) -> Pixmap {
    let cam = &scene.camera;
    let scale = (options.max_width.max(1) as f64 / cam.width.max(1) as f64).min(1.0);
    let (w, h) = (
        ((cam.width as f64 * scale).round() as u32).clamp(1, 8192),
        ((cam.height as f64 * scale).round() as u32).clamp(1, 8192),
    );
    let Some(mut pixmap) = Pixmap::new(w, h) else {
        return Pixmap::new(1, 1).expect("a 1x1 pixmap is always valid");
    };
    let [r, g, b, a] = BACKGROUND_RGBA;
    pixmap.fill(Color::from_rgba8(r, g, b, a));
    let view = ViewCamera { proj: cam.projector(), scale };

    let [sx, sy] = scene.table.size;
    let top = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(u, v)| Vector3::new(u * sx / 2.0, v * sy / 2.0, 0.0));
    polygon(&mut pixmap, &view.polygon(&top), Some(TABLE_RGBA), Some(([150, 130, 100, 255], 1.0)));

    let n = scene.objects.len().min(poses.len());
    let eye = Vector3::from(cam.pose.t);
    let mut order: Vec<usize> = (0..n).collect();
    let depth = |i: usize| view.proj.to_camera(&Vector3::from(poses[i].t)).z;
    order.sort_by(|&i, &j| depth(j).total_cmp(&depth(i)));
    for &i in &order {
        let obb = scene.objects[i].obb_at(&poses[i].isometry());
        let mark = marks.get(i).copied().unwrap_or_default();
        draw_box(&mut pixmap, &view, &obb, eye, mark_rgb(mark, i));
    }

    if options.keypoints {
        draw_keypoints(&mut pixmap, &view, scene, poses, n);
    }
    if options.labels {
        for (i, o) in scene.objects.iter().enumerate().take(n) {
            if let Some(px) = view.proj.project(&Vector3::from(poses[i].t)) {
                let (x, y) = view.px(px);
                draw_tag(&mut pixmap, x as f64, y as f64, &o.id, 2);
            }
        }
    }
    pixmap
}

/// The camera of the view, its image scaled by `scale` to the picture.
struct ViewCamera {
    /// The camera's projection of table-frame points into its image.
    proj: Projector,
    /// Picture pixels per camera image pixel.
    scale: f64,
}

impl ViewCamera {
    /// A point of the camera image in pixels of the picture.
    fn px(&self, p: Vector2<f64>) -> (f32, f32) {
        ((p.x * self.scale) as f32, (p.y * self.scale) as f32)
    }

    /// A polygon of table-frame points, clipped to the space in front of the camera, in pixels.
    fn polygon(&self, pts: &[Vector3<f64>]) -> Vec<(f32, f32)> {
        let proj = &self.proj;
        let cams: Vec<Vector3<f64>> = pts.iter().map(|p| proj.to_camera(p)).collect();
        let mut out = Vec::new();
        for k in 0..cams.len() {
            let (p, q) = (cams[k], cams[(k + 1) % cams.len()]);
            if p.z >= NEAR {
                out.push(p);
            }
            if (p.z >= NEAR) != (q.z >= NEAR) {
                let t = (NEAR - p.z) / (q.z - p.z);
                out.push(p + (q - p) * t);
            }
        }
        out.iter()
            .map(|c| self.px(Vector2::new(proj.fx * c.x / c.z + proj.cx, proj.fy * c.y / c.z + proj.cy)))
            .collect()
    }
}

/// The colour of object `i`'s box: red for a false estimate, cyan for a hidden object under
/// it, otherwise its colour of [`OBJECT_PALETTE`].
fn mark_rgb(mark: Mark, i: usize) -> [u8; 3] {
    if mark.false_estimate {
        [FALSE_RGBA[0], FALSE_RGBA[1], FALSE_RGBA[2]]
    } else if mark.hidden {
        [HIDDEN_RGBA[0], HIDDEN_RGBA[1], HIDDEN_RGBA[2]]
    } else {
        OBJECT_PALETTE[i % OBJECT_PALETTE.len()]
    }
}

/// Draws a box's faces that face the camera at `eye`, filled semi-transparent in `rgb` and
/// outlined in a darker shade of it.
fn draw_box(pixmap: &mut Pixmap, view: &ViewCamera, obb: &Obb, eye: Vector3<f64>, rgb: [u8; 3]) {
    let v = obb.vertices();
    for k in 0..3 {
        for bit in [0usize, 1] {
            // The face where vertex bit k equals `bit`, its corners in cyclic order.
            let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
            let base = bit << k;
            let face = [base, base | 1 << k1, base | 1 << k1 | 1 << k2, base | 1 << k2].map(|j| v[j]);
            let normal = obb.axis(k) * if bit == 1 { 1.0 } else { -1.0 };
            let center = (face[0] + face[2]) / 2.0;
            if normal.dot(&(eye - center)) <= 0.0 {
                continue;
            }
            let outline = [rgb[0] / 2, rgb[1] / 2, rgb[2] / 2, 255];
            polygon(pixmap, &view.polygon(&face), Some([rgb[0], rgb[1], rgb[2], 170]), Some((outline, 1.5)));
        }
    }
}

/// Draws the keypoints of the first `n` objects: each observed one, the model one projected
/// at the object's pose, and the line matching them (Fig. 4.15 b).
fn draw_keypoints(pixmap: &mut Pixmap, view: &ViewCamera, scene: &Scene, poses: &[Pose], n: usize) {
    for (i, o) in scene.objects.iter().enumerate().take(n) {
        let iso = poses[i].isometry();
        for kp in &o.keypoints {
            let seen = view.px(Vector2::new(kp.image[0], kp.image[1]));
            let p = iso * nalgebra::Point3::from(Vector3::from(kp.model));
            if let Some(px) = view.proj.project(&p.coords) {
                let at = view.px(px);
                line(pixmap, seen, at, 1.0, MATCH_RGBA);
                dot(pixmap, at, PROJECTED_RGBA);
            }
            dot(pixmap, seen, OBSERVED_RGBA);
        }
    }
}

/// A 3 x 3 pixel dot.
fn dot(pixmap: &mut Pixmap, at: (f32, f32), rgba: [u8; 4]) {
    if let Some(rect) = tiny_skia::Rect::from_xywh(at.0.round() - 1.0, at.1.round() - 1.0, 3.0, 3.0) {
        pixmap.fill_rect(rect, &paint(rgba), Transform::identity(), None);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn probabilities_stay_readable_when_the_page_shrinks_the_picture() {
        for width in [100.0, 300.0, 430.0, 700.0, 1200.0, 2000.0] {
            let f = probability_text_factor(width);
            let shown = (font::CAP_HEIGHT * f) as f32 * (GRAPH_DISPLAY_WIDTH / width).min(1.0);
            assert!(shown >= 10.9, "capitals {shown} px tall on a {width} px picture");
        }
        assert_eq!(probability_text_factor(300.0), 2);
    }
}

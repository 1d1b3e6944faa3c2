//! The posterior cloud: the last accepted worlds drawn together as thin lines.
//!
//! The dissertation shows how well a chain has settled by overlaying about 1000 accepted
//! samples on the classified map (Figs. 3.33 b, 3.35, 3.37 b): where the samples agree the
//! lines pile up into one crisp outline, where they disagree they fan out into a faint cloud.
//! [`draw_cloud`] draws exactly that: every unit rectangle of every sample as a one-pixel
//! outline through the centres of its border cells, placed on the map through the world's
//! [`Frame`], each outline semi-transparent so that overlapping outlines darken.
//!
//! Consecutive accepted worlds differ in one or two units, so a thousand samples hold far fewer
//! distinct rectangles than they hold rectangles. Each distinct rectangle is drawn once, at the
//! opacity that its number of copies would have reached drawn one over another
//! (`1 - (1 - a)^k`): the same picture as drawing every copy, at a fraction of the cost.

use crate::floorplan::{Frame, Rect};
use std::collections::HashMap;
use tiny_skia::{Color, Paint, PathBuilder, Pixmap, Stroke, Transform};

/// The cloud's colour: magenta, which neither the map (black, gray, white) nor a world (blue,
/// cyan, green) uses. The alpha is per sample, see [`cloud_alpha`].
pub const CLOUD_RGB: [u8; 3] = [214, 0, 140];

/// The opacity of one sample's outline when `samples` samples are drawn: high for a few
/// samples, low for many, so that an outline shared by all of them ends up nearly opaque
/// (about 98 %) whatever their number. Between 0.012 and 0.8.
pub fn cloud_alpha(samples: usize) -> f64 {
    if samples == 0 {
        return 0.0;
    }
    (4.0 / samples as f64).clamp(0.012, 0.8)
}

/// Draws the outlines of every rectangle of every sample (world-frame unit rectangles, as the
/// chain records them) over a pixmap holding a `map_width` x `map_height` map drawn at `scale`
/// pixels per cell. Outlines run through the centres of the rectangles' border cells; they are
/// one pixel wide up to scale 3 and about a third of a cell wide above that.
///
/// Never panics: rectangles with a side below 1 are skipped, a frame with a non-finite angle or
/// a scale of 0 draws nothing, and what falls off the pixmap is clipped.
///
/// ```
/// use ksmcmc::floorplan::{Frame, Rect};
/// use ksmcmc::grid::{Cell, Grid};
/// use ksmcmc::render::{draw_cloud, draw_map};
///
/// let mut pixmap = draw_map(&Grid::new(20, 10, Cell::Free));
/// let frame = Frame::identity(20, 10);
/// let a = [Rect::new(2, 2, 8, 6)];
/// let b = [Rect::new(2, 2, 8, 6), Rect::new(12, 1, 6, 8)];
/// draw_cloud(&mut pixmap, 20, 10, &frame, &[&a[..], &b[..]], 1);
/// // The rectangle both samples hold is darker than the one only the second holds.
/// let both = pixmap.pixel(5, 2).unwrap();
/// let one = pixmap.pixel(15, 1).unwrap();
/// assert!(both.green() < one.green() && one.green() < 255);
/// ```
pub fn draw_cloud(
    pixmap: &mut Pixmap,
    map_width: usize,
    map_height: usize,
    frame: &Frame,
    samples: &[&[Rect]],
    scale: u32,
) {
    if !frame.angle.is_finite() || scale == 0 || samples.is_empty() || map_width == 0 || map_height == 0 {
        return;
    }
    // Distinct rectangles and how many samples hold each; sorted so that the drawing order,
    // and with it every blended pixel, does not depend on the hash map's order.
    let mut copies: HashMap<Rect, u32> = HashMap::new();
    for sample in samples {
        for r in sample.iter().filter(|r| r.w >= 1 && r.h >= 1) {
            *copies.entry(*r).or_default() += 1;
        }
    }
    let mut distinct: Vec<(Rect, u32)> = copies.into_iter().collect();
    crate::sort::sort_by_key(&mut distinct, |(r, k)| (*k, r.x, r.y, r.w, r.h));

    let identity = frame.is_identity();
    let s = scale as f64;
    let to_pixel = |x: f64, y: f64| -> (f32, f32) {
        let (mx, my) = if identity { (x, y) } else { frame.to_map(x, y) };
        ((mx * s) as f32, (my * s) as f32)
    };
    let width = if scale <= 3 { 1.0 } else { (scale as f32 / 3.0).round() };
    let stroke = Stroke { width, ..Stroke::default() };
    let a = cloud_alpha(samples.len());
    // Outlines that fall entirely off the map are skipped (a generous box in world cells).
    let (mw, mh) = (map_width as f64, map_height as f64);
    let reach = (mw + mh) * 2.0;
    for (r, k) in distinct {
        let (x0, y0) = (r.x as f64 + 0.5, r.y as f64 + 0.5);
        // In f64: `r.right()` could overflow i32 for an unchecked rectangle.
        let (x1, y1) = (x0 + r.w as f64 - 1.0, y0 + r.h as f64 - 1.0);
        if x1 < -reach || y1 < -reach || x0 > reach || y0 > reach {
            continue;
        }
        let corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)].map(|(x, y)| to_pixel(x, y));
        let mut pb = PathBuilder::new();
        pb.move_to(corners[0].0, corners[0].1);
        for c in &corners[1..] {
            pb.line_to(c.0, c.1);
        }
        pb.close();
        // A one-cell rectangle is a point: nothing to outline.
        let Some(path) = pb.finish() else { continue };
        let opacity = 1.0 - libm::pow(1.0 - a, k as f64);
        let alpha = (opacity * 255.0).round().clamp(1.0, 255.0) as u8;
        let mut paint = Paint::default();
        paint.set_color(Color::from_rgba8(CLOUD_RGB[0], CLOUD_RGB[1], CLOUD_RGB[2], alpha));
        paint.anti_alias = false;
        pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::{Cell, Grid};
    use crate::render::draw_map;

    #[test]
    fn alpha_keeps_a_shared_outline_nearly_opaque() {
        assert_eq!(cloud_alpha(0), 0.0);
        assert_eq!(cloud_alpha(1), 0.8);
        for n in [10, 100, 1000] {
            let total = 1.0 - (1.0 - cloud_alpha(n)).powi(n as i32);
            assert!(total > 0.97, "{n}: {total}");
        }
    }

    #[test]
    fn copies_darken_and_odd_input_is_harmless() {
        let map = Grid::new(30, 20, Cell::Free);
        let frame = Frame::identity(30, 20);
        let r = Rect::new(3, 3, 10, 8);
        let one = [r];
        let mut few = draw_map(&map);
        draw_cloud(&mut few, 30, 20, &frame, &[&one[..]; 2], 1);
        let mut many = draw_map(&map);
        let other = [Rect::new(15, 3, 10, 8)];
        let mut samples: Vec<&[Rect]> = vec![&one[..]; 9];
        samples.push(&other[..]);
        draw_cloud(&mut many, 30, 20, &frame, &samples, 1);
        // (3.5, 3.5) is the outline's corner: pixel (3, 3).
        let g = |p: &Pixmap, x, y| p.pixel(x, y).unwrap().green();
        assert!(g(&few, 3, 3) < 255 && g(&few, 8, 3) < 255);
        assert_eq!(g(&few, 8, 6), 255, "inside stays untouched");
        assert!(g(&many, 20, 3) > g(&many, 8, 3), "one copy is fainter than nine");

        // Empty, degenerate, far-off and rotated input draws without panicking.
        let mut p = draw_map(&map);
        let odd = [Rect::new(0, 0, 0, 5), Rect::new(i32::MAX - 1, i32::MIN, 3, 3), Rect::new(4, 4, 1, 1)];
        draw_cloud(&mut p, 30, 20, &frame, &[&odd[..]], 1);
        draw_cloud(&mut p, 30, 20, &frame, &[], 1);
        draw_cloud(&mut p, 30, 20, &Frame { angle: f64::NAN, ..frame }, &[&one[..]], 1);
        draw_cloud(&mut p, 30, 20, &frame, &[&one[..]], 0);
        let rotated = Frame { angle: 0.3, world_size: [30, 20], map_size: [34, 27] };
        let mut q = draw_map(&Grid::new(34, 27, Cell::Free));
        draw_cloud(&mut q, 34, 27, &rotated, &[&one[..]], 2);
        assert!(q.pixels().iter().any(|p| p.green() < 255));
    }
}
